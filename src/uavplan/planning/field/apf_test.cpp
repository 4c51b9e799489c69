#include "uavplan/planning/field/apf.h"

#include <span>

#include <gtest/gtest.h>

#include "uavplan/core/geometry.h"
#include "uavplan/planning/field/field_guide.h"

namespace uavplan {
namespace {

World flat_world(std::vector<Obstacle> obstacles) {
  WorldSpec ws;
  ws.bounds = Aabb{Vec3(-20, -20, 0), Vec3(40, 40, 0)};
  ws.obstacles = std::move(obstacles);
  return World(std::move(ws));
}

UavSpec field_uav() {
  UavSpec u;
  u.radius_m = 0.1;
  return u;
}

ApfOptions opts(bool improved) {
  ApfOptions o = ApfOptions::from_params({}, improved ? ApfField::improved : ApfField::traditional);
  o.separation_m = 0.5;
  return o;
}

TEST(Apf, FreeSpacePointsAtTheGoal) {
  const World w = flat_world({});
  const PotentialField f(w, field_uav(), apf_resolved(opts(true), field_uav(), w));
  EXPECT_TRUE(f.direction(Vec3(0, 0, 0), Vec3(10, 5, 0), {}).isApprox(Vec3(10, 5, 0).normalized(), 1e-12));
}

TEST(Apf, RepulsionDeflectsAndTheSectorRuleKeepsOnlyTheNearest) {
  const Vec3 p(0, 0, 0), goal(10, 0, 0);
  const World one = flat_world({Sphere{Vec3(0.8, 0.3, 0), 0.1}});
  const World two =
      flat_world({Sphere{Vec3(0.8, 0.3, 0), 0.1}, Sphere{Vec3(1.2, 0.46, 0), 0.1}});  // same sector, farther
  for (const bool improved : {true, false}) {
    const ApfOptions o = apf_resolved(opts(improved), field_uav(), one);
    const Vec3 d1 = PotentialField(one, field_uav(), o).direction(p, goal, {});
    const Vec3 d2 = PotentialField(two, field_uav(), o).direction(p, goal, {});
    EXPECT_LT(d1.y(), 0.0) << "pushed away from the obstacle above the path";
    if (improved)
      EXPECT_TRUE(d1.isApprox(d2, 1e-12)) << "the farther obstacle in the same sector is ignored";
    else
      EXPECT_LT(d2.y(), d1.y()) << "the traditional field adds every obstacle";
  }
}

TEST(Apf, RepulsionFadesNearTheGoal) {
  // The same obstacle beside the UAV: far from the goal it pushes harder than next to it.
  const World w = flat_world({Sphere{Vec3(0, 0.6, 0), 0.1}});
  const PotentialField f(w, field_uav(), apf_resolved(opts(true), field_uav(), w));
  const Vec3 far = f.direction(Vec3(0, 0, 0), Vec3(10, 0, 0), {});
  const Vec3 near = f.direction(Vec3(0, 0, 0), Vec3(1.0, 0, 0), {});
  EXPECT_LT(std::abs(near.y()), std::abs(far.y()));
}

TEST(Apf, StepsAreSafeFromObstaclesAndPeers) {
  const World w = flat_world({Sphere{Vec3(1, 0, 0), 0.3}});
  const PotentialField f(w, field_uav(), apf_resolved(opts(true), field_uav(), w));
  const std::vector<PeerMotion> peers{{Vec3(0.5, 0.6, 0), Vec3(0.5, 0.5, 0), 0.1}};
  Vec3 p(0, 0, 0);
  for (int k = 0; k < 40; ++k) {
    const Vec3 q = f.step(p, Vec3(5, 0, 0), peers, 0);
    EXPECT_GE(w.segment_clearance(p, q, 10.0), 0.1);
    EXPECT_GE(point_segment_distance(Vec3::Zero(), p - peers[0].from, q - peers[0].to), 0.5);
    p = q;
  }
}

TEST(Apf, ReachesTheGoalPastAWallOrFailsWithAReason) {
  const World w = flat_world({Box{Vec3(5, -3, -1), Vec3(5.5, 3, 1)}});
  const PotentialField f(w, field_uav(), apf_resolved(opts(true), field_uav(), w));
  const ApfRun run = run_apf(f, Vec3(0, 0, 0), Vec3(10, 0, 0));
  ASSERT_TRUE(run.reached) << run.message;  // the wall is short: the guide goes round it
  for (std::size_t i = 1; i < run.points.size(); ++i)
    ASSERT_GE(w.segment_clearance(run.points[i - 1], run.points[i], 1.0), 0.1);
  // Enclosed goal: bounded, with a reason.
  const World cage = flat_world({Box{Vec3(8, -2, -1), Vec3(12, -1.5, 1)}, Box{Vec3(8, 1.5, -1), Vec3(12, 2, 1)},
                                 Box{Vec3(8, -2, -1), Vec3(8.5, 2, 1)}, Box{Vec3(11.5, -2, -1), Vec3(12, 2, 1)}});
  const PotentialField fc(cage, field_uav(), apf_resolved(opts(true), field_uav(), cage));
  const ApfRun trapped = run_apf(fc, Vec3(0, 0, 0), Vec3(10, 0, 0));
  EXPECT_FALSE(trapped.reached);
  EXPECT_NE(trapped.message.find("no route to the goal"), std::string::npos) << trapped.message;
}

TEST(Apf, EscapesACupAlongTheGuideRoute) {
  // A cup open toward the start, the goal behind its bottom: the field alone settles inside.
  const World cup = flat_world({Box{Vec3(6, -3, -1), Vec3(6.5, 3, 1)}, Box{Vec3(2, 2.5, -1), Vec3(6.5, 3, 1)},
                                Box{Vec3(2, -3, -1), Vec3(6.5, -2.5, 1)}});
  const PotentialField f(cup, field_uav(), apf_resolved(opts(true), field_uav(), cup));
  FieldFlight flight(f, Vec3(0, 0, 0), Vec3(10, 0, 0), 8);
  std::vector<Vec3> path{flight.position()};
  for (int k = 0; k < 2000 && !flight.arrived() && !flight.failed(); ++k) path.push_back(flight.advance({}, {}));
  EXPECT_FALSE(flight.arrived()) << "without a guide the cup holds the UAV";

  const ApfRun run = run_apf(f, Vec3(0, 0, 0), Vec3(10, 0, 0));
  ASSERT_TRUE(run.reached) << run.message;
  for (std::size_t i = 1; i < run.points.size(); ++i)
    ASSERT_GE(cup.segment_clearance(run.points[i - 1], run.points[i], 1.0), 0.1);
}

TEST(Apf, GuideRoutesAroundKeepOutsAndForgetsThem) {
  // A wall with one gap at y = 0; a keep-out in the gap sends the route round the wall's end.
  const World w = flat_world({Box{Vec3(5, -10, -1), Vec3(5.5, -0.5, 1)}, Box{Vec3(5, 0.5, -1), Vec3(5.5, 6, 1)}});
  FieldGuide guide(w, field_uav(), 0.25);
  auto length = [](const std::vector<Vec3>& r) {
    double l = 0;
    for (std::size_t i = 1; i < r.size(); ++i) l += (r[i] - r[i - 1]).norm();
    return l;
  };
  const std::vector<Vec3> through = guide.route(Vec3(0, 0, 0), Vec3(10, 0, 0), {});
  ASSERT_FALSE(through.empty());
  EXPECT_LT(length(through), 11.0);
  EXPECT_EQ(through.back(), Vec3(10, 0, 0));
  const KeepOut plug{Vec3(5.25, 0, 0), 0.6};
  const std::vector<Vec3> around = guide.route(Vec3(0, 0, 0), Vec3(10, 0, 0), std::span(&plug, 1));
  ASSERT_FALSE(around.empty());
  EXPECT_GT(length(around), 15.0);
  for (const Vec3& p : around) EXPECT_GE((p - plug.centre).norm(), plug.radius_m);
  EXPECT_NEAR(length(guide.route(Vec3(0, 0, 0), Vec3(10, 0, 0), {})), length(through), 1e-12)
      << "keep-outs last one query";
  // Closed in: no route.
  const KeepOut ring[] = {{Vec3(10, 0, 0) + Vec3(1, 0, 0), 0.6},
                          {Vec3(9, 0, 0), 0.6},
                          {Vec3(10, 1, 0), 0.6},
                          {Vec3(10, -1, 0), 0.6},
                          {Vec3(11, 1, 0), 0.6},
                          {Vec3(9, 1, 0), 0.6},
                          {Vec3(11, -1, 0), 0.6},
                          {Vec3(9, -1, 0), 0.6}};
  EXPECT_TRUE(guide.route(Vec3(0, 0, 0), Vec3(10, 0, 0), ring).empty());
}

TEST(Apf, TripleSmoothingStraightensAndRespectsRefusals) {
  std::vector<Vec3> zig;
  for (int i = 0; i <= 20; ++i) zig.emplace_back(i, (i % 2) * 0.5, 0);
  auto turn_sum = [](const std::vector<Vec3>& p) {
    double s = 0;
    for (std::size_t i = 1; i + 1 < p.size(); ++i) {
      const Vec3 a = p[i] - p[i - 1], b = p[i + 1] - p[i];
      s += std::acos(std::clamp(a.dot(b) / (a.norm() * b.norm()), -1.0, 1.0));
    }
    return s;
  };
  std::vector<Vec3> s = zig;
  EXPECT_GT(smooth_triples(s, deg_to_rad(5), [](std::size_t, const Vec3&) { return true; }), 0);
  EXPECT_LT(turn_sum(s), 0.5 * turn_sum(zig));
  EXPECT_EQ(s.front(), zig.front());
  EXPECT_EQ(s.back(), zig.back());
  std::vector<Vec3> kept = zig;
  EXPECT_EQ(smooth_triples(kept, deg_to_rad(5), [](std::size_t, const Vec3&) { return false; }), 0);
  EXPECT_EQ(kept, zig);
}

// A via point where the route turns back sharply stays on the route: the smoothing moves no via
// point (it once pulled the route off one, and the verifier failed the plan).
TEST(Apf, ViaPointsAtSharpTurnsStayOnTheRoute) {
  const World w = flat_world({});
  for (const bool improved : {true, false}) {
    ApfPlanner planner(opts(improved));
    Problem pb{field_uav(), Vec3(2, 1, 0), {Vec3(30, 10, 0), Vec3(-10, 30, 0)}};
    pb.uav.start = Vec3(0, 0, 0);
    const PlanResult r = planner.plan(pb, w, {});
    ASSERT_EQ(r.status, Status::solved) << r.message;
    const auto& pts = r.route.waypoints;
    for (const Vec3& via : pb.via) EXPECT_NE(std::find(pts.begin(), pts.end(), via), pts.end()) << via.transpose();
  }
}

}  // namespace
}  // namespace uavplan
