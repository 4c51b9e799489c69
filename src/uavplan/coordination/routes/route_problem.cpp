#include "uavplan/coordination/routes/route_problem.h"

namespace uavplan {

Problem uav_problem(const Scenario& sc, const MissionOptions& opt, const GroundPoints& ground, std::size_t i) {
  const UavSpec& u = sc.uavs[i];
  Problem pb{u, *u.goal, {}};
  if (sc.mission.type == "route") {
    pb.via = sc.mission.waypoints;
    pb.via_entry_heading_rad = sc.mission.waypoint_entry_heading_rad;
  }
  if (i < ground.home_visits.size() && ground.home_visits[i]) {  // home, its start, ..., its goal, home
    const GroundPoints::HomeVisits& visit = *ground.home_visits[i];
    pb.via_entry_heading_rad.resize(pb.via.size());
    if (visit.start) {
      pb.via.insert(pb.via.begin(), *visit.start);
      pb.via_entry_heading_rad.insert(pb.via_entry_heading_rad.begin(), std::nullopt);
    }
    if (visit.goal) {
      pb.via.push_back(*visit.goal);
      pb.via_entry_heading_rad.push_back(std::nullopt);
    }
  }
  pb.seed = opt.seed + i;  // one stream per UAV
  return pb;
}

}  // namespace uavplan
