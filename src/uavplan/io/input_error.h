// Bad input: one line naming the file, the place (line or key) and what is wrong. Whatever comes
// from the file (keys, values, names) is escaped on the way in: a newline or a terminal escape in
// it cannot break the line or reach the terminal.
#pragma once

#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace uavplan {

// The text with control characters and bytes that are not UTF-8 written as escapes (\n, \t,
// \x1b, ...); printable UTF-8 is kept.
std::string printable(std::string_view text);

// Whether the text is valid UTF-8; `bad_at` receives the offset of the first invalid byte.
bool valid_utf8(std::string_view text, std::size_t* bad_at = nullptr);

class InputError : public std::runtime_error {
 public:
  // line is 1-based; 0 when unknown.
  InputError(const std::string& file, int line, const std::string& place, const std::string& what)
      : std::runtime_error(format(file, line, place, what)) {}
  // Several errors of one input, one per line (each already an InputError's message).
  explicit InputError(const std::vector<std::string>& messages) : std::runtime_error(join(messages)) {}

 private:
  static std::string format(const std::string& file, int line, const std::string& place, const std::string& what) {
    // Appends one piece at a time (GCC 12 warns falsely on chained operator+ here).
    std::string s = printable(file);
    if (line > 0) {
      s.append(":");
      s.append(std::to_string(line));
    }
    if (!place.empty()) {
      s.append(": ");
      s.append(printable(place));
    }
    s.append(": ");
    s.append(printable(what));
    return s;
  }
  static std::string join(const std::vector<std::string>& messages) {
    std::string s;
    for (const std::string& m : messages) {
      if (!s.empty()) s.append("\n");
      s.append(m);
    }
    return s;
  }
};

}  // namespace uavplan
