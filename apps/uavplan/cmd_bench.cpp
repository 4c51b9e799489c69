// uavplan bench SET: benchmark sets that print tables (ours beside the references).
#include <iostream>

#include "commands.h"
#include "uavplan/evaluation/world_bench.h"

namespace uavplan::cli {

void add_bench_command(CLI::App& app, std::function<int()>& run) {
  CLI::App* cmd = app.add_subcommand("bench", "Run a benchmark set and print its table");
  cmd->require_subcommand(1);
  auto queries = std::make_shared<int>(2000);
  auto seed = std::make_shared<unsigned long long>(7);
  CLI::App* world = cmd->add_subcommand("world", "World queries: broad phase against brute force, 100-10,000 obstacles");
  world->add_option("--queries", *queries, "Queries per world (default 2000)")->check(CLI::PositiveNumber);
  world->add_option("--seed", *seed, "Seed of the random worlds");
  world->callback([queries, seed, &run] {
    run = [queries, seed] {
      const auto rows = run_world_bench({100, 1000, 10000}, *queries, *seed);
      std::cout << format_world_bench(rows);
      for (const auto& r : rows)
        if (r.mismatches) return kExitNotSolved;
      return kExitOk;
    };
  });
}

}  // namespace uavplan::cli
