// Strict command-line numbers: the whole argument is the number, finite and in range. CLI11's own
// conversion accepts "-1" for an unsigned seed (it wraps to 2^64-1), saturates overflow, reads ""
// as 0 and lets "nan" through NonNegativeNumber; these validators run on the text first.
#pragma once

#include <charconv>
#include <cmath>
#include <cstdint>
#include <sstream>
#include <string>

#include <CLI/CLI.hpp>

namespace asperity::app {

// A whole number in [lo, hi], digits only (an optional leading '-' when lo < 0).
inline CLI::Validator whole_number(long long lo, std::uint64_t hi) {
  std::ostringstream d;
  d << "INT in [" << lo << ", " << hi << "]";
  return CLI::Validator(
      [lo, hi](std::string& text) -> std::string {
        const std::string range = "a whole number from " + std::to_string(lo) + " to " +
                                  std::to_string(hi) + " (got \"" + text.substr(0, 40) + "\")";
        const char* b = text.data();
        const char* e = b + text.size();
        if (!text.empty() && text[0] == '-') {
          long long x = 0;
          const auto [p, ec] = std::from_chars(b, e, x);
          if (ec != std::errc{} || p != e || x < lo) return "must be " + range;
          return "";
        }
        std::uint64_t x = 0;
        const auto [p, ec] = std::from_chars(b, e, x);
        if (ec != std::errc{} || p != e || x > hi) return "must be " + range;
        return "";
      },
      d.str());
}

// A finite real number with lo < x (lo_open) or lo ≤ x, and x ≤ hi.
inline CLI::Validator real_number(double lo, double hi, bool lo_open) {
  std::ostringstream d;
  d << "FLOAT in " << (lo_open ? "(" : "[") << lo << ", " << hi << "]";
  const std::string desc = d.str();
  return CLI::Validator(
      [lo, hi, lo_open](std::string& text) -> std::string {
        std::ostringstream r;
        r << "must be a finite number " << (lo_open ? "> " : ">= ") << lo << " and <= " << hi
          << " (got \"" << text.substr(0, 40) << "\")";
        double x = 0;
        const char* b = text.data();
        const char* e = b + text.size();
        const auto [p, ec] = std::from_chars(b, e, x);
        if (ec != std::errc{} || p != e || !std::isfinite(x)) return r.str();
        if ((lo_open ? !(x > lo) : !(x >= lo)) || !(x <= hi)) return r.str();
        return "";
      },
      desc);
}

// Any finite real number (the range is checked where the value is used, with its own message).
inline CLI::Validator finite_number() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        double x = 0;
        const char* b = text.data();
        const char* e = b + text.size();
        const auto [p, ec] = std::from_chars(b, e, x);
        if (ec != std::errc{} || p != e || !std::isfinite(x))
          return "must be a finite number (got \"" + text.substr(0, 40) + "\")";
        return "";
      },
      "FLOAT");
}

}  // namespace asperity::app
