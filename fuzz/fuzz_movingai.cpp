// The grid benchmarks' readers (MovingAI's 2-D and 3-D maps and scenarios, libMultiRobotPlanning's
// MAPF instances): they read files, so the input goes to one; its first byte chooses the reader.
#include <unistd.h>

#include <fstream>

#include "fuzz_target.h"
#include "uavplan/io/mapf_file.h"
#include "uavplan/io/movingai.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  static const std::string path = "/tmp/uavplan-fuzz-movingai-" + std::to_string(::getpid());
  {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data + 1), static_cast<std::streamsize>(size - 1));
  }
  return uavplan::fuzz::run_reader([&] {
    switch (data[0] % 5) {
      case 0:
        uavplan::read_movingai_map(path);
        break;
      case 1:
        uavplan::read_movingai_scen(path);
        break;
      case 2:
        uavplan::read_movingai_3dmap(path);
        break;
      case 3:
        uavplan::read_movingai_3dscen(path);
        break;
      default:
        (void)uavplan::mapf_problem_mistake(uavplan::read_mapf_instance(path).problem());
    }
  });
}
