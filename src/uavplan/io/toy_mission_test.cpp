// A mission type added in one place: this file. `ferry` registers itself (no other file names
// it), declares its keys, reads its own section struct, plans, adds a rule to the verifier and
// is listed by `info --missions`; the scenario reader, the planner and the verifier find it
// through the registry alone.
#include <gtest/gtest.h>

#include <algorithm>
#include <memory>

#include "uavplan/coordination/mission.h"
#include "uavplan/coordination/mission_planner.h"
#include "uavplan/coordination/timing.h"
#include "uavplan/evaluation/verifier.h"
#include "uavplan/io/input_error.h"
#include "uavplan/io/scenario_io.h"
#include "uavplan/simulation/trajectory.h"

namespace uavplan {
namespace {

// Its own section: the height every UAV ferries at.
struct FerrySection : MissionSection {
  double height_m = 0.0;
};

// Each UAV climbs straight up to the ferry height, flies level to above its goal, and descends.
class FerryMission final : public Mission {
 public:
  const MissionDeclaration& declaration() const override {
    static const MissionDeclaration d = [] {
      MissionDeclaration m;
      m.name = "ferry";
      m.summary = "Each UAV climbs to the ferry height, flies level above its goal and descends.";
      m.keys = {{"ferry_height", "number", "", "m", "the height every UAV flies level at"}};
      m.algorithms = {"astar"};  // it plans alone; named so that no other planner is offered
      return m;
    }();
    return d;
  }
  void read_section(const Section& m, const Section& /*uavs*/, Scenario& sc) const override {
    auto section = std::make_shared<FerrySection>();
    section->height_m = m.req("ferry_height")->positive();
    if (section->height_m >= sc.world.bounds().max.z()) m.at("ferry_height")->fail("is above the world");
    sc.mission.section = std::move(section);
  }
  std::string describe(const Scenario& sc) const override {
    return ", at " + std::to_string(static_cast<int>(sc.mission.section_as<FerrySection>()->height_m)) + " m";
  }
  void plan(const Scenario& sc, const MissionContext& ctx, Plan& plan) const override {
    const double h = sc.mission.section_as<FerrySection>()->height_m;
    for (const UavSpec& u : sc.uavs) {
      const std::vector<Vec3> route = {u.start, {u.start.x(), u.start.y(), h}, {u.goal->x(), u.goal->y(), h}, *u.goal};
      plan.uavs.push_back(
          flown_plan(u.id, true, "", route, time_route(route, u.speed.cruise_mps, 0.0, ctx.options.max_sample_dt_s)));
    }
  }
  // Its rule: level flight at the ferry height between the climb and the descent.
  void check_uav(const Scenario& sc, const UavSpec& u, const Trajectory& tr, Violations& out) const override {
    const double h = sc.mission.section_as<FerrySection>()->height_m;
    const double top =
        std::max_element(tr.begin(), tr.end(), [](const auto& a, const auto& b) { return a.p.z() < b.p.z(); })->p.z();
    if (top < h - kDistanceTolerance_m)
      add_violation(out, ViolationKind::goal, u.id, std::nullopt, std::nullopt, "never reaches the ferry height");
  }
};

const MissionRegistration kFerry{std::make_unique<FerryMission>()};

const char* kScenario = R"(version: 1
name: ferry
world:
  bounds: {min: [0, 0, 0], max: [200, 200, 60]}
  obstacles:
    - {type: box, min: [90, 0, 0], max: [110, 200, 30]}
uavs:
  - {id: a, start: [10, 20, 5], goal: [190, 20, 5], speed: 5}
  - {id: b, start: [10, 120, 5], goal: [190, 120, 5], speed: 5}
mission: {type: ferry, separation: 5, ferry_height: 40}
)";

TEST(ToyMission, ReadPlannedVerifiedAndListedThroughTheRegistryAlone) {
  const Scenario sc = parse_scenario(kScenario, "ferry.yaml");
  ASSERT_EQ(sc.mission.type, "ferry");
  ASSERT_NE(sc.mission.section_as<FerrySection>(), nullptr);
  EXPECT_EQ(sc.mission.section_as<FerrySection>()->height_m, 40.0);
  EXPECT_EQ(find_mission("ferry")->describe(sc), ", at 40 m");

  MissionOptions o;
  Plan plan = plan_mission(sc, o);
  EXPECT_TRUE(finalize_plan(sc, plan).empty());
  EXPECT_EQ(plan.status, Status::solved) << plan.message;
  ASSERT_EQ(plan.uavs.size(), 2u);
  EXPECT_NEAR(plan.uavs[0].length_m, 35.0 + 180.0 + 35.0, 1e-6);

  // The verifier applies its rule: a plan flown under the ferry height is refused.
  Plan low = plan;
  for (UavPlan& u : low.uavs)
    for (auto& s : u.trajectory) s.p.z() = std::min(s.p.z(), 35.0);
  const auto violations = verify_plan(sc, low);
  EXPECT_TRUE(std::any_of(violations.begin(), violations.end(),
                          [](const Violation& v) { return v.message.find("ferry height") != std::string::npos; }));

  // Listed with its keys, in both of info's forms; its name is among the types a typo is told.
  EXPECT_NE(mission_catalog_text(false).find("ferry: Each UAV climbs"), std::string::npos);
  EXPECT_NE(mission_catalog_text(true).find("| `ferry_height` | number | required | m |"), std::string::npos);
  EXPECT_NE(mission_type_list().find("ferry"), std::string::npos);
}

TEST(ToyMission, ItsKeysAreCheckedAndItsPlannersDeclared) {
  std::string missing = kScenario;
  missing.replace(missing.find(", ferry_height: 40"), 18, "");
  EXPECT_THROW(parse_scenario(missing, "ferry.yaml"), InputError);
  std::string typo = kScenario;
  typo.replace(typo.find("ferry_height"), 12, "ferry_heigth");
  try {
    parse_scenario(typo, "ferry.yaml");
    FAIL() << "a typo in its key was read";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("ferry_height"), std::string::npos) << e.what();
  }
  const Scenario sc = parse_scenario(kScenario, "ferry.yaml");
  EXPECT_EQ(mission_algorithm(sc, std::nullopt), "astar");
  EXPECT_THROW(mission_algorithm(sc, std::string("rrt")), std::invalid_argument);
  // A second registration of the name, or a key of the common ones, is refused.
  EXPECT_THROW(register_mission(std::make_unique<FerryMission>()), std::invalid_argument);
}

}  // namespace
}  // namespace uavplan
