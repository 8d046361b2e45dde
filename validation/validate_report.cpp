// The report of `asperity validate` (validate_report.hpp).
#include "validation/validate_report.hpp"

#include <sstream>

#include "solver/io/atomic_file.hpp"
#include "solver/io/csv.hpp"

namespace asperity::validation {
namespace {

using OJson = nlohmann::ordered_json;

// A JSON value's text (a string as itself: its quotes are the CSV's to add), or "" when the
// check has no such key.
std::string text_of(const OJson& c, const char* key) {
  if (!c.contains(key)) return {};
  return c[key].is_string() ? c[key].get<std::string>() : c[key].dump();
}

std::string results_csv(const std::vector<CaseOutcome>& cases) {
  io::CsvWriter csv({"case", "quantity", "reference", "expected", "got", "rel_error", "rel_tol",
                     "abs_tol", "passed", "cpu_seconds"},
                    6);
  for (const CaseOutcome& k : cases) {
    for (const auto& c : k.check["checks"]) {
      csv.field(k.check["case"].get<std::string>())
          .field(c["quantity"].get<std::string>())
          .field(c["reference"].get<std::string>())
          .field(text_of(c, "expected"))
          .field(text_of(c, "got"))
          .field(text_of(c, "rel_error"))
          .field(text_of(c, "rel_tol"))
          .field(text_of(c, "abs_tol"))
          .field(c["passed"].get<bool>() ? "true" : "false")
          .number(k.cpu_seconds)
          .end_row();
    }
  }
  return csv.str();
}

// The tolerance column: "rel [+ abs]" for a tolerance check, the bound for max/min/range.
std::string tolerance_text(const OJson& c) {
  if (c.contains("rel_tol")) {
    std::ostringstream t;
    t << c["rel_tol"].get<double>() << " rel";
    if (c["abs_tol"].get<double>() != 0) t << " + " << c["abs_tol"].get<double>() << " abs";
    return t.str();
  }
  const std::string ref = c["reference"].get<std::string>();
  return ref == "max"     ? "≤ expected"
         : ref == "min"   ? "≥ expected"
         : ref == "range" ? "≤ " + c["upper"].dump()
                          : "equal";
}

std::string report_md(const std::vector<CaseOutcome>& cases, const std::string& solved_by,
                      std::size_t failed, double cpu_total) {
  const std::size_t n = cases.size();
  std::ostringstream md;
  md << "# asperity validation report\n\n"
     << "Solved by " << solved_by << ".\n\n"
     << n - failed << " of " << n << " cases pass; " << cpu_total << " s CPU in all.\n\n"
     << "Each case is a scene plus expected values (`validation/cases/`). `rel error` is "
        "(got − expected)/|expected|; a check passes when |got − expected| ≤ rel_tol·|expected| + "
        "abs_tol, or within its max/min bound.\n\n"
     << "| case | quantity | reference | expected | got | rel error | tolerance | pass |\n"
     << "|---|---|---|---|---|---|---|---|\n";
  for (const CaseOutcome& k : cases) {
    for (const auto& c : k.check["checks"]) {
      std::ostringstream err;
      if (c.contains("rel_error") && c["rel_error"].is_number()) {
        err.precision(3);
        err << c["rel_error"].get<double>();
      }
      md << "| " << k.check["case"].get<std::string>() << " | " << c["quantity"].get<std::string>()
         << " | " << c["reference"].get<std::string>() << " | " << c["expected"].dump() << " | "
         << c["got"].dump() << " | " << err.str() << " | " << tolerance_text(c) << " | "
         << (c["passed"].get<bool>() ? "yes" : "**NO**") << " |\n";
    }
  }
  return md.str();
}

}  // namespace

void write_validate_report(const std::vector<CaseOutcome>& cases, const std::filesystem::path& out,
                           const std::string& solved_by) {
  std::size_t failed = 0;
  double cpu_total = 0;
  OJson all = OJson::array();
  for (const CaseOutcome& k : cases) {
    cpu_total += k.cpu_seconds;
    if (!k.check["passed"].get<bool>()) ++failed;
    all.push_back(k.check);
  }
  io::write_atomically(out / "results.csv", results_csv(cases));
  io::write_atomically(out / "report.md", report_md(cases, solved_by, failed, cpu_total));
  OJson summary;
  summary["solver"] = solved_by;
  summary["cases"] = cases.size();
  summary["passed"] = cases.size() - failed;
  summary["failed"] = failed;
  summary["cpu_seconds"] = cpu_total;
  summary["results"] = all;
  io::write_atomically(out / "validation.json", summary.dump(2) + "\n");
}

}  // namespace asperity::validation
