#include "uavplan/io/export.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "uavplan/io/geo.h"
#include "uavplan/io/report.h"

namespace uavplan {
namespace {

Scenario scenario_with(std::vector<Obstacle> obstacles = {}) {
  Scenario sc;
  sc.name = "t";
  sc.origin = GeoOrigin{47.3977, 8.5456, 488.0};
  WorldSpec w;
  w.bounds = Aabb{Vec3(0, 0, 0), Vec3(1000, 1000, 100)};
  w.obstacles = std::move(obstacles);
  sc.world = World(std::move(w));
  UavSpec u;
  u.id = "a/1";
  u.start = Vec3(0, 0, 10);
  u.speed.cruise_mps = 5.0;
  sc.uavs.push_back(u);
  return sc;
}

// Holds 4 s at the start, flies east 100 m in two collinear samples at 5 m/s, turns north and
// flies 100 m at 10 m/s.
UavPlan sample_uav() {
  UavPlan u;
  u.id = "a/1";
  u.status = Status::solved;
  u.trajectory = {{0.0, Vec3(0, 0, 10)},   {4.0, Vec3(0, 0, 10)},    {14.0, Vec3(50, 0, 10)},
                  {24.0, Vec3(100, 0, 10)}, {34.0, Vec3(100, 100, 10)}};
  return u;
}

TEST(GeoFrame, RoundTripAndKnownScale) {
  const GeoFrame f(GeoOrigin{47.3977, 8.5456, 488.0});
  const LatLonAlt o = f.to_wgs84(Vec3::Zero());
  EXPECT_NEAR(o.lat_deg, 47.3977, 1e-12);
  EXPECT_NEAR(o.lon_deg, 8.5456, 1e-12);
  EXPECT_NEAR(o.alt_m, 488.0, 1e-9);
  // One kilometre north at 47.4 deg N is 1/111.18 of a degree of latitude (WGS84 meridian arc).
  const LatLonAlt n = f.to_wgs84(Vec3(0, 1000, 0));
  EXPECT_NEAR((n.lat_deg - 47.3977) * 111'180.0, 1000.0, 1.0);
  EXPECT_NEAR(n.lon_deg, 8.5456, 1e-9);
  const LatLonAlt e = f.to_wgs84(Vec3(1000, 0, 0));
  EXPECT_GT(e.lon_deg, 8.5456);
  const Vec3 p(123.4, -567.8, 42.0);
  const LatLonAlt g = f.to_wgs84(p);
  EXPECT_LT((f.to_local(g.lat_deg, g.lon_deg, g.alt_m) - p).norm(), 1e-6);
}

TEST(GeoFrame, AltitudeIsOriginPlusLocalHeightEvenFarAway) {
  // P4's world reaches 65 km from its origin: the tangent plane is 330 m above the datum there,
  // but a route at z = 100 m flies at origin.alt + 100 m.
  const GeoFrame f(GeoOrigin{30.0, 110.0, 500.0});
  for (const Vec3& p : {Vec3(65000, 0, 100), Vec3(-40000, 50000, 100), Vec3(2000, 0, 0)}) {
    const LatLonAlt g = f.to_wgs84(p);
    EXPECT_DOUBLE_EQ(g.alt_m, 500.0 + p.z());
    EXPECT_LT((f.to_local(g.lat_deg, g.lon_deg, g.alt_m) - p).norm(), 1e-6) << p.transpose();
  }
  // Horizontally: 65 km east is 65 km along the ground (to within the tangent plane's 1 m).
  const LatLonAlt e = f.to_wgs84(Vec3(65000, 0, 100));
  EXPECT_NEAR((e.lon_deg - 110.0) * 111'320.0 * std::cos(30.0 * kPi / 180.0), 65000.0, 150.0);
}

TEST(Export, MissionFollowsTheTrajectory) {
  const Scenario sc = scenario_with();
  const auto items = mission_items(sc, sample_uav(), {});
  std::vector<int> commands;
  for (const auto& it : items) commands.push_back(it.command);
  // takeoff, the 4 s hold, one waypoint for the collinear east legs, the speed change, north, land.
  EXPECT_EQ(commands, (std::vector<int>{kCmdTakeoff, kCmdLoiterTime, kCmdWaypoint, kCmdChangeSpeed, kCmdWaypoint, kCmdLand}));
  EXPECT_DOUBLE_EQ(items[1].params[0], 4.0);
  EXPECT_DOUBLE_EQ(items[3].params[1], 10.0);
  EXPECT_NEAR(items[0].params[6], 10.0, 1e-3);  // takeoff to the start's height above home
  EXPECT_NEAR(items[2].params[3], 90.0, 1e-6);  // east is compass yaw 90
  EXPECT_NEAR(items[4].params[3], 0.0, 1e-6);   // north is 0
  const GeoFrame f(*sc.origin);
  const LatLonAlt end = f.to_wgs84(Vec3(100, 100, 10));
  EXPECT_NEAR(items[4].params[4], end.lat_deg, 1e-9);
  EXPECT_NEAR(items[4].params[5], end.lon_deg, 1e-9);
  for (const auto& it : items) EXPECT_EQ(it.frame, kFrameGlobalRelativeAlt);
}

TEST(Export, ReturnOrNothingAtTheEnd) {
  const Scenario sc = scenario_with();
  ExportOptions opt;
  opt.end = MissionEnd::rtl;
  EXPECT_EQ(mission_items(sc, sample_uav(), opt).back().command, kCmdReturn);
  opt.end = MissionEnd::none;
  EXPECT_EQ(mission_items(sc, sample_uav(), opt).back().command, kCmdWaypoint);
}

TEST(Export, QgcPlanFollowsTheLoaderRules) {
  // A cylinder reaching above the flight height becomes an exclusion circle, a low box the UAV
  // flies over does not become a fence, a tall box becomes an exclusion polygon.
  const Scenario sc = scenario_with({Cylinder{Vec2(500, 500), 20, 0, 100}, Box{Vec3(200, 200, 0), Vec3(220, 220, 5)},
                                     Box{Vec3(300, 300, 0), Vec3(320, 320, 60)}});
  ExportOptions opt;
  opt.firmware = Firmware::ardupilot;
  const auto j = nlohmann::json::parse(qgc_plan_json(sc, sample_uav(), opt));
  EXPECT_EQ(j["fileType"], "Plan");
  EXPECT_EQ(j["version"], 1);
  EXPECT_EQ(j["mission"]["version"], 2);
  EXPECT_EQ(j["mission"]["firmwareType"], 3);
  EXPECT_EQ(j["mission"]["plannedHomePosition"].size(), 3u);
  for (const auto& it : j["mission"]["items"]) {
    ASSERT_EQ(it["params"].size(), 7u);
    for (const auto& p : it["params"]) EXPECT_TRUE(p.is_number());
    EXPECT_TRUE(it["AMSLAltAboveTerrain"].is_number());
    EXPECT_TRUE(it["Altitude"].is_number());
    EXPECT_TRUE(it["AltitudeMode"].is_number());
  }
  EXPECT_EQ(j["geoFence"]["version"], 2);
  EXPECT_EQ(j["geoFence"]["circles"].size(), 1u);
  ASSERT_EQ(j["geoFence"]["polygons"].size(), 2u);  // bounds (inclusion) and the tall box
  EXPECT_EQ(j["geoFence"]["polygons"][0]["inclusion"], true);
  EXPECT_EQ(j["geoFence"]["polygons"][1]["inclusion"], false);
  EXPECT_EQ(j["rallyPoints"]["version"], 2);
}

TEST(Export, WplRowsMatchTheMission) {
  const Scenario sc = scenario_with();
  const std::string text = qgc_wpl(sc, sample_uav(), {});
  EXPECT_EQ(text.rfind("QGC WPL 110\n0\t1\t0\t16\t", 0), 0u);
  EXPECT_EQ(text.find('\r'), std::string::npos);
  std::size_t rows = 0;
  for (char c : text) rows += c == '\n';
  EXPECT_EQ(rows, 1u + 1u + mission_items(sc, sample_uav(), {}).size());  // header, home, items
}

TEST(Export, GeoJsonIsLonLatAlt) {
  Scenario sc = scenario_with({Prism{{{0, 0}, {0, 10}, {10, 10}, {10, 0}}, 0, 5}});  // clockwise
  Plan plan;
  plan.uavs = {sample_uav()};
  const auto j = nlohmann::json::parse(plan_geojson(sc, plan));
  const auto& route = j["features"][0];
  EXPECT_EQ(route["geometry"]["type"], "LineString");
  EXPECT_EQ(route["geometry"]["coordinates"].size(), 4u);  // the hold collapses
  EXPECT_NEAR(route["geometry"]["coordinates"][0][0].get<double>(), 8.5456, 1e-9);  // lon first
  EXPECT_NEAR(route["geometry"]["coordinates"][0][1].get<double>(), 47.3977, 1e-9);
  const auto& ring = j["features"][1]["geometry"]["coordinates"][0];
  ASSERT_EQ(ring.size(), 5u);
  EXPECT_EQ(ring.front(), ring.back());
  double area2 = 0;
  for (std::size_t i = 0; i + 1 < ring.size(); ++i)
    area2 += ring[i][0].get<double>() * ring[i + 1][1].get<double>() - ring[i + 1][0].get<double>() * ring[i][1].get<double>();
  EXPECT_GT(area2, 0.0);  // counter-clockwise although given clockwise
}

TEST(Export, ClearErrors) {
  Scenario sc = scenario_with();
  Plan plan;
  plan.uavs = {sample_uav()};
  sc.origin.reset();
  EXPECT_THROW(export_plan(sc, plan, ExportFormat::qgc), ExportError);
  sc = scenario_with();
  plan.uavs[0].id = "ghost";
  EXPECT_THROW(export_plan(sc, plan, ExportFormat::qgc), ExportError);
}

TEST(Export, FileNamesAreSafeAndDistinct) {
  EXPECT_EQ(file_stem("a/1"), "a_1");
  EXPECT_EQ(file_stem("../x"), "_.._x");
  Scenario sc = scenario_with();
  UavSpec other = sc.uavs[0];
  other.id = "a?1";
  sc.uavs.push_back(other);
  Plan plan;
  plan.uavs = {sample_uav(), sample_uav()};
  plan.uavs[1].id = "a?1";
  const auto files = export_plan(sc, plan, ExportFormat::csv);
  ASSERT_EQ(files.size(), 2u);
  EXPECT_NE(files[0].name, files[1].name);
}

TEST(Report, PageCarriesDataAndViewer) {
  const Scenario sc = scenario_with({Box{Vec3(300, 300, 0), Vec3(320, 320, 60)}});
  Plan plan;
  plan.uavs = {sample_uav()};
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

}  // namespace
}  // namespace uavplan
