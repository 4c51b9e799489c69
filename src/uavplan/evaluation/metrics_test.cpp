#include "uavplan/evaluation/metrics.h"

#include <gtest/gtest.h>

namespace uavplan {
namespace {

TEST(Metrics, P3ScoreOfAStraightAndABentRoute) {
  WorldSpec ws;
  ws.bounds = Aabb{Vec3(0, 0, 0), Vec3(20, 20, 0)};
  ws.obstacles.push_back(Sphere{Vec3(5, 8, 0), 1.0});
  const World w(std::move(ws));
  const std::vector<Vec3> straight{{0, 0, 0}, {5, 0, 0}, {10, 0, 0}};
  const P3Score s = p3_score(straight, w);
  EXPECT_DOUBLE_EQ(s.y1, 10.0);
  EXPECT_DOUBLE_EQ(s.s1, 1.0);
  EXPECT_NEAR(s.y3, 0.0, 1e-12);  // theta = pi
  const double y2 = 1.0 / (std::hypot(5.0, 8.0) - 1) + 1.0 / 7.0 + 1.0 / (std::hypot(5.0, 8.0) - 1);
  EXPECT_NEAR(s.y2, y2, 1e-12);
  EXPECT_NEAR(s.s2, y2 / 3, 1e-12);
  const std::vector<Vec3> bent{{0, 0, 0}, {5, 5, 0}, {10, 0, 0}};
  const P3Score b = p3_score(bent, w);
  EXPECT_NEAR(b.y3, 1.0 / (kPi / 2) - 1.0 / kPi, 1e-12);
  EXPECT_GT(b.sc, s.sc);
}

TEST(Metrics, P1CostWeighsThreatAndLength) {
  WorldSpec ws;
  ws.bounds = Aabb{Vec3(0, 0, 0), Vec3(10, 10, 10)};
  ws.radars.push_back({Vec3(3, 1, 0), 1.0});
  const World w(std::move(ws));
  const std::vector<Vec3> pts{{0, 0, 0}, {6, 0, 0}};
  EXPECT_NEAR(p1_route_cost(pts, w), 0.5 * w.p1_threat_cost(pts[0], pts[1]) + 0.5 * 6.0, 1e-12);
}

}  // namespace
}  // namespace uavplan
