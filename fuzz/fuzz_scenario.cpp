// The scenario loader, YAML and JSON: the first byte of the input chooses the file name.
#include "fuzz_target.h"
#include "uavplan/io/scenario_io.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const std::string file = data[0] & 1 ? "f.json" : "f.yaml";
  const std::string text(reinterpret_cast<const char*>(data + 1), size - 1);
  return uavplan::fuzz::run_reader([&] { uavplan::parse_scenario(text, file); });
}
