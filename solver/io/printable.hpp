// Text from the input (a key, a name, a message quoting them) as it may appear on one line of a
// terminal: control characters (a newline, an escape sequence, a NUL that would end a C string)
// written as \xHH, and the whole cut to a length, with the length it had.
#pragma once

#include <string>
#include <string_view>

namespace asperity::io {

inline std::string printable(std::string_view text, std::size_t max_chars) {
  static const char* hex = "0123456789abcdef";
  std::string out;
  for (const char c : text) {
    if (out.size() >= max_chars) {
      // Not within a UTF-8 sequence: drop its continuation bytes and its lead byte.
      while (!out.empty() && (static_cast<unsigned char>(out.back()) & 0xC0) == 0x80)
        out.pop_back();
      if (!out.empty() && (static_cast<unsigned char>(out.back()) & 0x80)) out.pop_back();
      return out + "... (" + std::to_string(text.size()) + " characters)";
    }
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) {
      out += "\\x";
      out += hex[(static_cast<unsigned char>(c) >> 4) & 0xf];
      out += hex[static_cast<unsigned char>(c) & 0xf];
    } else {
      out += c;
    }
  }
  return out;
}

}  // namespace asperity::io
