#include "uavplan/io/airspace.h"

#include <gtest/gtest.h>

#include <cstdio>

#include "uavplan/io/input_error.h"

namespace uavplan {
namespace {

const Aabb kBounds{Vec3(-500, -500, 0), Vec3(500, 500, 200)};

// A square of 2 * half_m metres about the origin, [lon, lat] corners.
std::string square_lonlat(const GeoFrame& f, double half_m) {
  std::string out = "[";
  const double c[5][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}, {-1, -1}};
  for (int i = 0; i < 5; ++i) {
    const LatLonAlt p = f.to_wgs84(Vec3(c[i][0] * half_m, c[i][1] * half_m, 0));
    char buf[64];
    std::snprintf(buf, sizeof buf, "%s[%.10f, %.10f]", i ? ", " : "", p.lon_deg, p.lat_deg);
    out += buf;
  }
  return out + "]";
}

TEST(Airspace, GeoJsonZoneWithFloorAndCeilingAboveSeaLevel) {
  const GeoFrame f(GeoOrigin{47.3977, 8.5456, 488.0});
  const std::string text = R"({"type": "FeatureCollection", "features": [{"type": "Feature",
    "properties": {"floor_m": 538, "ceiling_m": 638}, "geometry": {"type": "Polygon", "coordinates": [)" +
                           square_lonlat(f, 100) + "]}}]}";
  const Airspace a = read_airspace(text, "zones.geojson", f, kBounds);
  ASSERT_EQ(a.zones.size(), 1u);
  const Prism& p = std::get<Prism>(a.zones[0]);
  EXPECT_NEAR(p.z_min_m, 50.0, 1e-9);  // 538 m AMSL over an origin at 488 m
  EXPECT_NEAR(p.z_max_m, 150.0, 1e-9);
  EXPECT_NEAR(std::abs(polygon_signed_area(p.polygon)), 200.0 * 200.0, 1.0);
  EXPECT_EQ(a.zone_ids[0], "zones.geojson zone 0");
  EXPECT_FALSE(a.inclusion_box);
}

TEST(Airspace, QgcFenceInclusionBoundsAndClosesTheRestOfItsBox) {
  const GeoFrame f(GeoOrigin{47.3977, 8.5456, 488.0});
  // An inclusion circle of 300 m about the origin and an exclusion circle of 20 m.
  const std::string text = R"({"geoFence": {"circles": [
    {"inclusion": true, "circle": {"center": [47.3977, 8.5456], "radius": 300}},
    {"inclusion": false, "circle": {"center": [47.3977, 8.5456], "radius": 20}}]}})";
  const Airspace a = read_airspace(text, "fence.plan", f, kBounds);
  ASSERT_TRUE(a.inclusion_box);
  EXPECT_NEAR(a.inclusion_box->max.x(), 300.0, 1e-6);
  EXPECT_NEAR(a.inclusion_box->min.y(), -300.0, 1.0);
  // Outside the inscribed 64-gon in the box is closed, the corners and the rim between sides.
  double closed = 0.0;
  int cylinders = 0;
  for (const Obstacle& o : a.zones) {
    if (const Prism* p = std::get_if<Prism>(&o)) closed += std::abs(polygon_signed_area(p->polygon));
    cylinders += std::holds_alternative<Cylinder>(o);
  }
  const double gon = 0.5 * 64 * 300.0 * 300.0 * std::sin(2 * kPi / 64);
  EXPECT_NEAR(closed, 600.0 * 600.0 - gon, 1.0);
  EXPECT_EQ(cylinders, 1);
  EXPECT_THROW(read_airspace(R"({"geoFence": {"circles": [
    {"inclusion": true, "circle": {"center": [47.3977, 8.5456], "radius": 300}},
    {"inclusion": true, "circle": {"center": [47.3977, 8.5456], "radius": 200}}]}})",
                             "fence.plan", f, kBounds),
               InputError);
}

// KML through GDAL (issue: real airspace, item 3): a Placemark's polygon with its heights in
// ExtendedData, kept corner for corner for the export's fence.
TEST(Airspace, KmlPolygonsWithFloorAndCeiling) {
  const GeoFrame f(GeoOrigin{47.3977, 8.5456, 488.0});
  std::string coords;
  std::vector<Vec2> latlon;
  const double c[5][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}, {-1, -1}};
  for (const auto& k : c) {
    const LatLonAlt p = f.to_wgs84(Vec3(k[0] * 50, k[1] * 80, 0));
    char buf[80];
    std::snprintf(buf, sizeof buf, "%.10f,%.10f,0 ", p.lon_deg, p.lat_deg);
    coords += buf;
    latlon.emplace_back(p.lat_deg, p.lon_deg);
  }
  const std::string kml = R"(<?xml version="1.0" encoding="UTF-8"?>
<kml xmlns="http://www.opengis.net/kml/2.2"><Document><Placemark><name>helipad</name>
<ExtendedData><Data name="floor_m"><value>500</value></Data><Data name="ceiling_m"><value>600</value></Data></ExtendedData>
<Polygon><outerBoundaryIs><LinearRing><coordinates>)" +
                          coords + R"(</coordinates></LinearRing></outerBoundaryIs></Polygon></Placemark>
<Placemark><name>pin</name><Point><coordinates>8.5456,47.3977,0</coordinates></Point></Placemark>
</Document></kml>)";
  const Airspace a = read_airspace(kml, "zones.kml", f, kBounds);
  ASSERT_EQ(a.zones.size(), 1u);  // the point closes nothing
  const Prism& p = std::get<Prism>(a.zones[0]);
  EXPECT_NEAR(p.z_min_m, 12.0, 1e-6);  // 500 m AMSL over 488 m
  EXPECT_NEAR(p.z_max_m, 112.0, 1e-6);
  EXPECT_NEAR(std::abs(polygon_signed_area(p.polygon)), 100.0 * 160.0, 1.0);
  ASSERT_EQ(a.fence.size(), 1u);
  ASSERT_EQ(a.fence[0].polygon_latlon.size(), 4u);  // the closing corner dropped
  for (std::size_t k = 0; k < 4; ++k) EXPECT_NEAR((a.fence[0].polygon_latlon[k] - latlon[k]).norm(), 0.0, 1e-9);
  EXPECT_EQ(a.fence[0].obstacles, std::vector<std::size_t>{0});
  EXPECT_DOUBLE_EQ(*a.fence[0].floor_amsl_m, 500.0);

  try {
    read_airspace("<kml><Document><Placemark>", "broken.kml", f, kBounds);
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("broken.kml"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace uavplan

namespace uavplan {
namespace {

std::string airspace_error(const std::string& text, const std::string& file) {
  const GeoFrame frame(GeoOrigin{46.8, 9.8, 0.0});
  const Aabb bounds{Vec3(-1000, -1000, 0), Vec3(1000, 1000, 500)};
  try {
    read_airspace(text, file, frame, bounds);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

// Values no fence or zone can hold are refused naming the file and the place, never a library's
// message without either; nesting past the JSON cap is refused before anything copies it.
TEST(Airspace, ValuesOutOfTheContractNameTheFileAndPlace) {
  EXPECT_NE(airspace_error(R"({"geoFence": {"circles": [{"inclusion": false,
      "circle": {"center": [46.8, 9.8], "radius": 1e300}}]}})",
                           "f.plan")
                .find("f.plan: geoFence.circles[0].circle.radius: must be a positive number of metres, at most 1e9"),
            std::string::npos);
  EXPECT_NE(airspace_error(R"({"geoFence": {"polygons": {"a": 1}}})", "f.plan")
                .find("f.plan: geoFence.polygons: expected a list"),
            std::string::npos);
  EXPECT_NE(airspace_error(R"({"geoFence": {"circles": [{"inclusion": "no",
      "circle": {"center": [46.8, 9.8], "radius": 10}}]}})",
                           "f.plan")
                .find("f.plan: geoFence.circles[0].inclusion: expected true or false"),
            std::string::npos);
  EXPECT_NE(airspace_error(R"({"type": "Feature", "properties": {"floor_m": -1e300}, "geometry": {"type": "Polygon",
      "coordinates": [[[9.8, 46.8], [9.801, 46.8], [9.801, 46.801], [9.8, 46.8]]]}})",
                           "z.geojson")
                .find("z.geojson: .properties.floor_m: a height of"),
            std::string::npos);
  std::string deep = R"({"type": "Feature", "geometry": null, "properties": )";
  for (int k = 0; k < 100000; ++k) deep += "{\"a\":";
  deep += "1" + std::string(100000, '}') + "}";
  EXPECT_NE(airspace_error(deep, "deep.geojson").find("deep.geojson: arrays and objects nest more than 128 deep"),
            std::string::npos);
}

// A .kml that GDAL's KML drivers do not read is an error, not a file of no zones.
TEST(Airspace, AKmlFileThatIsNotKmlIsRefused) {
  EXPECT_NE(airspace_error(R"({"type": "FeatureCollection", "features": []})", "zones.kml").find("zones.kml"),
            std::string::npos);
  EXPECT_NE(airspace_error("<OGRVRTDataSource><OGRVRTLayer name=\"z\"><SrcDataSource>/vsicurl/http://127.0.0.1:9/"
                           "z.csv</SrcDataSource></OGRVRTLayer></OGRVRTDataSource>",
                           "zones.kml")
                .find("cannot read it as KML"),
            std::string::npos);
}

}  // namespace
}  // namespace uavplan
