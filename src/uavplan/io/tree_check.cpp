#include "uavplan/io/tree_check.h"

#include <charconv>
#include <map>
#include <set>

#include "uavplan/io/input_error.h"

namespace uavplan {
namespace {

// Visits each node once (nodes are told apart by where they start in the file; an alias is the
// node it names), counting the values below it as the tree would expand them.
class TreeCheck {
 public:
  TreeCheck(const std::string& file, std::size_t max_values) : file_(file), max_(max_values) {}
  std::size_t values(const YAML::Node& n, const std::string& path) {
    if (!n.IsMap() && !n.IsSequence()) return 1;
    const auto key = std::make_pair(n.Mark().line, n.Mark().column);
    if (const auto it = memo_.find(key); it != memo_.end()) return it->second;
    // An alias inside the node its anchor names makes the tree a cycle: no reader could walk it.
    if (!open_.insert(key).second)
      throw InputError(file_, key.first + 1, path,
                       "a YAML alias inside the node it refers to (the value contains itself)");
    std::size_t total = 1;
    const auto add = [&](std::size_t k) { total = total > max_ ? total : total + k; };
    if (n.IsSequence()) {
      std::size_t i = 0;
      for (const auto& c : n) add(values(c, path + "[" + std::to_string(i++) + "]"));
    } else {
      std::map<std::string, int> seen;
      for (const auto& kv : n) {
        const std::string k = kv.first.IsScalar() ? kv.first.Scalar() : std::string("?");
        std::string at = path;
        if (!at.empty()) at += '.';
        at += k;
        const int line = kv.first.Mark().line + 1;
        if (const auto [it, fresh] = seen.emplace(k, line); !fresh)
          throw InputError(file_, line, at,
                           "duplicate key '" + k + "' (first at line " + std::to_string(it->second) + ")");
        add(values(kv.first, at));
        add(values(kv.second, at));
      }
    }
    open_.erase(key);
    memo_[key] = total;
    return total;
  }

 private:
  const std::string& file_;
  std::size_t max_;
  std::map<std::pair<int, int>, std::size_t> memo_;
  std::set<std::pair<int, int>> open_;  // the collections being walked, outermost first
};

}  // namespace

void check_tree(const YAML::Node& root, const std::string& file, std::size_t max_values) {
  if (TreeCheck(file, max_values).values(root, "") > max_values)
    throw InputError(file, 0, "",
                     "the file expands (through YAML aliases) to more than " + std::to_string(max_values) + " values");
}

KeyPath split_key_path(const std::string& path) {
  KeyPath kp;
  if (!path.empty() && path.back() == '.') kp.error = "empty key";  // nothing after the last '.'
  std::size_t i = 0;
  while (i < path.size()) {
    if (path[i] == '.') {
      ++i;
      continue;
    }
    if (path[i] == '[') {
      const auto close = path.find(']', i);
      if (close == std::string::npos) {
        kp.error = "unclosed '['";
        return kp;
      }
      std::size_t idx = 0;
      const auto [p, ec] = std::from_chars(path.data() + i + 1, path.data() + close, idx);
      if (ec != std::errc() || p != path.data() + close) {
        kp.error = "bad list index";
        return kp;
      }
      kp.steps.push_back({"", idx});
      i = close + 1;
    } else {
      const auto end = path.find_first_of(".[", i);
      kp.steps.push_back({path.substr(i, end == std::string::npos ? std::string::npos : end - i), std::nullopt});
      i = end == std::string::npos ? path.size() : end;
    }
  }
  return kp;
}

int line_of(const YAML::Node& root, const std::string& path) {
  YAML::Node cur;
  cur.reset(root);
  for (const KeyPath::Step& step : split_key_path(path).steps) {
    YAML::Node next;
    if (step.index) {
      if (!cur.IsSequence() || *step.index >= cur.size()) break;
      next.reset(cur[*step.index]);
    } else {
      if (!cur.IsMap() || !cur[step.key].IsDefined()) break;
      next.reset(cur[step.key]);
    }
    cur.reset(next);
  }
  return cur.IsDefined() && cur.Mark().line >= 0 ? cur.Mark().line + 1 : 0;
}

}  // namespace uavplan
