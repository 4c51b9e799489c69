#include "uavplan/coordination/routes/local_layer.h"

#include <stdexcept>

namespace uavplan {

LocalLayer local_layer(const MissionContext& ctx) {
  ParamReader r(ctx.mission_params, ctx.algorithm);
  LocalLayer out = local_layer(ctx, r);
  r.finish();
  return out;
}

LocalLayer local_layer(const MissionContext& ctx, ParamReader& r) {
  const std::string local = r.text("local", "improved_rrt");
  if (local != "improved_rrt" && local != "rrt")
    throw std::invalid_argument("planner.params.local: expected improved_rrt or rrt, got '" + local + "'");
  LocalLayer out;
  out.window_m = r.number("window_m", 0.0, 0.0, 1e12);
  // The global planner's own RRT parameters apply to the local one of the same kind.
  out.rrt = local == ctx.algorithm ? RrtOptions::from_params(ctx.params, local == "improved_rrt" ? RrtVariant::improved
                                                                                                 : RrtVariant::common)
            : local == "rrt"       ? RrtOptions::common()
                                   : RrtOptions::improved();
  return out;
}

}  // namespace uavplan
