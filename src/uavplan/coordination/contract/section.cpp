#include "uavplan/coordination/contract/section.h"

#include "uavplan/core/text.h"

namespace uavplan {

void check_placed(const Section& at, const Vec3& p, const World& world, const std::string& what) {
  if (!world.in_bounds(p)) at.fail(what + " is outside the world bounds");
  if (world.on_ground(p)) {
    if (world.segment_obstacle_clearance(p, p, 1e-9) <= 0.0) at.fail(what + " is inside " + world.nearest_label(p));
  } else if (world.terrain() && p.z() < world.ground_z(p.x(), p.y())) {
    at.fail(what + " is below the terrain: the ground is at z = " + num_text(world.ground_z(p.x(), p.y())) + " m here");
  } else if (world.clearance(p, 1e-9) <= 0.0) {
    at.fail(what + " is inside " + world.nearest_label(p));
  }
}

}  // namespace uavplan
