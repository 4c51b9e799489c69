// P4 benchmark: Table 3 (directional A* against the plain 26-neighbour grid A*), the rendezvous
// table, and the L x M length table of P4's Table 5, with the paper's numbers beside ours.
#pragma once

#include <string>

namespace uavplan::bench {

// Reads scenarios/p4_table3.yaml and scenarios/p4_rendezvous.yaml under `scenario_dir`;
// returns the printed tables. Throws InputError for unreadable scenarios.
std::string run_p4(const std::string& scenario_dir, bool* all_ok = nullptr);

}  // namespace uavplan::bench
