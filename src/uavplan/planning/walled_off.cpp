#include "uavplan/planning/walled_off.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "uavplan/core/geometry.h"
#include "uavplan/planning/voxel_grid.h"

namespace uavplan {
namespace {

using Face = std::array<Vec3, 4>;

// Every turn of the footprint the same way (collinear vertices allowed).
bool convex_polygon(const std::vector<Vec2>& poly) {
  const std::size_t n = poly.size();
  int sign = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2 e1 = poly[(i + 1) % n] - poly[i], e2 = poly[(i + 2) % n] - poly[(i + 1) % n];
    const double cross = e1.x() * e2.y() - e1.y() * e2.x();
    if (cross == 0.0) continue;
    const int s = cross > 0.0 ? 1 : -1;
    if (sign != 0 && s != sign) return false;
    sign = s;
  }
  return true;
}

bool convex(const Obstacle& o) {
  const Prism* p = std::get_if<Prism>(&o);
  return p == nullptr || convex_polygon(p->polygon);
}

// The face on the upper side of cell (i, j, k) across `axis`.
Face face_of(const VoxelGrid& g, int i, int j, int k, int axis) {
  const Vec3& c = g.cell();
  Vec3 base = g.origin() + Vec3(i * c.x(), j * c.y(), k * c.z());
  base[axis] += c[axis];
  Vec3 du = Vec3::Zero(), dv = Vec3::Zero();
  du[(axis + 1) % 3] = c[(axis + 1) % 3];
  dv[(axis + 2) % 3] = c[(axis + 2) % 3];
  return {base, base + du, base + dv, base + du + dv};
}

// The obstacle that closes the face (its index), -2 for the ceiling, -1 when it is open.
int closing(const World& w, const Face& f, double inflation_m, double ceiling_m) {
  bool above = true;
  for (const Vec3& p : f) above = above && p.z() > ceiling_m;
  if (above) return -2;
  const Vec3 centre = 0.25 * (f[0] + f[1] + f[2] + f[3]);
  const double half_diag = 0.5 * (f[3] - f[0]).norm();
  int found = -1;
  w.visit_near(centre, half_diag + inflation_m, [&](const Obstacle& o) {
    if (found >= 0) return;
    bool inside = point_distance(o, centre) + half_diag < inflation_m;
    if (!inside && convex(o)) {
      inside = true;
      for (const Vec3& p : f) inside = inside && point_distance(o, p) < inflation_m;
    }
    if (inside) found = static_cast<int>(&o - w.obstacles().data());
  });
  return found;
}

}  // namespace

WalledOff walled_off(const World& world, double inflation_m, double ceiling_m, const Vec3& a, const Vec3& b,
                     std::int64_t max_cells, const StopCondition& stop) {
  // Cells under twice the inflation gain nothing: a grid plane then lies inside every inflated
  // box wall, however thin, whose faces the corner test closes.
  const double c =
      std::max(cell_for_count_m(world.bounds().extent(), static_cast<double>(max_cells)), 1.9 * inflation_m);
  // Cells the obstacles may reach (voxelize's test): a face of a cell they cannot reach is open.
  const VoxelGrid near = voxelize(world, Vec3(c, c, c), inflation_m, ceiling_m, stop);
  VoxelGrid seen(world.bounds(), near.cell());
  int i, j, k;
  near.cell_of(a, i, j, k);
  const std::int64_t from = near.index(i, j, k);
  near.cell_of(b, i, j, k);
  const std::int64_t to = near.index(i, j, k);
  std::vector<char> closer(world.obstacles().size(), 0);
  std::vector<std::uint32_t> queue{static_cast<std::uint32_t>(from)};  // max_cells < 2^32
  seen.set_blocked(from);
  for (std::size_t head = 0; head < queue.size(); ++head) {
    if ((head & 4095) == 0) stop.throw_if_stopped();
    const std::int64_t cell = queue[head];
    if (cell == to) return {};
    near.coords(cell, i, j, k);
    for (int axis = 0; axis < 3; ++axis)
      for (const int step : {-1, 1}) {
        int n[3] = {i, j, k};
        n[axis] += step;
        if (!near.inside(n[0], n[1], n[2])) continue;
        const std::int64_t next = near.index(n[0], n[1], n[2]);
        if (seen.blocked(next)) continue;
        if (near.blocked(cell) && near.blocked(next)) {
          const Face f = step > 0 ? face_of(near, i, j, k, axis) : face_of(near, n[0], n[1], n[2], axis);
          const int by = closing(world, f, inflation_m, ceiling_m);
          if (by >= 0) closer[static_cast<std::size_t>(by)] = 1;
          if (by != -1) continue;
        }
        seen.set_blocked(next);
        queue.push_back(static_cast<std::uint32_t>(next));
      }
  }
  WalledOff out;
  out.apart = true;
  for (std::size_t o = 0; o < closer.size(); ++o)
    if (closer[o]) out.walls.push_back(world.obstacle_label(o));
  return out;
}

}  // namespace uavplan
