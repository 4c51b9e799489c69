#include "uavplan/coordination/routes/route_problem.h"

namespace uavplan {

Problem uav_problem(const Scenario& sc, const MissionOptions& opt, const GroundPoints& ground, std::size_t i) {
  const UavSpec& u = sc.uavs[i];
  Problem pb{u, *u.goal, {}};
  if (sc.mission.type == MissionType::route) {
    pb.via = sc.mission.waypoints;
    pb.via_entry_heading_rad = sc.mission.waypoint_entry_heading_rad;
  }
  if (i < ground.home_visits.size() && ground.home_visits[i]) {  // home, its start, ..., its goal, home
    pb.via.insert(pb.via.begin(), ground.home_visits[i]->first);
    pb.via.push_back(ground.home_visits[i]->second);
    pb.via_entry_heading_rad.resize(pb.via.size() - 2);
    pb.via_entry_heading_rad.insert(pb.via_entry_heading_rad.begin(), std::nullopt);
    pb.via_entry_heading_rad.push_back(std::nullopt);
  }
  pb.seed = opt.seed + i;  // one stream per UAV
  return pb;
}

}  // namespace uavplan
