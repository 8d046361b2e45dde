// One number format for messages and summaries: six significant digits, enough to recognise a
// value in an error line without echoing round-off.
#pragma once

#include <sstream>
#include <string>

namespace asperity {

inline std::string fmt(double x) {
  std::ostringstream s;
  s.precision(6);
  s << x;
  return s.str();
}

}  // namespace asperity
