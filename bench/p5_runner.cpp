#include "p5_runner.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>

#include "uavplan/coordination/contract/separation.h"
#include "uavplan/coordination/formation_mission/formation_group.h"
#include "uavplan/coordination/formation_mission/task_points.h"
#include "uavplan/coordination/mission_planner.h"
#include "uavplan/evaluation/random_worlds.h"
#include "uavplan/evaluation/verifier.h"
#include "uavplan/io/scenario_io.h"

namespace uavplan::bench {
namespace {

std::string line(const char* fmt, auto... args) {
  char buf[512];
  std::snprintf(buf, sizeof buf, fmt, args...);
  return buf;
}

Trajectory slice(const Trajectory& tr, double t0, double t1) {
  Trajectory out;
  if (tr.empty() || t1 < tr.front().t_s || t0 > tr.back().t_s) return out;
  t0 = std::max(t0, tr.front().t_s), t1 = std::min(t1, tr.back().t_s);
  out.push_back({t0, position_at(tr, t0)});
  for (const TrajectorySample& s : tr)
    if (s.t_s > t0 && s.t_s < t1) out.push_back(s);
  out.push_back({t1, position_at(tr, t1)});
  return out;
}

// Smallest distance in the air between any two UAVs within [t0, t1].
double min_separation(const Scenario& sc, const Plan& plan, double t0, double t1) {
  double best = World::kInf;
  for (std::size_t i = 0; i < plan.uavs.size(); ++i)
    for (std::size_t j = i + 1; j < plan.uavs.size(); ++j) {
      const Trajectory a = slice(plan.uavs[i].trajectory, t0, t1), b = slice(plan.uavs[j].trajectory, t0, t1);
      if (a.empty() || b.empty()) continue;
      best = std::min(best, airfield_encounter(sc, sc.uavs[i], a, sc.uavs[j], b).airborne_min_m);
    }
  return best;
}

// The largest turn between the coarse route's segments (the formation's waypoints).
double largest_route_turn_deg(const std::vector<Vec3>& w) {
  double worst = 0.0;
  for (std::size_t k = 1; k + 1 < w.size(); ++k) {
    const Vec2 a = (w[k] - w[k - 1]).head<2>(), b = (w[k + 1] - w[k]).head<2>();
    if (a.norm() > 0.0 && b.norm() > 0.0)
      worst = std::max(worst, std::acos(std::clamp(a.dot(b) / (a.norm() * b.norm()), -1.0, 1.0)));
  }
  return rad_to_deg(worst);
}

std::string phase_table(const std::string& dir, bool& ok) {
  const Scenario sc = load_scenario(dir + "/p5_mission.yaml");
  std::vector<double> ms;
  Plan plan;
  for (int r = 0; r < 3; ++r) {
    const auto t0 = std::chrono::steady_clock::now();
    plan = plan_mission(sc, MissionOptions{});
    ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
  }
  std::sort(ms.begin(), ms.end());
  const auto violations = finalize_plan(sc, plan);
  std::string out =
      "P5 4.3: the whole flight of p5_mission.yaml (4 UAVs, 3 task points, 10 cylinders; P5's task points and "
      "cylinders are random and\n"
      "unpublished: compare durations, not exact times), ours | P5 Table 2\n"
      "phase      end_s   duration_s | paper end_s  duration_s   min separation in the air (m, safety 50)\n";
  const char* names[] = {"form_up", "mission", "return", "dismiss", "landing"};
  const double paper[] = {212, 6618, 8830, 8921, 9170};
  double prev = 0.0, paper_prev = 0.0;
  const bool have = plan.formation && plan.formation->phases.size() == 5;
  for (int k = 0; k < 5; ++k) {
    const double end = have ? plan.formation->phases[k].end_s : NAN;
    out += line("%-9s %7.0f   %10.0f | %11.0f  %10.0f   %10.1f\n", names[k], end, end - prev, paper[k],
                paper[k] - paper_prev, have ? min_separation(sc, plan, prev, end) : NAN);
    prev = end, paper_prev = paper[k];
  }
  // The UAVs' waypoints: the parking place, the formation's route, the landing stop.
  const std::vector<Vec3> route =
      plan.uavs.empty() || plan.uavs[0].waypoints.size() < 3
          ? std::vector<Vec3>{}
          : std::vector<Vec3>(plan.uavs[0].waypoints.begin() + 1, plan.uavs[0].waypoints.end() - 1);
  const double turn = largest_route_turn_deg(route);
  out += line(
      "status %s, verified %s (%zu violations), route %.0f km, largest turn between route segments %.1f deg (limit "
      "30),\n"
      "whole mission planned and simulated in %.0f ms (median of 3; target < 1000 ms)\n\n",
      to_string(plan.status).data(), violations.empty() ? "yes" : "no", violations.size(),
      Route{route}.length_m() / 1000.0, turn, ms[1]);
  ok = ok && plan.status == Status::solved && violations.empty() && turn <= 30.0 + 1e-6 && ms[1] < 1000.0;
  return out;
}

// P5 4.2(b): a diamond of 60 m at 150 m/s, a 45 deg leg of 40 km, then 15 deg.
std::string turn_table(bool& ok) {
  AutopilotLimits lim;
  lim.speed = {70.0, 150.0, 200.0};
  lim.max_turn_rate_rad_s = deg_to_rad(2.2);
  lim.max_climb_rate_mps = 20.0;
  const std::vector<Vec3> diamond{{0, 0, 0}, {-60, 60, 0}, {-60, -60, 0}, {-120, 0, 0}};
  FormationGroup g(std::vector<AutopilotModel>(4, AutopilotModel(AutopilotParams{}, lim)), diamond,
                   complete_topology(4), {}, 0.0);
  const auto dir = [](double deg) { return Vec3(std::cos(deg_to_rad(deg)), std::sin(deg_to_rad(deg)), 0.0); };
  const Vec3 a(0, 0, 5000), b = a + 40000.0 * dir(45.0), c = b + 40000.0 * dir(15.0);
  FormationOrder o{150.0, deg_to_rad(45.0), 1.0, std::vector<double>(4, 5000.0)};
  const std::vector<Vec2> off = g.offsets_m(o);
  for (std::size_t i = 0; i < 4; ++i) {
    AutopilotState s;
    s.position = Vec3(off[i].x() + 60.0 * dir(45.0).x(), off[i].y() + 60.0 * dir(45.0).y(), 5000.0);
    s.speed_mps = 150.0;
    s.heading_rad = deg_to_rad(45.0);
    g.launch(i, s, FormationGroup::Launch::in_formation);
  }
  RouteSteering steer({a, b, c}, {}, 150.0 / deg_to_rad(2.2), 300.0);
  const auto nearest = [&] {
    double best = World::kInf;
    for (std::size_t i = 0; i < 4; ++i)
      for (std::size_t j = i + 1; j < 4; ++j) best = std::min(best, (g.state(i).position - g.state(j).position).norm());
    return best;
  };
  double lowest = World::kInf, miss = World::kInf;
  const double steady_before = nearest();
  while (steer.update(g.centroid()) && g.time_s() < 2000.0) {
    o.heading_rad = steer.heading_rad(g.centroid());
    g.step(o, {});
    lowest = std::min(lowest, nearest());
    miss = std::min(miss, (g.centroid() - b).head<2>().norm());
  }
  ok = ok && lowest > 50.0;
  return "P5 4.2(b): the 45 -> 15 deg turn (diamond of 60 m, 150 m/s, 2.2 deg/s), ours | paper\n"
         "steady nearest spacing m   min nearest spacing m   safety m   centroid's closest pass to the corner m\n" +
         line(
             "%10.2f | ~85            %8.2f | 70.5            50       %8.0f (turning on the arc R tan 15 deg = %.0f m "
             "short)\n",
             steady_before, lowest, miss, 150.0 / deg_to_rad(2.2) * std::tan(deg_to_rad(15.0))) +
         "(P5's 70.5 m depends on its unpublished gains; ours are papers.md P5's defaults, consensus.h)\n";
}

// Missions nobody tuned for (random_formation_mission): how many are solved, and whether every
// `solved` plan passes the verifier.
std::string random_table(int missions, bool& ok) {
  int solved = 0, bad = 0;
  double ms_sum = 0.0, ms_worst = 0.0;
  std::string failures;
  for (int s = 1; s <= missions; ++s) {
    const Scenario sc = random_formation_mission(static_cast<std::uint64_t>(s));
    const auto t0 = std::chrono::steady_clock::now();
    Plan plan = plan_mission(sc, MissionOptions{});
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    ms_sum += ms, ms_worst = std::max(ms_worst, ms);
    const bool claimed = plan.status == Status::solved;
    const bool holds = finalize_plan(sc, plan).empty();
    solved += claimed && holds;
    bad += claimed && !holds;
    if (!claimed) {
      std::string why;
      for (const UavPlan& u : plan.uavs)
        if (!u.message.empty()) {
          why = u.id + ": " + u.message;
          break;
        }
      failures += line("  seed %d (%zu UAVs, %zu task points): %s\n", s, sc.uavs.size(),
                       phased_section(sc).task_points.size(), why.c_str());
    }
  }
  ok = ok && bad == 0;
  return line(
             "\nRandom formation missions (300-1000 km, 3-6 UAVs in 4 shapes, 2-5 task points, 5-15 cylinders, any "
             "airfield and runway\n"
             "heading; every solved plan checked by the verifier; target >= 90%% solved, 0 bad claims)\n"
             "missions  solved  solved_%%  bad_claims  ms_per_mission(mean, worst)\n"
             "%8d  %6d  %8.1f  %10d  %10.0f %6.0f\n",
             missions, solved, 100.0 * solved / std::max(missions, 1), bad, ms_sum / std::max(missions, 1), ms_worst) +
         failures;
}

}  // namespace

std::string run_p5(const std::string& dir, bool* all_ok) {
  bool ok = true;
  std::string out = phase_table(dir, ok) + turn_table(ok) + random_table(30, ok);
  if (all_ok) *all_ok = ok;
  return out;
}

}  // namespace uavplan::bench
