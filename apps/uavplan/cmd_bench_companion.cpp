// `uavplan bench` in the program that does not link the benchmarks (companion.h): the whole
// command line, --help included, goes to uavplan-bench.
#include "commands.h"
#include "companion.h"

namespace uavplan::cli {

void add_bench_command(CLI::App& app, std::function<int()>& run) {
  CLI::App* cmd = app.add_subcommand("bench", "Run a benchmark set and print its table (uavplan-bench)");
  cmd->set_help_flag();
  cmd->allow_extras();
  cmd->prefix_command();
  cmd->callback([&run] { run = [] { return run_companion("uavplan-bench"); }; });
}

}  // namespace uavplan::cli
