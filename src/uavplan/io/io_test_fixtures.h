// What the io tests share: the small scenario and plan (exports, report), a temporary folder.
#pragma once

#include <unistd.h>

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "uavplan/coordination/contract/plan.h"
#include "uavplan/coordination/contract/scenario.h"

namespace uavplan::test {

// A fresh folder uavplan_TAG_PID under the system's temporary folder, removed with its contents
// at the end of the scope.
struct TempDir {
  std::filesystem::path path;
  explicit TempDir(const std::string& tag)
      : path(std::filesystem::temp_directory_path() / ("uavplan_" + tag + "_" + std::to_string(::getpid()))) {
    std::filesystem::remove_all(path);
    std::filesystem::create_directories(path);
  }
  ~TempDir() { std::filesystem::remove_all(path); }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
};

// A 1000 x 1000 x 100 m world near Zurich with one UAV "a/1" at (0, 0, 10).
inline Scenario scenario_with(std::vector<Obstacle> obstacles = {}) {
  Scenario sc;
  sc.name = "t";
  sc.origin = GeoOrigin{47.3977, 8.5456, 488.0};
  WorldSpec w;
  w.bounds = Aabb{Vec3(0, 0, 0), Vec3(1000, 1000, 100)};
  w.obstacles = std::move(obstacles);
  sc.world = World(std::move(w));
  UavSpec u;
  u.id = "a/1";
  u.start = Vec3(0, 0, 10);
  u.speed = {0.0, 5.0, 10.0};
  sc.uavs.push_back(u);
  return sc;
}

// Holds 4 s at the start, flies east 100 m in two collinear samples at 5 m/s, turns north and
// flies 100 m at 10 m/s.
inline UavPlan sample_uav() {
  UavPlan u;
  u.id = "a/1";
  u.status = Status::solved;
  u.trajectory = {{0.0, Vec3(0, 0, 10)},
                  {4.0, Vec3(0, 0, 10)},
                  {14.0, Vec3(50, 0, 10)},
                  {24.0, Vec3(100, 0, 10)},
                  {34.0, Vec3(100, 100, 10)}};
  return u;
}

inline Plan plan_of(std::vector<UavPlan> uavs) {
  Plan p;
  p.status = Status::solved;
  p.uavs = std::move(uavs);
  return p;
}

}  // namespace uavplan::test
