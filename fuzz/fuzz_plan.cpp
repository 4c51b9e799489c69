// The plan reader (verify, export and report read plans written by anyone).
#include "fuzz_target.h"
#include "uavplan/io/plan_io.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  return uavplan::fuzz::run_reader([&] { uavplan::parse_plan(text, "p.json"); });
}
