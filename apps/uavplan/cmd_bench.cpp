// uavplan bench SET: benchmark sets that print tables (ours beside the references).
#include <filesystem>
#include <iostream>

#include "commands.h"
#include "deconfliction_runner.h"
#include "mapf_runner.h"
#include "movingai_plan_runner.h"
#include "movingai_runner.h"
#include "p1_local_runner.h"
#include "p1_runner.h"
#include "p2_runner.h"
#include "p3_runner.h"
#include "p4_runner.h"
#include "p5_coarse_runner.h"
#include "p5_runner.h"
#include "soak_runner.h"
#include "uavplan/evaluation/world_bench.h"
#include "uavplan/io/files.h"
#include "uavplan/io/input_error.h"

namespace uavplan::cli {
namespace {

void add_world(CLI::App* cmd, std::function<int()>& run) {
  auto queries = std::make_shared<int>(2000);
  auto seed = std::make_shared<unsigned long long>(7);
  CLI::App* world =
      cmd->add_subcommand("world", "World queries: broad phase against brute force, 100-10,000 obstacles");
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

struct MovingAiArgs {
  std::string map, scen;
  bench::MovingAiOptions options;
  bool json = false;
};

struct MovingAiPlanArgs {
  std::string map, scen;
  bench::MovingAiPlanOptions options;
};

void add_movingai_plan(CLI::App* cmd, std::function<int()>& run) {
  auto a = std::make_shared<MovingAiPlanArgs>();
  CLI::App* m = cmd->add_subcommand(
      "movingai-plan", "`plan` itself on a MovingAI map made a scenario: JPS and A* beside the file's optima");
  m->add_option("map", a->map, "MovingAI .map (2-D) or .3dmap (3-D)")->required();
  m->add_option("scen", a->scen, "Its .scen or .3dscen")->required();
  m->add_option("--limit", a->options.limit,
                "Plan this many problems, spread evenly over the file (default 100; 0: all)");
  m->add_flag("!--no-astar", a->options.astar_too, "Skip planning each problem again with A* alone");
  m->add_option("--scenario-out", a->options.scenario_out, "Write the first problem's scenario to this file");
  m->footer(
      "Example: uavplan bench movingai-plan ../shared/data/movingai-3d/Complex.3dmap "
      "../shared/data/movingai-3d/Complex.3dmap.3dscen --limit 200");
  m->callback([a, &run] {
    run = [a] {
      try {
        const auto rep = bench::run_movingai_plan(a->map, a->scen, a->options);
        std::cout << bench::format_movingai_plan(rep);
        return rep.passed() ? kExitOk : kExitNotSolved;
      } catch (const InputError& e) {
        std::cerr << e.what() << "\n";
        return kExitBadInput;
      }
    };
  });
}

void add_movingai(CLI::App* cmd, std::function<int()>& run) {
  auto a = std::make_shared<MovingAiArgs>();
  CLI::App* m = cmd->add_subcommand("movingai", "MovingAI grid benchmark: ours against the optimum and a textbook A*");
  m->add_option("map", a->map, "MovingAI .map (2-D) or .3dmap (3-D)")->required();
  m->add_option("scen", a->scen, "Its .scen or .3dscen")->required();
  m->add_option("--algorithm", a->options.algorithm,
                "astar (default), jps (2-D or 3-D; in 3-D from both ends in turns), jps-forward (3-D, from the start "
                "alone), jps+ (2-D, jump table built once, its time printed apart) or theta (Lazy Theta*, any-angle)");
  m->add_option("--limit", a->options.limit, "Run this many problems, spread evenly over the file (default all)");
  m->add_flag("--json", a->json, "Print JSON instead of the table");
  m->add_flag("!--no-reference", a->options.reference, "Skip the textbook A*");
  m->footer(
      "Example: uavplan bench movingai ../shared/data/movingai-2d/Boston_0_256.map "
      "../shared/data/movingai-2d/Boston_0_256.map.scen --algorithm jps");
  m->callback([a, &run] {
    run = [a] {
      try {
        const auto rep = bench::run_movingai(a->map, a->scen, a->options);
        std::cout << (a->json ? bench::movingai_json(rep) : bench::format_movingai(rep));
        return rep.passed() ? kExitOk : kExitNotSolved;
      } catch (const InputError& e) {
        std::cerr << e.what() << "\n";
        return kExitBadInput;
      }
    };
  });

  add_movingai_plan(cmd, run);

  auto blocked = std::make_shared<long long>(2'000'000);
  auto scratch = std::make_shared<std::string>("/tmp/uavplan-a1-probe.3dmap");
  CLI::App* mem = cmd->add_subcommand(
      "movingai-memory", "Resident memory of loading a Warframe A1-size map (896 x 390 x 255), synthesised");
  mem->add_option("--blocked", *blocked, "Blocked voxels in the synthetic map (default 2,000,000)");
  mem->add_option("--scratch", *scratch, "Where to write the synthetic map (removed afterwards)");
  mem->callback([blocked, scratch, &run] {
    run = [blocked, scratch] {
      const auto probe = bench::probe_a1_memory(*scratch, *blocked);
      std::printf("synthetic A1 map 896 x 390 x 255, %lld blocked voxels, file %.1f MB\n",
                  static_cast<long long>(probe.blocked), probe.file_mb);
      std::printf("load %.0f ms, grid %.2f MB, peak resident %.1f MB (target < 50 MB): %s\n", probe.load_ms,
                  probe.grid_mb, probe.peak_rss_mb, probe.peak_rss_mb < 50.0 ? "met" : "MISSED");
      return probe.peak_rss_mb < 50.0 ? kExitOk : kExitNotSolved;
    };
  });
}

// The bundled scenarios' folder when --scenarios is not given: ./scenarios when it holds `file`,
// else beside the binary (build/uavplan -> scenarios/; bin/uavplan -> share/uavplan/scenarios/),
// so the tables run from any folder.
std::string bundled_scenarios(const std::string& file) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (fs::is_regular_file(fs::path("scenarios") / file, ec)) return "scenarios";
  const fs::path exe = fs::canonical("/proc/self/exe", ec);
  if (!ec)
    for (const fs::path& dir : {exe.parent_path().parent_path() / "scenarios",
                                exe.parent_path().parent_path() / "share" / "uavplan" / "scenarios"})
      if (fs::is_regular_file(dir / file, ec)) return dir.string();
  return "scenarios";  // the error then names ./scenarios
}

// A paper's tables from scenarios in a folder (--scenarios): exit 0 when its targets are met,
// 2 on a bad scenario file.
CLI::App* add_tables(CLI::App* cmd, std::function<int()>& run, const std::string& name, const std::string& what,
                     const std::string& files, const std::function<std::string(const std::string&, bool*)>& tables) {
  auto dir = std::make_shared<std::string>();
  CLI::App* sub = cmd->add_subcommand(name, what);
  sub->add_option(
      "--scenarios", *dir,
      "Folder holding " + files +
          " (default: ./scenarios, else the bundled ones beside the binary: ../scenarios from build/uavplan, "
          "../share/uavplan/scenarios when installed)");
  const std::string first = files.substr(0, files.find(' '));
  sub->callback([dir, tables, first, &run] {
    run = [dir, tables, first] {
      try {
        bool ok = false;
        std::cout << tables(dir->empty() ? bundled_scenarios(first) : *dir, &ok);
        return ok ? kExitOk : kExitNotSolved;
      } catch (const InputError& e) {
        std::cerr << e.what() << "\n";
        return kExitBadInput;
      }
    };
  });
  return sub;
}

void add_papers(CLI::App* cmd, std::function<int()>& run) {
  add_tables(cmd, run, "p4", "P4 tables: directional A* against grid A*, rendezvous, L x M lengths",
             "p4_table3.yaml and p4_rendezvous.yaml",
             [](const std::string& d, bool* ok) { return bench::run_p4(d, ok); });
  auto runs = std::make_shared<int>(20);
  add_tables(cmd, run, "p1",
             "P1 tables: global route, colony vs Dijkstra, Table 2 (whole formation mission, A-RRT vs common RRT)",
             "p1_formation.yaml", [runs](const std::string& d, bool* ok) { return bench::run_p1(d, *runs, ok); })
      ->add_option("--runs", *runs, "Seeded runs of the whole mission per method (default: 20)")
      ->check(CLI::Range(1, 100000));
  auto worlds = std::make_shared<int>(100);
  add_tables(cmd, run, "p5-coarse",
             "P5 coarse planning: multi- vs single-step PSO (4.1), entry headings (4.2a), random large worlds",
             "p5_coarse.yaml and p5_entry.yaml",
             [worlds](const std::string& d, bool* ok) { return bench::run_p5_coarse(d, *worlds, ok); })
      ->add_option("--worlds", *worlds, "Random large worlds (default: 100)")
      ->check(CLI::Range(0, 100000));
  add_tables(cmd, run, "p5",
             "P5 whole mission: the phase timetable beside Table 2, separation per phase, the 45 -> 15 deg turn",
             "p5_mission.yaml", [](const std::string& d, bool* ok) { return bench::run_p5(d, ok); });
  add_tables(cmd, run, "p3", "P3 tables: group scores before/after smoothing, traditional baseline, scaling",
             "p3_group9.yaml", [](const std::string& d, bool* ok) { return bench::run_p3(d, ok); });
  add_tables(cmd, run, "p2", "P2 tables: times to the task points for 25-100 ants, ant colony vs the A* optimum",
             "p2_city.yaml", [](const std::string& d, bool* ok) { return bench::run_p2(d, ok); });
}

void add_p1_local(CLI::App* cmd, std::function<int()>& run) {
  auto opt = std::make_shared<bench::P1LocalOptions>();
  auto json = std::make_shared<bool>(false);
  CLI::App* p = cmd->add_subcommand(
      "p1-local", "P1 Table 1: improved vs common RRT vs OMPL RRT/RRTConnect/RRT* in the 40 m x 45 m window");
  p->add_option("--problems", opt->problems, "Seeded local problems (default 200)")->check(CLI::PositiveNumber);
  p->add_option("--seed", opt->seed, "Seed of the problems (default 1)");
  p->add_option("--rrtstar-ms", opt->rrtstar_budget_ms, "RRT*'s time budget per problem (default 25 ms)")
      ->check(CLI::PositiveNumber);
  p->add_flag("--json", *json, "Print one JSON object per planner instead of the table");
  p->callback([opt, json, &run] {
    run = [opt, json] {
      const auto rows = bench::run_p1_local(*opt);
      std::cout << (*json ? bench::p1_local_json(rows) : bench::format_p1_local(rows, *opt));
      return bench::p1_local_targets_met(rows) ? kExitOk : kExitNotSolved;
    };
  });
}

void add_mapf(CLI::App* cmd, std::function<int()>& run) {
  auto opt = std::make_shared<bench::MapfBenchOptions>();
  auto dir = std::make_shared<std::string>();
  auto method = std::make_shared<std::string>("auto");
  CLI::App* m = cmd->add_subcommand(
      "mapf", "Grid MAPF on libMultiRobotPlanning's instance files: solved, times, sum of costs beside its ECBS");
  m->add_option("dir", *dir, "Folder of instance files (map: {dimensions, obstacles}, agents: [{name, start, goal}])")
      ->required();
  m->add_option("--method", *method,
                "auto (ECBS with 3/4 of the time limit, then prioritized; default), prioritized, ecbs or cbs")
      ->check(CLI::IsMember({"auto", "prioritized", "ecbs", "cbs"}));
  m->add_option("--w", opt->solver.w, "ECBS's suboptimality bound (default 1.3)")->check(CLI::Range(1.0, 100.0));
  m->add_option("--orders", opt->solver.orders, "Agent orders prioritized planning tries (default 8)")
      ->check(CLI::Range(1, 1000000));
  m->add_option("--time-limit", opt->time_limit_s, "Seconds per instance (default 30)")->check(positive_number());
  m->add_option("--optimal-limit", opt->optimal_limit_s,
                "Also run CBS per instance for this many seconds: its optimum is the yardstick where it finishes")
      ->check(positive_number());
  m->add_option("--limit", opt->limit, "This many instances per agent count, spread evenly (default all)")
      ->check(CLI::PositiveNumber);
  m->add_option("--out", opt->out_dir, "Write each solution here in libMultiRobotPlanning's output format");
  m->footer("Example: uavplan bench mapf ../shared/data/mapf/32x32_obst204 --limit 10 --out /tmp/mapf-solutions");
  m->callback([opt, dir, method, &run] {
    run = [opt, dir, method] {
      parse_mapf_method(*method, opt->solver.method);
      opt->solver.stop = StopCondition::cancel_flag(interrupt_flag());
      install_interrupt_handlers();
      Progress progress;
      try {
        const auto rep = bench::run_mapf_bench(*dir, *opt, [&](std::size_t done, std::size_t total) {
          progress.update("mapf: " + std::to_string(done) + "/" + std::to_string(total) + " instances");
        });
        progress.finish();
        if (interrupted()) {
          std::cerr << "uavplan: interrupted; nothing written\n";
          return kExitInterrupted;
        }
        std::cout << bench::format_mapf_bench(rep);
        return rep.passed() ? kExitOk : kExitNotSolved;
      } catch (const InputError& e) {
        std::cerr << e.what() << "\n";
        return kExitBadInput;
      } catch (const OutputError& e) {
        std::cerr << e.what() << "\n";
        return kExitOutputError;
      }
    };
  });
}

void add_deconfliction(CLI::App* cmd, std::function<int()>& run) {
  auto opt = std::make_shared<bench::DeconflictionOptions>();
  CLI::App* d = cmd->add_subcommand("deconfliction",
                                    "Many UAVs crossing in random 1 km cities, planned in space and time and verified");
  d->add_option("--sizes", opt->sizes, "UAV counts (default 10 50 100 200)")->check(CLI::Range(1, 1000));
  d->add_option("--cities", opt->cities, "Random cities per size and layout (default 3)")->check(CLI::PositiveNumber);
  d->add_option("--seed", opt->seed, "Seed of the cities (default 1)");
  d->add_option("--method", opt->method, "auto (prioritized, then ECBS; default), prioritized, ecbs or cbs")
      ->check(CLI::IsMember({"auto", "prioritized", "ecbs", "cbs"}));
  d->add_option("--time-limit", opt->time_limit_s, "Seconds per city (default 60)")->check(positive_number());
  d->footer("Example: uavplan bench deconfliction --sizes 50 200 --cities 5");
  d->callback([opt, &run] {
    run = [opt] {
      Progress progress;
      progress.update("deconfliction: planning");
      const auto runs = bench::run_deconfliction(*opt);
      progress.finish();
      std::cout << bench::format_deconfliction(runs, *opt);
      return bench::deconfliction_passed(runs) ? kExitOk : kExitNotSolved;
    };
  });
}

void add_soak(CLI::App* cmd, std::function<int()>& run) {
  auto opt = std::make_shared<bench::SoakOptions>();
  CLI::App* s =
      cmd->add_subcommand("soak", "Random worlds per planner and mission: every claimed solution must verify");
  s->add_option("--worlds", opt->worlds, "Random worlds per row (default 1000)")->check(CLI::PositiveNumber);
  s->add_option("--seed", opt->seed, "Seed of the worlds (default 1)");
  s->add_option("--stop-s", opt->stop_s,
                "Each plan's time limit in seconds (default 2); a plan must end within it + 0.2 s")
      ->check(CLI::Range(0.001, 3600.0));
  s->callback([opt, &run] {
    run = [opt] {
      bool held = false;
      std::cout << bench::run_soak(*opt, &held);
      return held ? kExitOk : kExitNotSolved;
    };
  });
}

}  // namespace

void add_bench_command(CLI::App& app, std::function<int()>& run) {
  CLI::App* cmd = app.add_subcommand("bench", "Run a benchmark set and print its table");
  cmd->require_subcommand(1);
  add_world(cmd, run);
  add_movingai(cmd, run);
  add_papers(cmd, run);
  add_p1_local(cmd, run);
  add_soak(cmd, run);
  add_mapf(cmd, run);
  add_deconfliction(cmd, run);
}

}  // namespace uavplan::cli
