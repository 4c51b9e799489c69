#include "p3_runner.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>

#include "stats.h"
#include "uavplan/coordination/group/group_planner.h"
#include "uavplan/coordination/mission_planner.h"
#include "uavplan/core/rng.h"
#include "uavplan/evaluation/metrics.h"
#include "uavplan/evaluation/verifier.h"
#include "uavplan/io/scenario_io.h"

namespace uavplan::bench {
namespace {

// n UAVs in a square block at the lower left (3-D: a cube of layers 1.5 m apart from 2 m up),
// goals in the same block shape at the upper right, random spheres in between and among the
// goals (none within the separation of a goal). Spacing 1.5 m (so that a UAV can still pass
// between two that have arrived), separation 0.5 m, radius 0.1 m.
Scenario random_group(int n, std::uint64_t seed, bool three_d) {
  const int side_n =
      static_cast<int>(std::ceil(three_d ? std::cbrt(static_cast<double>(n)) : std::sqrt(static_cast<double>(n))));
  const double spacing = 1.5, side = spacing * side_n, separation = 0.5, radius = 0.1;
  const double span = 3.0 * side + 10.0, height = three_d ? side + 4.0 : 0.0;
  Scenario sc;
  sc.name = "random_group_" + std::to_string(n) + (three_d ? "_3d" : "");
  for (int i = 0; i < n; ++i) {
    UavSpec u;
    u.id = "u" + std::to_string(i + 1);
    const int layer = three_d ? i / (side_n * side_n) : 0, in_layer = three_d ? i % (side_n * side_n) : i;
    u.start = Vec3(spacing * (in_layer % side_n), spacing * (in_layer / side_n), three_d ? 2.0 + spacing * layer : 0.0);
    u.goal = u.start + Vec3(span - side, span - side, 0);
    u.radius_m = radius;
    u.speed = {0, 1, 1};
    sc.uavs.push_back(u);
  }
  Rng rng(seed);
  WorldSpec ws;
  ws.bounds = Aabb{Vec3(-2, -2, 0), Vec3(span + side + 2, span + side + 2, height)};
  const int obstacles = (three_d ? 2 * n : 2 * side * side / 3) + 5;
  while (static_cast<int>(ws.obstacles.size()) < obstacles) {
    const Vec3 c(rng.uniform(side + 2.0, span - 2.0), rng.uniform(side + 2.0, span - 2.0),
                 three_d ? rng.uniform(0.0, height) : 0.0);
    const double r = three_d ? rng.uniform(0.2, 0.8) : rng.uniform(0.1, 0.4);
    const bool on_a_goal = std::any_of(sc.uavs.begin(), sc.uavs.end(), [&](const UavSpec& u) {
      return (*u.goal - c).norm() < r + radius + separation;
    });
    if (!on_a_goal) ws.obstacles.push_back(Sphere{c, r});
  }
  sc.world = World(std::move(ws));
  sc.mission.type = "group";
  sc.mission.separation_m = separation;
  sc.planner.algorithm = "apf";
  return sc;
}

}  // namespace

std::string run_p3(const std::string& dir, bool* all_ok) {
  std::string out;
  char buf[300];
  bool ok = true;
  const Scenario sc = load_scenario(dir + "/p3_group9.yaml");
  const double paper_before[9] = {303.3, 12.6, 1.8, 109.8, 32.8, 10.5, 3.4, 12.6, 11.7};
  const double paper_after[9] = {2.9, 2.6, 1.8, 2.8, 2.7, 2.6, 2.4, 2.9, 2.8};
  for (const bool improved : {true, false}) {
    ApfOptions o = ApfOptions::from_params({}, improved ? ApfField::improved : ApfField::traditional);
    o.smooth = true;  // the baseline's "after" column shows what smoothing alone would do
    const auto t0 = Clock::now();
    const GroupResult g = plan_group(sc, o, {});
    const double ms = ms_since(t0);
    std::snprintf(buf, sizeof buf,
                  "P3 Tables 3-4, %s field: path score SC before and after smoothing (lower is better)\n",
                  improved ? "improved" : "traditional");
    out += buf;
    std::snprintf(buf, sizeof buf, "%-5s %8s %9s %9s %9s %8s %8s %8s %8s\n", "uav", "reached", "before", "paper",
                  "after", "paper", "Y1_m", "Y2", "Y3");
    out += buf;
    double tb = 0, ta = 0, pb = 0, pa = 0;
    for (std::size_t i = 0; i < g.uavs.size(); ++i) {
      const P3Score b = p3_score(g.uavs[i].raw, sc.world), a = p3_score(g.uavs[i].smoothed, sc.world);
      tb += b.sc;
      ta += a.sc;
      pb += paper_before[i];
      pa += paper_after[i];
      std::snprintf(buf, sizeof buf, "%-5s %8s %9.2f %9.1f %9.2f %8.1f %8.2f %8.2f %8.3f\n", g.uavs[i].id.c_str(),
                    g.uavs[i].reached ? "yes" : "NO", b.sc, paper_before[i], a.sc, paper_after[i], a.y1, a.y2, a.y3);
      out += buf;
      if (improved) ok &= g.uavs[i].reached;
    }
    std::snprintf(buf, sizeof buf, "%-5s %8s %9.2f %9.1f %9.2f %8.1f   (planning %.1f ms, %d frames of %.2f s)\n\n",
                  "total", "", tb, pb, ta, pa, ms, g.frames, g.frame_s);
    out += buf;
    if (improved) ok &= ta < tb;
  }
  for (const bool three_d : {false, true}) {
    out += three_d
               ? "\nP3 scaling, 3-D: a cube of UAVs through random spheres (0.2-0.8 m) at every height\n"
               : "P3 scaling: random obstacle fields, block to block (1.5 m spacing), separation 0.5 m (verified)\n";
    std::snprintf(buf, sizeof buf, "%6s %10s %9s %12s %12s %12s\n", "uavs", "obstacles", "solved", "plan_ms",
                  "min_sep_m", "group_SC");
    out += buf;
    for (const int n : {9, 25, 100, 400}) {
      const Scenario rs = random_group(n, 100 + n, three_d);
      const auto t0 = Clock::now();
      Plan plan = plan_mission(rs, {});
      const double ms = ms_since(t0);
      finalize_plan(rs, plan);
      int solved = 0;
      for (const auto& u : plan.uavs) solved += u.status == Status::solved;
      const auto sep = plan.metrics.find("min_separation_m");
      std::snprintf(buf, sizeof buf, "%6d %10zu %6d/%-3d %12.1f %12.3f %12.2f\n", n, rs.world.obstacles().size(),
                    solved, n, ms, sep == plan.metrics.end() ? 0.0 : sep->second,
                    plan.metrics.count("p3_group_score") ? plan.metrics.at("p3_group_score") : 0.0);
      out += buf;
      if (n == 100) ok &= solved == n;
    }
  }
  out +=
      "(scores: S1 = Y1 / |goal - start|, S2 = Y2 / points, S3 = Y3, SC = S1 + S2 + S3; the paper leaves its\n"
      " normalisation open, so only the before/after contrast compares)\n";
  if (all_ok) *all_ok = ok;
  return out;
}

}  // namespace uavplan::bench
