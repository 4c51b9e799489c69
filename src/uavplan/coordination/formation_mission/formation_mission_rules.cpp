// The formation mission's part of the contract (P5): the airfield, the task points, the
// topology and the parked UAVs, as read; the runway, the task points and the airfield's
// separation rule, as verified.
#include <cmath>
#include <string>

#include "uavplan/coordination/contract/runway.h"
#include "uavplan/coordination/contract/separation.h"
#include "uavplan/coordination/formation/formation_mission.h"
#include "uavplan/coordination/formation_mission/consensus.h"
#include "uavplan/coordination/formation_mission/phased_formation_mission.h"
#include "uavplan/coordination/formation_mission/task_points.h"
#include "uavplan/core/text.h"
#include "uavplan/core/units.h"

namespace uavplan {
namespace {

// Landed on the runway (contract): within a metre of the airfield's height, within the runway's
// length and kLandedOffCentreline_m of its centreline.
constexpr double kLandedAbove_m = 1.0;
constexpr double kLandedOffCentreline_m = 100.0;

// The threshold on the ground, the runway inside the bounds.
Airfield read_airfield(const Section& a, const World& world) {
  a.keys({"position", "runway_heading_deg", "runway_length"});
  Airfield af;
  af.position = a.req("position")->vec3();
  if (a.has("runway_heading_deg")) af.runway_heading_rad = deg_to_rad(a.at("runway_heading_deg")->number());
  if (a.has("runway_length")) af.runway_length_m = a.at("runway_length")->positive();
  check_placed(*a.at("position"), af.position, world, "the airfield");
  if (!world.on_ground(af.position))
    a.at("position")->fail("the airfield must lie on the ground (z = the ground there)");
  const Vec3 end =
      af.position + af.runway_length_m * Vec3(std::cos(af.runway_heading_rad), std::sin(af.runway_heading_rad), 0.0);
  if (!world.in_bounds(end)) a.at("runway_length")->fail("the runway leaves the world bounds");
  return af;
}

std::vector<TaskPoint> read_task_points(const Section& list, const World& world) {
  list.expect_seq();
  if (list.size() == 0) list.fail("a formation_mission needs at least one task point");
  std::vector<TaskPoint> points;
  for (std::size_t i = 0; i < list.size(); ++i) {
    const auto row = list.item(i);
    row->keys({"position", "entry_heading_deg", "radius"});
    TaskPoint tp;
    tp.position = row->req("position")->vec3();
    check_placed(*row->at("position"), tp.position, world, "task point");
    if (row->has("entry_heading_deg")) tp.entry_heading_rad = deg_to_rad(row->at("entry_heading_deg")->number());
    if (row->has("radius")) tp.radius_m = row->at("radius")->positive();
    points.push_back(tp);
  }
  return points;
}

// a_ij: a row per UAV, every UAV connected to the others.
std::vector<std::vector<double>> read_topology(const Section& t, std::size_t uavs) {
  t.expect_seq();
  if (t.size() != uavs)
    t.fail("needs a row a_ij per UAV (" + std::to_string(uavs) + "), got " + std::to_string(t.size()));
  std::vector<std::vector<double>> topology;
  for (std::size_t i = 0; i < t.size(); ++i) {
    const auto row = t.item(i);
    row->expect_seq();
    if (row->size() != uavs) row->fail("needs " + std::to_string(uavs) + " entries a_ij");
    std::vector<double> r;
    for (std::size_t j = 0; j < row->size(); ++j) r.push_back(row->item(j)->non_negative());
    topology.push_back(std::move(r));
  }
  if (!topology_connected(topology)) t.fail("leaves a UAV out: the UAVs must all be connected, through the others");
  return topology;
}

// UAVs parked on the ground, off the runway, at least the separation apart, with no goal.
void check_parked(const Section& uavs, const Scenario& sc) {
  const MissionSpec& ms = sc.mission;
  for (std::size_t i = 0; i < sc.uavs.size(); ++i) {
    const UavSpec& u = sc.uavs[i];
    const auto ui = uavs.item(i);
    if (u.goal) ui->at("goal")->fail("a formation_mission UAV has no goal: it lands on the runway");
    if (!sc.world.on_ground(u.start))
      ui->at("start")->fail("a formation_mission UAV starts parked on the ground at the airfield");
    // The take-off rolls and climb-outs pass over the runway: nobody may wait on it.
    const Vec3 along = Vec3(std::cos(ms.airfield->runway_heading_rad), std::sin(ms.airfield->runway_heading_rad), 0.0);
    const Vec3 rel = u.start - ms.airfield->position;
    const double s_m = rel.dot(along), off_m = std::abs(along.x() * rel.y() - along.y() * rel.x());
    if (s_m > 0.0 && s_m <= ms.airfield->runway_length_m && off_m < ms.separation_m)
      ui->at("start")->fail("is parked on the runway (" + num_text(std::round(off_m)) +
                            " m from its centreline), where the others take off; park it at least the separation " +
                            num_text(ms.separation_m) + " m beside the runway or behind its threshold");
    for (std::size_t j = 0; j < i; ++j)
      if ((sc.uavs[j].start - u.start).norm() < ms.separation_m)
        ui->at("start")->fail("is " + num_text((sc.uavs[j].start - u.start).norm()) + " m from " + sc.uavs[j].id +
                              "'s start; starts must be at least the separation " + num_text(ms.separation_m) +
                              " m apart");
  }
}

}  // namespace

const MissionDeclaration& PhasedFormationMission::declaration() const {
  static const MissionDeclaration d = [] {
    MissionDeclaration m;
    m.name = "formation_mission";
    m.summary =
        "P5's whole formation mission of fixed wings in five phases: take-off from the airfield, form up, fly the "
        "task points in shape (multi-step PSO waypoints, consensus control), dismiss, land without conflicts; "
        "no goals: the UAVs land on the runway.";
    m.keys = {formation_shape_key(),
              {"airfield", "{position: [x, y, z], runway_heading_deg, runway_length_m}", "", "m, deg",
               "the runway's threshold on the ground, its heading (0 = east) and length (default " +
                   num_text(Airfield{}.runway_length_m) + " m)"},
              {"task_points", "list of {position: [x, y, z], entry_heading_deg, radius_m}", "", "m, deg",
               "reached in order by the formation's reference within radius_m (default " +
                   num_text(TaskPoint{}.radius_m) + " m), along the entry heading where one is given"},
              {"topology", "list of rows a_ij", "the complete graph", "",
               "the consensus control's communication weights, a row per UAV in scenario order"}};
    m.algorithms = {"pso_mpc"};
    m.default_algorithm = "pso_mpc";
    m.parameters = {"layer_spacing_m",  "enlargement",        "shape_tolerance_m",
                    "form_up_height_m", "takeoff_interval_s", "dismiss_within_m"};
    m.needs_goals = false;
    m.times_ground_legs = true;
    m.own_ground = true;
    m.export_rules = ExportRules::own_pair_rule;
    return m;
  }();
  return d;
}

std::string PhasedFormationMission::describe(const Scenario& sc) const {
  std::string out = ", shape of " + std::to_string(formation_shape(sc).size()) + " slots";
  if (const auto& af = sc.mission.airfield)
    out += strf("\nairfield  threshold (%g, %g, %g), runway %g m heading %g deg", af->position.x(), af->position.y(),
                af->position.z(), af->runway_length_m, rad_to_deg(af->runway_heading_rad));
  const auto& points = phased_section(sc).task_points;
  for (std::size_t k = 0; k < points.size(); ++k) {
    const TaskPoint& t = points[k];
    out += strf("\ntask %-4zu (%g, %g, %g) within %g m", k, t.position.x(), t.position.y(), t.position.z(), t.radius_m);
    if (t.entry_heading_rad) out += strf(", entered at %g deg", rad_to_deg(*t.entry_heading_rad));
  }
  return out;
}

std::optional<double> PhasedFormationMission::pair_distance_m(const Scenario& sc, const UavSpec& a,
                                                              const Trajectory& ta, const UavSpec& b,
                                                              const Trajectory& tb) const {
  return airfield_encounter(sc, a, ta, b, tb).airborne_min_m;
}

void PhasedFormationMission::read_section(const Section& m, const Section& uavs, Scenario& sc) const {
  PhasedFormationSection& s = sc.mission.edit_section<PhasedFormationSection>();
  if (m.has("shape")) s.shape = read_formation_shape(*m.at("shape"), sc);
  sc.mission.airfield = read_airfield(*m.req("airfield"), sc.world);
  s.task_points = read_task_points(*m.req("task_points"), sc.world);
  if (m.has("topology")) s.topology = read_topology(*m.at("topology"), sc.uavs.size());
  if (!m.has("shape")) m.req("shape");
  check_parked(uavs, sc);
}

void PhasedFormationMission::check_pair(const Scenario& sc, const UavSpec& a, const Trajectory& ta, const UavSpec& b,
                                        const Trajectory& tb, double need_m, Violations& out) const {
  const AirfieldEncounter e = airfield_encounter(sc, a, ta, b, tb);
  if (e.conflict)
    add_violation(out, ViolationKind::separation, a.id, e.t_s, e.where,
                  "distance " + num_text(e.distance_m) + " m to '" + b.id + "', below " + num_text(e.need_m) + " m" +
                      (e.need_m < need_m ? " (their bodies, on the ground)" : ""));
  if (!sc.mission.airfield) return;
  const Airfield& af = *sc.mission.airfield;
  if (const auto o = runway_overlap(runway_occupancy(af, ta), runway_occupancy(af, tb)))
    add_violation(out, ViolationKind::runway, a.id, o->from_s, position_at(ta, o->from_s),
                  "on the runway with '" + b.id + "' from t=" + num_text(o->from_s) + " to " + num_text(o->to_s) +
                      " s (it holds one UAV at a time)");
}

void PhasedFormationMission::check_plan(const Scenario& sc, const FlownUavs& flown, Violations& out) const {
  std::vector<const Trajectory*> trs;
  for (const auto& f : flown) trs.push_back(&f.second->trajectory);
  const std::vector<TaskVisit> visits = task_visits(sc, formation_reference(sc, trs));
  for (std::size_t k = 0; k < phased_section(sc).task_points.size(); ++k) {
    const TaskPoint& tp = phased_section(sc).task_points[k];
    if (k < visits.size() && visits[k].reached) continue;
    std::string why = "task point " + std::to_string(k) + " not reached in order by the formation's reference";
    if (k < visits.size() && std::isfinite(visits[k].miss_m))
      why += " (within " + num_text(tp.radius_m) + " m only " + num_text(rad_to_deg(visits[k].heading_error_rad)) +
             " deg off its entry heading)";
    add_violation(out, ViolationKind::via_point, "", std::nullopt, tp.position, why);
    break;
  }
  if (!sc.mission.airfield) return;
  const Airfield& af = *sc.mission.airfield;
  const Vec2 along(std::cos(af.runway_heading_rad), std::sin(af.runway_heading_rad));
  for (const auto& [u, up] : flown) {
    const Vec3 end = up->trajectory.back().p;
    const Vec2 rel = (end - af.position).head<2>();
    const double a = rel.dot(along), off = std::abs(rel.x() * along.y() - rel.y() * along.x());
    if (std::abs(end.z() - af.position.z()) > kLandedAbove_m || a < -kPositionTolerance_m ||
        a > af.runway_length_m + kPositionTolerance_m || off > kLandedOffCentreline_m)
      add_violation(out, ViolationKind::goal, u->id, up->trajectory.back().t_s, end,
                    "does not end on the runway (" + num_text(a) + " m along it, " + num_text(off) +
                        " m off its centreline, " + num_text(end.z() - af.position.z()) + " m above it)");
  }
}

}  // namespace uavplan
