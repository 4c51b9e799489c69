// The OpenStreetMap buildings reader (world.buildings).
#include "fuzz_target.h"
#include "uavplan/io/geo.h"
#include "uavplan/io/osm_buildings.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const uavplan::GeoFrame frame(uavplan::GeoOrigin{40.7128, -74.006, 10.0});
  const std::string text(reinterpret_cast<const char*>(data), size);
  return uavplan::fuzz::run_reader([&] { uavplan::buildings_from_geojson(text, "b.geojson", frame, {}); });
}
