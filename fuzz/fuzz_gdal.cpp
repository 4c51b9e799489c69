// Inputs that go through GDAL or name files (world.terrain, world.airspace): the fuzzer's bytes
// become one file in a scratch folder, beside a small valid raster a VRT may name, and a scenario
// that names it is loaded. The first byte chooses what the rest is: a VRT elevation model, a KML,
// GeoJSON or QGC fence. Every refusal must be an InputError; nothing may crash, hang or read
// outside the folder (the folder holds nothing else to read).
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "fuzz_target.h"
#include "uavplan/io/scenario_io.h"

namespace {

namespace fs = std::filesystem;

const fs::path& scratch() {
  static const fs::path dir = [] {
    char name[] = "/tmp/uavplan-fuzz-gdal-XXXXXX";
    const char* made = ::mkdtemp(name);
    const fs::path d = made ? made : "/tmp/uavplan-fuzz-gdal";
    fs::create_directories(d);
    // A 4 x 4 ASCII grid in CH1903 / LV03 over the scenario's origin, for a VRT to name.
    std::ofstream(d / "src.asc") << "ncols 4\nnrows 4\nxllcorner 780000\nyllcorner 186000\ncellsize 100\n"
                                    "NODATA_value -9999\n1 2 3 4\n5 6 7 8\n9 10 11 12\n13 14 15 16\n";
    std::ofstream(d / "src.prj")
        << "PROJCS[\"CH1903 / LV03\",GEOGCS[\"CH1903\",DATUM[\"CH1903\",SPHEROID[\"Bessel 1841\","
           "6377397.155,299.1528128]],PRIMEM[\"Greenwich\",0],UNIT[\"degree\",0.0174532925199433]],"
           "PROJECTION[\"Hotine_Oblique_Mercator_Azimuth_Center\"],PARAMETER[\"latitude_of_center\","
           "46.9524055555556],PARAMETER[\"longitude_of_center\",7.43958333333333],PARAMETER["
           "\"azimuth\",90],PARAMETER[\"rectified_grid_angle\",90],PARAMETER[\"scale_factor\",1],"
           "PARAMETER[\"false_easting\",600000],PARAMETER[\"false_northing\",200000],UNIT[\"metre\",1]]";
    return d;
  }();
  return dir;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1) return 0;
  static const char* const kinds[] = {"dem.vrt", "zones.kml", "zones.geojson", "zones.plan"};
  const int kind = data[0] % 4;
  const fs::path file = scratch() / kinds[kind];
  std::ofstream(file, std::ios::binary).write(reinterpret_cast<const char*>(data + 1), static_cast<long>(size - 1));
  const std::string world =
      kind == 0 ? "  terrain: {file: dem.vrt}\n" : "  airspace: [{file: " + std::string(kinds[kind]) + "}]\n";
  const std::string scenario =
      "version: 1\norigin: {lat: 46.80256, lon: 9.79959, alt: 0}\nworld:\n  bounds: {min: [-100, -100, 0], max: [100, "
      "100, 3000]}\n" +
      world + "uavs:\n  - {id: a, start: [-50, -50, 2900], goal: [50, 50, 2900]}\n";
  const fs::path path = scratch() / "s.yaml";
  std::ofstream(path) << scenario;
  return uavplan::fuzz::run_reader([&] { uavplan::load_scenario(path.string()); });
}
