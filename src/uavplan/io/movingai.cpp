#include "uavplan/io/movingai.h"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>
#include <type_traits>

#include <nlohmann/json.hpp>

#include "uavplan/io/input_error.h"

namespace uavplan {
namespace {

std::ifstream open_or_throw(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path, 0, "", std::string("cannot open: ") + std::strerror(errno));
  return in;
}

void strip_cr(std::string& s) {
  if (!s.empty() && s.back() == '\r') s.pop_back();
}

// Whitespace-separated fields of a line.
std::vector<std::string> fields(const std::string& line, char sep = 0) {
  std::vector<std::string> out;
  if (sep) {
    std::stringstream ss(line);
    std::string f;
    while (std::getline(ss, f, sep)) out.push_back(f);
    return out;
  }
  std::istringstream ss(line);
  std::string f;
  while (ss >> f) out.push_back(f);
  return out;
}

template <class T>
T parse_num(const std::string& s, const std::string& path, int line, const char* what) {
  T v{};
  const auto [p, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (ec != std::errc() || p != s.data() + s.size())
    throw InputError(path, line, what, "expected a number, got '" + s + "'");
  if constexpr (std::is_floating_point_v<T>)
    if (!std::isfinite(v) || std::abs(v) > 1e15)
      throw InputError(path, line, what, "must be a finite number below 1e15, got '" + s + "'");
  return v;
}

}  // namespace

bool is_movingai_3d(const std::string& p) { return p.size() >= 6 && p.compare(p.size() - 6, 6, ".3dmap") == 0; }

BitGrid read_movingai_map(const std::string& path) {
  std::ifstream in = open_or_throw(path);
  std::string line;
  int width = -1, height = -1, lineno = 0;
  while (std::getline(in, line)) {
    ++lineno;
    strip_cr(line);
    const auto f = fields(line);
    if (f.empty()) continue;
    if (f[0] == "map") break;
    if (f[0] == "height" && f.size() == 2) height = parse_num<int>(f[1], path, lineno, "height");
    if (f[0] == "width" && f.size() == 2) width = parse_num<int>(f[1], path, lineno, "width");
  }
  if (width <= 0 || height <= 0)
    throw InputError(path, lineno, "header", "missing or bad 'height'/'width' before 'map'");
  // Every cell is a character of the file: a header claiming more is refused before allocating.
  std::error_code ec;
  const auto bytes = std::filesystem::file_size(path, ec);
  if (!ec && static_cast<double>(width) * height > static_cast<double>(bytes))
    throw InputError(path, lineno, "header",
                     std::to_string(width) + " x " + std::to_string(height) + " cells, more than the file's " +
                         std::to_string(bytes) + " bytes can hold");
  BitGrid g(width, height, 1);
  for (int y = 0; y < height; ++y) {
    if (!std::getline(in, line))
      throw InputError(path, lineno + 1, "map", "expected " + std::to_string(height) + " rows");
    ++lineno;
    strip_cr(line);
    if (static_cast<int>(line.size()) < width)
      throw InputError(path, lineno, "map",
                       "row has " + std::to_string(line.size()) + " cells, expected " + std::to_string(width));
    for (int x = 0; x < width; ++x) {
      const char c = line[x];
      if (c != '.' && c != 'G' && c != 'S') g.set_blocked(g.index(x, y, 0));
    }
  }
  return g;
}

std::vector<MovingAiProblem> read_movingai_scen(const std::string& path) {
  std::ifstream in = open_or_throw(path);
  std::string line;
  std::vector<MovingAiProblem> out;
  int lineno = 0;
  while (std::getline(in, line)) {
    ++lineno;
    strip_cr(line);
    if (line.empty() || line.rfind("version", 0) == 0) continue;
    auto f = fields(line, '\t');
    if (f.size() != 9) f = fields(line);
    if (f.size() != 9)
      throw InputError(path, lineno, "", "expected 9 fields: bucket map width height sx sy gx gy optimal");
    MovingAiProblem p;
    p.bucket = parse_num<int>(f[0], path, lineno, "bucket");
    p.start[0] = parse_num<int>(f[4], path, lineno, "start x");
    p.start[1] = parse_num<int>(f[5], path, lineno, "start y");
    p.goal[0] = parse_num<int>(f[6], path, lineno, "goal x");
    p.goal[1] = parse_num<int>(f[7], path, lineno, "goal y");
    p.optimal = parse_num<double>(f[8], path, lineno, "optimal");
    out.push_back(p);
  }
  return out;
}

BitGrid read_movingai_3dmap(const std::string& path) {
  std::unique_ptr<FILE, int (*)(FILE*)> f(std::fopen(path.c_str(), "r"), &std::fclose);
  if (!f) throw InputError(path, 0, "", std::string("cannot open: ") + std::strerror(errno));
  char buf[256];
  int lineno = 0, dims[3] = {0, 0, 0};
  while (std::fgets(buf, sizeof buf, f.get())) {
    ++lineno;
    if (std::sscanf(buf, "voxel %d %d %d", &dims[0], &dims[1], &dims[2]) == 3) break;
    if (buf[strspn(buf, " \t\r\n")] != '\0') throw InputError(path, lineno, "header", "expected 'voxel X Y Z'");
  }
  if (dims[0] <= 0 || dims[1] <= 0 || dims[2] <= 0)
    throw InputError(path, lineno, "header", "bad or missing 'voxel X Y Z'");
  if (static_cast<double>(dims[0]) * dims[1] * dims[2] > kMaxMovingAiVoxels)
    throw InputError(
        path, lineno, "header",
        "more than " + std::to_string(static_cast<long long>(kMaxMovingAiVoxels)) + " voxels (a grid of 128 MiB)");
  BitGrid g(dims[0], dims[1], dims[2]);
  while (std::fgets(buf, sizeof buf, f.get())) {
    ++lineno;
    int x, y, z;
    const int n = std::sscanf(buf, "%d %d %d", &x, &y, &z);
    if (n == EOF || (n <= 0 && buf[strspn(buf, " \t\r\n")] == '\0')) continue;
    if (n != 3) throw InputError(path, lineno, "", "expected 'x y z'");
    if (!g.inside(x, y, z)) throw InputError(path, lineno, "", "voxel outside the map");
    g.set_blocked(g.index(x, y, z));
  }
  return g;
}

std::vector<MovingAiProblem> read_movingai_3dscen(const std::string& path) {
  std::ifstream in = open_or_throw(path);
  std::string line;
  std::vector<MovingAiProblem> out;
  int lineno = 0;
  while (std::getline(in, line)) {
    ++lineno;
    strip_cr(line);
    const auto f = fields(line);
    if (f.empty() || f[0] == "version" || f.size() == 1) continue;  // header and map name
    if (f.size() < 7) throw InputError(path, lineno, "", "expected 'sx sy sz gx gy gz optimal [ratio]'");
    MovingAiProblem p;
    for (int k = 0; k < 3; ++k) {
      p.start[k] = parse_num<int>(f[k], path, lineno, "start");
      p.goal[k] = parse_num<int>(f[3 + k], path, lineno, "goal");
    }
    p.optimal = parse_num<double>(f[6], path, lineno, "optimal");
    // The 3-D files carry no bucket; group by tens of the optimal cost as the 2-D ones do.
    // An unsolvable ('inf') or absurd cost has no bucket.
    const double bucket = std::floor(p.optimal / 10.0);
    p.bucket = std::isfinite(bucket) && bucket >= 0.0 && bucket < 1e6 ? static_cast<int>(bucket) : -1;
    out.push_back(p);
  }
  return out;
}

namespace {

// Whether every cell of the box [i0, i1) x [j0, j1) x {k} is blocked and not yet taken.
bool all_open_blocked(const BitGrid& grid, const BitGrid& taken, int i0, int i1, int j0, int j1, int k) {
  for (int j = j0; j < j1; ++j)
    for (int i = i0; i < i1; ++i) {
      const std::int64_t idx = grid.index(i, j, k);
      if (!grid.blocked(idx) || taken.blocked(idx)) return false;
    }
  return true;
}

}  // namespace

std::vector<CellBox> merge_blocked_cells(const BitGrid& grid) {
  std::vector<CellBox> boxes;
  BitGrid taken(grid.nx(), grid.ny(), grid.nz());
  for (int k = 0; k < grid.nz(); ++k)
    for (int j = 0; j < grid.ny(); ++j)
      for (int i = 0; i < grid.nx(); ++i) {
        if (!all_open_blocked(grid, taken, i, i + 1, j, j + 1, k)) continue;
        int i1 = i + 1, j1 = j + 1, k1 = k + 1;
        while (i1 < grid.nx() && all_open_blocked(grid, taken, i1, i1 + 1, j, j + 1, k)) ++i1;
        while (j1 < grid.ny() && all_open_blocked(grid, taken, i, i1, j1, j1 + 1, k)) ++j1;
        while (k1 < grid.nz() && all_open_blocked(grid, taken, i, i1, j, j1, k1)) ++k1;
        for (int c = k; c < k1; ++c)
          for (int b = j; b < j1; ++b)
            for (int a = i; a < i1; ++a) taken.set_blocked(grid.index(a, b, c));
        boxes.push_back({{i, j, k}, {i1, j1, k1}});
      }
  return boxes;
}

std::string movingai_scenario_yaml(const BitGrid& grid, const std::vector<CellBox>& boxes, const std::string& name,
                                   const MovingAiProblem& problem) {
  // A 2-D map is a world of zero height (z = 0): its boxes reach 1 m below and above it.
  const bool flat = grid.nz() == 1;
  const auto z_low = [flat](int k) { return flat ? -1 : k; };
  const auto z_high = [flat](int k) { return flat ? 1 : k; };
  const auto centre = [&](const int c[3]) {
    return "[" + std::to_string(c[0]) + ".5, " + std::to_string(c[1]) + ".5, " +
           (flat ? std::string("0") : std::to_string(c[2]) + ".5") + "]";
  };
  std::ostringstream out;
  out << "version: 1\nname: " << nlohmann::json(name).dump() << "\nworld:\n  bounds: {min: [0, 0, 0], max: ["
      << grid.nx() << ", " << grid.ny() << ", " << (flat ? 0 : grid.nz()) << "]}\n  obstacles:\n";
  if (boxes.empty()) out << "    []\n";
  for (const CellBox& b : boxes)
    out << "    - {type: box, min: [" << b.min[0] << ", " << b.min[1] << ", " << z_low(b.min[2]) << "], max: ["
        << b.max[0] << ", " << b.max[1] << ", " << z_high(b.max[2]) << "]}\n";
  out << "uavs:\n  - {id: u1, start: " << centre(problem.start) << ", goal: " << centre(problem.goal)
      << ", radius: 0, speed: 5}\nmission: {type: independent}\n"
      << "planner: {algorithm: astar, params: {cell_m: 1}}\n";
  return out.str();
}

}  // namespace uavplan
