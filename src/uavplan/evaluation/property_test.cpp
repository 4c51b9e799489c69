// Properties every registered planner and mission type keeps on random worlds: what a planner
// calls solved holds under the verifier (before the verifier gets to fail it), what it does not
// solve says why, an enclosed goal fails within the stop condition, start = goal is handled, and
// the same seed gives the same plan. (bench/soak runs thousands of these.) Under a sanitizer the
// sweeps run a sample and check the claims only; the rates are checked on the whole sweep in
// release (core/build_info.h).
#include <gtest/gtest.h>

#include <chrono>

#include "uavplan/coordination/mission_planner.h"
#include "uavplan/core/build_info.h"
#include "uavplan/evaluation/random_worlds.h"
#include "uavplan/evaluation/verifier.h"
#include "uavplan/planning/registry.h"

namespace uavplan {
namespace {

constexpr double kLimit_s = 2.0;
// The random-world properties must not depend on the machine's speed: their stop is only a net
// (every planner ends on its own iteration or expansion budget well before it). Under a sanitizer
// code runs up to 40x slower: the single-step swarm's full budget on one world took more than 30 s
// there, hit the net at a point that varies from run to run, and failed the repeat check.
constexpr double kSafetyNet_s = kSanitizedBuild ? 900.0 : 30.0;

MissionOptions options(const std::string& algorithm, std::uint64_t seed, double limit_s = kLimit_s) {
  MissionOptions o;
  o.algorithm = algorithm;
  o.seed = seed;
  o.stop = StopCondition::time_limit(limit_s);
  return o;
}

// The planner's own claims, checked: a UAV it calls solved has no violation.
void expect_claims_hold(const Scenario& sc, const Plan& plan, const std::string& what) {
  const auto violations = verify_plan(sc, plan);
  for (const UavPlan& u : plan.uavs) {
    if (u.status != Status::solved) {
      EXPECT_FALSE(u.message.empty()) << what << " " << u.id << ": failed without a reason";
      continue;
    }
    for (const Violation& v : violations) EXPECT_TRUE(v.uav != u.id) << what << ": solved but " << describe(v);
  }
}

bool same_trajectories(const Plan& a, const Plan& b) {
  if (a.uavs.size() != b.uavs.size()) return false;
  for (std::size_t i = 0; i < a.uavs.size(); ++i) {
    const Trajectory &x = a.uavs[i].trajectory, &y = b.uavs[i].trajectory;
    if (x.size() != y.size() || a.uavs[i].status != b.uavs[i].status) return false;
    for (std::size_t k = 0; k < x.size(); ++k)
      if (x[k].t_s != y[k].t_s || x[k].p != y[k].p) return false;
  }
  return true;
}

class PlannerProperties : public ::testing::TestWithParam<std::string> {};

TEST_P(PlannerProperties, RandomWorldsClaimsHoldAndRepeat) {
  const std::string name = GetParam();
  // 200 worlds a planner; the ant colony (100 ants by default) takes 80 to stay within a minute,
  // the single-step swarm (100 particles x 500 iterations over every waypoint) 20, the multi-step
  // one 100 (a route that fails or comes out long is planned twice).
  const std::uint64_t worlds = sweep_cases(name == "cellular_aco" ? 80
                                           : name == "pso_single" ? 20
                                           : name == "pso_mpc"    ? 100
                                                                  : 200);
  int solved = 0, uavs = 0;
  for (std::uint64_t seed = 1; seed <= worlds; ++seed) {
    const Scenario sc = random_world(seed * 7919 + name.size());
    const Plan plan = plan_mission(sc, options(name, seed, kSafetyNet_s));
    expect_claims_hold(sc, plan, name + " seed " + std::to_string(seed));
    for (const UavPlan& u : plan.uavs) solved += u.status == Status::solved, ++uavs;
    if (seed % 10 == 0 || (kSanitizedBuild && seed == 1)) {  // determinism, on a sample
      const Plan again = plan_mission(sc, options(name, seed, kSafetyNet_s));
      EXPECT_TRUE(same_trajectories(plan, again)) << name << " seed " << seed << ": not repeatable";
    }
  }
  RecordProperty("solved", solved);
  if (!kSanitizedBuild) {
    EXPECT_GT(solved, uavs / 3) << name << ": " << solved << " of " << uavs;
  }
}

// Starts and goals on the ground (take-off and landing legs), clearance and min_agl: every
// planner honours them through the mission layer, and the verifier checks them.
TEST_P(PlannerProperties, GroundStartsClearanceAndMinAglHold) {
  const std::string name = GetParam();
  const std::uint64_t worlds = sweep_cases(name == "cellular_aco" ? 25 : name == "pso_single" ? 16 : 60);
  RandomWorldOptions o;
  o.ground_and_margins = true;
  int solved = 0, uavs = 0, grounded = 0;
  for (std::uint64_t seed = 1; seed <= worlds; ++seed) {
    const Scenario sc = random_world(seed * 104729 + name.size(), o);
    for (const UavSpec& u : sc.uavs) grounded += sc.world.on_ground(u.start) + (u.goal && sc.world.on_ground(*u.goal));
    const Plan plan = plan_mission(sc, options(name, seed, kSafetyNet_s));
    expect_claims_hold(sc, plan, name + " margins seed " + std::to_string(seed));
    for (const UavPlan& u : plan.uavs) solved += u.status == Status::solved, ++uavs;
  }
  if (kSanitizedBuild) return;  // the rates on the whole sweep, in release
  EXPECT_GT(grounded, 10);
  EXPECT_GT(solved, uavs / 3) << name << ": " << solved << " of " << uavs;
}

TEST_P(PlannerProperties, EnclosedGoalFailsWithinTheStop) {
  const std::string name = GetParam();
  for (std::uint64_t seed = 1; seed <= 3; ++seed) {
    const Scenario sc = enclosed_goal_world(seed);
    const auto t0 = std::chrono::steady_clock::now();
    const Plan plan = plan_mission(sc, options(name, seed));
    const double took = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    EXPECT_EQ(plan.uavs[0].status, Status::failed) << name;
    EXPECT_FALSE(plan.uavs[0].message.empty()) << name;
    // A sanitizer's run is several times slower between two stop checks: a wider margin there.
    EXPECT_LT(took, kLimit_s * 1.25 + (kSanitizedBuild ? 1.0 : 0.2)) << name;
  }
}

TEST_P(PlannerProperties, StartEqualsGoalIsHandled) {
  const std::string name = GetParam();
  Scenario sc = random_world(42);
  sc.uavs.resize(1);
  sc.uavs[0].goal = sc.uavs[0].start;
  const Plan plan = plan_mission(sc, options(name, 1));
  expect_claims_hold(sc, plan, name + " start = goal");
}

std::vector<std::string> planners() {
  std::vector<std::string> n;
  for (const auto& p : planner_catalog()) n.push_back(p.name);
  return n;
}

INSTANTIATE_TEST_SUITE_P(Registered, PlannerProperties, ::testing::ValuesIn(planners()),
                         [](const auto& param_info) { return param_info.param; });

// Mission types that plan with their own method: group (P3), rendezvous (P4), and independent
// UAVs with sensors flown in the loop (P1's local layer).
TEST(MissionProperties, GroupRendezvousAndSensingClaimsHold) {
  for (std::uint64_t seed = 1; seed <= sweep_cases(25); ++seed) {
    for (const std::string& type : {std::string("group"), std::string("rendezvous")}) {
      RandomWorldOptions o;
      o.mission = type;
      o.limits = type == "rendezvous";
      const Scenario sc = random_world(seed * 31 + (type == "group" ? 2 : 3), o);
      const Plan plan = plan_mission(sc, options(type == "group" ? "apf" : "directional_astar", seed));
      expect_claims_hold(sc, plan, type + " seed " + std::to_string(seed));
    }
    Scenario sensing = random_world(seed * 17);
    WorldSpec ws = sensing.world.spec();
    ws.moving.push_back({"m", 2.0, sensing.world.bounds().center(), Vec3(1.5, -1.0, 0.0)});
    sensing.world = World(std::move(ws));
    for (UavSpec& u : sensing.uavs) u.sensor_range_m = 30.0;
    const Plan plan = plan_mission(sensing, options("improved_rrt", seed));
    expect_claims_hold(sensing, plan, "sensing seed " + std::to_string(seed));
  }
}

// P1's local layer on routes with via points and movers just short of them: a detour rejoins
// the route before the next via point or at it (never past it), so what is called solved holds,
// and nearly every UAV is solved (40 worlds here; bench p1 runs 200 against the 95 % target).
TEST(MissionProperties, DetoursKeepTheirViaPointsOnRandomRoutes) {
  int uavs = 0, solved = 0;
  for (std::uint64_t seed = 1; seed <= sweep_cases(40); ++seed) {
    const Scenario sc = random_via_world(seed);
    const Plan plan = plan_mission(sc, options("improved_rrt", seed));
    expect_claims_hold(sc, plan, "via seed " + std::to_string(seed));
    for (const UavPlan& u : plan.uavs) uavs += 1, solved += u.status == Status::solved;
  }
  if (!kSanitizedBuild) {  // (bench p1 holds the 95 % target over 200 worlds; UAVs that share via points may meet)
    EXPECT_GE(solved, 0.9 * uavs) << solved << " of " << uavs << " UAVs solved";
  }
}

// P1's formation on random fields (3-7 UAVs, radars, cylinders, crossing, head-on and turning
// movers, 20-100 m sensors): what is called solved holds, and nearly every UAV is solved (a UAV
// out of its slot at goals that are the slots waits there for the others; a re-forming that
// would run a catching-up UAV over a mate is put off; mates hear each other's plans; bench p1
// has the table).
TEST(MissionProperties, FormationClaimsHoldOnRandomFields) {
  int uavs = 0, solved = 0;
  const std::uint64_t fields = sweep_cases(30);
  for (std::uint64_t seed = 1; seed <= fields; ++seed) {
    const Scenario sc = random_formation_world(seed);
    const Plan plan = plan_mission(sc, options("aco_voronoi", seed));
    expect_claims_hold(sc, plan, "formation seed " + std::to_string(seed));
    for (const UavPlan& u : plan.uavs) uavs += 1, solved += u.status == Status::solved;
  }
  if (!kSanitizedBuild) {
    EXPECT_GE(solved, 0.95 * uavs) << solved << " of " << uavs << " UAVs solved";
  }
}

// pso_mpc through P5's model on large random worlds: a flown route it calls solved holds (its
// turns' overshoot kept off the cylinders and inside the bounds).
TEST(MissionProperties, PsoMpcFlownRoutesHoldOnLargeRandomWorlds) {
  for (std::uint64_t seed = 80; seed < 80 + sweep_cases(16); ++seed) {
    const Scenario sc = random_p5_world(seed);
    const Plan plan = plan_mission(sc, options("pso_mpc", seed, kSafetyNet_s));
    expect_claims_hold(sc, plan, "p5 world seed " + std::to_string(seed));
  }
}

// P5's whole mission on airfields, task points and shapes nobody tuned for: every `solved` plan
// passes the verifier (separation in the air, task points with their headings, every UAV on the
// runway), and most are solved (the benchmark `uavplan bench p5` runs more).
TEST(MissionProperties, FormationMissionClaimsHoldOnRandomMissions) {
  int solved = 0;
  const std::uint64_t missions = sweep_cases(12);
  for (std::uint64_t seed = 1; seed <= missions; ++seed) {
    const Scenario sc = random_formation_mission(seed);
    const Plan plan = plan_mission(sc, options("pso_mpc", seed, kSafetyNet_s));
    expect_claims_hold(sc, plan, "formation_mission seed " + std::to_string(seed));
    if (plan.status != Status::solved) continue;
    ++solved;
    for (const Violation& v : verify_plan(sc, plan))
      ADD_FAILURE() << "formation_mission seed " << seed << ": solved but " << describe(v);
  }
  if (!kSanitizedBuild) {
    EXPECT_GE(solved, 0.8 * static_cast<double>(missions)) << solved << " of " << missions << " missions solved";
  }
}

}  // namespace
}  // namespace uavplan
