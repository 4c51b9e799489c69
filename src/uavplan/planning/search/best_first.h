// One best-first search loop for grid A*, JPS, Lazy Theta*, cell A* and directional A*
// (warthog's design, Harabor and Grastien: the loop is a template on its parts). A search
// brings an expansion policy (which children a node has, what they cost, when to stop) and a
// heuristic; the open list is a third parameter. The compiler inlines all three into the loop:
// no virtual call and no allocation per node (nodes live in SearchBuffers' pages, entries in the
// open list's reused storage).
//
// An expansion policy `E` provides
//   bool stop_now(std::uint64_t expanded);                 // checked once per expansion
//   void expand(std::uint32_t id, const SearchBuffers::Node& n, Relax& relax);
// and optionally
//   void settle(std::uint32_t id);                         // before `id` is closed (Theta*'s SetVertex)
//   double refine(std::uint32_t id, double f, double g);   // lazy heuristic (below)
// `expand` offers each child through relax(child, g, parent, position): g is the child's cost
// through `parent` (the node itself, or for Theta* the node's parent), and the heuristic, a
// callable on the policy's own position type (cell coordinates, a point), is evaluated only when
// the child improves.
//
// `refine` is for a heuristic too costly for every child (directional A*'s relaxed distances):
// children go in with a cheap lower bound, and a node's f is raised to the costly bound when it
// comes off the list; if that is larger, the node goes back in with it (never when infinite:
// the goal is out of its reach). Nodes are still closed in the order of the costly f, so the
// search expands what A* with the costly heuristic expands, but evaluates it only for nodes
// taken off the list, not for every child.
#pragma once

#include <algorithm>
#include <cstdint>
#include <limits>
#include <vector>

#include "uavplan/core/stop.h"
#include "uavplan/planning/search/open_list.h"
#include "uavplan/planning/search/search_buffers.h"

namespace uavplan {

struct SearchCounts {
  std::uint64_t expanded = 0;
  std::uint64_t generated = 0;  // entries pushed: a node again each time its g improves
  std::uint64_t opened = 0;     // distinct nodes ever on the list, the start included
  std::uint64_t open_max = 0;
};

enum class SearchEnd { goal, exhausted, stopped };

// The stop condition asked every `every` expansions (a power of two): a clock read per node would
// cost more than the node.
inline bool stop_due(const StopCondition& stop, std::uint64_t expanded, std::uint64_t every) {
  return (expanded & (every - 1)) == 0 && stop.should_stop(expanded);
}

template <class Open = OpenList>
class BestFirst {
 public:
  // Offers a child to the search: kept (and pushed) when its g beats its best so far.
  template <class Heuristic>
  class Relax {
   public:
    Relax(BestFirst& search, const Heuristic& h, SearchCounts& counts) : s_(search), h_(h), counts_(counts) {}
    template <class Position>
    bool operator()(std::uint32_t child, double g, std::uint32_t parent, const Position& at) {
      SearchBuffers::Node& c = s_.nodes_.at(child);
      if (SearchBuffers::closed(c) || !(g < c.g)) return false;
      if (c.g == std::numeric_limits<double>::infinity()) ++counts_.opened;  // first time on the list
      c.g = g;
      c.parent = parent;
      s_.open_.push(g + h_(at), g, child);
      ++counts_.generated;
      counts_.open_max = std::max<std::uint64_t>(counts_.open_max, s_.open_.size());
      return true;
    }

   private:
    BestFirst& s_;
    const Heuristic& h_;
    SearchCounts& counts_;
  };

  // Starts a query over ids [0, ids) (at most 2^32 - 1); nothing is cleared but a stamp.
  void begin(std::int64_t ids, double f0 = 0.0, double bucket_width = std::numeric_limits<double>::infinity()) {
    nodes_.begin(ids);
    open_.reset(f0, bucket_width);
    pending_ = SearchBuffers::kNoParent;
  }

  // Searches from `start` (whose parent is `start_parent`: kNoParent, or itself for Theta*) until
  // `goal` is closed, the list runs dry, or the policy stops.
  template <class Expansion, class Heuristic, class Position>
  SearchEnd run(Expansion& expansion, const Heuristic& h, std::uint32_t start, std::uint32_t start_parent,
                const Position& start_at, std::uint32_t goal, SearchCounts& counts) {
    seed(h, start, start_parent, start_at, counts);
    return resume(expansion, h, goal, counts);
  }

  // run() in two parts: the start on the list, then the loop. A search the policy stopped goes on
  // where it was with resume() (the node closed as it stopped is expanded first), so two searches
  // can take turns (3-D JPS runs one from each end).
  template <class Heuristic, class Position>
  void seed(const Heuristic& h, std::uint32_t start, std::uint32_t start_parent, const Position& start_at,
            SearchCounts& counts) {
    SearchBuffers::Node& s = nodes_.at(start);
    s.g = 0.0;
    s.parent = start_parent;
    open_.push(h(start_at), 0.0, start);
    ++counts.opened;
    counts.open_max = std::max<std::uint64_t>(counts.open_max, 1);
  }
  template <class Expansion, class Heuristic>
  SearchEnd resume(Expansion& expansion, const Heuristic& h, std::uint32_t goal, SearchCounts& counts) {
    Relax<Heuristic> relax(*this, h, counts);
    if (pending_ != SearchBuffers::kNoParent) {
      const std::uint32_t id = pending_;
      pending_ = SearchBuffers::kNoParent;
      expansion.expand(id, nodes_.at(id), relax);
    }
    while (!open_.empty()) {
      const typename Open::Entry e = open_.pop();
      SearchBuffers::Node& n = nodes_.at(e.id);
      // A node's later entries are stale: it carries its best g and parent itself.
      if (SearchBuffers::closed(n)) continue;
      if constexpr (requires { expansion.refine(e.id, e.f, n.g); }) {
        const double f = expansion.refine(e.id, e.f, n.g);
        if (f > e.f) {
          if (f < std::numeric_limits<double>::infinity()) open_.push(f, n.g, e.id);
          continue;
        }
      }
      if constexpr (requires { expansion.settle(e.id); }) expansion.settle(e.id);
      SearchBuffers::close(n);
      if (e.id == goal) return SearchEnd::goal;
      if (expansion.stop_now(++counts.expanded)) {
        pending_ = e.id;
        return SearchEnd::stopped;
      }
      expansion.expand(e.id, n, relax);
    }
    return SearchEnd::exhausted;
  }

  SearchBuffers::Node& node(std::uint32_t id) { return nodes_.at(id); }
  // The ids from `start` to `to` along the parents.
  std::vector<std::int64_t> path(std::uint32_t start, std::uint32_t to) {
    std::vector<std::int64_t> ids{to};
    for (std::uint32_t c = to; c != start; ids.push_back(c)) c = nodes_.at(c).parent;
    std::reverse(ids.begin(), ids.end());
    return ids;
  }
  Open& open() { return open_; }
  std::size_t memory_bytes() const { return nodes_.memory_bytes() + open_.memory_bytes(); }

 private:
  SearchBuffers nodes_;
  Open open_;
  std::uint32_t pending_ = SearchBuffers::kNoParent;  // closed as the policy stopped, not expanded yet
};

}  // namespace uavplan
