#include "uavplan/coordination/contract/plan.h"

namespace uavplan {

Status combined_status(const std::vector<UavPlan>& uavs) {
  std::size_t solved = 0;
  for (const auto& u : uavs) solved += u.status == Status::solved;
  if (!uavs.empty() && solved == uavs.size()) return Status::solved;
  return solved == 0 ? Status::failed : Status::partial;
}

}  // namespace uavplan
