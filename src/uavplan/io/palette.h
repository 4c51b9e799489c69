// One colour per UAV, the same in every view (report, KML): a palette of well-separated hues.
#pragma once

#include <array>
#include <cstddef>
#include <string>

namespace uavplan {

inline constexpr std::array<const char*, 10> kUavPalette = {"#e6194b", "#3cb44b", "#4363d8", "#f58231", "#911eb4",
                                                            "#46f0f0", "#f032e6", "#bcd23d", "#800000", "#008080"};

inline const char* uav_colour(std::size_t index) { return kUavPalette[index % kUavPalette.size()]; }

// KML writes colours as aabbggrr.
inline std::string kml_colour(std::size_t index) {
  const std::string c = uav_colour(index);
  return "ff" + c.substr(5, 2) + c.substr(3, 2) + c.substr(1, 2);
}

}  // namespace uavplan
