#include "uavplan/simulation/closed_loop.h"

#include <gtest/gtest.h>

namespace uavplan {
namespace {

UavSpec uav(const std::string& id, double speed) {
  UavSpec u;
  u.id = id;
  u.speed = {0.0, speed, speed};
  return u;
}

// Flies the routes as given and records what every sensor held.
class Recorder final : public FlightController {
 public:
  void control(double t, std::span<FlightState>, std::span<const Sensor> sensors) override {
    for (const Sensor& s : sensors)
      for (const Track& k : s.tracks) seen.emplace_back(t, k.id);
  }
  std::vector<std::pair<double, std::string>> seen;
};

TEST(ClosedLoop, FliesRoutesExactlyWithARowAtEveryVertexAndPeriod) {
  WorldSpec ws;
  ws.bounds = Aabb{Vec3(-100, -100, 0), Vec3(100, 100, 0)};
  const World w(std::move(ws));
  const UavSpec u = uav("u1", 4.0);
  const std::vector<LoopUav> uavs{{&u, {Vec3(0, 0, 0), Vec3(6, 0, 0), Vec3(6, 8, 0)}, 10.0, 2.0}};
  Recorder none;
  LoopOptions opt;
  opt.step_s = 2.0;
  opt.max_sample_dt_s = 1.0;
  const LoopResult r = fly_closed_loop(w, uavs, {}, none, opt, {});
  ASSERT_TRUE(r.uavs[0].done);
  const Trajectory& tr = r.uavs[0].flown;
  // Departs at t = 2, the corner at t = 3.5, arrives at t = 5.5; rows at most 1 s apart.
  EXPECT_EQ(tr.front().t_s, 0.0);
  EXPECT_EQ(position_at(tr, 2.0), Vec3(0, 0, 0));
  EXPECT_TRUE(position_at(tr, 3.5).isApprox(Vec3(6, 0, 0), 1e-12));
  EXPECT_NEAR(tr.back().t_s, 5.5, 1e-12);
  EXPECT_EQ(tr.back().p, Vec3(6, 8, 0));
  for (std::size_t i = 1; i < tr.size(); ++i) {
    EXPECT_LE(tr[i].t_s - tr[i - 1].t_s, 1.0 + 1e-12);
    const double v = (tr[i].p - tr[i - 1].p).norm() / (tr[i].t_s - tr[i - 1].t_s);
    EXPECT_TRUE(v < 1e-12 || std::abs(v - 4.0) < 1e-9) << v;
  }
}

// A route vertex a rounding error from where the UAV is (a controller's path starting at its
// own nominal point) is reached without a row: a row a few ulps later and a few ulps away would
// read as any speed at all.
TEST(ClosedLoop, AVertexWhereTheUavIsLeavesNoSliverRow) {
  const UavSpec u = uav("u1", 4.0);
  FlightState s;
  s.spec = &u;
  s.position = Vec3(491.18213, 402.87531, 0.0);
  s.speed_mps = 4.0;
  s.flown.push_back({109.0, s.position});
  s.route = {s.position + Vec3(3e-14, -5e-14, 0.0), s.position + Vec3(4.0, 0.0, 0.0)};
  advance(s, 109.0, 1.0);
  const Trajectory& tr = s.flown;
  for (std::size_t i = 1; i < tr.size(); ++i) {
    const double dt = tr[i].t_s - tr[i - 1].t_s, len = (tr[i].p - tr[i - 1].p).norm();
    if (dt > 0.0) {
      EXPECT_LE(len / dt, 4.0 * (1.0 + 1e-9)) << "row " << i;
    }
    EXPECT_FALSE(dt > 0.0 && dt < 1e-9) << "a sliver row at " << tr[i].t_s;
  }
  EXPECT_TRUE(s.done);
  EXPECT_EQ(tr.back().t_s, 110.0);
}

TEST(ClosedLoop, SensorsSeeOnlyWhatIsInRange) {
  WorldSpec ws;
  ws.bounds = Aabb{Vec3(-200, -200, 0), Vec3(200, 200, 0)};
  ws.moving.push_back({"near", 1.0, Vec3(50, 10, 0), Vec3(0, 0, 0)});
  ws.moving.push_back({"far", 1.0, Vec3(50, 40, 0), Vec3(0, 0, 0)});
  const World w(std::move(ws));
  const UavSpec u = uav("u1", 5.0);
  const std::vector<LoopUav> uavs{{&u, {Vec3(0, 0, 0), Vec3(100, 0, 0)}, 20.0, 0.0}};
  Recorder rec;
  fly_closed_loop(w, uavs, {}, rec, {}, {});
  bool near = false;
  for (const auto& [t, id] : rec.seen) {
    EXPECT_NE(id, "far");
    if (id == "near") {
      near = true;
      EXPECT_LE((Vec3(5 * t, 0, 0) - Vec3(50, 10, 0)).norm() - 1.0, 20.0 + 1e-9);
    }
  }
  EXPECT_TRUE(near);
}

TEST(ClosedLoop, AParkedUavKeepsTheLoopRunningWhileSomethingWillReachIt) {
  WorldSpec ws;
  ws.bounds = Aabb{Vec3(-200, -200, 0), Vec3(200, 200, 0)};
  ws.moving.push_back({"late", 1.0, Vec3(10, -100, 0), Vec3(0, 2, 0)});  // reaches (10, 0) at t = 50
  const World w(std::move(ws));
  const UavSpec u = uav("u1", 5.0);
  const std::vector<LoopUav> uavs{{&u, {Vec3(0, 0, 0), Vec3(10, 0, 0)}, 20.0, 0.0}};
  Recorder rec;
  const LoopResult r = fly_closed_loop(w, uavs, {}, rec, {}, {});
  EXPECT_TRUE(r.uavs[0].done);
  EXPECT_GE(r.steps, 50) << "arrived at t = 2, watched until the obstacle passed";
  EXPECT_LT(r.steps, 60);
}

}  // namespace
}  // namespace uavplan
