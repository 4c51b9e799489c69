// Where and when an agent's space-time search meets others: vertices at times, moves between
// times, and vertices where an agent stays from some time on. Filled from other agents' paths
// (prioritised planning's reservations, ECBS's conflicts to avoid) or from a conflict-based
// search's constraints; the search reads every entry the same way: as forbidden (hard) or
// as a count of conflicts (soft).
#pragma once

#include <climits>
#include <cstdint>
#include <vector>

#include "uavplan/coordination/spacetime/flat_counts.h"

namespace uavplan {

// Vertex at t = 0, 1, ...; after its last entry the agent stays at its last vertex for ever.
using SpaceTimePath = std::vector<int>;

inline int vertex_at(const SpaceTimePath& p, int t) { return t < static_cast<int>(p.size()) ? p[t] : p.back(); }

class SpaceTimeTable {
 public:
  static constexpr int kMostVertices = 1 << 20;
  static constexpr int kLastTime = (1 << 24) - 1;

  // Empties the table for a graph of `vertex_count` vertices (at most 2^20; std::invalid_argument
  // beyond).
  void clear(int vertex_count, std::size_t expected_entries = 0);

  // `v` at time t.
  void add_vertex(int v, int t);
  // The move u -> v between t and t + 1.
  void add_move(int u, int v, int t);
  // `v` from time t on, for ever.
  void add_stay(int v, int t);
  // The move u -> v (u == v: a wait) in every step from t on.
  void add_move_stay(int u, int v, int t);
  // A whole path, as what another agent must not meet: its vertices at their times, its moves
  // reversed (a swap), and its last vertex from its end on.
  void add_path(const SpaceTimePath& path);

  int at(int v, int t) const {
    return vertex_.get(vertex_key(v, t)) + (stays_from_.empty() || t < stays_from_[v] ? 0 : 1);
  }
  // Entries on the move u -> v in step t (u == v: waiting at u from t to t + 1).
  int moves(int u, int v, int t) const {
    const int stayed = move_stays_.size() == 0 ? 0 : move_stays_.get(move_key(u, v, 0));
    return moves_.get(move_key(u, v, t)) + (stayed > 0 && t + 1 >= stayed ? 1 : 0);
  }
  // The last time `v` is taken or waiting there is forbidden (INT_MAX when for ever; -1 when
  // never): an agent may end at `v` only after it.
  int last_time_at(int v) const;
  // The last time of any entry (stays count from their start): after it only stays remain.
  int last_time() const { return last_time_; }

 private:
  static std::uint64_t vertex_key(int v, int t) {
    return static_cast<std::uint64_t>(static_cast<std::uint32_t>(t)) << 32 | static_cast<std::uint32_t>(v);
  }
  static std::uint64_t move_key(int u, int v, int t) {
    // Exact: vertices below 2^20 (clear() refuses more), times below 2^24.
    return static_cast<std::uint64_t>(static_cast<std::uint32_t>(t)) << 40 |
           static_cast<std::uint64_t>(static_cast<std::uint32_t>(u)) << 20 | static_cast<std::uint32_t>(v);
  }

  void note_taken(int v, int t);
  void close_end(int v);

  int vertex_count_ = 0;
  FlatCounts vertex_, moves_;
  FlatCounts move_stays_;        // move key at time 0 -> first time + 1
  std::vector<int> stays_from_;  // INT_MAX where none; sized on the first stay
  std::vector<int> stayed_;      // vertices with a stay, to reset
  std::vector<int> last_at_;     // last time each vertex is taken; sized lazily
  std::vector<int> touched_;
  std::vector<char> ended_;       // waiting there is forbidden from some time on; sized lazily
  std::vector<int> closed_ends_;  // vertices marked in ended_, to reset
  int last_time_ = -1;
};

}  // namespace uavplan
