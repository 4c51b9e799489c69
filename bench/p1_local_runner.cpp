#include "p1_local_runner.h"

#include <ompl/base/MotionValidator.h>
#include <ompl/base/SpaceInformation.h>
#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/geometric/PathGeometric.h>
#include <ompl/geometric/planners/rrt/RRT.h>
#include <ompl/geometric/planners/rrt/RRTConnect.h>
#include <ompl/geometric/planners/rrt/RRTstar.h>
#include <ompl/util/Console.h>
#include <ompl/util/RandomNumbers.h>

#include <algorithm>
#include <cstdio>
#include <functional>
#include <mutex>
#include <nlohmann/json.hpp>

#include "stats.h"
#include "uavplan/core/rng.h"
#include "uavplan/planning/sampling/rrt.h"
#include "uavplan/planning/smoothing/waypoint_pruning.h"

namespace uavplan::bench {
namespace {

namespace ob = ompl::base;
namespace og = ompl::geometric;

// papers.md P1: the UAV at 5 m/s with T = 1 s (a 5 m step), RRT step 2 m; obstacles of
// radius 2 m at 1-3 m/s crossing the straight line from the window's bottom to its top,
// inflated to discs of radius T |V_b| + their radius + the UAV's, at their current positions.
constexpr double kWidth_m = 40, kLength_m = 45, kSpeed_mps = 5, kPeriod_s = 1, kUavRadius_m = 0.5;

struct Problem1 {
  std::vector<MovingKeepOut> discs;
  Vec3 bias = Vec3::Zero();  // V_b of the obstacle nearest the start
};

Problem1 make_problem(Rng& r, const Vec3& start, const Vec3& goal) {
  Problem1 p;
  const int n = static_cast<int>(r.uniform_int(1, 3));
  double nearest = World::kInf;
  while (static_cast<int>(p.discs.size()) < n) {
    const double speed = r.uniform(1, 3), heading = r.uniform(-kPi / 6, kPi / 6) + (r.uniform01() < 0.5 ? 0 : kPi);
    const Vec3 v(speed * std::cos(heading), speed * std::sin(heading), 0);
    const Vec3 c(kWidth_m / 2 + r.uniform(-6, 6), r.uniform(8, kLength_m - 8), 0);
    const double radius = kPeriod_s * speed + 2.0 + kUavRadius_m;
    if ((c - start).norm() < radius + 1 || (c - goal).norm() < radius + 1) continue;
    p.discs.push_back({c, Vec3::Zero(), radius, 0.0});
    if ((c - start).norm() < nearest) {
      nearest = (c - start).norm();
      p.bias = v;
    }
  }
  return p;
}

struct Outcome {
  bool ok = false;
  double ms = 0.0, cost = 0.0;
  double nodes = 0.0;
};

// The same segment check for every planner: the world's rule and the discs, exactly.
struct Check {
  const SegmentRule* rule;
  const std::vector<MovingKeepOut>* discs;
  bool point(const Vec3& p) const {
    if (!rule->point_ok(p)) return false;
    for (const MovingKeepOut& d : *discs)
      if ((p - d.center).norm() < d.radius_m) return false;
    return true;
  }
  bool segment(const Vec3& a, const Vec3& b) const {
    if (!(*rule)(a, b)) return false;
    for (const MovingKeepOut& d : *discs)
      if (keep_out_distance(d, a, 0, b, 0) < d.radius_m) return false;
    return true;
  }
};

Vec3 to_vec(const ob::State* s) {
  const auto* v = s->as<ob::RealVectorStateSpace::StateType>();
  return {v->values[0], v->values[1], 0.0};
}

class ExactMotion final : public ob::MotionValidator {
 public:
  ExactMotion(const ob::SpaceInformationPtr& si, Check check) : ob::MotionValidator(si), check_(check) {}
  bool checkMotion(const ob::State* a, const ob::State* b) const override {
    const bool ok = check_.segment(to_vec(a), to_vec(b));
    if (ok)
      ++valid_;
    else
      ++invalid_;
    return ok;
  }
  bool checkMotion(const ob::State* a, const ob::State* b, std::pair<ob::State*, double>& last) const override {
    if (checkMotion(a, b)) return true;
    // The last valid fraction, by bisection (only the connect steps of some planners ask).
    double lo = 0.0, hi = 1.0;
    const Vec3 pa = to_vec(a), pb = to_vec(b);
    for (int i = 0; i < 30; ++i) {
      const double mid = 0.5 * (lo + hi);
      (check_.segment(pa, pa + mid * (pb - pa)) ? lo : hi) = mid;
    }
    if (last.first) si_->getStateSpace()->interpolate(a, b, lo, last.first);
    last.second = lo;
    return false;
  }

 private:
  Check check_;
};

Outcome run_ompl(const std::string& name, const Check& check, const Vec3& start, const Vec3& goal, double budget_ms) {
  Outcome o;
  const Clock::time_point t0 = Clock::now();
  auto space = std::make_shared<ob::RealVectorStateSpace>(2);
  ob::RealVectorBounds b(2);
  b.setLow(0, 0);
  b.setHigh(0, kWidth_m);
  b.setLow(1, 0);
  b.setHigh(1, kLength_m);
  space->setBounds(b);
  auto si = std::make_shared<ob::SpaceInformation>(space);
  si->setStateValidityChecker([check](const ob::State* s) { return check.point(to_vec(s)); });
  si->setMotionValidator(std::make_shared<ExactMotion>(si, check));
  si->setup();
  auto pdef = std::make_shared<ob::ProblemDefinition>(si);
  ob::ScopedState<> s(space), g(space);
  s[0] = start.x();
  s[1] = start.y();
  g[0] = goal.x();
  g[1] = goal.y();
  pdef->setStartAndGoalStates(s, g, 1e-9);
  ob::PlannerPtr planner;
  double seconds = 1.0;
  if (name == "ompl_rrt") {
    auto p = std::make_shared<og::RRT>(si);
    p->setRange(2.0);
    planner = p;
  } else if (name == "ompl_rrtconnect") {
    auto p = std::make_shared<og::RRTConnect>(si);
    p->setRange(2.0);
    planner = p;
  } else {
    auto p = std::make_shared<og::RRTstar>(si);
    p->setRange(2.0);
    planner = p;
    seconds = budget_ms / 1000.0;
  }
  planner->setProblemDefinition(pdef);
  planner->setup();
  const ob::PlannerStatus st = planner->solve(ob::timedPlannerTerminationCondition(seconds));
  if (st != ob::PlannerStatus::EXACT_SOLUTION) {
    o.ms = ms_since(t0);
    return o;
  }
  std::vector<Vec3> path;
  for (const ob::State* st_ : pdef->getSolutionPath()->as<og::PathGeometric>()->getStates())
    path.push_back(to_vec(st_));
  if (path.back() != goal) path.push_back(goal);
  // The improved RRT's simplification: P1's pruning within one UAV step, then the shortcut.
  const TimedSegmentCheck ok = [&](const Vec3& a, double, const Vec3& c) { return check.segment(a, c); };
  path = shortcut_within_limits(prune_within_step(path, kSpeed_mps * kPeriod_s, 5, {}, ok), {}, ok);
  o.ms = ms_since(t0);
  o.ok = true;
  o.cost = Route{path}.length_m();
  ob::PlannerData data(si);  // (not timed)
  planner->getPlannerData(data);
  o.nodes = data.numVertices();
  return o;
}

Outcome run_ours(const RrtOptions& options, const SegmentRule& rule, const Problem1& p, const Vec3& start,
                 const Vec3& goal, const World& world, std::uint64_t seed) {
  Outcome o;
  const Clock::time_point t0 = Clock::now();
  RrtQuery q;
  q.start = start;
  q.goal = goal;
  q.sample_box = world.bounds();
  q.planar = true;
  q.speed_mps = kSpeed_mps;
  q.keep_outs = p.discs;
  q.bias_velocity_mps = p.bias;
  q.uav_step_m = kSpeed_mps * kPeriod_s;
  q.seed = seed;
  const RrtResult r = rrt_search(rule, kPi, q, options, {});
  o.ms = ms_since(t0);
  o.ok = r.solved();
  o.nodes = r.nodes;
  if (r.solved()) o.cost = Route{r.path}.length_m();
  return o;
}

P1LocalRow summarise(const std::string& name, const std::vector<Outcome>& out) {
  P1LocalRow row;
  row.planner = name;
  row.problems = static_cast<int>(out.size());
  std::vector<double> ms;
  for (const Outcome& o : out) {
    ms.push_back(o.ms);
    row.mean_ms += o.ms / static_cast<double>(out.size());
    if (!o.ok) continue;
    ++row.solved;
    row.mean_cost += o.cost;
    row.mean_nodes += o.nodes;
  }
  if (row.solved) {
    row.mean_cost /= row.solved;
    row.mean_nodes /= row.solved;
  }
  std::sort(ms.begin(), ms.end());
  if (!ms.empty()) {
    row.median_ms = ms[ms.size() / 2];
    row.p95_ms = ms[std::min(ms.size() - 1, ms.size() * 95 / 100)];
  }
  return row;
}

}  // namespace

std::vector<P1LocalRow> run_p1_local(const P1LocalOptions& opt) {
  static std::once_flag seeded;
  std::call_once(seeded, [&] {
    ompl::msg::setLogLevel(ompl::msg::LOG_NONE);
    ompl::RNG::setSeed(static_cast<std::uint_fast32_t>(opt.seed));  // OMPL takes one seed per process
  });
  WorldSpec ws;
  ws.bounds = Aabb{Vec3::Zero(), Vec3(kWidth_m, kLength_m, 0)};
  const World world(std::move(ws));
  UavSpec uav;
  uav.radius_m = kUavRadius_m;
  uav.speed = {0, kSpeed_mps, kSpeed_mps};
  const SegmentRule rule(world, uav);
  const Vec3 start(kWidth_m / 2, 1, 0), goal(kWidth_m / 2, kLength_m - 1, 0);
  const std::vector<std::string> names{"improved_rrt", "rrt", "ompl_rrt", "ompl_rrtconnect", "ompl_rrtstar"};
  std::vector<Problem1> problems;
  std::vector<std::uint64_t> seeds;
  Rng rng(opt.seed);
  for (int k = 0; k < opt.problems; ++k) {
    problems.push_back(make_problem(rng, start, goal));
    seeds.push_back(rng.next_u64());
  }
  // Planner by planner over all problems, each after an untimed pass of every fast planner over
  // the problems (the first milliseconds of a process run slower: caches, clock ramp-up).
  std::vector<std::vector<Outcome>> out(names.size());
  for (int pass = 0; pass < 2; ++pass)
    for (std::size_t k = 0; k < problems.size(); ++k) {
      run_ours(RrtOptions::improved(), rule, problems[k], start, goal, world, seeds[k]);
      run_ompl("ompl_rrtconnect", Check{&rule, &problems[k].discs}, start, goal, opt.rrtstar_budget_ms);
    }
  for (std::size_t n = 0; n < names.size(); ++n) {
    const auto run = [&](std::size_t k) {
      const Check check{&rule, &problems[k].discs};
      if (n == 0) return run_ours(RrtOptions::improved(), rule, problems[k], start, goal, world, seeds[k]);
      if (n == 1) return run_ours(RrtOptions::common(), rule, problems[k], start, goal, world, seeds[k]);
      return run_ompl(names[n], check, start, goal, opt.rrtstar_budget_ms);
    };
    if (!problems.empty()) run(0);
    for (std::size_t k = 0; k < problems.size(); ++k) out[n].push_back(run(k));
  }
  std::vector<P1LocalRow> rows;
  for (std::size_t n = 0; n < names.size(); ++n) rows.push_back(summarise(names[n], out[n]));
  return rows;
}

std::string format_p1_local(const std::vector<P1LocalRow>& rows, const P1LocalOptions& opt) {
  std::string s;
  char buf[256];
  std::snprintf(buf, sizeof buf,
                "P1 Table 1: local replanning in the 40 m x 45 m window, %d problems (1-3 obstacles of 2 m at 1-3 m/s\n"
                "across the route, discs T |V_b| + radii, T = 1 s), seed %llu; cost = local route length (m)\n",
                opt.problems, static_cast<unsigned long long>(opt.seed));
  s += buf;
  std::snprintf(buf, sizeof buf, "%-22s %9s %9s %9s %9s %10s %8s %8s %9s %10s\n", "planner", "solved", "mean_ms",
                "median_ms", "p95_ms", "cost_m", "vs_rrt", "nodes", "paper_ms", "paper_cost");
  s += buf;
  double common = 0.0;
  for (const auto& r : rows)
    if (r.planner == "rrt") common = r.mean_cost;
  for (const auto& r : rows) {
    const std::string name = r.planner == "ompl_rrtstar"
                                 ? "ompl_rrtstar (" + std::to_string(static_cast<int>(opt.rrtstar_budget_ms)) + " ms)"
                                 : r.planner;
    const char* paper_ms = r.planner == "improved_rrt" ? "15.60" : r.planner == "rrt" ? "28.60" : "-";
    const char* paper_cost = r.planner == "improved_rrt" ? "8.33" : r.planner == "rrt" ? "12.56" : "-";
    std::snprintf(buf, sizeof buf, "%-22s %4d/%-4d %9.3f %9.3f %9.3f %10.2f %8.3f %8.0f %9s %10s\n", name.c_str(),
                  r.solved, r.problems, r.mean_ms, r.median_ms, r.p95_ms, r.mean_cost,
                  common > 0 ? r.mean_cost / common : 0.0, r.mean_nodes, paper_ms, paper_cost);
    s += buf;
  }
  s += "(the paper: Matlab, 2.26 GHz; its cost units are not given, its improved/common cost ratio is 0.663)\n";
  return s;
}

std::string p1_local_json(const std::vector<P1LocalRow>& rows) {
  nlohmann::ordered_json j = nlohmann::ordered_json::array();
  for (const auto& r : rows)
    j.push_back({{"planner", r.planner},
                 {"problems", r.problems},
                 {"solved", r.solved},
                 {"median_ms", r.median_ms},
                 {"mean_ms", r.mean_ms},
                 {"mean_cost", r.mean_cost}});
  return j.dump(1) + "\n";
}

bool p1_local_targets_met(const std::vector<P1LocalRow>& rows) {
  const auto find = [&](const char* n) {
    for (const auto& r : rows)
      if (r.planner == n) return r;
    return P1LocalRow{};
  };
  const P1LocalRow imp = find("improved_rrt"), rrt = find("rrt"), ompl = find("ompl_rrt"),
                   conn = find("ompl_rrtconnect");
  return imp.solved == imp.problems && imp.median_ms <= conn.median_ms && imp.mean_cost < rrt.mean_cost &&
         imp.mean_cost < ompl.mean_cost;
}

}  // namespace uavplan::bench
