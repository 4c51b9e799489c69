#include "uavplan/io/plan_io.h"

#include <gtest/gtest.h>

#include <limits>

#include "uavplan/io/input_error.h"

namespace uavplan {
namespace {

Plan sample_plan() {
  Plan p;
  p.scenario = "s";
  p.algorithm = "astar";
  p.seed = 7;
  p.status = Status::partial;
  p.message = "b: failed";
  UavPlan a;
  a.id = "a";
  a.status = Status::solved;
  a.waypoints = {{0, 0, 10}, {1.0 / 3.0, 2, 10}};
  a.trajectory = {{0.0, Vec3(0, 0, 10)}, {0.1234567890123, Vec3(1.0 / 3.0, 2, 10)}};
  a.length_m = 2.0276;
  a.route_length_m = 2.5;
  a.metrics["length_m"] = 2.0276;
  UavPlan b;
  b.id = "b";
  b.message = "no route";
  b.arrival_s = std::numeric_limits<double>::infinity();  // never at its goal to stay
  p.uavs = {a, b};
  return p;
}

TEST(PlanIo, RoundTripIsExact) {
  const Plan p = sample_plan();
  const std::string text = plan_to_json(p);
  const Plan q = parse_plan(text, "p.json");
  ASSERT_EQ(q.uavs.size(), 2u);
  EXPECT_EQ(q.status, Status::partial);
  EXPECT_EQ(q.uavs[0].trajectory[1].t_s, p.uavs[0].trajectory[1].t_s);
  EXPECT_EQ(q.uavs[0].trajectory[1].p, p.uavs[0].trajectory[1].p);
  EXPECT_EQ(q.uavs[1].status, Status::failed);
  EXPECT_EQ(text.find("null"), std::string::npos) << "a UAV that never arrives has no arrival_s, not null";
  EXPECT_EQ(q.uavs[0].metrics, p.uavs[0].metrics) << "metrics are read back (the report shows them)";
  EXPECT_EQ(q.uavs[0].length_m, 2.0276);
  EXPECT_EQ(q.uavs[0].route_length_m, 2.5);
  EXPECT_EQ(plan_to_json(q).size() > 0, true);
  EXPECT_EQ(text, plan_to_json(p));  // deterministic
  EXPECT_NE(text.find("\"timing\": {}"), std::string::npos);
  EXPECT_NE(plan_to_json(p, {true}).find("plan_ms"), std::string::npos);
}

void expect_error(const std::string& text, const std::string& part) {
  try {
    parse_plan(text, "p.json");
    FAIL() << "no error, expected " << part;
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
    EXPECT_EQ(std::string(e.what()).rfind("p.json", 0), 0u);
  }
}

TEST(PlanIo, MalformedPlansNameThePlace) {
  expect_error("", "empty");
  expect_error("{\"format\": ", "not valid JSON");
  expect_error("[1, 2]", "top level");
  expect_error(R"({"format": "x", "version": 1})", "format");
  expect_error(R"({"format": "uavplan-plan", "version": 2, "status": "solved", "uavs": []})", "version");
  expect_error(R"({"format": "uavplan-plan", "version": 1, "status": "great", "uavs": []})", "status");
  expect_error(R"({"format": "uavplan-plan", "version": 1, "status": "solved",
                  "uavs": [{"id": "a", "status": "solved", "trajectory": [[0, 1, 2]]}]})",
               "uavs[0].trajectory[0]");
  expect_error(R"({"format": "uavplan-plan", "version": 1, "status": "solved",
                  "uavs": [{"id": "a", "status": "solved", "trajectory": [[0, 1, 2, "x"]]}]})",
               "expected a number");
  expect_error(R"({"format": "uavplan-plan", "version": 1, "status": "solved",
                  "uavs": [{"id": "a", "status": "solved", "trajectory": []}, {"id": "a", "status": "solved", "trajectory": []}]})",
               "duplicate");
  // Each row's checks, behind the fast path for rows that hold.
  const std::string uav = R"({"format": "uavplan-plan", "version": 1, "status": "solved", "uavs": [{"id": "a",
                             "status": "solved", )";
  expect_error(uav + R"("trajectory": [[0, 1, 2, 3], [-1, 1, 2, 3]]}]})", "uavs[0].trajectory[1]: time must be");
  expect_error(uav + R"("trajectory": [[0, 1, 2e9, 3]]}]})", "uavs[0].trajectory[0]: coordinates must be within");
  expect_error(uav + R"("trajectory": [[0, 1, 2, 3], [1, 2, 3, 4, 5]]}]})", "uavs[0].trajectory[1]: expected [t,");
  expect_error(uav + R"("waypoints": [[0, 1, 2], [1, null, 3]], "trajectory": []}]})",
               "uavs[0].waypoints[1]: expected a number");
  expect_error(uav + R"("waypoints": [[0, 1]], "trajectory": []}]})", "uavs[0].waypoints[0]: expected [x, y, z]");
}

TEST(PlanIo, ErrorsCarryTheLineAndDuplicateKeysAreRefused) {
  const std::string head = "{\"format\": \"uavplan-plan\", \"version\": 1, \"status\": \"solved\",\n\"uavs\": [\n";
  expect_error(head + "{\"id\": \"a\", \"status\": \"solved\",\n\"trajectory\": [[0, 1, 2, 3],\n[1, 2, 3]]}]}",
               "p.json:5: uavs[0].trajectory[1]");
  expect_error(head + "{\"id\": \"a\", \"status\": \"solved\", \"status\": \"failed\", \"trajectory\": []}]}",
               "p.json:3: uavs[0].status: duplicate key 'status'");
  expect_error(head + "{\"id\": \"a\\u0000\xff\", \"status\": \"solved\", \"trajectory\": []}]}",
               "p.json:3: not valid UTF-8");
  expect_error(head + "{\"id\": \"a\", \"status\": \"solved\", \"trajectory\": [[1e400, 0, 0, 0]]}]}",
               "p.json:3: not valid JSON");
}

}  // namespace
}  // namespace uavplan
