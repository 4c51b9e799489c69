// P1's formation: the schedule's slots, leaving a slot to avoid, re-forming by eq. 8-9, one ETA.
#include <gtest/gtest.h>

#include <cmath>

#include "uavplan/coordination/formation/formation_mission.h"
#include "uavplan/coordination/formation/formation_schedule.h"
#include "uavplan/coordination/mission_planner.h"
#include "uavplan/simulation/trajectory.h"

namespace uavplan {
namespace {

const std::vector<Vec3> kWedge{{0, 0, 0}, {-5, 5, 0}, {-5, -5, 0}};

// The shape's heading at knot k: from the wedge's centroid to its apex (slot 0).
double wedge_heading(const FormationSchedule& s, std::size_t k) {
  const Vec3 c = (s.slots[0][k] + s.slots[1][k] + s.slots[2][k]) / 3.0;
  return std::atan2(s.slots[0][k].y() - c.y(), s.slots[0][k].x() - c.x());
}

TEST(FormationSchedule, SlotsTurnWithTheRouteAndShareOneClock) {
  // An L-shaped route east then north; starts at the first slots, goals at the last.
  const std::vector<Vec3> route{{0, 0, 0}, {100, 0, 0}, {100, 100, 0}};
  const Vec3 c(-10.0 / 3.0, 0, 0);  // the wedge's centroid
  std::vector<Vec3> starts, goals;
  for (const Vec3& o : kWedge) {
    starts.push_back(route[0] + (o - c));
    goals.push_back(route[2] + Vec3(-(o - c).y(), (o - c).x(), 0));  // heading north: forward is +y
  }
  const FormationSchedule s = formation_schedule(route, kWedge, starts, goals, {5.0, 0.0, {}, {}});
  ASSERT_EQ(s.slots.size(), 3u);
  for (const auto& p : s.slots) EXPECT_EQ(p.size(), s.knots_s.size());
  EXPECT_NEAR(s.knots_s[s.form_up_knot], 0.0, 1e-12);  // already in their slots
  // The reference pursues the route (a radius of twice the shape's reach, 5.27 m): a rigid shape
  // turning with its heading by 5 deg a step at most, never more than that radius off the route,
  // no slot backing up, each leg as long as its widest move takes at 5 m/s.
  const double radius = 2.0 * std::hypot(5.0 - 10.0 / 3.0, 5.0);
  for (std::size_t k = s.form_up_knot; k + 1 < s.knots_s.size(); ++k) {
    double widest = 0.0;
    const double h0 = wedge_heading(s, k), h1 = wedge_heading(s, k + 1);
    EXPECT_LE(std::abs(std::remainder(h1 - h0, 2.0 * M_PI)), M_PI / 36.0 + 1e-9) << k;
    const Vec3 forward(std::cos(h0), std::sin(h0), 0.0);
    for (std::size_t i = 0; i < 3; ++i) {
      const Vec3 d = s.slots[i][k + 1] - s.slots[i][k];
      widest = std::max(widest, d.norm());
      EXPECT_GE(d.dot(forward), -1e-3) << "slot " << i << " backs up in leg " << k;
      for (std::size_t j = i + 1; j < 3; ++j)
        EXPECT_NEAR((s.slots[i][k + 1] - s.slots[j][k + 1]).norm(), (kWedge[i] - kWedge[j]).norm(), 1e-9);
    }
    EXPECT_NEAR(s.knots_s[k + 1] - s.knots_s[k], widest / 5.0, 1e-9);
    const Vec3 ref = (s.slots[0][k] + s.slots[1][k] + s.slots[2][k]) / 3.0;
    EXPECT_LE(std::min(std::hypot(ref.y(), std::max(0.0, ref.x() - 100.0)),
                       std::hypot(ref.x() - 100.0, std::min(0.0, ref.y()))),
              radius)
        << k;
  }
  for (std::size_t i = 0; i < 3; ++i) EXPECT_NEAR((s.at(i, s.end_s()) - goals[i]).norm(), 0.0, 1e-9);
  EXPECT_GT(s.end_s(), 2.0 * (100.0 - radius) / 5.0);
  EXPECT_LT(s.end_s(), 45.0);  // 200 m at 5 m/s, less the corner cut, plus the wings' wider turn
  // The shape keeps them apart all the way (in a chord, at least cos 10 deg of their distance).
  for (std::size_t k = 0; k + 1 < s.knots_s.size(); ++k)
    EXPECT_GE(schedule_gap_m(s, 1, 2, k), 10.0 * std::cos(M_PI / 18.0) - 1e-9);
}

// The form-up: the wedge's starts lie heading north, the route leaves east. Where flying each UAV
// straight into its east-facing slot keeps the pairs apart, that is one leg (no jog into the
// north-facing shape and turn back); where it would not, the shape forms as the starts lie and
// turns as a rigid body.
TEST(FormationSchedule, TheFormUpFliesStraightIntoTheSlotsWhereThatKeepsThePairsApart) {
  const std::vector<Vec3> route{{0, 0, 0}, {100, 0, 0}};
  const Vec3 c(-10.0 / 3.0, 0, 0);
  std::vector<Vec3> starts, goals;
  for (const Vec3& o : kWedge) {
    starts.push_back(Vec3(-(o - c).y(), (o - c).x(), 0));  // heading north
    goals.push_back(route[1] + (o - c));
  }
  FormationScheduleOptions opt{5.0, 0.0, {}, {}};
  opt.pair_need_m = [](std::size_t, std::size_t) { return 2.0; };
  const FormationSchedule direct = formation_schedule(route, kWedge, starts, goals, opt);
  EXPECT_EQ(direct.form_up_knot, 1u);
  for (std::size_t i = 0; i < 3; ++i) EXPECT_LT((direct.slots[i][1] - (route[0] + kWedge[i] - c)).norm(), 1e-9);
  opt.pair_need_m = [](std::size_t, std::size_t) { return 6.0; };  // the straight moves pass closer
  const FormationSchedule turned = formation_schedule(route, kWedge, starts, goals, opt);
  EXPECT_GT(turned.form_up_knot, 1u);
  EXPECT_NEAR(wedge_heading(turned, 1), M_PI / 2, 1e-6);  // formed heading north first
}

// Where a smooth path or an arc would cut into an obstacle, the shape turns with the route
// itself, about the corner.
TEST(FormationSchedule, AboutTheCornerWhereNothingElseIsClear) {
  const std::vector<Vec3> route{{0, 0, 0}, {100, 0, 0}, {100, 100, 0}};
  std::vector<Vec3> starts, goals;
  const Vec3 c(-10.0 / 3.0, 0, 0);
  for (const Vec3& o : kWedge) starts.push_back(o - c), goals.push_back(route[2] + Vec3(-(o - c).y(), (o - c).x(), 0));
  FormationScheduleOptions opt{5.0, 0.0, {}, {}};
  opt.slot_clear = [](std::size_t, const Vec3& a, const Vec3& b) {
    return std::max(a.y(), b.y()) < 1.0 || a.x() > 99.0;
  };
  const FormationSchedule pivot = formation_schedule(route, kWedge, starts, goals, opt);
  EXPECT_NEAR(pivot.knots_s[2] - pivot.knots_s[1], 20.0, 1e-9);  // the whole segment, then the turn about the corner
  for (std::size_t i = 0; i < 3; ++i) EXPECT_NEAR((pivot.slots[i][2] - pivot.slots[i][1]).y(), 0.0, 1e-9);
}

// With an approach, the shape turns as the goals lie before them and every UAV moves until the
// end: none waits at its goal for the others.
TEST(FormationSchedule, AnApproachWhereNoneWaitsAtItsGoal) {
  const std::vector<Vec3> route{{0, 0, 0}, {100, 0, 0}, {100, 100, 0}};
  std::vector<Vec3> starts, goals;
  const Vec3 c(-10.0 / 3.0, 0, 0);
  for (const Vec3& o : kWedge) starts.push_back(o - c), goals.push_back(route[2] + Vec3(-(o - c).y(), (o - c).x(), 0));
  const FormationSchedule s = formation_schedule(route, kWedge, starts, goals, {5.0, 30.0, {}, {}});
  // The last 30 m of the route in shape, into the goals at 5 m/s (the pursued path meets the
  // route where the approach begins, heading north to within a degree).
  EXPECT_NEAR(s.end_s() - s.knots_s[s.final_knot], 30.0 / 5.0, 1e-2);
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_NEAR((s.slots[i][s.final_knot] - goals[i]).norm(), 30.0, 0.1);
    EXPECT_NEAR((s.at(i, s.end_s() - 0.1) - goals[i]).norm(), 0.5, 1e-2);  // still moving in
  }
}

TEST(FormationSchedule, AColumnTurningRoundNeverRunsThroughItself) {
  // East, then back west: a column of three turns 180 deg about the corner.
  const std::vector<Vec3> column{{0, 0, 0}, {-6, 0, 0}, {-12, 0, 0}};
  const std::vector<Vec3> route{{0, 0, 0}, {100, 0, 0}, {100, 1e-9, 0}, {0, 1e-9, 0}};
  std::vector<Vec3> starts, goals;
  for (const Vec3& o : column) starts.push_back(Vec3(6, 0, 0) + o), goals.push_back(Vec3(-6, 0, 0) - o);
  const FormationSchedule s = formation_schedule(route, column, starts, goals, {5.0, 0.0, {}, {}});
  for (std::size_t k = 0; k + 1 < s.knots_s.size(); ++k)
    for (std::size_t i = 0; i < 3; ++i)
      for (std::size_t j = i + 1; j < 3; ++j)
        EXPECT_GE(schedule_gap_m(s, i, j, k), 6.0 * std::cos(M_PI / 18.0) - 1e-9) << k;
}

Scenario crossing(bool with_obstacle) {
  Scenario sc;
  sc.name = "formation_test";
  WorldSpec ws;
  ws.bounds = Aabb{Vec3(0, 0, 0), Vec3(300, 120, 0)};
  if (with_obstacle) ws.moving.push_back(MovingObstacle{"crosser", 2.0, Vec3(150, 0, 0), Vec3(0, 2, 0)});
  sc.world = World(std::move(ws));
  const std::vector<Vec3> starts{{20, 60, 0}, {14, 64, 0}, {14, 56, 0}};
  for (std::size_t i = 0; i < 3; ++i) {
    UavSpec u;
    u.id = "u" + std::to_string(i + 1);
    u.start = starts[i];
    u.goal = starts[i] + Vec3(250, 0, 0);
    u.radius_m = 0.5;
    u.speed = {0, 5, 5};
    u.sensor_range_m = 20;
    sc.uavs.push_back(u);
  }
  sc.mission.type = "formation";
  sc.mission.separation_m = 2;
  sc.mission.edit_section<FormationSection>().shape = kWedge;
  sc.planner.algorithm = "aco_voronoi";
  return sc;
}

TEST(FormationMission, LeavesItsSlotToAvoidAndReformsWithOneEta) {
  const Scenario sc = crossing(true);
  MissionOptions opt;
  const Plan p = plan_mission(sc, opt);
  ASSERT_EQ(p.status, Status::solved) << p.uavs[0].message << " | " << p.uavs[1].message << " | " << p.uavs[2].message;
  for (std::size_t i = 0; i < 3; ++i)
    for (std::size_t j = i + 1; j < 3; ++j)
      EXPECT_GE(closest_approach(p.uavs[i].trajectory, p.uavs[j].trajectory).distance_m, 2.0);
  ASSERT_TRUE(p.formation);
  ASSERT_FALSE(p.formation->breaks.empty());  // the crosser meets the wedge at about x = 150
  double last_reform = 0.0;
  for (const auto& b : p.formation->breaks) {
    EXPECT_LT(b.from_s, b.to_s);
    EXPECT_LT(b.to_s, p.formation->eta_s);
    last_reform = std::max(last_reform, b.to_s);
  }
  // Re-formed: once the last break ends they fly the shape again (the wedge's distances).
  const double t = last_reform + 1.0;
  const Vec3 a = position_at(p.uavs[0].trajectory, t), b = position_at(p.uavs[1].trajectory, t),
             c = position_at(p.uavs[2].trajectory, t);
  EXPECT_NEAR((a - b).norm(), std::hypot(5.0, 5.0), 1e-6);
  EXPECT_NEAR((b - c).norm(), 10.0, 1e-6);
  // One ETA: they arrive together (each at its goal to stay, within arrival_tolerance_s of the
  // last), none waiting at its goal for the others; never faster than V_max.
  ASSERT_TRUE(p.formation->arrival_spread_s);
  EXPECT_LE(*p.formation->arrival_spread_s, formation_section(sc).arrival_tolerance_s);
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_LE(p.uavs[i].arrival_s, p.formation->eta_s);
    EXPECT_GE(p.uavs[i].arrival_s, p.formation->eta_s - formation_section(sc).arrival_tolerance_s);
    EXPECT_GT(p.uavs[i].arrival_s, p.uavs[i].trajectory.back().t_s - 1.0) << "waited at its goal";
    EXPECT_NEAR((p.uavs[i].trajectory.back().p - *sc.uavs[i].goal).norm(), 0.0, 1e-6);
    const Trajectory& tr = p.uavs[i].trajectory;
    for (std::size_t k = 1; k < tr.size(); ++k)
      if (tr[k].t_s > tr[k - 1].t_s) {
        EXPECT_LE((tr[k].p - tr[k - 1].p).norm() / (tr[k].t_s - tr[k - 1].t_s), 5.0 + 1e-6);
      }
  }
}

TEST(FormationMission, WithNothingToAvoidTheShapeIsNeverBroken) {
  const Plan p = plan_mission(crossing(false), {});
  ASSERT_EQ(p.status, Status::solved);
  ASSERT_TRUE(p.formation);
  EXPECT_TRUE(p.formation->breaks.empty());
  // Straight east at 5 m/s: 250 m in 50 s once formed.
  EXPECT_NEAR(p.formation->eta_s, 50.0 + p.formation->phases.front().end_s, 1.0 + 1e-9);
}

}  // namespace
}  // namespace uavplan
