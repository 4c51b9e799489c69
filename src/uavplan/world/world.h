// One immutable World that answers point, segment and time queries: collision after
// inflation by a radius, clearance, threat cost. Thread-safe for concurrent queries.
#pragma once

#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "uavplan/core/vec.h"
#include "uavplan/world/bvh.h"
#include "uavplan/world/moving.h"
#include "uavplan/world/shapes.h"
#include "uavplan/world/terrain.h"
#include "uavplan/world/threat.h"
#include "uavplan/world/world_memo.h"

namespace uavplan {

struct WorldSpec {
  Aabb bounds;
  std::vector<Obstacle> obstacles;
  std::vector<Radar> radars;
  std::optional<TerrainGrid> terrain;
  std::vector<MovingObstacle> moving;
  // Names the scenario gives obstacles and radars (`id`), by index; shorter or empty: unnamed.
  std::vector<std::string> obstacle_ids;
  std::vector<std::string> radar_ids;
};

class World {
 public:
  static constexpr double kInf = std::numeric_limits<double>::infinity();

  World() : World(WorldSpec{Aabb{Vec3::Zero(), Vec3::Zero()}, {}, {}, {}, {}, {}, {}}) {}
  // Throws std::invalid_argument on an inconsistent world (empty bounds, bad shapes).
  explicit World(WorldSpec spec);

  const Aabb& bounds() const { return spec_.bounds; }
  const std::vector<Obstacle>& obstacles() const { return spec_.obstacles; }
  const std::vector<Radar>& radars() const { return spec_.radars; }
  const TerrainGrid* terrain() const { return spec_.terrain ? &*spec_.terrain : nullptr; }
  const std::vector<MovingObstacle>& moving() const { return spec_.moving; }
  const WorldSpec& spec() const { return spec_; }

  bool in_bounds(const Vec3& p) const { return spec_.bounds.contains(p); }
  // Obstacle k in words: "obstacle hangar" (its id), "obstacle 3 (box)" when it has none.
  std::string obstacle_label(std::size_t k) const;
  // What the clearance at p is measured to, by name: the nearest obstacle's label, or
  // kTerrainLabel.
  static constexpr const char* kTerrainLabel = "the terrain";
  std::string nearest_label(const Vec3& p) const;

  // Distance from p to the nearest static obstacle or terrain column (0 inside), capped at `cap`.
  double clearance(const Vec3& p, double cap = kInf) const;
  // Exact distance from segment [a, b] to the nearest static obstacle or terrain, capped.
  double segment_clearance(const Vec3& a, const Vec3& b, double cap = kInf) const;
  // The same, obstacles only (a UAV standing on the ground is not colliding with it).
  double segment_obstacle_clearance(const Vec3& a, const Vec3& b, double cap = kInf) const;

  // The ground under (x, y): the terrain there, else the bottom of the bounds (never below it).
  double ground_z(double x, double y) const;
  // On the ground: at most 1 mm above it (and not below it by more than that). A flat world
  // (no height) is a plane to fly in: nothing stands on a ground there.
  bool on_ground(const Vec3& p) const {
    return spec_.bounds.max.z() > spec_.bounds.min.z() && std::abs(p.z() - ground_z(p.x(), p.y())) <= 1e-3;
  }
  // On one vertical column: at most 1 mm apart horizontally (a take-off's or a landing's rows).
  static bool same_column(const Vec3& a, const Vec3& b) { return (a.head<2>() - b.head<2>()).norm() <= 1e-3; }
  // A piece of a leg to or from the ground at height ground_z: its distance to obstacles all
  // along, and to the terrain where it is more than `keep_m` above ground_z, capped at keep_m.
  double ground_leg_clearance(const Vec3& a, const Vec3& b, double keep_m, double ground_z) const;
  // Smallest height of segment [a, b] above the ground under it (exact).
  double lowest_height_above_ground(const Vec3& a, const Vec3& b) const;
  // Largest height of segment [a, b] above the ground under it (terrain or floor), exact.
  double highest_height_above_ground(const Vec3& a, const Vec3& b) const;

  // Collision after inflating every static obstacle by `inflation_m`.
  bool point_collides(const Vec3& p, double inflation_m) const { return clearance(p, inflation_m) < inflation_m; }
  bool segment_collides(const Vec3& a, const Vec3& b, double inflation_m) const {
    return segment_clearance(a, b, inflation_m) < inflation_m;
  }
  // Inside the bounds and clear of every static obstacle after inflation.
  bool segment_valid(const Vec3& a, const Vec3& b, double inflation_m) const {
    return in_bounds(a) && in_bounds(b) && !segment_collides(a, b, inflation_m);
  }

  // Calls f(obstacle) for every static obstacle whose bounding box lies within `radius` of p.
  template <class F>
  void visit_near(const Vec3& p, double radius, F&& f) const {
    bvh_.visit_point(p, radius, [&](std::int32_t i, double&) {
      f(spec_.obstacles[static_cast<std::size_t>(i)]);
      return false;
    });
  }

  // Smallest gap between the surface of any moving obstacle and a UAV flying straight from a
  // (at t_a) to b (at t_b); +inf without moving obstacles. `index_out` names the closest.
  double moving_clearance(const Vec3& a, double t_a_s, const Vec3& b, double t_b_s, int* index_out = nullptr) const;

  double threat_density(const Vec3& p) const { return uavplan::threat_density(p, spec_.radars); }
  double p1_threat_cost(const Vec3& a, const Vec3& b) const { return uavplan::p1_threat_cost(a, b, spec_.radars); }
  double threat_integral(const Vec3& a, const Vec3& b) const { return uavplan::threat_integral(a, b, spec_.radars); }

  // What planners derive from this world and reuse (world_memo.h).
  const WorldMemo& memo() const { return *memo_; }

 private:
  WorldSpec spec_;
  Bvh bvh_;
  std::shared_ptr<WorldMemo> memo_ = std::make_shared<WorldMemo>();
};

}  // namespace uavplan
