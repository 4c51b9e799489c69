#include "uavplan/io/elevation_model.h"

#include <gtest/gtest.h>
#include <unistd.h>
#include <GeographicLib/UTMUPS.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>

#include "uavplan/io/input_error.h"
#include "uavplan/io/io_test_fixtures.h"
#include "uavplan/io/scenario_io.h"

namespace uavplan {
namespace {

namespace fs = std::filesystem;

const GeoOrigin kOrigin{47.0, 8.0, 400.0};
// WGS 84 / UTM zone 32N (EPSG:32632) in WKT: no datum shift, so UTM from GeographicLib is exact.
const char* kUtm32nPrj =
    R"(PROJCS["WGS 84 / UTM zone 32N",GEOGCS["WGS 84",DATUM["WGS_1984",SPHEROID["WGS 84",6378137,298.257223563]],)"
    R"(PRIMEM["Greenwich",0],UNIT["degree",0.0174532925199433]],PROJECTION["Transverse_Mercator"],)"
    R"(PARAMETER["latitude_of_origin",0],PARAMETER["central_meridian",9],PARAMETER["scale_factor",0.9996],)"
    R"(PARAMETER["false_easting",500000],PARAMETER["false_northing",0],UNIT["metre",1]])";

Vec2 utm_of(double lat, double lon) {
  int zone = 0;
  bool north = true;
  double e = 0, n = 0;
  GeographicLib::UTMUPS::Forward(lat, lon, zone, north, e, n, 32);
  return {e, n};
}

// An ASCII grid (.asc, with a .prj unless `prj` is empty) of 200 x 200 pixels of 5 m in UTM 32N
// about the origin: 450 m everywhere, a 700 m mast pixel 123 m east and 77 m south of the
// origin, and a 4 x 4 pixel hole without data (-9999) 150 m north.
std::string write_grid(const fs::path& dir, const std::string& prj) {
  const Vec2 o = utm_of(kOrigin.lat_deg, kOrigin.lon_deg);
  const double x0 = std::floor(o.x()) - 500, y0 = std::floor(o.y()) - 500;
  std::ostringstream s;
  s << "ncols 200\nnrows 200\nxllcorner " << x0 << "\nyllcorner " << y0 << "\ncellsize 5\nNODATA_value -9999\n";
  const int mast_col = static_cast<int>((o.x() + 123 - x0) / 5),
            mast_row = 199 - static_cast<int>((o.y() - 77 - y0) / 5);
  const int hole_col = static_cast<int>((o.x() - x0) / 5), hole_row = 199 - static_cast<int>((o.y() + 150 - y0) / 5);
  for (int r = 0; r < 200; ++r) {
    for (int c = 0; c < 200; ++c) {
      const bool hole = c >= hole_col && c < hole_col + 4 && r >= hole_row && r < hole_row + 4;
      s << (c ? " " : "") << (r == mast_row && c == mast_col ? 700 : hole ? -9999 : 450);
    }
    s << "\n";
  }
  const fs::path asc = dir / "dem.asc";
  std::ofstream(asc) << s.str();
  if (!prj.empty()) std::ofstream(dir / "dem.prj") << prj;
  return asc.string();
}

TEST(ElevationModel, PlacesARasterInAnotherCrsThroughTheOrigin) {
  const test::TempDir d("dem_utm");
  const std::string asc = write_grid(d.path, kUtm32nPrj);
  const GeoFrame frame(kOrigin);
  const Aabb bounds{Vec3(-400, -400, 0), Vec3(400, 400, 500)};
  const ElevationModel m = read_elevation_model(asc, "dem.asc", frame, bounds, std::nullopt, {1u << 24});
  EXPECT_NE(m.source.crs.find("UTM zone 32N"), std::string::npos) << m.source.crs;
  EXPECT_EQ(m.source.driver, "AAIGrid");
  EXPECT_EQ(m.source.raster_nx, 200);
  EXPECT_NEAR(m.source.raster_cell_m, 5.0, 0.01);  // UTM's scale near 8 deg E, one degree off its meridian
  EXPECT_DOUBLE_EQ(m.source.cell_m, 5.0);
  EXPECT_EQ(m.grid.nx(), 160);
  EXPECT_NEAR(m.source.max_amsl_m, 700.0, 1e-9);
  EXPECT_NEAR(m.source.min_amsl_m, 450.0, 1e-9);
  EXPECT_GT(m.source.nodata_filled, 0u);  // the hole's inner cells, from their neighbours

  // The mast stands where its UTM position is in the local frame: the cell under it is 300 m
  // (700 m less the origin's 400 m) and every cell more than a pixel's diagonal plus a cell's
  // diagonal away is the plain's 50 m. A placement off by 15 m fails.
  double lat = 0, lon = 0;
  const Vec2 o = utm_of(kOrigin.lat_deg, kOrigin.lon_deg);
  const double x0 = std::floor(o.x()) - 500, y0 = std::floor(o.y()) - 500;
  const double mast_e = x0 + 5 * std::floor((o.x() + 123 - x0) / 5) + 2.5;
  const double mast_n = y0 + 5 * std::floor((o.y() - 77 - y0) / 5) + 2.5;
  GeographicLib::UTMUPS::Reverse(32, true, mast_e, mast_n, lat, lon);
  const Vec3 mast = frame.to_local(lat, lon, 0.0);
  EXPECT_NEAR(m.grid.height_at(mast.x(), mast.y()), 300.0, 1e-9);
  int high = 0;
  for (int j = 0; j < m.grid.ny(); ++j)
    for (int i = 0; i < m.grid.nx(); ++i) {
      const Vec2 c = m.grid.origin() + Vec2((i + 0.5) * 5.0, (j + 0.5) * 5.0);
      const double h = m.grid.height(i, j);
      if (h > 50.0) ++high;
      if ((c - mast.head<2>()).norm() > 5.0 * std::sqrt(2.0) * 2) {
        EXPECT_DOUBLE_EQ(h, 50.0) << i << ", " << j;
      }
    }
  EXPECT_GE(high, 1);
  EXPECT_LE(high, 4);  // one pixel touches at most 2 x 2 cells of its size
}

TEST(ElevationModel, ACellIsTheHighestPixelItTouches) {
  const test::TempDir d("dem_coarse");
  const std::string asc = write_grid(d.path, kUtm32nPrj);
  const GeoFrame frame(kOrigin);
  const Aabb bounds{Vec3(-400, -400, 0), Vec3(400, 400, 500)};
  const ElevationModel m = read_elevation_model(asc, "dem.asc", frame, bounds, 40.0, {1u << 24});
  EXPECT_EQ(m.grid.nx(), 20);
  EXPECT_NEAR(m.grid.max_height(), 300.0, 1e-9);  // the mast survives coarser cells: never lowered
  // A cap on the cells coarsens them rather than fail.
  const ElevationModel capped = read_elevation_model(asc, "dem.asc", frame, bounds, std::nullopt, {400});
  EXPECT_LE(static_cast<std::size_t>(capped.grid.nx()) * capped.grid.ny(), 400u);
  EXPECT_NEAR(capped.grid.max_height(), 300.0, 1e-9);
}

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(ElevationModel, BadFilesAreClearErrors) {
  const test::TempDir d("dem_bad");
  const GeoFrame frame(kOrigin);
  const Aabb bounds{Vec3(-400, -400, 0), Vec3(400, 400, 500)};
  const std::string asc = write_grid(d.path, "");
  EXPECT_NE(error_of([&] {
              read_elevation_model(asc, "dem.asc", frame, bounds, std::nullopt, {1u << 24});
            }).find("dem.asc: terrain: the raster has no coordinate system"),
            std::string::npos);
  write_grid(d.path, kUtm32nPrj);
  const Aabb wide{Vec3(-600, -400, 0), Vec3(400, 400, 500)};
  EXPECT_NE(error_of([&] {
              read_elevation_model(asc, "dem.asc", frame, wide, std::nullopt, {1u << 24});
            }).find("reach beyond the elevation model"),
            std::string::npos);
  const fs::path junk = d.path / "junk.tif";
  std::ofstream(junk) << "not a raster\n";
  EXPECT_NE(error_of([&] {
              read_elevation_model(junk.string(), "junk.tif", frame, bounds, std::nullopt, {1u << 24});
            }).find("junk.tif: terrain: GDAL cannot read it as a raster"),
            std::string::npos);
}

TEST(ElevationModel, TheBundledDavosModelLoadsInItsSwissCrs) {
  const std::string yaml = R"(version: 1
name: t
origin: {lat: 46.8195, lon: 9.8291, alt: 1500}
world:
  bounds: {min: [-2700, -2400, 0], max: [2500, 2100, 1500]}
  terrain: {file: davosdorf.tif}
uavs:
  - {id: a, start: [0, 0, 1400], goal: [100, 0, 1400]}
)";
  const std::string file = std::string(UAVPLAN_SOURCE_DIR) + "/scenarios/data/s.yaml";
  const Scenario sc = parse_scenario(yaml, file);
  ASSERT_TRUE(sc.elevation);
  EXPECT_NE(sc.elevation->crs.find("EPSG:21781"), std::string::npos);
  EXPECT_EQ(sc.elevation->raster_nx, 559);
  EXPECT_EQ(sc.elevation->raster_ny, 495);
  ASSERT_TRUE(sc.world.terrain());
  EXPECT_EQ(sc.world.terrain()->nx(), 520);
  EXPECT_EQ(sc.world.terrain()->ny(), 450);
  // swisstopo's heights of the valley: 1536-2843 m over the whole model.
  EXPECT_GE(sc.elevation->min_amsl_m, 1535.9);
  EXPECT_LE(sc.elevation->max_amsl_m, 2843.1);
  EXPECT_GT(sc.elevation->max_amsl_m - sc.elevation->min_amsl_m, 1000.0);
  // Without an origin it cannot be placed.
  std::string no_origin = yaml;
  no_origin.erase(no_origin.find("origin:"), no_origin.find("world:") - no_origin.find("origin:"));
  try {
    parse_scenario(no_origin, file);
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("needs the scenario's 'origin'"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace uavplan

namespace uavplan {
namespace {

// Read a strip of a few rows at a time, the cells are those of one read: every strip boundary
// falls inside cells, and the mast and the hole land where they do in one read.
TEST(ElevationModel, StripsGiveTheCellsOfOneRead) {
  const test::TempDir d("dem_strips");
  const std::string asc = write_grid(d.path, kUtm32nPrj);
  const GeoFrame frame(kOrigin);
  const Aabb bounds{Vec3(-400, -400, 0), Vec3(400, 400, 500)};
  const ElevationModel whole = read_elevation_model(asc, "dem.asc", frame, bounds, 13.0, {});
  for (const std::size_t strip_bytes : {1u, 200u * 8u * 3u, 200u * 8u * 7u}) {
    ElevationReadOptions o;
    o.strip_bytes = strip_bytes;
    const ElevationModel m = read_elevation_model(asc, "dem.asc", frame, bounds, 13.0, o);
    ASSERT_EQ(m.grid.nx(), whole.grid.nx());
    ASSERT_EQ(m.grid.ny(), whole.grid.ny());
    for (int j = 0; j < m.grid.ny(); ++j)
      for (int i = 0; i < m.grid.nx(); ++i) ASSERT_EQ(m.grid.height(i, j), whole.grid.height(i, j)) << i << "," << j;
  }
  EXPECT_NEAR(whole.grid.max_height(), 300.0, 1e-9);
}

// A window past the memory cap is refused before a pixel is read, naming --max-memory; a stop
// that holds ends the read between strips.
TEST(ElevationModel, TheReadStaysWithinTheRunsLimits) {
  const test::TempDir d("dem_limits");
  const std::string asc = write_grid(d.path, kUtm32nPrj);
  const GeoFrame frame(kOrigin);
  const Aabb bounds{Vec3(-400, -400, 0), Vec3(400, 400, 500)};
  ElevationReadOptions o;
  o.stop = StopCondition().with_memory_cap(1u << 20);
  EXPECT_NE(
      error_of([&] { read_elevation_model(asc, "dem.asc", frame, bounds, std::nullopt, o); }).find("--max-memory"),
      std::string::npos);
  ElevationReadOptions stopped;
  stopped.stop = StopCondition::time_limit(0.0);
  EXPECT_THROW(read_elevation_model(asc, "dem.asc", frame, bounds, std::nullopt, stopped), Stopped);
}

// What is not a place or a height is refused: a geotransform that is not finite, heights past
// 1e9 m (an undeclared NoData such as -3.4e38).
TEST(ElevationModel, NonFiniteGeotransformsAndHugeHeightsAreRefused) {
  const test::TempDir d("dem_values");
  const GeoFrame frame(kOrigin);
  const Aabb bounds{Vec3(-400, -400, 0), Vec3(400, 400, 500)};
  const std::string asc = write_grid(d.path, kUtm32nPrj);
  std::ifstream in(asc);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const fs::path low = d.path / "low.asc";
  std::string low_text = text;
  low_text.replace(low_text.find("NODATA_value -9999\n"), 19, "");
  for (std::size_t at; (at = low_text.find("-9999")) != std::string::npos;) low_text.replace(at, 5, "-3.4e38");
  std::ofstream(low) << low_text;
  std::ofstream(d.path / "low.prj") << kUtm32nPrj;
  EXPECT_NE(error_of([&] {
              read_elevation_model(low.string(), "low.asc", frame, bounds, std::nullopt, {});
            }).find("beyond +-1e9 m: declare the raster's NoData value"),
            std::string::npos);
  const fs::path nan = d.path / "nan.asc";
  std::string nan_text = text;
  nan_text.replace(nan_text.find("cellsize 5"), 10, "cellsize nan");
  std::ofstream(nan) << nan_text;
  std::ofstream(d.path / "nan.prj") << kUtm32nPrj;
  const std::string e =
      error_of([&] { read_elevation_model(nan.string(), "nan.asc", frame, bounds, std::nullopt, {}); });
  EXPECT_TRUE(e.find("geotransform") != std::string::npos || e.find("GDAL cannot read it") != std::string::npos) << e;
}

}  // namespace
}  // namespace uavplan
