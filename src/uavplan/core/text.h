// Numbers and points in messages: six significant digits, no trailing zeros ("2.5", "1e+06").
#pragma once

#include <cstdio>
#include <string>
#include <vector>

#include "uavplan/core/vec.h"

namespace uavplan {

// printf into a string as long as it needs: a message that quotes an id or a name is never cut.
[[gnu::format(printf, 1, 2)]] std::string strf(const char* format, ...);

inline std::string num_text(double x) {
  char buf[48];
  std::snprintf(buf, sizeof buf, "%.6g", x);
  return buf;
}

inline std::string point_text(const Vec3& p) {
  char buf[112];
  std::snprintf(buf, sizeof buf, "(%.6g, %.6g, %.6g)", p.x(), p.y(), p.z());
  return buf;
}

// "a, b or c" (conjunction "and": "a, b and c"); "" for none.
std::string word_list(const std::vector<std::string>& words, const std::string& conjunction = "or");

// The candidate a mistyped word most likely meant: the nearest by edit distance (a swap of two
// neighbouring letters counts one), when it is within a third of the word's length (at least
// one edit); "" when none is that near.
std::string nearest_word(const std::string& word, const std::vector<std::string>& candidates);

// "1 UAV", "3 UAVs": a count with its noun, plural but for one (the noun's plural adds "s").
inline std::string count_text(std::size_t n, const std::string& noun) {
  return std::to_string(n) + " " + noun + (n == 1 ? "" : "s");
}

}  // namespace uavplan
