// Mission `formation` (P1): the UAVs fly as one shape from their starts to their goals.
// 1. The reference route: the chosen planner (P1's aco_voronoi by default, any registered one by
//    --algorithm) from the starts' centroid to the goals' centroid, for a body as wide as the
//    shape (so every slot's translate of it is clear), else, when that finds none, for one UAV.
// 2. The schedule (formation_schedule.h): form up, fly the route in shape, turn into the goals.
// 3. The flight in the closed loop (formation_flight.h): sensing, leaving a slot to avoid with the
//    local RRT (`local`: improved_rrt or rrt), re-forming by P1 eq. 8-9 after
//    `reform_after_steps` clear periods, one ETA.
// Every flown trajectory is then checked against the truth (moving obstacles, the other UAVs,
// the separation) and the arrival spread against `arrival_tolerance_s`.
#pragma once

#include "uavplan/coordination/mission.h"

namespace uavplan {

// A formation's shape (formation and formation_mission): a slot per UAV in scenario order,
// forward / left / up (m) from the reference point in a frame turning with its heading.
struct FormationShapeSection : MissionSection {
  std::vector<Vec3> shape;
};
// formation's section: the shape, the clear periods before re-forming, the largest spread of
// the arrival times.
struct FormationSection : FormationShapeSection {
  int reform_after_steps = 5;
  double arrival_tolerance_s = 2.0;
};
// The scenario's shape (empty where its mission has none), and formation's section (the
// defaults where it has none).
const std::vector<Vec3>& formation_shape(const Scenario& scenario);
const FormationSection& formation_section(const Scenario& scenario);

class FormationMission final : public Mission {
 public:
  const MissionDeclaration& declaration() const override;
  // `shape`, `reform_after_steps`, `arrival_tolerance_s` (formation_rules.cpp).
  void read_section(const Section& mission, const Section& uavs, Scenario& scenario) const override;
  std::string describe(const Scenario& scenario) const override;
  void plan(const Scenario& scenario, const MissionContext& context, Plan& plan) const override;
  void check_plan(const Scenario& scenario, const FlownUavs& flown, Violations& out) const override;
};

// A formation's `shape` (formation and formation_mission): one slot per UAV, every two slots at
// least the separation (and their bodies) apart.
std::vector<Vec3> read_formation_shape(const Section& list, const Scenario& scenario);
// The `shape` key's declaration (both types read it).
MissionKey formation_shape_key();

}  // namespace uavplan
