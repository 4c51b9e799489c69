#include "uavplan/io/mapf_file.h"

#include <yaml-cpp/yaml.h>

#include <cstdio>
#include <limits>
#include <map>

#include "uavplan/io/files.h"
#include "uavplan/io/input_error.h"
#include "uavplan/io/text_input.h"
#include "uavplan/io/tree_check.h"

namespace uavplan {
namespace {

constexpr int kMostSide = 1 << 10;  // 1024 x 1024 cells: the space-time table's 2^20 vertices
constexpr std::size_t kMostValues = 4'000'000;

// A key a const node lacks reads as a node that throws on every question but IsDefined: every
// check asks that first.
int node_line(const YAML::Node& n) { return n.IsDefined() && n.Mark().line >= 0 ? n.Mark().line + 1 : 0; }

[[noreturn]] void bad(const std::string& file, const YAML::Node& n, const std::string& place, const std::string& what) {
  throw InputError(file, node_line(n), place, what);
}

int whole_number(const std::string& file, const YAML::Node& n, const std::string& place) {
  long long v = 0;
  if (!n.IsDefined() || !n.IsScalar() || !YAML::convert<long long>::decode(n, v) ||
      v < std::numeric_limits<int>::min() || v > std::numeric_limits<int>::max())
    bad(file, n, place, "a whole number expected");
  return static_cast<int>(v);
}

// A cell [x, y] inside the map.
std::array<int, 2> cell(const std::string& file, const YAML::Node& n, const std::string& place, int w, int h) {
  if (!n.IsDefined() || !n.IsSequence() || n.size() != 2) bad(file, n, place, "a cell [x, y] expected");
  const std::array<int, 2> c{whole_number(file, n[0], place + "[0]"), whole_number(file, n[1], place + "[1]")};
  if (c[0] < 0 || c[1] < 0 || c[0] >= w || c[1] >= h)
    bad(file, n, place,
        "[" + std::to_string(c[0]) + ", " + std::to_string(c[1]) + "] is outside the map (" + std::to_string(w) +
            " x " + std::to_string(h) + ")");
  return c;
}

void read_map(const std::string& file, const YAML::Node& map, MapfInstance& in) {
  if (!map.IsDefined() || !map.IsMap()) bad(file, map, "map", "a map {dimensions, obstacles} expected");
  const YAML::Node dims = map["dimensions"];
  if (!dims.IsDefined() || !dims.IsSequence() || dims.size() != 2)
    bad(file, dims.IsDefined() ? dims : map, "map.dimensions", "[W, H] expected");
  in.width = whole_number(file, dims[0], "map.dimensions[0]");
  in.height = whole_number(file, dims[1], "map.dimensions[1]");
  if (in.width < 1 || in.height < 1 || in.width > kMostSide || in.height > kMostSide)
    bad(file, dims, "map.dimensions", "each side must be 1 to " + std::to_string(kMostSide) + " cells");
  in.blocked.assign(static_cast<std::size_t>(in.width) * static_cast<std::size_t>(in.height), 0);
  const YAML::Node obstacles = map["obstacles"];
  if (!obstacles.IsDefined() || obstacles.IsNull()) return;
  if (!obstacles.IsSequence()) bad(file, obstacles, "map.obstacles", "a list of cells [x, y] expected");
  for (std::size_t k = 0; k < obstacles.size(); ++k) {
    const auto c = cell(file, obstacles[k], "map.obstacles[" + std::to_string(k) + "]", in.width, in.height);
    in.blocked[in.cell_index(c)] = 1;
  }
}

void read_agents(const std::string& file, const YAML::Node& agents, MapfInstance& in) {
  if (!agents.IsDefined() || !agents.IsSequence() || agents.size() == 0)
    bad(file, agents, "agents", "a list of agents expected");
  for (std::size_t k = 0; k < agents.size(); ++k) {
    const YAML::Node a = agents[k];
    const std::string place = "agents[" + std::to_string(k) + "]";
    if (!a.IsMap()) bad(file, a, place, "an agent {name, start, goal} expected");
    const YAML::Node name = a["name"];
    if (!name.IsDefined() || !name.IsScalar() || name.Scalar().empty())
      bad(file, name.IsDefined() ? name : a, place + ".name", "a name expected");
    in.names.push_back(name.Scalar());
    for (const char* key : {"start", "goal"}) {
      const YAML::Node n = a[key];
      const auto c = cell(file, n.IsDefined() ? n : a, place + "." + key, in.width, in.height);
      if (in.blocked[in.cell_index(c)]) bad(file, n, place + "." + key, "on an obstacle");
      (key[0] == 's' ? in.starts : in.goals).push_back(c);
    }
  }
  // Each name, start and goal once (the first agent that has it, for the message).
  std::map<std::string, std::size_t> names;
  std::map<std::array<int, 2>, std::size_t> starts, goals;
  for (std::size_t k = 0; k < in.names.size(); ++k) {
    const std::string place = "agents[" + std::to_string(k) + "]";
    const auto once = [&](auto& seen, const auto& value, const char* key) {
      const auto [it, fresh] = seen.emplace(value, k);
      if (!fresh)
        bad(file, agents[k], place + "." + key,
            std::string("the ") + key + " of agents[" + std::to_string(it->second) + "] too");
    };
    once(names, in.names[k], "name");
    once(starts, in.starts[k], "start");
    once(goals, in.goals[k], "goal");
  }
}

// A YAML double-quoted string: whatever the name holds stays data.
std::string quoted(const std::string& s) {
  std::string out = "\"";
  for (const unsigned char c : s) {
    if (c == '"' || c == '\\') {
      out += '\\';
      out += static_cast<char>(c);
    } else if (c < 0x20 || c == 0x7f) {
      char esc[8];
      std::snprintf(esc, sizeof esc, "\\x%02x", c);
      out += esc;
    } else {
      out += static_cast<char>(c);
    }
  }
  return out + "\"";
}

}  // namespace

MapfProblem MapfInstance::problem() const {
  MapfProblem p;
  p.graph = grid4(width, height, blocked);
  for (std::size_t i = 0; i < starts.size(); ++i) {
    p.starts.push_back(starts[i][1] * width + starts[i][0]);
    p.goals.push_back(goals[i][1] * width + goals[i][0]);
  }
  return p;
}

MapfInstance parse_mapf_instance(const std::string& text, const std::string& file) {
  YAML::Node root;
  try {
    root = YAML::Load(checked_text(text, file));
  } catch (const YAML::Exception& e) {
    throw InputError(file, e.mark.line >= 0 ? e.mark.line + 1 : 0, "", "YAML syntax error: " + e.msg);
  }
  check_tree(root, file, kMostValues);
  if (!root.IsMap()) bad(file, root, "", "a map with keys map and agents expected");
  for (const auto& kv : root) {
    const std::string key = kv.first.Scalar();
    if (key != "map" && key != "agents") bad(file, kv.first, key, "unknown key (map and agents expected)");
  }
  MapfInstance in;
  read_map(file, root["map"], in);
  read_agents(file, root["agents"], in);
  return in;
}

MapfInstance read_mapf_instance(const std::string& path) { return parse_mapf_instance(read_text_file(path), path); }

std::string mapf_solution_yaml(const MapfInstance& in, const MapfResult& r, double runtime_s) {
  char line[160];
  std::snprintf(line, sizeof line, "statistics:\n  cost: %d\n  makespan: %d\n  runtime: %.6f\nschedule:\n",
                r.sum_of_costs, r.makespan, runtime_s);
  std::string out = line;
  for (std::size_t i = 0; i < r.paths.size() && i < in.names.size(); ++i) {
    out += "  " + quoted(in.names[i]) + ":\n";
    for (std::size_t t = 0; t < r.paths[i].size(); ++t) {
      const int v = r.paths[i][t];
      std::snprintf(line, sizeof line, "    - x: %d\n      y: %d\n      t: %zu\n", v % in.width, v / in.width, t);
      out += line;
    }
  }
  return out;
}

}  // namespace uavplan
