// The route mission's part of the contract: its via points, as read and as verified.
#include <algorithm>
#include <cmath>

#include "uavplan/coordination/routes/routes_mission.h"
#include "uavplan/core/geometry.h"
#include "uavplan/core/text.h"
#include "uavplan/core/tolerances.h"
#include "uavplan/core/units.h"

namespace uavplan {

RoutesMission::RoutesMission(RoutesKind kind) : kind_(kind) {
  MissionDeclaration& d = declaration_;
  const bool route = kind == RoutesKind::route;
  d.name = route ? "route" : "independent";
  d.summary = std::string(route ? "Every UAV flies through the via points in order, each" : "Each UAV flies") +
              " on its own route by the chosen planner; the routes are timed so that the UAVs keep their "
              "separation and clear the moving obstacles (departure delays, or space and time), UAVs with a "
              "sensor_range replanning in the loop (P1's rolling window).";
  d.parameters = {"local", "window_m", "deconfliction", "space_time_method", "space_time_cell_m"};
  d.flies_homes = true;
  d.times_ground_legs = true;
  if (route)
    d.keys = {{"waypoints", "list of [x, y, z] or {position: [x, y, z], entry_heading_deg}", "", "m, deg",
               "the via points every UAV passes in order; entry_heading_deg: the heading to enter one along"}};
}

bool route_with_entry_headings(const Scenario& sc) {
  const auto& headings = sc.mission.waypoint_entry_heading_rad;
  return sc.mission.type == "route" &&
         std::any_of(headings.begin(), headings.end(), [](const std::optional<double>& h) { return h.has_value(); });
}

std::string RoutesMission::describe(const Scenario& sc) const {
  return kind_ == RoutesKind::route ? ", " + std::to_string(sc.mission.waypoints.size()) + " via points" : "";
}

std::string RoutesMission::planner_refusal(const Scenario& sc, const PlannerInfo& p) const {
  if (kind_ != RoutesKind::route) return {};
  if (route_with_entry_headings(sc) && !p.entry_headings)
    return "'" + p.name + "' does not fly into a via point along its entry_heading_deg";
  if (!p.via_points) return "'" + p.name + "' does not plan through via points";
  return {};
}

std::string RoutesMission::default_algorithm(const Scenario& sc) const {
  return route_with_entry_headings(sc) ? "pso_mpc" : declaration_.default_algorithm;
}

// A row is [x, y, z], or {position: [x, y, z], entry_heading_deg: h}.
void RoutesMission::read_section(const Section& m, const Section& /*uavs*/, Scenario& sc) const {
  if (kind_ != RoutesKind::route) return;
  const auto list = m.req("waypoints");
  list->expect_seq();
  for (std::size_t i = 0; i < list->size(); ++i) {
    const auto row = list->item(i);
    std::optional<double> entry;
    Vec3 p;
    if (row->is_map()) {
      row->keys({"position", "entry_heading_deg"});
      p = row->req("position")->vec3();
      if (row->has("entry_heading_deg")) entry = deg_to_rad(row->at("entry_heading_deg")->number());
    } else {
      p = row->vec3();
    }
    check_placed(row->is_map() ? *row->at("position") : *row, p, sc.world, "waypoint");
    sc.mission.waypoints.push_back(p);
    sc.mission.waypoint_entry_heading_rad.push_back(entry);
  }
  if (sc.mission.waypoints.empty()) list->fail("a route mission needs at least one waypoint");
}

// Via points visited in order (within the UAV's radius), entered at their headings.
void RoutesMission::check_uav(const Scenario& sc, const UavSpec& u, const Trajectory& tr, Violations& out) const {
  if (kind_ != RoutesKind::route) return;
  const std::string& id = u.id;
  const double tol = std::max(u.radius_m, kPositionTolerance_m);
  TrackProgress at;
  if (u.home) passes_within(tr, u.start, tol, at);  // its via points come after its start
  for (std::size_t v = 0; v < sc.mission.waypoints.size(); ++v) {
    const Vec3& via = sc.mission.waypoints[v];
    const bool hit = passes_within(tr, via, tol, at);
    const std::size_t seg = at.segment;
    const double from = at.fraction;
    const std::optional<double> entry =
        v < sc.mission.waypoint_entry_heading_rad.size() ? sc.mission.waypoint_entry_heading_rad[v] : std::nullopt;
    if (hit && entry && tr.size() > 1) {  // the heading it arrives with: the row into the point
      const std::size_t k = from <= kSamePoint_m && seg > 0 ? seg - 1 : seg;
      const Vec3 d = tr[std::min(k + 1, tr.size() - 1)].p - tr[k].p;
      const double off = d.head<2>().norm() > 0.0 ? std::abs(wrap_angle_rad(std::atan2(d.y(), d.x()) - *entry)) : kPi;
      if (off > deg_to_rad(kEntryHeadingTolerance_deg))
        add_violation(out, ViolationKind::via_point, id, tr[k].t_s, via,
                      "via point " + std::to_string(v) + " entered at " +
                          num_text(rad_to_deg(std::atan2(d.y(), d.x()))) + " deg, " + num_text(rad_to_deg(off)) +
                          " deg off its entry heading " + num_text(rad_to_deg(*entry)) + " deg");
    }
    if (!hit) {
      add_violation(out, ViolationKind::via_point, id, std::nullopt, via,
                    "via point " + std::to_string(v) + " is not visited in order (within " + num_text(tol) + " m)");
      break;
    }
  }
}

}  // namespace uavplan
