#include "uavplan/io/export_common.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <numbers>

#include "uavplan/core/geometry.h"

namespace uavplan {
namespace {

constexpr int kCircleVertices = 64;

std::string name_at(const std::vector<std::string>& ids, std::size_t k, const char* kind) {
  return k < ids.size() && !ids[k].empty() ? ids[k] : std::string(kind) + " " + std::to_string(k);
}

}  // namespace

double round_deg(double v) { return std::round(v * 1e9) / 1e9; }
double round_m(double v) { return std::round(v * 1e4) / 1e4; }
LatLonAlt rounded(LatLonAlt g) { return {round_deg(g.lat_deg), round_deg(g.lon_deg), round_m(g.alt_m)}; }

std::string short_num(double v) {
  if (v == 0.0) return "0";
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}

std::vector<Vec2> footprint(const Obstacle& o) {
  std::vector<Vec2> ring;
  auto circle = [&](const Vec2& c, double r) {
    for (int k = 0; k < kCircleVertices; ++k) {
      const double a = 2.0 * std::numbers::pi * k / kCircleVertices;
      ring.emplace_back(c.x() + r * std::cos(a), c.y() + r * std::sin(a));
    }
  };
  std::visit(
      [&](const auto& s) {
        using T = std::decay_t<decltype(s)>;
        if constexpr (std::is_same_v<T, Sphere>) {
          circle(Vec2(s.center.x(), s.center.y()), s.radius_m);
        } else if constexpr (std::is_same_v<T, Cylinder>) {
          circle(s.center, s.radius_m);
        } else if constexpr (std::is_same_v<T, Box>) {
          ring = {{s.min.x(), s.min.y()}, {s.max.x(), s.min.y()}, {s.max.x(), s.max.y()}, {s.min.x(), s.max.y()}};
        } else {
          ring = s.polygon;
          if (polygon_signed_area(ring) < 0.0) std::reverse(ring.begin(), ring.end());
        }
      },
      o);
  return ring;
}

std::string obstacle_name(const World& w, std::size_t k) { return name_at(w.spec().obstacle_ids, k, "obstacle"); }
std::string radar_name(const World& w, std::size_t k) { return name_at(w.spec().radar_ids, k, "radar"); }

}  // namespace uavplan
