// P4's cones as tables (DirectionalCones): one per heading offset, built once and shared by the
// searches of a planner.
#include <unordered_map>
#include <unordered_set>

#include "uavplan/core/tolerances.h"
#include "uavplan/planning/search/directional_lattice.h"

namespace uavplan {

using namespace directional;

namespace {

// One cone (see DirectionalCones): the expansion of the search for a lattice point away from the
// bounds, in cells: the target L cells along each direction, the corners of its lattice cell
// nearest first, the first corner that keeps the limits.
DirectionalCones::Cone build_cone(const DirectionalCones::Key& key, int dx, int dy, int dz) {
  const ConeLimits lim(key.max_yaw_rad, key.max_pitch_rad);
  const std::optional<Vec3> heading = Vec3(dx, dy, dz);
  const double yaw0 = std::atan2(heading->y(), heading->x());
  const int m = key.directions, mp = key.flat ? 1 : m;
  DirectionalCones::Cone c;
  ConeDirections(mp, key.max_pitch_rad).for_each(yaw0, key.max_yaw_rad, m, true, [&](const Vec3& dir) {
    const Vec3 t = key.step_cells * dir;
    const Vec3 lo(std::floor(t.x()), std::floor(t.y()), key.flat ? 0.0 : std::floor(t.z()));
    Vec3 pts[8];
    double d2[8];
    int n = 0;
    for (int cz = 0; cz <= (key.flat ? 0 : 1); ++cz)
      for (int cy = 0; cy <= 1; ++cy)
        for (int cx = 0; cx <= 1; ++cx) {
          const Vec3 corner = lo + Vec3(cx, cy, cz);
          const double dist = (corner - t).squaredNorm();
          int j = n++;
          for (; j > 0 && d2[j - 1] > dist; --j) {  // insertion, nearest first (as Lattice::corners)
            d2[j] = d2[j - 1];
            pts[j] = pts[j - 1];
          }
          d2[j] = dist;
          pts[j] = corner;
        }
    for (int i = 0; i < n; ++i) {
      const Vec3& seg = pts[i];
      if (seg.norm() < kSamePoint_m || !lim.turn_ok(heading, seg) || !lim.pitch_ok(seg)) continue;
      const DirectionalCones::Child child{
          {static_cast<std::int16_t>(seg.x()), static_cast<std::int16_t>(seg.y()), static_cast<std::int16_t>(seg.z())},
          seg.norm()};
      const bool seen = std::any_of(c.children.begin(), c.children.end(), [&](const DirectionalCones::Child& o) {
        return o.d[0] == child.d[0] && o.d[1] == child.d[1] && o.d[2] == child.d[2];
      });
      if (!seen) {
        c.children.push_back(child);
        c.max_length_cells = std::max(c.max_length_cells, child.length_cells);
      }
      break;
    }
  });
  return c;
}

}  // namespace

struct DirectionalCones::Table {
  Key key;
  std::unordered_map<std::uint32_t, Cone> cones;  // by packed heading offset
  std::unordered_set<std::uint32_t> level_kept;   // headings from which no move changes level
};

DirectionalCones::DirectionalCones() = default;
DirectionalCones::~DirectionalCones() = default;

DirectionalCones::Table& DirectionalCones::table(const Key& key) {
  const std::lock_guard lock(mutex_);
  for (const auto& t : tables_)
    if (t->key == key) return *t;
  tables_.push_back(std::make_unique<Table>(Table{key, {}, {}}));
  return *tables_.back();
}

const DirectionalCones::Cone& DirectionalCones::cone(Table& table, int dx, int dy, int dz) {
  const std::lock_guard lock(mutex_);
  return cone_locked(table, dx, dy, dz);
}

const DirectionalCones::Cone& DirectionalCones::cone_locked(Table& table, int dx, int dy, int dz) {
  const std::uint32_t k = pack_offset(dx, dy, dz);
  if (const auto it = table.cones.find(k); it != table.cones.end()) return it->second;
  return table.cones.emplace(k, build_cone(table.key, dx, dy, dz)).first->second;
}

bool DirectionalCones::level_change_reachable(Table& table, const std::vector<std::uint32_t>& headings) {
  const std::lock_guard lock(mutex_);
  std::vector<std::uint32_t> frontier;  // headings whose cones are not yet read
  std::unordered_set<std::uint32_t> seen;
  auto visit = [&](std::uint32_t k) {
    if (!table.level_kept.contains(k) && seen.insert(k).second) frontier.push_back(k);
  };
  for (const std::uint32_t k : headings) visit(k);
  while (!frontier.empty()) {
    const std::uint32_t k = frontier.back();
    frontier.pop_back();
    const int dx = static_cast<int>(k >> 20) - 512, dy = static_cast<int>((k >> 10) & 1023) - 512,
              dz = static_cast<int>(k & 1023) - 512;
    for (const Child& c : cone_locked(table, dx, dy, dz).children) {
      if (c.d[2] != 0) return true;
      visit(pack_offset(c.d[0], c.d[1], c.d[2]));
    }
  }
  // Every heading seen leads only to headings seen or known to keep the level.
  table.level_kept.insert(seen.begin(), seen.end());
  return false;
}

}  // namespace uavplan
