// The formation mission's part of the contract (P1): its shape, re-forming and arrival
// tolerance, as read and as verified.
#include <algorithm>
#include <cmath>
#include <string>

#include "uavplan/coordination/contract/arrival_points.h"
#include "uavplan/coordination/formation/formation_mission.h"
#include "uavplan/core/text.h"

namespace uavplan {

const std::vector<Vec3>& formation_shape(const Scenario& sc) {
  static const std::vector<Vec3> none;
  const FormationShapeSection* s = sc.mission.section_as<FormationShapeSection>();
  return s ? s->shape : none;
}

const FormationSection& formation_section(const Scenario& sc) {
  static const FormationSection defaults;
  const FormationSection* s = sc.mission.section_as<FormationSection>();
  return s ? *s : defaults;
}

std::vector<Vec3> read_formation_shape(const Section& list, const Scenario& sc) {
  list.expect_seq();
  if (list.size() != sc.uavs.size())
    list.fail("has " + std::to_string(list.size()) + " slots for " + std::to_string(sc.uavs.size()) +
              " UAVs (one slot per UAV, in scenario order)");
  std::vector<Vec3> shape;
  for (std::size_t i = 0; i < list.size(); ++i) shape.push_back(list.item(i)->vec3());
  for (std::size_t i = 0; i < shape.size(); ++i)
    for (std::size_t j = 0; j < i; ++j) {
      const double d = (shape[i] - shape[j]).norm();
      const double need = std::max(sc.mission.separation_m, sc.uavs[i].radius_m + sc.uavs[j].radius_m);
      if (d < need)
        list.item(i)->fail("is " + num_text(d) + " m from slot " + std::to_string(j) + " (" + sc.uavs[j].id +
                           "); slots must be at least " + num_text(need) +
                           " m apart (the separation, and the UAVs' bodies)");
    }
  return shape;
}

MissionKey formation_shape_key() {
  return {"shape", "list of [forward, left, up]", "", "m",
          "one slot per UAV in scenario order, from the reference point in a frame turning with its heading"};
}

const MissionDeclaration& FormationMission::declaration() const {
  static const MissionDeclaration d = [] {
    MissionDeclaration m;
    m.name = "formation";
    m.summary =
        "P1's formation: the UAVs fly one shape along a reference route, leave their slots to avoid what they "
        "sense (the local RRT) and re-form, and arrive at one time.";
    const FormationSection defaults;
    m.keys = {formation_shape_key(),
              {"reform_after_steps", "integer", std::to_string(defaults.reform_after_steps), "",
               "clear control periods before a UAV re-forms"},
              {"arrival_tolerance_s", "number", num_text(defaults.arrival_tolerance_s), "s",
               "the largest spread of the arrival times"}};
    m.default_algorithm = "aco_voronoi";
    m.parameters = {"local", "window_m"};
    return m;
  }();
  return d;
}

std::string FormationMission::describe(const Scenario& sc) const {
  return ", shape of " + std::to_string(formation_shape(sc).size()) + " slots, arrivals within " +
         num_text(formation_section(sc).arrival_tolerance_s) + " s";
}

void FormationMission::read_section(const Section& m, const Section& /*uavs*/, Scenario& sc) const {
  FormationSection& s = sc.mission.edit_section<FormationSection>();
  s.shape = read_formation_shape(*m.req("shape"), sc);
  if (m.has("reform_after_steps")) {
    const std::int64_t n = m.at("reform_after_steps")->integer();
    if (n < 1 || n > 1000000)
      m.at("reform_after_steps")->fail("expected at least 1 clear step before re-forming, got " + std::to_string(n));
    s.reform_after_steps = static_cast<int>(n);
  }
  if (m.has("arrival_tolerance_s")) s.arrival_tolerance_s = m.at("arrival_tolerance_s")->non_negative();
}

// The UAVs' arrivals (contract: at the goal to stay) within arrival_tolerance_s of one another.
void FormationMission::check_plan(const Scenario& sc, const FlownUavs& flown, Violations& out) const {
  if (flown.size() < 2) return;
  const std::vector<Arrival> arrivals = arrival_points(sc);
  double lo = World::kInf, hi = -World::kInf;
  std::string first, last;
  for (const auto& [u, up] : flown) {
    const std::size_t i = static_cast<std::size_t>(u - sc.uavs.data());
    const double t = arrival_s(*u, arrivals[i], up->trajectory);
    if (!std::isfinite(t)) continue;  // never there: the goal check says so
    if (t < lo) lo = t, first = u->id;
    if (t > hi) hi = t, last = u->id;
  }
  if (hi - lo > formation_section(sc).arrival_tolerance_s + 1e-6)
    add_violation(out, ViolationKind::arrival_spread, "", std::nullopt, std::nullopt,
                  "arrival times differ by " + num_text(hi - lo) + " s (" + first + " at its goal to stay at " +
                      num_text(lo) + " s, " + last + " at " + num_text(hi) + " s), above arrival_tolerance_s " +
                      num_text(formation_section(sc).arrival_tolerance_s) + " s");
}

}  // namespace uavplan
