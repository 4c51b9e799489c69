#include "uavplan/coordination/spacetime/space_time_table.h"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace uavplan {

void SpaceTimeTable::clear(int vertex_count, std::size_t expected_entries) {
  if (vertex_count > kMostVertices)
    throw std::invalid_argument("a space-time search takes at most " + std::to_string(kMostVertices) +
                                " vertices, not " + std::to_string(vertex_count));
  if (vertex_count != vertex_count_) {  // another graph: the per-vertex arrays start again
    stays_from_.clear();
    stayed_.clear();
    last_at_.clear();
    touched_.clear();
    ended_.clear();
    closed_ends_.clear();
    vertex_count_ = vertex_count;
  }
  vertex_.clear(expected_entries);
  moves_.clear(expected_entries);
  move_stays_.clear();
  for (const int v : stayed_) stays_from_[v] = INT_MAX;
  stayed_.clear();
  for (const int v : touched_) last_at_[v] = -1;
  for (const int v : closed_ends_) ended_[v] = 0;
  closed_ends_.clear();
  touched_.clear();
  last_time_ = -1;
}

void SpaceTimeTable::add_vertex(int v, int t) {
  if (t > kLastTime) return;  // beyond every search's horizon
  vertex_.add(vertex_key(v, t));
  note_taken(v, t);
  last_time_ = std::max(last_time_, t);
}

void SpaceTimeTable::note_taken(int v, int t) {
  if (last_at_.empty()) last_at_.assign(static_cast<std::size_t>(vertex_count_), -1);
  if (last_at_[v] < 0) touched_.push_back(v);
  last_at_[v] = std::max(last_at_[v], t);
}

void SpaceTimeTable::add_move(int u, int v, int t) {
  if (t > kLastTime) return;
  moves_.add(move_key(u, v, t));
  last_time_ = std::max(last_time_, t + 1);
  if (u == v) note_taken(v, t);  // an agent ending at v by t would wait there in step t
}

void SpaceTimeTable::add_move_stay(int u, int v, int t) {
  if (u == v) {  // waiting at v from t on: v cannot be an end
    close_end(v);
  }
  const std::uint64_t key = move_key(u, v, 0);
  const int held = move_stays_.get(key);
  const int from = std::min(t, kLastTime) + 1;
  if (held == 0 || from < held) move_stays_.add(key, from - held);
  last_time_ = std::max(last_time_, std::min(t, kLastTime));
}

void SpaceTimeTable::add_stay(int v, int t) {
  if (stays_from_.empty()) stays_from_.assign(static_cast<std::size_t>(vertex_count_), INT_MAX);
  if (stays_from_[v] == INT_MAX) stayed_.push_back(v);
  stays_from_[v] = std::min(stays_from_[v], t);
  last_time_ = std::max(last_time_, t);
}

void SpaceTimeTable::close_end(int v) {
  if (ended_.empty()) ended_.assign(static_cast<std::size_t>(vertex_count_), 0);
  if (!ended_[v]) closed_ends_.push_back(v);
  ended_[v] = 1;
}

void SpaceTimeTable::add_path(const SpaceTimePath& path) {
  const int end = static_cast<int>(path.size()) - 1;
  for (int t = 0; t < end; ++t) {
    add_vertex(path[t], t);
    if (path[t] != path[t + 1]) add_move(path[t + 1], path[t], t);  // the swap meets it
  }
  add_stay(path.back(), end);
}

int SpaceTimeTable::last_time_at(int v) const {
  if (!stays_from_.empty() && stays_from_[v] != INT_MAX) return INT_MAX;
  if (!ended_.empty() && ended_[v]) return INT_MAX;
  return last_at_.empty() ? -1 : last_at_[v];
}

}  // namespace uavplan
