#include "uavplan/io/scenario_io.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>

#include "uavplan/coordination/formation/formation_mission.h"
#include "uavplan/coordination/mission.h"
#include "uavplan/coordination/rendezvous/rendezvous_mission.h"
#include "uavplan/io/input_error.h"
#include "uavplan/io/tree_check.h"

namespace uavplan {
namespace {

const std::string kGood = R"(version: 1
name: t
seed: 3
origin: {lat: 47.0, lon: 8.0, alt: 400}
world:
  bounds: {min: [0, 0, 0], max: [100, 100, 50]}
  obstacles:
    - {type: sphere, center: [50, 50, 20], radius: 5}
    - {type: cylinder, center: [20, 70], radius: 4, z_min: 0, z_max: 50}
    - {type: box, min: [70, 10, 0], max: [80, 20, 30]}
    - {type: prism, polygon: [[10, 40], [20, 40], [15, 50]], z_min: 0, z_max: 25}
  threats:
    - {type: radar, position: [60, 80, 0], weight: 2}
  terrain: {type: grid, origin: [0, 0], cell: 50, heights: [[0, 1], [2, 3]]}
  moving_obstacles:
    - {id: m1, radius: 1, position: [0, 50, 10], velocity: [1, 0, 0]}
uavs:
  - id: u1
    start: [5, 5, 10]
    heading_deg: 90
    goal: [95, 95, 10]
    radius: 0.5
    speed: {min: 1, cruise: 4, max: 6}
    max_turn_deg: 60
    max_climb_deg: 30
mission:
  type: route
  separation: 2
  waypoints: [[50, 10, 10]]
planner:
  algorithm: astar
  params: {cell_m: 2}
)";

std::string replace(std::string s, const std::string& from, const std::string& to) {
  const auto p = s.find(from);
  EXPECT_NE(p, std::string::npos) << from;
  if (p != std::string::npos) s.replace(p, from.size(), to);
  return s;
}

// The error is one line naming the file, and contains each of `parts`.
void expect_error(const std::string& text, std::initializer_list<std::string> parts, const std::string& file = "s.yaml",
                  const Overrides& overrides = {}) {
  try {
    parse_scenario(text, file, overrides);
    FAIL() << "no error for: " << *parts.begin();
  } catch (const InputError& e) {
    const std::string msg = e.what();
    EXPECT_EQ(msg.rfind(file, 0), 0u) << msg;
    // One line, unless several errors are expected (every typo of a file is named).
    if (std::none_of(parts.begin(), parts.end(),
                     [](const std::string& p) { return p.find('\n') != std::string::npos; })) {
      EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
    }
    for (const auto& p : parts) EXPECT_NE(msg.find(p), std::string::npos) << "'" << p << "' not in: " << msg;
  }
}

TEST(ScenarioIo, ReadsEveryContractField) {
  const Scenario sc = parse_scenario(kGood, "s.yaml");
  EXPECT_EQ(sc.name, "t");
  EXPECT_EQ(*sc.seed, 3u);
  EXPECT_DOUBLE_EQ(sc.origin->alt_m, 400);
  EXPECT_EQ(sc.world.obstacles().size(), 4u);
  EXPECT_EQ(sc.world.radars().size(), 1u);
  ASSERT_NE(sc.world.terrain(), nullptr);
  EXPECT_DOUBLE_EQ(sc.world.terrain()->height(1, 1), 3.0);
  EXPECT_EQ(sc.world.moving().size(), 1u);
  const UavSpec& u = sc.uavs[0];
  EXPECT_NEAR(*u.heading_rad, kPi / 2, 1e-12);
  EXPECT_DOUBLE_EQ(u.speed.max_mps, 6);
  EXPECT_NEAR(u.max_turn_rad, kPi / 3, 1e-12);
  EXPECT_EQ(sc.mission.type, "route");
  EXPECT_EQ(sc.mission.waypoints.size(), 1u);
  EXPECT_EQ(sc.planner.params.at("cell_m"), "2");
}

TEST(ScenarioIo, JsonIsTheSameStructure) {
  const std::string json = R"({"version": 1, "name": "j",
    "world": {"bounds": {"min": [0, 0, 0], "max": [10, 10, 5]}},
    "uavs": [{"id": "a", "start": [1, 1, 1], "goal": [9, 9, 1], "speed": 2}]})";
  const Scenario sc = parse_scenario(json, "s.json");
  EXPECT_EQ(sc.uavs[0].id, "a");
  EXPECT_DOUBLE_EQ(sc.uavs[0].speed.cruise_mps, 2);
  expect_error(R"({"version": 1, "world": {,}})", {"s.json:1", "JSON"}, "s.json");
}

TEST(ScenarioIo, Overrides) {
  const Scenario sc =
      parse_scenario(kGood, "s.yaml", {{"cell_m", "7"}, {"uavs[0].speed", "3"}, {"mission.separation", "9"}});
  EXPECT_EQ(sc.planner.params.at("cell_m"), "7");
  EXPECT_DOUBLE_EQ(sc.uavs[0].speed.cruise_mps, 3);
  EXPECT_DOUBLE_EQ(sc.mission.separation_m, 9);
  expect_error(kGood, {"--set uavs[4].speed", "no list element"}, "s.yaml", {{"uavs[4].speed", "3"}});
  expect_error(kGood, {"uavs[0].speed", "positive"}, "s.yaml", {{"uavs[0].speed", "-3"}});
  expect_error(kGood, {"planner.params.cell_m", "single values"}, "s.yaml", {{"cell_m", "[1, 2]"}});
}

TEST(ScenarioIo, BadInputIsOneClearLine) {
  expect_error("", {"empty"});
  expect_error(std::string("\x7f"
                           "ELF\0\0\x01\x02",
                           8),
               {"not a text file"});
  expect_error("\x89PNG garbage here ::: [[[", {"s.yaml"});
  expect_error("version: 1\nworld: [1, 2\n", {"YAML syntax error"});
  expect_error("version: 1\nworld: " + std::string(2000, '[') + std::string(2000, ']') + "\n",
               {"s.yaml:2", "nested too deeply"});
  // Counted before parsing: a tree of 500 bytes a value would exhaust memory first.
  expect_error("version: 1\nworld: [" + std::string(4'000'001, ',') + "]\n", {"s.yaml", "values", "at most 4000000"});
  expect_error(replace(kGood, "version: 1", "version: 2"), {"s.yaml:1", "version", "unsupported version 2"});
  expect_error(replace(kGood, "    start: [5, 5, 10]\n", ""), {"uavs[0]", "missing required key 'start'"});
  expect_error(replace(kGood, "    radius: 0.5\n", "    radius: 0.5\n    raduis: 3\n"),
               {"s.yaml:23", "uavs[0].raduis", "unknown key 'raduis' (did you mean 'radius'?)"});
  // Every typo is named, each on its own line, before an error it may have caused.
  expect_error(
      replace(replace(replace(kGood, "    radius: 0.5\n", "    radius: 0.5\n    raduis: 3\n"), "max_turn_deg: 60",
                      "max_trun_deg: 60"),
              "separation: 2", "separation: -2"),
      {"s.yaml:23: uavs[0].raduis", "\ns.yaml:25: uavs[0].max_trun_deg: unknown key 'max_trun_deg' (did you mean",
       "\ns.yaml:29: mission.separation: must not be negative"});
  expect_error(replace(kGood, "    radius: 0.5\n", "    colour: red\n"),
               {"unknown key 'colour' (expected one of: id, "});
  expect_error(replace(kGood, "max_turn_deg: 60", "max_turn_deg: sixty"),
               {"s.yaml:24", "uavs[0].max_turn_deg", "expected a number"});
  expect_error(replace(kGood, "max_turn_deg: 60", "max_turn_deg: \"60\""), {"uavs[0].max_turn_deg", "quoted string"});
  expect_error(replace(kGood, "start: [5, 5, 10]", "start: [5, 5]"), {"uavs[0].start", "3 numbers"});
  expect_error(replace(kGood, "radius: 5}", "radius: .nan}"), {"world.obstacles[0].radius", "finite"});
  expect_error(replace(kGood, "weight: 2", "weight: .inf"), {"world.threats[0].weight", "finite"});
  expect_error(replace(kGood, "radius: 5}", "radius: -5}"), {"world.obstacles[0].radius", "positive"});
  expect_error(replace(kGood, "    radius: 0.5\n", "    radius: -0.5\n"), {"uavs[0].radius", "negative"});
  expect_error(replace(kGood, "cell: 50", "cell: -50"), {"world.terrain.cell", "positive"});
  expect_error(replace(kGood, "heights: [[0, 1], [2, 3]]", "heights: [[0, 1], [2]]"),
               {"world.terrain.heights[1]", "rows must be equal"});
  expect_error(replace(kGood, "start: [5, 5, 10]", "start: [50, 50, 20]"),
               {"s.yaml:19", "uavs[0].start", "inside obstacle 0 (sphere)"});
  expect_error(replace(kGood, "goal: [95, 95, 10]", "goal: [95, 195, 10]"),
               {"uavs[0].goal", "outside the world bounds"});
  expect_error(replace(kGood, "start: [5, 5, 10]", "start: [60, 60, 2]"), {"uavs[0].start", "below the terrain"});
  expect_error(replace(kGood, "type: sphere", "type: cone"), {"world.obstacles[0].type", "unknown obstacle type"});
  expect_error(replace(kGood, "type: route", "type: swarm"), {"mission.type", "unknown mission type"});
  expect_error(
      replace(kGood, "bounds: {min: [0, 0, 0], max: [100, 100, 50]}", "bounds: {min: [0, 0, 0], max: [-100, 100, 50]}"),
      {"world.bounds.max"});
  expect_error("- a\n- b\n", {"top level must be a mapping"});
  expect_error(
      replace(kGood, "uavs:\n  - id: u1", "uavs:\n  - id: u1\n    start: [1, 1, 10]\n    goal: [2, 2, 10]\n  - id: u1"),
      {"duplicate UAV id"});
}

TEST(ScenarioIo, SensingAndPathObstacles) {
  const std::string text = replace(
      replace(replace(kGood, "    - {id: m1, radius: 1, position: [0, 50, 10], velocity: [1, 0, 0]}\n",
                      "    - {id: m1, radius: 1, position: [0, 50, 10], velocity: [1, 0, 0]}\n"
                      "    - {id: m2, radius: 2, trajectory: [[0, 0, 0, 10], [10, 50, 0, 10], [20, 50, 50, 10]]}\n"),
              "    max_climb_deg: 30\n", "    max_climb_deg: 30\n    sensor_range: 40\n"),
      "  separation: 2\n", "  separation: 2\n  step_s: 0.5\n");
  const Scenario sc = parse_scenario(text, "s.yaml");
  ASSERT_EQ(sc.world.moving().size(), 2u);
  EXPECT_EQ(sc.world.moving()[1].path.size(), 3u);
  EXPECT_EQ(sc.world.moving()[1].position_at(15), Vec3(50, 25, 10));
  EXPECT_DOUBLE_EQ(*sc.uavs[0].sensor_range_m, 40);
  EXPECT_DOUBLE_EQ(sc.mission.step_s, 0.5);

  const std::string m1 = "{id: m1, radius: 1, position: [0, 50, 10], velocity: [1, 0, 0]}";
  auto with_m = [&](const std::string& m) { return replace(kGood, m1, m); };
  expect_error(with_m("{id: m1, radius: 1, trajectory: [[0, 0, 0, 10]]}"),
               {"world.moving_obstacles[0].trajectory", "at least 2 rows"});
  expect_error(with_m("{id: m1, radius: 1, trajectory: [[0, 0, 0, 10], [0, 5, 0, 10]]}"),
               {"world.moving_obstacles[0].trajectory[1][0]", "times must increase"});
  expect_error(with_m("{id: m1, radius: 1, trajectory: [[5, 0, 0, 10], [2, 5, 0, 10]]}"), {"times must increase"});
  expect_error(with_m("{id: m1, radius: 1, trajectory: [[0, 0, 0, 10], [1, .nan, 0, 10]]}"),
               {"world.moving_obstacles[0].trajectory[1][1]", "finite"});
  expect_error(with_m("{id: m1, radius: 1, trajectory: [[0, 0, 0, 10], [.inf, 1, 0, 10]]}"), {"finite"});
  expect_error(with_m("{id: m1, radius: 1, trajectory: [[0, 0, 0, 10], [1, 0, 10]]}"),
               {"trajectory[1]", "[t, x, y, z]"});
  expect_error(with_m("{id: m1, radius: 1, velocity: [1, 0, 0], trajectory: [[0, 0, 0, 10], [1, 1, 0, 10]]}"),
               {"world.moving_obstacles[0].velocity", "not both"});
  expect_error(with_m("{id: m1, radius: 1, position: [0, 0, 10], trajectory: [[0, 0, 0, 10], [1, 1, 0, 10]]}"),
               {"world.moving_obstacles[0].position"});
  // Neither: both ways named (a 'path' is the usual guess).
  expect_error(with_m("{id: m1, radius: 1, path: [[0, 0, 0, 10], [1, 1, 0, 10]]}"),
               {"world.moving_obstacles[0].path: unknown key 'path'", "\n",
                "world.moving_obstacles[0]: needs a 'position'", "or a 'trajectory' of [t, x, y, z] rows"});
  const std::string climb = "    max_climb_deg: 30\n";
  expect_error(replace(kGood, climb, climb + "    sensor_range: 0\n"), {"uavs[0].sensor_range", "positive"});
  expect_error(replace(kGood, climb, climb + "    sensor_range: -4\n"), {"uavs[0].sensor_range", "positive"});
  expect_error(replace(kGood, climb, climb + "    sensor_range: far\n"), {"uavs[0].sensor_range", "expected a number"});
  expect_error(replace(kGood, climb, climb + "    sensor_range: .nan\n"), {"uavs[0].sensor_range", "finite"});
  expect_error(replace(kGood, "  separation: 2\n", "  separation: 2\n  step_s: 0\n"), {"mission.step_s", "must be in"});
}

TEST(ScenarioIo, DuplicateKeysAndSecondDocumentsAreErrors) {
  // yaml-cpp would take the first radius, a JSON reader the last: one file, two worlds.
  expect_error(replace(kGood, "{type: sphere, center: [50, 50, 20], radius: 5}",
                       "{type: sphere, center: [50, 50, 20], radius: 1, radius: 10}"),
               {"s.yaml:8", "world.obstacles[0].radius", "duplicate key 'radius'"});
  expect_error(replace(kGood, "name: t\n", "name: t\nname: u\n"),
               {"s.yaml:3", "duplicate key 'name' (first at line 2)"});
  const std::string json = R"({"version": 1, "world": {"bounds": {"min": [0, 0, 0], "max": [10, 10, 5]}},
    "uavs": [{"id": "a", "start": [1, 1, 1], "goal": [9, 9, 1], "goal": [2, 2, 1]}]})";
  expect_error(json, {"s.json:2", "uavs[0].goal", "duplicate key"}, "s.json");
  // A via point after "..." (or in a second document) is not silently dropped.
  expect_error(kGood + "...\nmission: {type: independent}\n", {"s.yaml:34", "after the document's end"});
  expect_error(kGood + "---\nname: other\n", {"s.yaml:33", "second YAML document"});
  // A leading comma made yaml-cpp 0.7's LoadAll loop forever (found by fuzz_scenario).
  expect_error(",erss\": {\"NUavs\": []}", {"s.yaml"});
  EXPECT_NO_THROW(parse_scenario("---\n" + kGood + "...\n", "s.yaml"));
}

TEST(ScenarioIo, ErrorsStayOneEscapedLineNamingTheFile) {
  // A key with a newline and a terminal escape in it.
  const std::string evil = replace(kGood, "    radius: 0.5\n", "    \"bad\\nkey\\e[31m\": 3\n");
  try {
    parse_scenario(evil, "s.yaml");
    FAIL();
  } catch (const InputError& e) {
    const std::string msg = e.what();
    EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
    EXPECT_EQ(msg.find('\x1b'), std::string::npos) << msg;
    EXPECT_NE(msg.find("bad\\nkey\\x1b[31m"), std::string::npos) << msg;
  }
  // 1e400 in JSON, invalid UTF-8 in an id: the file and the line.
  expect_error(R"({"version": 1,
    "world": {"bounds": {"min": [0, 0, 0], "max": [1e400, 10, 5]}}})",
               {"s.json:2", "1e400"}, "s.json");
  expect_error(replace(kGood, "  - id: u1",
                       "  - id: u\xff"
                       "1"),
               {"s.yaml:18", "not valid UTF-8"});
  // CR-only line endings read like any other.
  std::string cr = kGood;
  for (char& c : cr)
    if (c == '\n') c = '\r';
  EXPECT_EQ(parse_scenario(cr, "s.yaml").uavs[0].id, "u1");
  // A string tagged !!str is not a number; bounds beyond the documented limit are refused.
  expect_error(replace(kGood, "max_turn_deg: 60", "max_turn_deg: !!str 60"), {"uavs[0].max_turn_deg", "tagged"});
  expect_error(replace(kGood, "max: [100, 100, 50]", "max: [1e308, 100, 50]"), {"world.bounds.max[0]", "within"});
}

TEST(ScenarioIo, SizesAreCheckedBeforeTheyAreBuilt) {
  // Rows that are aliases of one row: 4200 x 4200 cells (17.6 M) from a few kilobytes, refused
  // before a height is read; 20 000 x 20 000 (400 M) is refused as an expansion.
  const auto terrain = [](int n) {
    std::string t =
        "version: 1\nworld:\n  bounds: {min: [0, 0, 0], max: [10, 10, 5]}\n  terrain:\n    type: grid\n"
        "    origin: [0, 0]\n    cell: 1\n    heights:\n      - &row [0";
    for (int i = 1; i < n; ++i) t += ", 0";
    t += "]\n";
    for (int i = 1; i < n; ++i) t += "      - *row\n";
    return t + "uavs: [{id: a, start: [1, 1, 1]}]\n";
  };
  const auto t0 = std::chrono::steady_clock::now();
  expect_error(terrain(4200), {"world.terrain.heights", "cells, above"});
  expect_error(terrain(20000), {"expands", "values"});
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), 5.0);
  // Nested aliases: a list of lists of lists ... (billions of values).
  std::string laughs =
      "version: 1\nname: x\nworld:\n  bounds: {min: [0, 0, 0], max: [10, 10, 5]}\n  a0: &a0 [1, 1, 1, 1, 1, 1, 1, 1, "
      "1, 1]\n";
  for (int i = 1; i < 10; ++i) {
    laughs += "  a" + std::to_string(i) + ": &a" + std::to_string(i) + " [";
    for (int k = 0; k < 10; ++k) laughs += std::string(k ? ", " : "") + "*a" + std::to_string(i - 1);
    laughs += "]\n";
  }
  expect_error(laughs, {"expands", "values"});
  // An alias inside its own anchor's node: a cycle, refused before anything walks it (the
  // scenario fuzzer's find: it overflowed the stack).
  expect_error(
      "version: 1\nworld:\n  bounds: {min: [0, 0, 0], max: [1, 1, 1]}\n  terrain: {heights: [&r [0, *r]]}\n"
      "uavs: [{id: a, start: [1, 1, 1]}]\n",
      {"s.yaml:4", "world.terrain.heights[0][1]", "contains itself"});
  // A speed that would need ten million trajectory rows.
  expect_error(replace(kGood, "speed: {min: 1, cruise: 4, max: 6}", "speed: 1e-6"),
               {"uavs[0].speed", "at most 1e+06 s"});
  expect_error(replace(kGood, "speed: {min: 1, cruise: 4, max: 6}", "speed: 1e-300"), {"uavs[0].speed"});
  // A home 1e6 s of flight away: its legs count (plan.json would hold millions of rows).
  const std::string far_home =
      "version: 1\nworld: {bounds: {min: [-1e7, -1e7, 0], max: [1e7, 1e7, 100]}}\n"
      "uavs: [{id: a, start: [0, 0, 50], goal: [100, 0, 50], home: [-6e6, 0, 0], speed: 10}]\n";
  expect_error(far_home, {"uavs[0].speed", "from its home and back", "at most 1e+06 s"});
  // Flights each within the limit that add up past the fleet's.
  std::string fleet = "version: 1\nworld: {bounds: {min: [-1e7, -1e7, 0], max: [1e7, 1e7, 100]}}\nuavs:\n";
  for (int k = 0; k < 3; ++k)
    fleet += "  - {id: u" + std::to_string(k) + ", start: [0, " + std::to_string(k * 10) + ", 50], goal: [9e6, " +
             std::to_string(k * 10) + ", 50], speed: 10}\n";
  expect_error(fleet, {"uavs[2]", "add up to", "over all its UAVs"});
}

TEST(ScenarioIo, SetErrorsNameTheArgument) {
  try {
    parse_scenario(kGood, "s.yaml", {{"uavs[0].speed", "-3"}});
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("s.yaml: --set uavs[0].speed=-3: must be positive"), std::string::npos)
        << e.what();
  }
  expect_error(kGood, {"--set uavs[0].radius=x", "expected a number"}, "s.yaml", {{"uavs[0].radius", "x"}});
  // Key paths (io/tree_check.h): an index past the list, a malformed index, nothing after a '.'.
  expect_error(kGood, {"no list element 3"}, "s.yaml", {{"uavs[3].radius", "1"}});
  expect_error(kGood, {"bad list index"}, "s.yaml", {{"uavs[x].radius", "1"}});
  expect_error(kGood, {"unclosed '['"}, "s.yaml", {{"uavs[0.radius", "1"}});
  expect_error(kGood, {"empty key"}, "s.yaml", {{"planner.params.", "1"}});
  EXPECT_EQ(parse_scenario(kGood, "s.yaml", {{"uavs[0].radius", "0.75"}}).uavs[0].radius_m, 0.75);
}

TEST(ScenarioIo, KeyPathsSplitIntoKeysAndIndices) {
  const KeyPath kp = split_key_path("world.obstacles[12].radius");
  ASSERT_EQ(kp.steps.size(), 4u);
  EXPECT_EQ(kp.steps[1].key, "obstacles");
  EXPECT_EQ(kp.steps[2].index, 12u);
  EXPECT_EQ(kp.steps[3].key, "radius");
  EXPECT_TRUE(kp.error.empty());
  EXPECT_EQ(split_key_path("a[2").error, "unclosed '['");
  EXPECT_EQ(split_key_path("a[2x]").steps.size(), 1u);
}

// Margins, the ground and shared goals (issue: outputs a user can trust, items 11, 12, 15, 16).
TEST(ScenarioIo, ClearanceMinAglGroundStartsAndGoalSpacing) {
  const std::string climb = "    max_climb_deg: 30\n";
  const Scenario sc =
      parse_scenario(replace(replace(replace(kGood, climb, climb + "    clearance: 1.5\n    min_agl: 4\n"),
                                     "start: [5, 5, 10]", "start: [5, 5, 0]"),
                             "  separation: 2\n", "  separation: 2\n  goal_spacing: 6\n"),
                     "s.yaml");
  EXPECT_DOUBLE_EQ(sc.uavs[0].clearance_m, 1.5);
  EXPECT_DOUBLE_EQ(sc.uavs[0].min_agl_m, 4);
  EXPECT_DOUBLE_EQ(*sc.mission.goal_spacing_m, 6);
  EXPECT_TRUE(sc.world.on_ground(sc.uavs[0].start));  // standing on the terrain (0 there)
  // On the terrain of another cell (3 m there) too; under it is still an error.
  EXPECT_NO_THROW(parse_scenario(replace(kGood, "start: [5, 5, 10]", "start: [60, 60, 3]"), "s.yaml"));
  expect_error(replace(kGood, "start: [5, 5, 10]", "start: [60, 60, 2]"), {"uavs[0].start", "below the terrain"});
  expect_error(replace(kGood, "start: [5, 5, 10]", "start: [20, 70, 0]"),
               {"uavs[0].start", "below the terrain", "the ground is at z = 2 m here"});
  expect_error(replace(kGood, "start: [5, 5, 10]", "start: [69.8, 15, 1]"),
               {"uavs[0].start", "vertical column", "0.5 m"});
  expect_error(replace(kGood, climb, climb + "    min_agl: 12\n"),
               {"uavs[0].start", "10 m above the ground, below min_agl"});
  expect_error(replace(kGood, climb, climb + "    clearance: -1\n"), {"uavs[0].clearance", "negative"});
  expect_error(replace(kGood, "  separation: 2\n", "  separation: 2\n  goal_spacing: -1\n"),
               {"mission.goal_spacing", "negative"});
  const std::string flat =
      replace(replace(kGood, "max: [100, 100, 50]", "max: [100, 100, 0]"),
              "  terrain: {type: grid, origin: [0, 0], cell: 50, heights: [[0, 1], [2, 3]]}\n", "");
  expect_error(replace(replace(replace(replace(flat, climb, climb + "    min_agl: 3\n"), "[5, 5, 10]", "[5, 5, 0]"),
                               "[95, 95, 10]", "[95, 95, 0]"),
                       "[[50, 10, 10]]", "[[50, 10, 0]]"),
               {"uavs[0].min_agl", "flat world"});
}

// What planning would find out too late is an error at load (item 12).
// Each mission type reads its own keys of the section (Mission::read_section); a scenario that
// switches `type` keeps the others' keys, which are known but not read.
TEST(ScenarioIo, EachMissionTypeReadsItsOwnKeys) {
  const Scenario route = parse_scenario(kGood, "s.yaml");
  ASSERT_EQ(route.mission.waypoints.size(), 1u);
  const Scenario independent = parse_scenario(replace(kGood, "type: route", "type: independent"), "s.yaml");
  EXPECT_TRUE(independent.mission.waypoints.empty());
  const std::string extra =
      "  waypoints: [[50, 10, 10]]\n  arrival_tolerance: 5\n  shape: [[0, 0, 0]]\n"
      "  airfield: {position: [1, 1, 0]}\n";
  const Scenario rendezvous =
      parse_scenario(replace(replace(kGood, "type: route", "type: rendezvous"), "  waypoints: [[50, 10, 10]]\n", extra),
                     "s.yaml", {{"planner.algorithm", "directional_astar"}});
  EXPECT_EQ(rendezvous_section(rendezvous).arrival_tolerance_m, 5.0);
  EXPECT_TRUE(rendezvous.mission.waypoints.empty());
  EXPECT_TRUE(formation_shape(rendezvous).empty());
  EXPECT_FALSE(rendezvous.mission.airfield.has_value());
  expect_error(replace(kGood, "type: route", "type: formation"), {"mission", "missing required key 'shape'"});
  expect_error(
      replace(kGood, "  waypoints: [[50, 10, 10]]\n", "  waypoint: [[50, 10, 10]]\n"),
      {"unknown key 'waypoint' (did you mean 'waypoints'?)\ns.yaml:27: mission: missing required key 'waypoints'"});
  expect_error(replace(kGood, "  waypoints: [[50, 10, 10]]\n", "  waypoints: [[50, 10, 10]]\n  colour: red\n"),
               {"unknown key 'colour'", "airfield"});
}

// A route whose via points have entry headings plans with a planner that flies into them along
// the heading: pso_mpc by default; naming one that does not is an error before any planning.
TEST(ScenarioIo, EntryHeadingsNeedAPlannerThatKeepsThem) {
  const std::string entered = replace(kGood, "  waypoints: [[50, 10, 10]]\n",
                                      "  waypoints: [{position: [50, 10, 10], entry_heading_deg: 90}]\n");
  expect_error(entered,
               {"planner.algorithm", "'astar' does not fly into a via point along its entry_heading_deg", "pso_mpc"});
  const Scenario by_default =
      parse_scenario(replace(entered, "  algorithm: astar\n  params: {cell_m: 2}\n", ""), "s.yaml");
  EXPECT_EQ(mission_algorithm(by_default, std::nullopt), "pso_mpc");
  const Scenario plain = parse_scenario(replace(kGood, "  algorithm: astar\n  params: {cell_m: 2}\n", ""), "s.yaml");
  EXPECT_EQ(mission_algorithm(plain, std::nullopt), "astar");  // no entry heading: as before
}

TEST(ScenarioIo, ProblemsPlanningWouldMeetAreLoadErrors) {
  const std::string second = "uavs:\n  - id: u2\n    start: [5.3, 5, 10]\n    goal: [90, 90, 10]\n";
  expect_error(replace(kGood, "uavs:\n", second), {"uavs[1].start", "closer to u2's start", "radii"});
  expect_error(replace(kGood, "start: [5, 5, 10]", "start: [0.5, 50, 10]"),
               {"uavs[0].start", "moving obstacle 'm1' at t = 0"});
  expect_error(replace(replace(kGood, "    goal: [95, 95, 10]\n", ""), "type: route", "type: independent"),
               {"uavs[0]", "missing required key 'goal'", "independent"});
  expect_error(replace(kGood, "    - {type: sphere, center: [50, 50, 20], radius: 5}\n",
                       "    - {type: box, min: [-5, -5, -5], max: [105, 105, 60]}\n"),
               {"world.obstacles[0]", "covers the whole world"});
  expect_error(replace(kGood, "type: route", "type: group"), {"planner.algorithm", "apf"});
  expect_error(
      replace(kGood, "polygon: [[10, 40], [20, 40], [15, 50]]", "polygon: [[10, 40], [20, 50], [20, 40], [10, 52]]"),
      {"world.obstacles[3].polygon", "self-intersecting", "vertex 0", "vertex 2"});
}

}  // namespace
}  // namespace uavplan
