// JUnit XML writer (the schema's common subset that GitLab, GitHub actions and Jenkins read).
#include "validation/junit.hpp"

#include <unistd.h>

#include <fstream>
#include <sstream>
#include <stdexcept>

namespace asperity::validation {
namespace {

std::string xml_escape(const std::string& s) {
  std::string o;
  for (char c : s) {
    switch (c) {
      case '&':
        o += "&amp;";
        break;
      case '<':
        o += "&lt;";
        break;
      case '>':
        o += "&gt;";
        break;
      case '"':
        o += "&quot;";
        break;
      case '\n':
        o += "&#10;";
        break;
      default:
        o += c;
    }
  }
  return o;
}

}  // namespace

void write_junit(const std::filesystem::path& file, const std::string& suite,
                 const std::vector<JUnitCase>& cases) {
  int failures = 0, errors = 0, skipped = 0;
  double seconds = 0;
  for (const JUnitCase& c : cases) {
    failures += c.failed && !c.error ? 1 : 0;
    errors += c.error ? 1 : 0;
    skipped += c.skipped ? 1 : 0;
    seconds += c.seconds;
  }
  std::ostringstream x;
  x << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
    << "<testsuites tests=\"" << cases.size() << "\" failures=\"" << failures << "\" errors=\""
    << errors << "\">\n"
    << "  <testsuite name=\"" << xml_escape(suite) << "\" tests=\"" << cases.size()
    << "\" failures=\"" << failures << "\" errors=\"" << errors << "\" skipped=\"" << skipped
    << "\" time=\"" << seconds << "\">\n";
  for (const JUnitCase& c : cases) {
    x << "    <testcase classname=\"" << xml_escape(c.classname) << "\" name=\""
      << xml_escape(c.name) << "\" time=\"" << c.seconds << "\"";
    if (!c.failed && !c.error && c.details.empty()) {
      x << "/>\n";
      continue;
    }
    x << ">\n";
    if (c.skipped) {
      x << "      <skipped message=\"" << xml_escape(c.message) << "\"/>\n";
    } else if (c.error || c.failed) {
      const char* tag = c.error ? "error" : "failure";
      x << "      <" << tag << " message=\"" << xml_escape(c.message) << "\">"
        << xml_escape(c.details) << "</" << tag << ">\n";
    } else {
      x << "      <system-out>"
        << xml_escape(c.message + (c.details.empty() ? "" : "; ") + c.details) << "</system-out>\n";
    }
    x << "    </testcase>\n";
  }
  x << "  </testsuite>\n</testsuites>\n";
  if (file.has_parent_path()) std::filesystem::create_directories(file.parent_path());
  const std::filesystem::path tmp = file.string() + ".partial-" + std::to_string(::getpid());
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    out << x.str();
    if (!out.flush()) throw std::runtime_error(tmp.string() + ": write failed");
  }
  std::filesystem::rename(tmp, file);
}

}  // namespace asperity::validation
