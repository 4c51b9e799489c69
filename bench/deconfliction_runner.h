// Many UAVs in one city: random 1 x 1 km cities (box buildings, ceiling 120 m) with 10-200 UAVs
// whose straight routes cross (swaps across a circle, two crossing streams, random pairs), each
// planned by the independent mission with space-time deconfliction and checked by the verifier;
// per size and layout: solved, median and p95 time (plan and verify), delay and path-length
// overhead against each UAV alone on the same lattice.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace uavplan::bench {

struct DeconflictionOptions {
  std::vector<int> sizes{10, 50, 100, 200};
  int cities = 3;  // random cities per size and layout
  std::uint64_t seed = 1;
  std::string method = "auto";  // space_time_method
  double time_limit_s = 60.0;   // per instance
};

struct DeconflictionRun {
  int uavs = 0;
  std::string layout;
  int solved = 0;         // UAVs solved
  int rejected = 0;       // solved UAVs the verifier rejects
  double ms = 0.0;        // plan and verify
  double delay_s = 0.0;   // total arrival delay against each UAV alone
  double length_m = 0.0;  // total flown length
  double alone_m = 0.0;   // total flown length alone
};

std::vector<DeconflictionRun> run_deconfliction(const DeconflictionOptions& options);
std::string format_deconfliction(const std::vector<DeconflictionRun>& runs, const DeconflictionOptions& options);
// Every UAV solved and no claim rejected.
bool deconfliction_passed(const std::vector<DeconflictionRun>& runs);

}  // namespace uavplan::bench
