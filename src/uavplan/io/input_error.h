// Bad input: one line naming the file, the place (line or key) and what is wrong.
#pragma once

#include <stdexcept>
#include <string>

namespace uavplan {

class InputError : public std::runtime_error {
 public:
  // line is 1-based; 0 when unknown.
  InputError(const std::string& file, int line, const std::string& place, const std::string& what)
      : std::runtime_error(format(file, line, place, what)) {}

 private:
  static std::string format(const std::string& file, int line, const std::string& place, const std::string& what) {
    // Appends one piece at a time (GCC 12 warns falsely on chained operator+ here).
    std::string s = file;
    if (line > 0) {
      s.append(":");
      s.append(std::to_string(line));
    }
    if (!place.empty()) {
      s.append(": ");
      s.append(place);
    }
    s.append(": ");
    s.append(what);
    return s;
  }
};

}  // namespace uavplan
