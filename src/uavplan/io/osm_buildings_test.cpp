#include "uavplan/io/osm_buildings.h"

#include <gtest/gtest.h>

#include <unistd.h>
#include <filesystem>
#include <fstream>

#include "uavplan/core/geometry.h"
#include "uavplan/io/files.h"
#include "uavplan/io/input_error.h"
#include "uavplan/io/scenario_io.h"

namespace uavplan {
namespace {

TEST(OsmLength, MetresFeetAndInches) {
  EXPECT_DOUBLE_EQ(*parse_osm_length_m("12"), 12.0);
  EXPECT_DOUBLE_EQ(*parse_osm_length_m(" 12.5 "), 12.5);
  EXPECT_DOUBLE_EQ(*parse_osm_length_m("12 m"), 12.0);
  EXPECT_DOUBLE_EQ(*parse_osm_length_m("7metres"), 7.0);
  EXPECT_DOUBLE_EQ(*parse_osm_length_m("40 ft"), 40 * 0.3048);
  EXPECT_DOUBLE_EQ(*parse_osm_length_m("40'"), 40 * 0.3048);
  EXPECT_DOUBLE_EQ(*parse_osm_length_m("12'6\""), 12 * 0.3048 + 6 * 0.0254);
  for (const char* bad : {"", "tall", "-3", "12 km", "10-12", "12,5", "1e3", "nan", "12'6"})
    EXPECT_FALSE(parse_osm_length_m(bad).has_value()) << bad;
}

// Footprints around (lat 40, lon -74): on the WGS84 ellipsoid 0.0001 deg is 8.539 m east and
// 11.104 m north there.
const std::string kCollection = R"({"type": "FeatureCollection", "features": [
  {"type": "Feature", "properties": {"building": "yes", "height": "12 m"},
   "geometry": {"type": "Polygon", "coordinates": [[[-74.0, 40.0], [-73.9999, 40.0], [-73.9999, 40.0001], [-74.0, 40.0001], [-74.0, 40.0]],
                                                  [[-73.99996, 40.00004], [-73.99994, 40.00004], [-73.99994, 40.00006], [-73.99996, 40.00004]]]}},
  {"type": "Feature", "properties": {"building:levels": "4", "roof:levels": 1},
   "geometry": {"type": "MultiPolygon", "coordinates": [[[[-74.001, 40.0], [-74.0009, 40.0], [-74.0009, 40.0001], [-74.001, 40.0]]],
                                                       [[[-74.002, 40.0], [-74.0019, 40.0], [-74.0019, 40.0001], [-74.002, 40.0]]]]}},
  {"type": "Feature", "properties": {"building": "shed", "height": "unknown"},
   "geometry": {"type": "Polygon", "coordinates": [[[-74.0, 40.001], [-73.9999, 40.001], [-73.9999, 40.0011], [-74.0, 40.001]]]}},
  {"type": "Feature", "properties": {"building:part": "yes", "height": 30, "min_height": 20},
   "geometry": {"type": "Polygon", "coordinates": [[[-74.0, 40.002], [-73.9999, 40.002], [-73.9999, 40.0021], [-74.0, 40.002]]]}},
  {"type": "Feature", "properties": {"entrance": "main"}, "geometry": {"type": "Point", "coordinates": [-74.0, 40.0]}},
  {"type": "Feature", "properties": {"height": 5}, "geometry": {"type": "Polygon", "coordinates": [[[-74.0, 40.0], [-73.9999, 40.0], [-74.0, 40.0]]]}},
  {"type": "Feature", "properties": {}, "geometry": null}
]})";

TEST(OsmBuildings, HeightsLevelsDefaultsAndParts) {
  const GeoFrame frame(GeoOrigin{40.0, -74.0, 10.0});
  BuildingOptions opt;
  opt.level_height_m = 3.5;
  opt.default_height_m = 9.0;
  BuildingCounts counts;
  const std::vector<Prism> ps = buildings_from_geojson(kCollection, "c.geojson", frame, opt, &counts);
  ASSERT_EQ(ps.size(), 5u);
  EXPECT_EQ(counts.from_height, 3);  // the zero-area footprint has a height but is skipped
  EXPECT_EQ(counts.from_levels, 1);
  EXPECT_EQ(counts.defaulted, 1);
  EXPECT_EQ(counts.skipped, 3);  // a point, a zero-area ring, a null geometry

  // "12 m", the outer ring only (the courtyard is filled), closing vertex dropped.
  EXPECT_DOUBLE_EQ(ps[0].z_min_m, 0.0);
  EXPECT_DOUBLE_EQ(ps[0].z_max_m, 12.0);
  ASSERT_EQ(ps[0].polygon.size(), 4u);
  EXPECT_NEAR(ps[0].polygon[0].x(), 0.0, 1e-6);
  EXPECT_NEAR(ps[0].polygon[0].y(), 0.0, 1e-6);
  EXPECT_NEAR(ps[0].polygon[2].x(), 8.539, 0.002);
  EXPECT_NEAR(ps[0].polygon[2].y(), 11.104, 0.002);
  // (4 + 1 roof) levels of 3.5 m, one prism per polygon of the MultiPolygon, west of the origin.
  EXPECT_DOUBLE_EQ(ps[1].z_max_m, 17.5);
  EXPECT_DOUBLE_EQ(ps[2].z_max_m, 17.5);
  EXPECT_NEAR(ps[2].polygon[0].x(), -170.79, 0.01);
  // An unreadable height falls back to the default.
  EXPECT_DOUBLE_EQ(ps[3].z_max_m, 9.0);
  // A building part from min_height to height.
  EXPECT_DOUBLE_EQ(ps[4].z_min_m, 20.0);
  EXPECT_DOUBLE_EQ(ps[4].z_max_m, 30.0);
}

TEST(OsmBuildings, BadInputNamesTheFileAndFeature) {
  const GeoFrame frame(GeoOrigin{40.0, -74.0, 0.0});
  const auto message = [&](const std::string& text) {
    try {
      buildings_from_geojson(text, "b.geojson", frame, {});
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message("{\"type\": ").find("b.geojson:1: not valid JSON"), std::string::npos);
  EXPECT_NE(message("[1, 2]").find("expected a GeoJSON object"), std::string::npos);
  // Projected metres where degrees belong (a common export mistake).
  const std::string projected = R"({"type": "FeatureCollection", "features": [{"type": "Feature", "properties": {},
    "geometry": {"type": "Polygon", "coordinates": [[[583000, 4507000], [583010, 4507000], [583010, 4507010], [583000, 4507000]]]}}]})";
  const std::string m = message(projected);
  EXPECT_NE(m.find("features[0].geometry.coordinates[0][0]"), std::string::npos) << m;
  EXPECT_NE(m.find("WGS84"), std::string::npos) << m;
  const std::string mercator =
      R"({"type": "FeatureCollection", "crs": {"type": "name", "properties": {"name": "urn:ogc:def:crs:EPSG::3857"}}, "features": []})";
  EXPECT_NE(message(mercator).find("crs"), std::string::npos);
  EXPECT_NE(
      message(R"({"type": "FeatureCollection", "features": [{"type": "Feature", "geometry": {"type": "Polygon"}}]})")
          .find("coordinates"),
      std::string::npos);
  // A part whose bottom is above its top is a tagging error, named (it was dropped without a word).
  const std::string upside_down = R"({"type": "FeatureCollection", "features": [{"type": "Feature",
    "properties": {"height": 20, "min_height": 30},
    "geometry": {"type": "Polygon", "coordinates": [[[-74.0, 40.0], [-73.9999, 40.0], [-73.9999, 40.0001], [-74.0, 40.0]]]}}]})";
  const std::string u = message(upside_down);
  EXPECT_NE(u.find("features[0]"), std::string::npos) << u;
  EXPECT_NE(u.find("not below its top"), std::string::npos) << u;
}

// The bundled OpenStreetMap extract: 15 New York buildings, every height tagged in metres.
TEST(OsmBuildings, NewYorkExtract) {
  const std::string path = std::string(UAVPLAN_SOURCE_DIR) + "/scenarios/data/ny.geojson";
  const GeoFrame frame(GeoOrigin{40.69219, -73.89658, 20.0});
  BuildingCounts counts;
  const std::vector<Prism> ps = buildings_from_geojson(read_text_file(path), path, frame, {}, &counts);
  ASSERT_EQ(ps.size(), 15u);
  EXPECT_EQ(counts.from_height, 15);
  double lo = 1e9, hi = 0, extent = 0;
  for (const Prism& p : ps) {
    lo = std::min(lo, p.z_max_m);
    hi = std::max(hi, p.z_max_m);
    // Footprints are real houses and garages: a few to a few hundred square metres.
    const double area = std::abs(polygon_signed_area(p.polygon));
    EXPECT_GT(area, 10.0);
    EXPECT_LT(area, 1000.0);
    for (const Vec2& v : p.polygon) extent = std::max(extent, v.norm());
  }
  EXPECT_DOUBLE_EQ(lo, 3.2);
  EXPECT_DOUBLE_EQ(hi, 11.7);
  EXPECT_LT(extent, 80.0);  // the block spans about 100 x 75 m around its centre
}

class ScenarioBuildings : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() / ("uavplan_buildings_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir_ / "data");
    std::ofstream(dir_ / "data" / "c.geojson") << kCollection;
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  std::string write(const std::string& yaml) const {
    const std::string p = (dir_ / "s.yaml").string();
    std::ofstream(p) << yaml;
    return p;
  }
  std::filesystem::path dir_;
};

TEST_F(ScenarioBuildings, LoadsRelativeToTheScenarioAndClipsToBounds) {
  const std::string head =
      "version: 1\norigin: {lat: 40.0, lon: -74.0}\nworld:\n  bounds: {min: [-100, -20, 0], max: [100, 150, 60]}\n";
  const std::string tail = "uavs: [{id: u, start: [50, -10, 5], goal: [-50, -10, 5]}]\n";
  // The MultiPolygon lies 85 and 171 m west: only its first prism is within x >= -100; the
  // building part 222 m north is outside y <= 150.
  const Scenario a = load_scenario(write(head + "  buildings: data/c.geojson\n" + tail));
  EXPECT_EQ(a.world.obstacles().size(), 3u);
  const Scenario b =
      load_scenario(write(head + "  buildings: [{file: data/c.geojson, level_height: 2, default_height: 4}]\n" + tail));
  ASSERT_EQ(b.world.obstacles().size(), 3u);
  EXPECT_DOUBLE_EQ(bounding_box(b.world.obstacles()[1]).max.z(), 10.0);  // (4 + 1) x 2 m
  EXPECT_DOUBLE_EQ(bounding_box(b.world.obstacles()[2]).max.z(), 4.0);   // the default
  EXPECT_TRUE(b.world.segment_collides(Vec3(-20, 5, 5), Vec3(20, 5, 5), 0.1));
  EXPECT_FALSE(b.world.segment_collides(Vec3(-20, 5, 13), Vec3(20, 5, 13), 0.1));  // over the 12 m roof
}

TEST_F(ScenarioBuildings, ErrorsNameTheScenarioKey) {
  const auto message = [&](const std::string& yaml) {
    try {
      load_scenario(write(yaml));
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  const std::string world = "world:\n  bounds: {min: [-100, -20, 0], max: [100, 150, 60]}\n";
  const std::string uav = "uavs: [{id: u, start: [50, -10, 5]}]\n";
  EXPECT_NE(message("version: 1\n" + world + "  buildings: data/c.geojson\n" + uav)
                .find("world.buildings: placing lon/lat footprints needs the scenario's 'origin'"),
            std::string::npos);
  const std::string origin = "version: 1\norigin: {lat: 40.0, lon: -74.0}\n";
  EXPECT_NE(message(origin + world + "  buildings: data/missing.geojson\n" + uav)
                .find("world.buildings: cannot read the buildings file"),
            std::string::npos);
  EXPECT_NE(
      message(origin + world + "  buildings: {file: data/c.geojson, levels: 3}\n" + uav).find("unknown key 'levels'"),
      std::string::npos);
}

}  // namespace
}  // namespace uavplan
