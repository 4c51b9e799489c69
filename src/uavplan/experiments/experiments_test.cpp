#include <gtest/gtest.h>

#include <cmath>

#include "uavplan/experiments/ompl_log.h"
#include "uavplan/experiments/results.h"
#include "uavplan/experiments/sweep.h"
#include "uavplan/io/input_error.h"

namespace uavplan {
namespace {

const std::string kDemo = std::string(UAVPLAN_SOURCE_DIR) + "/scenarios/demo.yaml";

Sweep sweep_of(const std::string& body) { return parse_sweep("scenarios: [" + kDemo + "]\n" + body, "/tmp/s.yaml"); }

TEST(Sweep, TheProductIsNumberedScenarioPlannerParametersSeed) {
  const Sweep s = sweep_of(
      "planners: [astar, {name: rrt, params: {goal_bias: [0.1, 0.2]}}]\nseeds: [4, 9]\nparams: {cell_m: [5, 10]}\n");
  EXPECT_EQ(run_count(s), 1u * 3u * 2u * 2u);
  const auto runs = expand_runs(s);
  ASSERT_EQ(runs.size(), 12u);
  for (std::size_t i = 0; i < runs.size(); ++i) EXPECT_EQ(runs[i].index, i);
  EXPECT_EQ(runs[0].planner, "astar");
  EXPECT_EQ(runs[0].seed, 4u);
  EXPECT_EQ(runs[1].seed, 9u);
  EXPECT_EQ(params_text(runs[2].params), "cell_m=10");
  EXPECT_EQ(runs[4].planner, "rrt");
  EXPECT_EQ(params_text(runs[4].params), "cell_m=5;goal_bias=0.1");
  EXPECT_EQ(params_text(runs[11].params), "cell_m=10;goal_bias=0.2");
}

TEST(Sweep, ACountOfSeedsIsOneToN) {
  const Sweep s = sweep_of("seeds: 5\n");
  EXPECT_EQ(s.seeds, (std::vector<std::uint64_t>{1, 2, 3, 4, 5}));
  ASSERT_EQ(s.planners.size(), 1u);
  EXPECT_TRUE(s.planners[0].name.empty());  // the scenario's own
}

TEST(Sweep, ErrorsNameTheLineAndKey) {
  try {
    sweep_of("planners: [astar]\nseeds: [1, -2]\n");
    FAIL() << "a negative seed was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("s.yaml:3: seeds[1]"), std::string::npos) << e.what();
  }
  EXPECT_THROW(sweep_of("seeds: 0\n"), InputError);
  EXPECT_THROW(sweep_of("time_limit_s: -1\n"), InputError);
  EXPECT_THROW(sweep_of("planners: [{params: {a: [1]}}]\n"), InputError);
  EXPECT_THROW(sweep_of("params: {cell_m: []}\n"), InputError);
  try {
    check_sweep(sweep_of("planners: [astar]\nparams: {goal_bias: [0.1]}\n"));
    FAIL() << "a parameter astar does not take was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("params.goal_bias"), std::string::npos) << e.what();
  }
  EXPECT_NO_THROW(check_sweep(sweep_of("planners: [astar]\nparams: {cell_m: [4]}\n")));
}

RunRecord record(std::size_t index, RunStatus status, double length) {
  RunRecord r;
  r.spec.index = index;
  r.spec.scenario = "a.yaml";
  r.spec.planner = "astar";
  r.spec.seed = index + 1;
  r.spec.params = {{"cell_m", "5"}};
  r.outcome.status = status;
  r.outcome.verified = status == RunStatus::solved;
  if (status != RunStatus::solved) r.outcome.reason = Reason::no_route;
  r.outcome.length_m = length;
  r.outcome.uavs = 2;
  r.outcome.message = "a, \"quoted\" message";
  r.outcome.plan_ms = 12.5 + double(index);
  r.outcome.wall_ms = 100.0 + double(index);
  r.plan_file = run_plan_file(index);
  return r;
}

TEST(Results, RowsByRunNumberWithQuotedFieldsAndEmptyMissingNumbers) {
  const std::string csv =
      results_csv({record(1, RunStatus::failed, std::nan("")), record(0, RunStatus::solved, 100.0)});
  const auto second_line = csv.substr(csv.find('\n') + 1);
  EXPECT_EQ(second_line.substr(0, 2), "0,");
  EXPECT_NE(csv.find(",solved,1,0,2,0,100.000,,0,,runs/000000.plan.json,none,\"a, \"\"quoted\"\" message\"\n"),
            std::string::npos)
      << csv;
  EXPECT_NE(csv.find("\n1,a.yaml,astar,2,cell_m=5,failed,0,"), std::string::npos) << csv;
  EXPECT_NE(csv.find(",no_route,\"a, "), std::string::npos) << csv;  // the failed row's reason
  EXPECT_EQ(csv.find("12.5"), std::string::npos);                    // timing stays out
  EXPECT_NE(timings_csv({record(0, RunStatus::solved, 1.0)}).find("0,12.500,"), std::string::npos);
}

TEST(Results, JournalLinesRoundTripAndACutLineIsDropped) {
  const RunRecord r = record(7, RunStatus::solved, 1234.5);
  const std::string line = journal_line(r);
  EXPECT_EQ(line.find('\n'), std::string::npos);
  const auto back = parse_journal_line(line);
  ASSERT_TRUE(back);
  EXPECT_TRUE(same_run(back->spec, r.spec));
  EXPECT_EQ(journal_line(*back), line);
  EXPECT_FALSE(parse_journal_line(line.substr(0, line.size() - 5)));
  const RunRecord failed = record(8, RunStatus::failed, 0.0);
  const auto failed_back = parse_journal_line(journal_line(failed));
  ASSERT_TRUE(failed_back);
  EXPECT_EQ(failed_back->outcome.status, RunStatus::failed);
  EXPECT_EQ(failed_back->outcome.reason, Reason::no_route);
  std::string unknown = journal_line(failed);
  unknown.replace(unknown.find("\"failed\""), 8, "\"brokn\"");
  EXPECT_FALSE(parse_journal_line(unknown));  // a status no run has
  RunSpec other = r.spec;
  other.seed = 99;
  EXPECT_FALSE(same_run(other, r.spec));
}

TEST(OmplLog, FollowsTheGrammar) {
  std::vector<RunRecord> runs = {record(0, RunStatus::solved, 10.0), record(1, RunStatus::failed, std::nan("")),
                                 record(2, RunStatus::solved, 12.0)};
  runs[2].spec.planner = "rrt";
  OmplLogHeader h;
  h.experiment = "my sweep";
  h.host = "host";
  h.date = "2026-01-01 00:00:00";
  h.setup = "line one\nline two";
  h.time_limit_s = 5.0;
  const std::string log = ompl_log(runs, h);
  // This experiment's runs, 100 + 101 + 102 ms: not the batch's whole time.
  EXPECT_NE(log.find("\n0.303 seconds spent to collect the data\n"), std::string::npos) << log;
  EXPECT_EQ(log.rfind("uavplan version ", 0), 0u);
  EXPECT_NE(log.find("\nExperiment my_sweep\n"), std::string::npos);
  EXPECT_NE(log.find("\n<<<|\nline one\nline two\n|>>>\n1 is the random seed\n5 seconds per run\n"), std::string::npos);
  EXPECT_EQ(log.find("runs per planner"), std::string::npos);  // 2 and 1 runs: no common count
  EXPECT_NE(
      log.find(
          "\n2 planners\nastar[cell_m=5]\n1 common properties\ncell_m = 5\n9 properties for each run\ntime REAL\n"),
      std::string::npos)
      << log;
  // The failed run has no length: an empty field.
  EXPECT_NE(log.find("\n2 runs\n0.0125; 1; 1; 10; 0; 1; 0; ; ; \n0.0135; 0; ; ; 0; 2; 0; ; ; \n.\n"), std::string::npos)
      << log;
  EXPECT_EQ(log.substr(log.size() - 3), "\n.\n");
}

}  // namespace
}  // namespace uavplan

namespace uavplan {
namespace {

// A run that its time limit stopped is a `timeout` row for every mission type and the planner
// it plans with (read from the UAVs' reason, never from a message).
TEST(Batch, ARunItsLimitStoppedIsATimeoutForEveryMission) {
  const std::string dir = std::string(UAVPLAN_SOURCE_DIR) + "/scenarios/";
  ScenarioCache cache;
  BatchOptions opt;
  opt.time_limit_s = 1e-9;
  for (const char* name : {"demo", "p5_entry", "p3_group9", "p4_rendezvous", "p1_formation", "p5_mission", "p2_city"}) {
    RunSpec run;
    run.scenario = dir + name + ".yaml";
    std::string json;
    const RunOutcome o = run_in_process(run, cache, opt, json);
    EXPECT_EQ(o.status, RunStatus::timeout) << name << ": " << o.message;
  }
}

// A journal line carries its scenario's fingerprint: a run of an edited scenario is another run.
TEST(Results, AnEditedScenarioIsAnotherRun) {
  RunSpec a;
  a.scenario = kDemo;
  a.scenario_fingerprint = "0123456789abcdef";
  RunRecord r;
  r.spec = a;
  const auto back = parse_journal_line(journal_line(r));
  ASSERT_TRUE(back);
  EXPECT_TRUE(same_run(back->spec, a));
  RunSpec edited = a;
  edited.scenario_fingerprint = "fedcba9876543210";
  EXPECT_FALSE(same_run(back->spec, edited));
  EXPECT_EQ(expand_runs(sweep_of("seeds: 1\n"))[0].scenario_fingerprint.size(), 16u);
}

// A scenario named twice (by two globs, or a name and a glob) is run once.
TEST(Sweep, AScenarioNamedTwiceRunsOnce) {
  const Sweep s = parse_sweep(
      "scenarios: [" + kDemo + ", " + kDemo + ", \"" + std::string(UAVPLAN_SOURCE_DIR) + "/scenarios/dem?.yaml\"]\n",
      "/tmp/s.yaml");
  EXPECT_EQ(s.scenarios.size(), 1u);
}

}  // namespace
}  // namespace uavplan
