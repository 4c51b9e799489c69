#include "uavplan/coordination/contract/plan.h"

namespace uavplan {

Status combined_status(const std::vector<UavPlan>& uavs) {
  std::size_t solved = 0;
  for (const auto& u : uavs) solved += u.status == Status::solved;
  if (!uavs.empty() && solved == uavs.size()) return Status::solved;
  return solved == 0 ? Status::failed : Status::partial;
}

void combine_outcomes(Plan& plan) {
  plan.status = combined_status(plan.uavs);
  plan.reason = Reason::none;
  for (const UavPlan& u : plan.uavs)
    if (u.status != Status::solved) {
      plan.reason = u.reason;
      if (plan.message.empty()) plan.message = u.id + ": " + u.message;
      break;
    }
}

}  // namespace uavplan
