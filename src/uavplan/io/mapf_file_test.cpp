#include "uavplan/io/mapf_file.h"

#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include "uavplan/coordination/spacetime/mapf_conflicts.h"
#include "uavplan/io/input_error.h"

namespace uavplan {
namespace {

const char* kSwap = R"(map:
  dimensions: [5, 2]
  obstacles:
  - [0, 1]
  - [1, 1]
  - [3, 1]
  - [4, 1]
agents:
- name: left
  start: [0, 0]
  goal: [4, 0]
- {name: "right", start: [4, 0], goal: [0, 0]}
)";

std::string error_of(const std::string& text) {
  try {
    parse_mapf_instance(text, "inst.yaml");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

std::string with(const std::string& from, const std::string& to) {
  std::string s = kSwap;
  s.replace(s.find(from), from.size(), to);
  return s;
}

TEST(MapfFile, ReadsAnInstanceAndWritesASolutionACheckerCanRead) {
  const MapfInstance in = parse_mapf_instance(kSwap, "inst.yaml");
  ASSERT_EQ(in.names.size(), 2u);
  EXPECT_EQ(in.width, 5);
  const MapfProblem p = in.problem();
  const MapfResult r = solve_mapf(p, {});
  ASSERT_TRUE(r.solved());
  // Read the file back as a checker would: every agent's cells at their times.
  const YAML::Node out = YAML::Load(mapf_solution_yaml(in, r, 0.001));
  EXPECT_EQ(out["statistics"]["cost"].as<int>(), r.sum_of_costs);
  EXPECT_EQ(out["statistics"]["makespan"].as<int>(), r.makespan);
  std::vector<SpaceTimePath> read;
  for (const std::string& name : in.names) {
    SpaceTimePath path;
    const YAML::Node steps = out["schedule"][name];
    for (std::size_t k = 0; k < steps.size(); ++k) {
      EXPECT_EQ(steps[k]["t"].as<std::size_t>(), k);
      path.push_back(steps[k]["y"].as<int>() * in.width + steps[k]["x"].as<int>());
    }
    read.push_back(path);
  }
  EXPECT_EQ(read, r.paths);
  EXPECT_FALSE(mapf_solution_problem(p.graph, p.starts, p.goals, read).has_value());
}

TEST(MapfFile, NamesAreWrittenAsData) {
  MapfInstance in = parse_mapf_instance(with("name: left", "name: \"a\\\"b\\nc: d\""), "inst.yaml");
  const MapfResult r = solve_mapf(in.problem(), {});
  const YAML::Node out = YAML::Load(mapf_solution_yaml(in, r, 0.0));
  EXPECT_TRUE(out["schedule"]["a\"b\nc: d"].IsSequence());
  EXPECT_EQ(out["schedule"].size(), 2u);
}

TEST(MapfFile, BadInstancesNameTheFileThePlaceAndTheFault) {
  EXPECT_EQ(error_of(with("start: [0, 0]", "start: [7, 0]")),
            "inst.yaml:10: agents[0].start: [7, 0] is outside the map (5 x 2)");
  EXPECT_EQ(error_of(with("goal: [4, 0]", "goal: [4, 1]")), "inst.yaml:11: agents[0].goal: on an obstacle");
  EXPECT_EQ(error_of(with("goal: [0, 0]", "goal: [4, 0]")), "inst.yaml:12: agents[1].goal: the goal of agents[0] too");
  EXPECT_EQ(error_of(with("name: \"right\"", "name: \"left\"")),
            "inst.yaml:12: agents[1].name: the name of agents[0] too");
  EXPECT_EQ(error_of(with("start: [4, 0]", "start: [0, 0]")),
            "inst.yaml:12: agents[1].start: the start of agents[0] too");
  EXPECT_EQ(error_of(with("dimensions: [5, 2]", "dimensions: [5]")), "inst.yaml:2: map.dimensions: [W, H] expected");
  EXPECT_EQ(error_of(with("[3, 1]", "[3, x]")), "inst.yaml:6: map.obstacles[2][1]: a whole number expected");
  EXPECT_EQ(error_of(with("agents:", "agnets:")), "inst.yaml:8: agnets: unknown key (map and agents expected)");
  // Keys missing (a const node's missing key throws on any question but IsDefined).
  EXPECT_EQ(error_of(with("  dimensions: [5, 2]\n", "")), "inst.yaml:2: map.dimensions: [W, H] expected");
  EXPECT_EQ(error_of("map: {dimensions: [2, 2]}\n"), "inst.yaml: agents: a list of agents expected");
  EXPECT_EQ(error_of("agents: []\n"), "inst.yaml: map: a map {dimensions, obstacles} expected");
  EXPECT_EQ(error_of(with("name: left", "nome: left")), "inst.yaml:9: agents[0].name: a name expected");
  EXPECT_EQ(error_of(with("  start: [0, 0]\n", "")), "inst.yaml:9: agents[0].start: a cell [x, y] expected");
  EXPECT_NE(error_of("map: [").find("inst.yaml:1: YAML syntax error"), std::string::npos);
}

}  // namespace
}  // namespace uavplan
