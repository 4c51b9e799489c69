// The local layer in the closed loop: a UAV acts only on what its sensor saw.
#include "uavplan/coordination/routes/rolling_window.h"

#include <gtest/gtest.h>

#include <algorithm>

namespace uavplan {
namespace {

UavSpec p1_uav(double range_m) {
  UavSpec u;
  u.id = "u1";
  u.start = Vec3(10, 50, 0);
  u.goal = Vec3(190, 50, 0);
  u.radius_m = 0.5;
  u.speed = {0, 5, 5};
  u.sensor_range_m = range_m;
  return u;
}

World flat(std::vector<MovingObstacle> moving) {
  WorldSpec ws;
  ws.bounds = Aabb{Vec3(0, 0, 0), Vec3(200, 100, 0)};
  ws.moving = std::move(moving);
  return World(std::move(ws));
}

struct Flight {
  LoopResult loop;
  RollingWindowLog log;
};

Flight fly(const World& w, const UavSpec& u) {
  RollingWindowOptions opt;
  RollingWindow rw(w, opt, {*u.sensor_range_m}, {u.id});
  const std::vector<LoopUav> uavs{{&u, {u.start, *u.goal}, *u.sensor_range_m, 0.0}};
  Flight f{fly_closed_loop(w, uavs, {}, rw, {}, {}), {}};
  f.log = rw.log(0);
  return f;
}

TEST(RollingWindow, AnObstacleThatTurnsAfterBeingSeenIsAvoidedFromTheUavsObservations) {
  // Flies east 30 m north of the route (no threat) and is seen from t = 10 on; at t = 14.5 it
  // turns south at 4 m/s, to cross the route just when the UAV gets there.
  const MovingObstacle turner{"turner",
                              2.0,
                              Vec3::Zero(),
                              Vec3::Zero(),
                              {{0, Vec3(74, 80, 0)}, {14.5, Vec3(117.5, 80, 0)}, {34.5, Vec3(117.5, 0, 0)}}};
  const World w = flat({turner});
  const Flight f = fly(w, p1_uav(60.0));
  ASSERT_TRUE(f.loop.uavs[0].done);
  ASSERT_FALSE(f.log.events.empty());
  // Nothing before the turn can be known: the first reaction comes after two looks (at 14 and
  // 15 s at the earliest), with V_b as eq. 7 makes it from them: the displacement over the last
  // period, which straddles the turn at 15 s (not the true velocity then).
  const ReplanEvent& first = f.log.events.front();
  EXPECT_EQ(first.object, "turner");
  EXPECT_GE(first.t_s, 15.0);
  const Vec3 observed = turner.position_at(first.t_s) - turner.position_at(first.t_s - 1.0);
  EXPECT_TRUE(first.velocity_mps.isApprox(observed, 1e-9)) << first.velocity_mps.transpose();
  EXPECT_LT(first.velocity_mps.y(), -1.0) << "it knows the obstacle now heads south";
  EXPECT_GE(f.log.replans, 1);
  // And it kept clear of the obstacle's true motion.
  EXPECT_GE(closest_moving_approach(w, f.loop.uavs[0].flown).distance_m, 0.5);
  // The same UAV, told nothing about obstacles (no sensor): it would have flown into it.
  const std::vector<Vec3> straight{Vec3(10, 50, 0), Vec3(190, 50, 0)};
  EXPECT_LT(closest_moving_approach(w, time_route(straight, 5.0, 0.0, 1.0)).distance_m, 0.5);
}

// The closest the flown polyline comes to p.
double closest_to(const Trajectory& tr, const Vec3& p) {
  double best = World::kInf;
  for (std::size_t k = 1; k < tr.size(); ++k) {
    const Vec3 seg = tr[k].p - tr[k - 1].p;
    const double f =
        seg.squaredNorm() > 0.0 ? std::clamp((p - tr[k - 1].p).dot(seg) / seg.squaredNorm(), 0.0, 1.0) : 0.0;
    best = std::min(best, (tr[k - 1].p + f * seg - p).norm());
  }
  return best;
}

TEST(RollingWindow, ADetourNeverRejoinsPastTheNextViaPoint) {
  // An obstacle holds still 5 m short of the via point at x = 100: the first clear point one
  // step past it lies beyond the via point, so the detour must end at the via point itself.
  const World w = flat({MovingObstacle{"parked", 2.0, Vec3(95, 50, 0), Vec3::Zero()}});
  const UavSpec u = p1_uav(60.0);
  const Vec3 via(100, 50, 0);
  for (const bool told : {false, true}) {
    RollingWindowOptions opt;
    if (told) opt.via_points = {via};
    RollingWindow rw(w, opt, {*u.sensor_range_m}, {u.id});
    const std::vector<LoopUav> uavs{{&u, {u.start, via, *u.goal}, *u.sensor_range_m, 0.0}};
    const LoopResult loop = fly_closed_loop(w, uavs, {}, rw, {}, {});
    ASSERT_TRUE(loop.uavs[0].done);
    ASSERT_GE(rw.log(0).replans, 1);
    EXPECT_GE(closest_moving_approach(w, loop.uavs[0].flown).distance_m, 0.5);
    if (told) {
      EXPECT_LE(closest_to(loop.uavs[0].flown, via), 1e-6) << "the detour skipped the via point";
    } else {
      EXPECT_GT(closest_to(loop.uavs[0].flown, via), 0.1) << "the test no longer needs the rule";
    }
  }
}

TEST(RollingWindow, AnObstacleOutsideTheSensorRangeIsNeverUsed) {
  // Its straight path would cross the route ahead; it stops 25 m short of it (beyond the 20 m
  // range of a UAV on the route), so the UAV never learns of it and flies straight.
  const MovingObstacle lurker{
      "lurker", 1.0, Vec3::Zero(), Vec3::Zero(), {{0, Vec3(100, 95, 0)}, {10, Vec3(100, 75, 0)}}};
  const World w = flat({lurker});
  const Flight f = fly(w, p1_uav(20.0));
  EXPECT_TRUE(f.log.events.empty());
  const Trajectory& tr = f.loop.uavs[0].flown;
  for (const TrajectorySample& s : tr) EXPECT_DOUBLE_EQ(s.p.y(), 50.0);
  // With a longer sensor it sees it, as a disc that does not move: still nothing to avoid.
  const Flight seeing = fly(w, p1_uav(40.0));
  EXPECT_TRUE(seeing.log.events.empty());
}

TEST(RollingWindow, DiscsGrowWithTheEstimatedSpeedAndSeparation) {
  UavSpec u = p1_uav(40);
  Track obstacle{0, "m", 2.0, false, 3.0, Vec3(10, 0, 0), Vec3::Zero(), Vec3(3, 4, 0), 0.0};
  Track uav{1, "u2", 0.5, true, 3.0, Vec3(0, 10, 0), Vec3::Zero(), Vec3::Zero(), 0.0};
  Track fresh{2, "new", 1.0, false, 3.0, Vec3(0, -10, 0), Vec3::Zero(), std::nullopt, 7.0};
  const auto discs = threat_discs(u, {obstacle, uav, fresh}, 3.0, 1.0, 6.0);
  EXPECT_NEAR(discs[0].disc.radius_m, 5.0 + 2.0 + 0.5, 1e-2);       // T |V_b| + both radii
  EXPECT_NEAR(discs[1].disc.radius_m, 6.0, 1e-2);                   // the separation
  EXPECT_NEAR(discs[2].disc.radius_m, 7.0 + 1.0 + 0.5, 1e-2);       // seen once: the speed it entered at
  EXPECT_TRUE(discs[2].disc.velocity_mps.isApprox(Vec3(0, 7, 0)));  // taken to come straight at the UAV
  EXPECT_NEAR(discs[0].body_m, 2.5, 1e-2);
}

}  // namespace
}  // namespace uavplan
