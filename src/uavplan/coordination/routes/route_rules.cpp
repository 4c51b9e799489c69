// The route mission's part of the contract: its via points, as read and as verified.
#include <algorithm>
#include <cmath>

#include "uavplan/coordination/routes/routes_mission.h"
#include "uavplan/core/geometry.h"
#include "uavplan/core/text.h"
#include "uavplan/core/units.h"

namespace uavplan {

std::vector<const char*> RoutesMission::section_keys() const {
  if (type_ == MissionType::route) return {"waypoints"};
  return {};
}

// A row is [x, y, z], or {position: [x, y, z], entry_heading_deg: h}.
void RoutesMission::read_section(const Section& m, const Section& /*uavs*/, Scenario& sc) const {
  if (type_ != MissionType::route) return;
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
  if (type_ != MissionType::route) return;
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
      const std::size_t k = from <= 1e-9 && seg > 0 ? seg - 1 : seg;
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
