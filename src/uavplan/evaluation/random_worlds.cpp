#include "uavplan/evaluation/random_worlds.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include "uavplan/coordination/formation/formation_mission.h"
#include "uavplan/coordination/formation_mission/phased_formation_mission.h"
#include "uavplan/coordination/planning_view.h"
#include "uavplan/coordination/rendezvous/rendezvous_mission.h"
#include "uavplan/core/rng.h"
#include "uavplan/core/units.h"

namespace uavplan {
namespace {

Obstacle random_obstacle(Rng& r, const Aabb& b) {
  const Vec3 e = b.extent();
  const double s = r.uniform(0.04, 0.12) * std::max(e.x(), e.y());
  const Vec3 c(r.uniform(b.min.x(), b.max.x()), r.uniform(b.min.y(), b.max.y()),
               e.z() > 0.0 ? r.uniform(b.min.z(), b.max.z()) : b.min.z());
  const double z0 = e.z() > 0.0 ? b.min.z() : b.min.z() - 1.0,
               z1 = e.z() > 0.0 ? r.uniform(c.z(), b.max.z()) + 1.0 : b.min.z() + 1.0;
  switch (r.uniform_int(0, 3)) {
    case 0:
      return Sphere{c, s};
    case 1:
      return Cylinder{c.head<2>(), s, z0, z1};
    case 2:
      return Box{Vec3(c.x() - s, c.y() - 0.6 * s, z0), Vec3(c.x() + s, c.y() + 0.6 * s, z1)};
    default:
      return Prism{{{c.x() - s, c.y() - s},
                    {c.x() + s, c.y() - 0.5 * s},
                    {c.x() + 0.3 * s, c.y() + s},
                    {c.x() - s, c.y() + 0.2 * s}},
                   z0,
                   z1};
  }
}

// A free point: inside the bounds, clear of everything by `margin` (none after 500 tries).
std::optional<Vec3> free_point(Rng& r, const World& w, double margin) {
  const Aabb& b = w.bounds();
  for (int k = 0; k < 500; ++k) {
    Vec3 p(r.uniform(b.min.x(), b.max.x()), r.uniform(b.min.y(), b.max.y()),
           b.extent().z() > 0.0 ? r.uniform(b.min.z(), b.max.z()) : b.min.z());
    if (b.extent().z() > 2 * margin) p.z() = std::clamp(p.z(), b.min.z() + margin, b.max.z() - margin);
    if (w.clearance(p, margin) >= margin) return p;
  }
  return std::nullopt;
}

// Half the time, p put down on the ground when the UAV can take off or land there; else p raised
// to min_agl when it is below it. False when p cannot be either.
bool place_for_margins(Rng& r, const Scenario& sc, const UavSpec& u, Vec3& p) {
  const World& w = sc.world;
  const double keep = keep_off_m(u), ground = w.ground_z(p.x(), p.y());
  if (r.uniform01() < 0.5) {
    const Vec3 down(p.x(), p.y(), ground);
    if (!ground_column_problem(sc, u, down).empty()) return false;
    p = down;
    return true;
  }
  p.z() = std::max(p.z(), ground + u.min_agl_m + keep + 0.1);
  return w.in_bounds(p) && w.clearance(p, keep) >= keep;
}

}  // namespace

Scenario random_world(std::uint64_t seed, const RandomWorldOptions& opt) {
  Rng r(seed);
  const bool flat = r.uniform01() < 0.4;
  const double size = r.uniform(60, 200), height = flat ? 0.0 : r.uniform(20, 60);
  WorldSpec ws;
  ws.bounds = Aabb{Vec3::Zero(), Vec3(size, r.uniform(0.6, 1.0) * size, height)};
  for (int k = static_cast<int>(r.uniform_int(0, 12)); k > 0; --k)
    ws.obstacles.push_back(random_obstacle(r, ws.bounds));
  if (!flat && r.uniform01() < 0.3) {
    const int n = 6;
    std::vector<double> h(n * n);
    for (double& x : h) x = r.uniform(0, 0.25 * height);
    ws.terrain = TerrainGrid(Vec2::Zero(), size / n, n, n, std::move(h));
  }
  Scenario sc;
  sc.name = "random" + std::to_string(seed);
  sc.world = World(std::move(ws));
  sc.mission.type = opt.mission;
  sc.mission.separation_m = r.uniform(1, 4);
  const int n = static_cast<int>(r.uniform_int(1, opt.max_uavs));
  const std::optional<Vec3> common_goal = free_point(r, sc.world, 5);
  // One min_agl for the world's UAVs: planners keep the largest of a scenario's for all of them.
  const double min_agl_m = opt.ground_and_margins && !flat ? r.uniform(0.0, 0.15 * height) : 0.0;
  for (int i = 0; i < n; ++i) {
    UavSpec u;
    u.id = "u" + std::to_string(i + 1);
    u.radius_m = r.uniform(0.2, 1.0);
    std::optional<Vec3> start;
    for (int k = 0; k < 20 && !start; ++k) {
      start = free_point(r, sc.world, u.radius_m + 2);
      for (const UavSpec& o : sc.uavs)
        if (start && (o.start - *start).norm() < 3 * sc.mission.separation_m + o.radius_m + u.radius_m) start.reset();
    }
    const std::optional<Vec3> goal =
        opt.mission == "rendezvous" ? common_goal : free_point(r, sc.world, u.radius_m + 2);
    if (!start || !goal) continue;  // a crowded world: fewer UAVs
    u.start = *start;
    u.goal = *goal;
    if (opt.ground_and_margins && !flat) {
      u.clearance_m = r.uniform(0.0, 1.5);
      u.min_agl_m = min_agl_m;
      if (!place_for_margins(r, sc, u, u.start) || !place_for_margins(r, sc, u, *u.goal)) continue;
      bool apart = true;
      for (const UavSpec& o : sc.uavs)
        apart = apart && (o.start - u.start).norm() >= 3 * sc.mission.separation_m + o.radius_m + u.radius_m;
      if (!apart) continue;
    }
    const double v = r.uniform(2, 10);
    u.speed = {0, v, v};
    if (opt.limits && r.uniform01() < 0.4) u.max_turn_rad = deg_to_rad(r.uniform(45, 120));
    if (opt.limits && !flat && r.uniform01() < 0.4) u.max_climb_rad = deg_to_rad(r.uniform(25, 60));
    sc.uavs.push_back(u);
  }
  if (opt.ground_and_margins) {  // as the scenario loader does: UAVs the planners cannot place go
    const auto problems = placement_problems(sc);
    std::vector<UavSpec> kept;
    for (std::size_t i = 0; i < sc.uavs.size(); ++i)
      if (problems[i].start.empty() && problems[i].goal.empty()) kept.push_back(sc.uavs[i]);
    sc.uavs = std::move(kept);
  }
  if (sc.uavs.empty()) return random_world(seed + 1000003, opt);
  if (opt.mission == "rendezvous") sc.mission.edit_section<RendezvousSection>().arrival_tolerance_m = r.uniform(5, 30);
  return sc;
}

namespace {

// Slots (forward, left, up) of n UAVs `gap_m` apart: 0 a wedge, 1 a line abreast, 2 a column.
std::vector<Vec3> formation_shape(int kind, int n, double gap_m) {
  std::vector<Vec3> shape;
  for (int k = 0; k < n; ++k) {
    const double rank = std::ceil(k / 2.0), side = k % 2 == 1 ? 1.0 : -1.0;
    if (kind == 0)
      shape.emplace_back(-gap_m * rank, side * gap_m * rank, 0.0);
    else if (kind == 1)
      shape.emplace_back(0.0, side * gap_m * rank, 0.0);
    else
      shape.emplace_back(-gap_m * k, 0.0, 0.0);
  }
  return shape;
}

// A moving obstacle that is at `meet` at `t_meet_s`, crossing (0), meeting head-on (1) or turning
// there (2), relative to `dir`, the formation's direction of travel.
MovingObstacle mover(Rng& r, int kind, const Vec3& meet, double t_meet_s, const Vec3& dir) {
  MovingObstacle m;
  m.id = "mover" + std::to_string(kind);
  m.radius_m = r.uniform(1.0, 3.0);
  const double speed = r.uniform(1.0, 3.0);
  const Vec3 left(-dir.y(), dir.x(), 0.0);
  const Vec3 v = speed * (kind == 0 ? (r.uniform01() < 0.5 ? left : Vec3(-left)) : Vec3(-dir));
  if (kind < 2) {
    m.position = meet - v * t_meet_s;
    m.velocity_mps = v;
    return m;
  }
  const double a = r.uniform(-2.0, 2.0);
  const Vec3 in = std::cos(a) * left + std::sin(a) * dir, out = -dir;
  m.path = {{0.0, meet - speed * t_meet_s * in}, {t_meet_s, meet}, {t_meet_s + 200.0, meet + speed * 200.0 * out}};
  return m;
}

}  // namespace

Scenario random_formation_world(std::uint64_t seed) {
  Rng r(seed);
  const double size = r.uniform(400, 1000);
  WorldSpec ws;
  ws.bounds = Aabb{Vec3::Zero(), Vec3(size, size, 0.0)};
  const double margin = 0.12 * size;
  const Vec3 from(r.uniform(margin, 0.35 * size), r.uniform(margin, 0.35 * size), 0.0);
  const Vec3 to(r.uniform(0.65 * size, size - margin), r.uniform(0.65 * size, size - margin), 0.0);
  const auto far_from_ends = [&](const Vec3& p, double d) { return (p - from).norm() > d && (p - to).norm() > d; };
  for (int k = static_cast<int>(r.uniform_int(5, 30)); k > 0; --k) {
    const Vec3 p(r.uniform(0, size), r.uniform(0, size), 0.0);
    if (far_from_ends(p, 60.0)) ws.radars.push_back({p, std::pow(10.0, r.uniform(4.0, 6.0))});
  }
  for (int k = static_cast<int>(r.uniform_int(0, 4)); k > 0; --k) {
    const double radius = r.uniform(15, 40);
    const Vec2 c(r.uniform(margin, size - margin), r.uniform(margin, size - margin));
    if (far_from_ends(Vec3(c.x(), c.y(), 0.0), radius + 60.0)) ws.obstacles.push_back(Cylinder{c, radius, -1.0, 1.0});
  }
  Scenario sc;
  sc.name = "formation" + std::to_string(seed);
  sc.mission.type = "formation";
  sc.mission.separation_m = r.uniform(1.5, 4.0);
  const int n = static_cast<int>(r.uniform_int(3, 7));
  const std::vector<Vec3>& shape = sc.mission.edit_section<FormationSection>().shape =
      formation_shape(static_cast<int>(r.uniform_int(0, 2)), n, r.uniform(2.5, 4.0) * sc.mission.separation_m);
  const Vec3 dir = (to - from).normalized(), left(-dir.y(), dir.x(), 0.0);
  const double v = r.uniform(3, 8), sensor = r.uniform(20, 100);
  for (int i = 0; i < n; ++i) {
    UavSpec u;
    u.id = "uav" + std::to_string(i + 1);
    const Vec3 slot = shape[static_cast<std::size_t>(i)];
    const Vec3 offset = slot.x() * dir + slot.y() * left;
    u.start = from + offset;
    u.goal = to + offset;
    u.radius_m = r.uniform(0.3, 0.6);
    u.speed = {0, v, v};
    u.sensor_range_m = sensor;
    sc.uavs.push_back(u);
  }
  const double trip_m = (to - from).norm();
  for (int k = static_cast<int>(r.uniform_int(1, 4)); k > 0; --k) {
    const double f = r.uniform(0.25, 0.8);
    ws.moving.push_back(mover(r, static_cast<int>(r.uniform_int(0, 2)), from + f * (to - from), f * trip_m / v, dir));
    ws.moving.back().id += "_" + std::to_string(k);
  }
  sc.world = World(std::move(ws));
  return sc;
}

Scenario random_via_world(std::uint64_t seed) {
  Rng r(seed);
  const double size = r.uniform(200, 600);
  WorldSpec ws;
  ws.bounds = Aabb{Vec3::Zero(), Vec3(size, size, 0.0)};
  std::vector<Vec3> route{Vec3(r.uniform(0.05, 0.2) * size, r.uniform(0.05, 0.95) * size, 0.0)};
  const int vias = static_cast<int>(r.uniform_int(1, 3));
  for (int k = 1; k <= vias + 1; ++k)
    route.emplace_back((0.05 + 0.9 * k / (vias + 1.0)) * size, r.uniform(0.1, 0.9) * size, 0.0);
  // Cylinders off the route (at least 25 m from each leg).
  for (int k = static_cast<int>(r.uniform_int(0, 6)); k > 0; --k) {
    const Vec2 c(r.uniform(0, size), r.uniform(0, size));
    const double radius = r.uniform(5, 20);
    bool clear = true;
    for (std::size_t m = 1; m < route.size(); ++m) {
      const Vec2 a = route[m - 1].head<2>(), d = route[m].head<2>() - a;
      const double f = std::clamp((c - a).dot(d) / d.squaredNorm(), 0.0, 1.0);
      clear = clear && (a + f * d - c).norm() > radius + 25.0;
    }
    if (clear) ws.obstacles.push_back(Cylinder{c, radius, -1.0, 1.0});
  }
  const double v = r.uniform(3, 8);
  double along = 0.0;
  for (int k = 1; k <= vias; ++k) {
    const Vec3 a = route[static_cast<std::size_t>(k) - 1], b = route[static_cast<std::size_t>(k)];
    along += (b - a).norm();
    if (r.uniform01() < 0.2) continue;
    const Vec3 dir = (b - a).normalized(), left(-dir.y(), dir.x(), 0.0);
    MovingObstacle m;
    m.id = "m" + std::to_string(k);
    m.radius_m = r.uniform(1.0, 2.5);
    const int kind = static_cast<int>(r.uniform_int(0, 2));
    // A parked one leaves the via point a way past it (its radius, a UAV's and 1.5 m).
    const double short_m = r.uniform(kind == 0 ? m.radius_m + 2.5 : 2.0, 10.0);
    const Vec3 meet = b - short_m * dir;
    const double t_meet = (along - short_m) / v;
    Vec3 vel = Vec3::Zero();  // parked
    if (kind > 0) vel = r.uniform(0.5, 2.0) * (kind == 1 ? left : Vec3(-dir));
    m.position = meet - vel * t_meet;
    m.velocity_mps = vel;
    ws.moving.push_back(m);
  }
  Scenario sc;
  sc.name = "via" + std::to_string(seed);
  sc.world = World(std::move(ws));
  sc.mission.type = "route";
  sc.mission.separation_m = r.uniform(1.5, 3.0);
  sc.mission.waypoints.assign(route.begin() + 1, route.end() - 1);
  const double sensor = r.uniform(20, 60);
  const int n = static_cast<int>(r.uniform_int(1, 3));
  for (int i = 0; i < n; ++i) {
    UavSpec u;
    u.id = "u" + std::to_string(i + 1);
    u.radius_m = r.uniform(0.3, 0.6);
    u.start = route.front() + Vec3(0.0, 8.0 * i, 0.0);
    u.goal = route.back() + Vec3(0.0, 8.0 * i, 0.0);
    u.speed = {0, v, v};
    u.sensor_range_m = sensor;
    sc.uavs.push_back(u);
  }
  return sc;
}

Scenario random_p5_world(std::uint64_t seed) {
  Rng r(seed);
  const double size = r.uniform(100000, 1000000), height = 10000;
  WorldSpec ws;
  ws.bounds = Aabb{Vec3::Zero(), Vec3(size, size, height)};
  const Vec3 start(r.uniform(0.03, 0.1) * size, r.uniform(0.03, 0.1) * size, 5000);
  std::vector<Vec3> keep{start};  // places no cylinder may come near
  const int vias = static_cast<int>(r.uniform_int(1, 3));
  for (int k = 0; k <= vias; ++k)
    keep.emplace_back(r.uniform(0.2, 0.9) * size, r.uniform(0.2, 0.9) * size, r.uniform(3000, 7000));
  const double l = std::min(5000.0, size / 40.0);
  for (int k = static_cast<int>(r.uniform_int(5, 20)); k > 0; --k) {
    const double radius = std::min(r.uniform(10000, 60000), 0.08 * size);
    const Vec2 c(r.uniform(0.1, 0.9) * size, r.uniform(0.1, 0.9) * size);
    bool clear = true;
    for (const Vec3& p : keep) clear = clear && (p.head<2>() - c).norm() > radius + 3.5 * l;
    if (clear) ws.obstacles.push_back(Cylinder{c, radius, 0.0, height});
  }
  Scenario sc;
  sc.name = "p5_random" + std::to_string(seed);
  sc.world = World(std::move(ws));
  sc.mission.type = "route";
  for (int k = 1; k <= vias; ++k) {
    sc.mission.waypoints.push_back(keep[static_cast<std::size_t>(k)]);
    sc.mission.waypoint_entry_heading_rad.push_back(deg_to_rad(45.0 * static_cast<double>(r.uniform_int(-3, 4))));
  }
  UavSpec u;
  u.id = "uav1";
  u.start = start;
  u.goal = keep.back();
  u.heading_rad = deg_to_rad(r.uniform(0, 360));
  u.radius_m = 120;
  u.speed = {70, 150, 200};
  u.max_turn_rad = deg_to_rad(30);
  u.max_turn_rate_rad_s = deg_to_rad(2.2);
  u.max_climb_rate_mps = 20;
  u.model = AutopilotParams{};
  sc.uavs.push_back(u);
  sc.planner.algorithm = "pso_mpc";
  return sc;
}

namespace {

// A ring a_ij (each UAV talks to the ones before and after it): connected, far from complete.
std::vector<std::vector<double>> ring_topology(std::size_t n) {
  std::vector<std::vector<double>> a(n, std::vector<double>(n, 0.0));
  for (std::size_t i = 0; i < n; ++i) a[i][(i + 1) % n] = a[(i + 1) % n][i] = 1.0;
  return a;
}

// n UAVs parked `gap_m` apart: a row beside the runway (either side), or a line behind the
// threshold on its axis.
std::vector<Vec3> parking(Rng& r, const Airfield& af, std::size_t n, double gap_m) {
  const Vec3 dir(std::cos(af.runway_heading_rad), std::sin(af.runway_heading_rad), 0.0), left(-dir.y(), dir.x(), 0.0);
  std::vector<Vec3> out;
  const bool beside = r.uniform01() < 0.7;
  const double side = (r.uniform01() < 0.5 ? 1.0 : -1.0) * r.uniform(150.0, 400.0), first = r.uniform(-300.0, 500.0);
  for (std::size_t k = 0; k < n; ++k) {
    const double at = static_cast<double>(k) * gap_m;
    out.push_back(beside ? Vec3(af.position + (first + at) * dir + side * left)
                         : Vec3(af.position - (200.0 + at) * dir));
  }
  return out;
}

}  // namespace

Scenario random_formation_mission(std::uint64_t seed) {
  Rng r(seed);
  const double size = r.uniform(300000, 1000000), height = 10000;
  Airfield af;
  af.position = Vec3(r.uniform(60000, size - 60000), r.uniform(60000, size - 60000), 0.0);
  af.runway_heading_rad = deg_to_rad(r.uniform(-180.0, 180.0));
  af.runway_length_m = r.uniform(2000, 4000);
  const Vec3 dir(std::cos(af.runway_heading_rad), std::sin(af.runway_heading_rad), 0.0);
  // Places no cylinder may come near: the airfield, its landing cylinder and departure point.
  std::vector<std::pair<Vec3, double>> keep{{af.position, 40000.0},
                                            {af.position - 10000.0 * dir, 30000.0},
                                            {af.position + (af.runway_length_m + 15000.0) * dir, 30000.0}};
  Scenario sc;
  sc.name = "p5_mission_random" + std::to_string(seed);
  sc.mission.type = "formation_mission";
  sc.mission.separation_m = 50.0;
  sc.mission.airfield = af;
  for (int k = static_cast<int>(r.uniform_int(2, 5)); k > 0; --k) {
    TaskPoint tp;
    tp.position = Vec3(r.uniform(0.1, 0.9) * size, r.uniform(0.1, 0.9) * size, r.uniform(3000, 7000));
    tp.entry_heading_rad = deg_to_rad(r.uniform(-180.0, 180.0));
    sc.mission.edit_section<PhasedFormationSection>().task_points.push_back(tp);
    keep.emplace_back(tp.position, 25000.0);
  }
  WorldSpec ws;
  ws.bounds = Aabb{Vec3::Zero(), Vec3(size, size, height)};
  for (int k = static_cast<int>(r.uniform_int(5, 15)); k > 0; --k) {
    const double radius = std::min(r.uniform(10000, 60000), 0.06 * size);
    const Vec2 c(r.uniform(0.05, 0.95) * size, r.uniform(0.05, 0.95) * size);
    bool clear = true;
    for (const auto& [p, margin] : keep) clear = clear && (p.head<2>() - c).norm() > radius + margin;
    if (clear) ws.obstacles.push_back(Cylinder{c, radius, 0.0, height});
  }
  sc.world = World(std::move(ws));
  const std::size_t n = static_cast<std::size_t>(r.uniform_int(3, 6));
  const double gap = r.uniform(60.0, 150.0);
  const int kind = static_cast<int>(r.uniform_int(0, 3));
  std::vector<Vec3>& shape = sc.mission.edit_section<PhasedFormationSection>().shape;
  if (kind < 3) {
    shape = formation_shape(kind, static_cast<int>(n), gap);
  } else {  // a diamond grid: rows of two, alternating sides
    for (std::size_t k = 0; k < n; ++k)
      shape.emplace_back(-gap * static_cast<double>(k), (k % 2 == 0 ? 0.5 : -0.5) * gap, 0.0);
  }
  if (r.uniform01() < 0.3)
    for (std::size_t k = 0; k < n; ++k) shape[k].z() = 30.0 * static_cast<double>(k % 3);
  if (r.uniform01() < 0.4) sc.mission.edit_section<PhasedFormationSection>().topology = ring_topology(n);
  const std::vector<Vec3> starts = parking(r, af, n, r.uniform(100.0, 250.0));
  const bool own_model = r.uniform01() < 0.5;
  for (std::size_t i = 0; i < n; ++i) {
    UavSpec u;
    u.id = "uav" + std::to_string(i + 1);
    u.start = starts[i];
    u.heading_rad = af.runway_heading_rad;
    u.radius_m = 5.0;
    u.speed = own_model ? SpeedLimits{70, 150, 200}
                        : SpeedLimits{r.uniform(55, 75), r.uniform(120, 170), r.uniform(190, 230)};
    u.max_turn_rad = deg_to_rad(30);
    if (own_model) u.max_turn_rate_rad_s = deg_to_rad(2.2);
    u.max_climb_rate_mps = 20;
    if (own_model) u.model = AutopilotParams{};
    sc.uavs.push_back(u);
  }
  if (!own_model)  // one vehicle type for the whole formation
    for (UavSpec& u : sc.uavs) u.speed = sc.uavs.front().speed;
  sc.planner.algorithm = "pso_mpc";
  return sc;
}

Scenario enclosed_goal_world(std::uint64_t seed) {
  Rng r(seed);
  WorldSpec ws;
  ws.bounds = Aabb{Vec3::Zero(), Vec3(100, 100, 40)};
  const Vec3 c(r.uniform(60, 80), r.uniform(60, 80), 20);
  const double in = 5, out = 7;
  ws.obstacles.push_back(Box{c + Vec3(-out, -out, -out), c + Vec3(out, out, -in)});
  ws.obstacles.push_back(Box{c + Vec3(-out, -out, in), c + Vec3(out, out, out)});
  ws.obstacles.push_back(Box{c + Vec3(-out, -out, -in), c + Vec3(-in, out, in)});
  ws.obstacles.push_back(Box{c + Vec3(in, -out, -in), c + Vec3(out, out, in)});
  ws.obstacles.push_back(Box{c + Vec3(-in, -out, -in), c + Vec3(in, -in, in)});
  ws.obstacles.push_back(Box{c + Vec3(-in, in, -in), c + Vec3(in, out, in)});
  Scenario sc;
  sc.name = "enclosed" + std::to_string(seed);
  sc.world = World(std::move(ws));
  UavSpec u;
  u.id = "u1";
  u.start = Vec3(r.uniform(5, 30), r.uniform(5, 30), r.uniform(5, 35));
  u.goal = c;
  sc.uavs.push_back(u);
  return sc;
}

}  // namespace uavplan
