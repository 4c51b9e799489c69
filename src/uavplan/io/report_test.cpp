#include "uavplan/io/report.h"

#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "uavplan/io/io_test_fixtures.h"

namespace uavplan {
namespace {

using test::scenario_with;

Plan report_plan() { return test::plan_of({test::sample_uav()}); }

TEST(Report, PageCarriesDataAndViewer) {
  const Scenario sc = scenario_with({Box{Vec3(300, 300, 0), Vec3(320, 320, 60)}});
  Plan plan = report_plan();
  plan.uavs[0].message = "</script><b>";
  const auto data = nlohmann::json::parse(report_data_json(sc, plan, {}));
  EXPECT_EQ(data["uavs"][0]["trajectory"].size(), 5u);
  EXPECT_DOUBLE_EQ(data["t_end_s"].get<double>(), 34.0);
  ASSERT_GT(data["series"]["t_s"].size(), 2u);
  // Speed: 0 while holding, 5 m/s east, 10 m/s north.
  const auto& t = data["series"]["t_s"];
  const auto& v = data["series"]["uavs"][0]["speed_mps"];
  for (std::size_t i = 0; i < t.size(); ++i) {
    const double ti = t[i].get<double>();
    const double vi = v[i].get<double>();
    const double expected = ti < 3.9 ? 0.0 : ti > 4.1 && ti < 23.9 ? 5.0 : ti > 24.1 && ti < 33.9 ? 10.0 : vi;
    EXPECT_NEAR(vi, expected, 1e-9) << "t = " << ti;
  }
  const std::string html = report_html(sc, plan, {});
  EXPECT_EQ(html.find("</script><b>"), std::string::npos);  // data cannot close its element
  EXPECT_NE(html.find("uavplan-data"), std::string::npos);
  EXPECT_GT(html.size(), 100'000u);  // the bundled viewer is inline
}

TEST(Report, MetricsAreThoseOfTheTrajectoriesShown) {
  const Scenario sc = scenario_with({Box{Vec3(300, 300, 0), Vec3(320, 320, 60)}});
  Plan plan = report_plan();
  plan.uavs[0].metrics = {{"length_m", 1.0}};  // a plan file saying something else
  const auto data = nlohmann::json::parse(report_data_json(sc, plan, {}));
  const auto& m = data["uavs"][0]["metrics"];
  EXPECT_DOUBLE_EQ(m["length_m"].get<double>(), 200.0);
  EXPECT_DOUBLE_EQ(m["max_turn_deg"].get<double>(), 90.0);
  EXPECT_DOUBLE_EQ(m["min_agl_m"].get<double>(), 10.0);
  EXPECT_TRUE(m.contains("min_clearance_m"));
  // The table's gap is the body's: the centre's distance less the radius.
  EXPECT_DOUBLE_EQ(m["min_gap_m"].get<double>(), m["min_clearance_m"].get<double>() - sc.uavs[0].radius_m);
  EXPECT_TRUE(data["metrics"].contains("total_length_m"));
}

TEST(Report, HeightProfileFollowsTheGroundUnderTheRoute) {
  Scenario sc = scenario_with();
  WorldSpec w = sc.world.spec();
  // Terrain 4 m high for x in [50, 100), 0 elsewhere (cells of 50 m).
  w.terrain = TerrainGrid(Vec2(0, 0), 50.0, 3, 3, {0, 4, 0, 0, 4, 0, 0, 4, 0});
  sc.world = World(std::move(w));
  const auto data = nlohmann::json::parse(report_data_json(sc, report_plan(), {}));
  const auto& p = data["uavs"][0]["profile"];
  const auto& s = p["s_m"];
  ASSERT_GE(s.size(), 400u);
  EXPECT_DOUBLE_EQ(s.back().get<double>(), 200.0);
  for (std::size_t k = 0; k < s.size(); ++k) {
    const double d = s[k].get<double>();
    if (k) {
      EXPECT_GE(d, s[k - 1].get<double>());
    }
    EXPECT_DOUBLE_EQ(p["z_m"][k].get<double>(), 10.0);
    const double x = d <= 100.0 ? d : 100.0;  // east, then north along x = 100
    if (std::abs(x - 50.0) > 0.6 && std::abs(x - 100.0) > 0.6) {
      EXPECT_DOUBLE_EQ(p["ground_m"][k].get<double>(), x > 50.0 && x < 100.0 ? 4.0 : 0.0) << "s = " << d;
    }
  }
  // A flat world has no height profile.
  Scenario flat = scenario_with();
  flat.world = World(WorldSpec{Aabb{Vec3(0, 0, 10), Vec3(1000, 1000, 10)}, {}, {}, {}, {}, {}, {}});
  EXPECT_TRUE(nlohmann::json::parse(report_data_json(flat, report_plan(), {}))["uavs"][0]["profile"].is_null());
}

TEST(Report, RadarShellsWhereTheThreatCostFallsToTheFuelCost) {
  Scenario sc = scenario_with();
  WorldSpec w = sc.world.spec();
  w.radars = {Radar{Vec3(500, 500, 0), 1e4}};
  sc.world = World(std::move(w));
  const auto data = nlohmann::json::parse(report_data_json(sc, report_plan(), {}));
  const auto& shells = data["threats"][0]["shells_m"];
  ASSERT_EQ(shells.size(), 3u);
  EXPECT_NEAR(shells[0].get<double>(), 10.0, 1e-6);  // 1e4 / d^4 = 1
  EXPECT_NEAR(shells[2].get<double>(), std::pow(1e6, 0.25), 1e-6);
}

// A phased mission (P5): its phases for the charts' bands, and the spacing chart by the
// airfield's rule: nothing while both UAVs are on the ground, nothing once one has gone.
TEST(Report, PhasesAndTheSpacingInTheAir) {
  Scenario sc = scenario_with();
  sc.mission.type = "formation_mission";
  sc.mission.airfield = Airfield{Vec3(0, 0, 0), 0.0, 1000.0};
  UavSpec b = sc.uavs[0];
  b.id = "b";
  sc.uavs.push_back(b);
  UavPlan ua = test::sample_uav(), ub = test::sample_uav();
  ub.id = "b";
  ua.trajectory = {{0.0, Vec3(0, 0, 0)}, {10.0, Vec3(0, 0, 0)}, {20.0, Vec3(0, 0, 50)}, {40.0, Vec3(0, 0, 50)}};
  ub.trajectory = {{0.0, Vec3(30, 0, 0)}, {10.0, Vec3(30, 0, 0)}, {20.0, Vec3(30, 0, 50)}, {30.0, Vec3(30, 0, 50)}};
  Plan plan = test::plan_of({ua, ub});
  plan.formation = FormationLog{};
  plan.formation->phases = {{"form_up", 12.0}, {"mission", 25.0}, {"landing", 40.0}};
  const auto data = nlohmann::json::parse(report_data_json(sc, plan, {}));
  const auto& ph = data["phases"];
  ASSERT_EQ(ph.size(), 3u);
  EXPECT_EQ(ph[1]["name"], "mission");
  EXPECT_DOUBLE_EQ(ph[1]["start_s"].get<double>(), 12.0);
  EXPECT_DOUBLE_EQ(ph[1]["end_s"].get<double>(), 25.0);
  const auto& t = data["series"]["t_s"];
  const auto& near = data["series"]["uavs"][0]["nearest_m"];
  for (std::size_t i = 0; i < t.size(); ++i) {
    const double ti = t[i].get<double>();
    if (ti < 11.0 || ti > 30.5) {
      EXPECT_TRUE(near[i].is_null()) << "t = " << ti;
    } else if (ti > 19.0 && ti < 29.5) {
      EXPECT_NEAR(near[i].get<double>(), 30.0, 1e-9) << "t = " << ti;
    }
  }
  // Other missions: no phases.
  EXPECT_TRUE(nlohmann::json::parse(report_data_json(scenario_with(), report_plan(), {}))["phases"].empty());
}

}  // namespace
}  // namespace uavplan
