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
  const std::string local = r.choice("local", "improved_rrt", {"improved_rrt", "rrt"},
                                     "the local replanner of UAVs with sensors (P1's improved RRT, or the common one)");
  LocalLayer out;
  out.window_m = r.number("window_m", 0.0, 0.0, 1e12, "the route ahead a sensing UAV checks, m; 0: its sensor range");
  // The global planner's own RRT parameters apply to the local one of the same kind.
  out.rrt = local == ctx.algorithm ? RrtOptions::from_params(ctx.params, local == "improved_rrt" ? RrtVariant::improved
                                                                                                 : RrtVariant::common)
            : local == "rrt"       ? RrtOptions::common()
                                   : RrtOptions::improved();
  return out;
}

}  // namespace uavplan
