#include "deconfliction_runner.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>

#include "stats.h"
#include "uavplan/coordination/mission_planner.h"
#include "uavplan/coordination/routes/space_time_routes.h"
#include "uavplan/core/rng.h"
#include "uavplan/evaluation/verifier.h"

namespace uavplan::bench {
namespace {

constexpr double kSide_m = 1000.0, kCeiling_m = 120.0, kSeparation_m = 5.0, kCruise_mps = 10.0;
constexpr const char* kLayouts[] = {"swap", "streams", "pairs"};

struct Leg {
  Vec3 start, goal;
};

// The UAVs' starts and goals: on a circle to the far side, two streams crossing at right angles
// (west to east and south to north, at two heights), or random pairs at least 300 m apart.
std::vector<Leg> legs(const std::string& layout, int n, Rng& rng) {
  std::vector<Leg> out;
  const Vec3 c(kSide_m / 2, kSide_m / 2, 0.0);
  for (int i = 0; i < n; ++i) {
    if (layout == "swap") {
      const double a = 2.0 * kPi * i / n;
      const Vec3 r(440.0 * std::cos(a), 440.0 * std::sin(a), 0.0);
      out.push_back({c + r + Vec3(0, 0, 50), c - r + Vec3(0, 0, 50)});
    } else if (layout == "streams") {
      const int half = (n + 1) / 2, k = i / 2;
      const double across = 150.0 + 700.0 * (k + 0.5) / half;
      const double z = 40.0 + 20.0 * (k % 2);
      if (i % 2 == 0)
        out.push_back({Vec3(30, across, z), Vec3(kSide_m - 30, across, z)});
      else
        out.push_back({Vec3(across, 30, z), Vec3(across, kSide_m - 30, z)});
    } else {
      for (;;) {
        const Vec3 s(rng.uniform(30, kSide_m - 30), rng.uniform(30, kSide_m - 30), rng.uniform(30, 100));
        const Vec3 g(rng.uniform(30, kSide_m - 30), rng.uniform(30, kSide_m - 30), rng.uniform(30, 100));
        bool clear = (s - g).norm() >= 300.0;
        for (const Leg& l : out)
          clear = clear && (l.start - s).norm() > 3 * kSeparation_m && (l.goal - g).norm() > 3 * kSeparation_m;
        if (clear) {
          out.push_back({s, g});
          break;
        }
      }
    }
  }
  return out;
}

// A city of box buildings on a 100 m block grid (streets between them), none within 20 m of a
// UAV's start or goal.
Scenario city(const std::vector<Leg>& uavs, Rng& rng) {
  WorldSpec ws{Aabb{Vec3::Zero(), Vec3(kSide_m, kSide_m, kCeiling_m)}, {}, {}, {}, {}, {}, {}};
  for (int bx = 0; bx < 10; ++bx)
    for (int by = 0; by < 10; ++by) {
      if (rng.uniform01() < 0.4) continue;
      const double w = rng.uniform(30, 75), d = rng.uniform(30, 75), h = rng.uniform(15, 110);
      const Vec3 lo(bx * 100.0 + (100 - w) / 2, by * 100.0 + (100 - d) / 2, 0.0);
      const Box b{lo, lo + Vec3(w, d, h)};
      bool clear = true;
      for (const Leg& l : uavs)
        for (const Vec3& p : {l.start, l.goal}) clear = clear && (p - p.cwiseMax(b.min).cwiseMin(b.max)).norm() > 20.0;
      if (clear) ws.obstacles.push_back(b);
    }
  Scenario sc;
  sc.name = "city";
  sc.world = World(ws);
  sc.mission.type = "independent";
  sc.mission.separation_m = kSeparation_m;
  for (std::size_t i = 0; i < uavs.size(); ++i) {
    UavSpec u;
    u.id = "u" + std::to_string(i);
    u.start = uavs[i].start;
    u.goal = uavs[i].goal;
    u.speed = {0.0, kCruise_mps, kCruise_mps};
    sc.uavs.push_back(u);
  }
  return sc;
}

DeconflictionRun run_one(const Scenario& sc, const std::string& layout, const DeconflictionOptions& o,
                         std::uint64_t seed) {
  DeconflictionRun run;
  run.uavs = static_cast<int>(sc.uavs.size());
  run.layout = layout;
  MissionOptions mo;
  mo.seed = seed;
  mo.params["deconfliction"] = "space_time";
  mo.params["space_time_method"] = o.method;
  mo.stop = StopCondition::time_limit(o.time_limit_s);
  const auto t0 = std::chrono::steady_clock::now();
  const Plan plan = plan_mission(sc, mo);
  const std::vector<Violation> violations = verify_plan(sc, plan);
  run.ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  std::map<std::string, int> rejected;
  for (const Violation& v : violations) rejected[v.uav] = 1;
  std::vector<std::size_t> all;
  for (std::size_t i = 0; i < sc.uavs.size(); ++i) all.push_back(i);
  const MissionContext ctx{mo, "astar", {}, {}, {}};
  const std::vector<LoneFlight> alone = lone_space_time_flights(sc, ctx, all, {});
  for (std::size_t i = 0; i < plan.uavs.size(); ++i) {
    const UavPlan& up = plan.uavs[i];
    if (up.status != Status::solved) continue;
    ++run.solved;
    run.rejected += rejected.count(up.id) ? 1 : 0;
    if (!alone[i].found) continue;
    run.delay_s += up.arrival_s - alone[i].arrival_s;
    run.length_m += flown_length_m(up.trajectory);
    run.alone_m += alone[i].length_m;
  }
  return run;
}

}  // namespace

std::vector<DeconflictionRun> run_deconfliction(const DeconflictionOptions& o) {
  std::vector<DeconflictionRun> runs;
  for (const int n : o.sizes)
    for (const char* layout : kLayouts)
      for (int k = 0; k < o.cities; ++k) {
        const std::uint64_t seed = o.seed * 1000003 + static_cast<std::uint64_t>(n) * 101 + k;
        Rng rng(seed);
        const std::vector<Leg> l = legs(layout, n, rng);
        runs.push_back(run_one(city(l, rng), layout, o, seed));
      }
  return runs;
}

std::string format_deconfliction(const std::vector<DeconflictionRun>& runs, const DeconflictionOptions& o) {
  std::string out;
  char buf[256];
  std::snprintf(buf, sizeof buf,
                "random 1 x 1 km cities (box buildings, ceiling 120 m), separation %g m, cruise %g m/s; "
                "independent mission, deconfliction space_time (%s), %d cities per row; every plan verified\n",
                kSeparation_m, kCruise_mps, o.method.c_str(), o.cities);
  out += buf;
  std::snprintf(buf, sizeof buf, "%5s %-8s | %7s %8s | %9s %9s %9s | %12s %10s\n", "uavs", "layout", "solved",
                "rejected", "median ms", "p95 ms", "worst ms", "delay s/UAV", "length +%");
  out += buf;
  for (const int n : o.sizes)
    for (const char* layout : kLayouts) {
      int uavs = 0, solved = 0, rejected = 0;
      double delay = 0, length = 0, alone = 0;
      std::vector<double> ms;
      for (const DeconflictionRun& r : runs) {
        if (r.uavs != n || r.layout != layout) continue;
        uavs += r.uavs;
        solved += r.solved;
        rejected += r.rejected;
        delay += r.delay_s;
        length += r.length_m;
        alone += r.alone_m;
        ms.push_back(r.ms);
      }
      if (ms.empty()) continue;
      std::snprintf(buf, sizeof buf, "%5d %-8s | %6.1f%% %8d | %9.0f %9.0f %9.0f | %12.1f %10.1f\n", n, layout,
                    100.0 * solved / std::max(uavs, 1), rejected, median(ms), percentile(ms, 95),
                    *std::max_element(ms.begin(), ms.end()), solved > 0 ? delay / solved : 0.0,
                    alone > 0 ? 100.0 * (length / alone - 1.0) : 0.0);
      out += buf;
    }
  out += "targets: 50 UAVs swapping across a 1 km city solved and verified in < 1 s, 200 in < 10 s; 0 rejected\n";
  return out;
}

bool deconfliction_passed(const std::vector<DeconflictionRun>& runs) {
  for (const DeconflictionRun& r : runs)
    if (r.solved != r.uavs || r.rejected > 0) return false;
  return true;
}

}  // namespace uavplan::bench
