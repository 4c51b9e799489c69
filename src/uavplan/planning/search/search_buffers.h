// Search state reused across queries: per-cell g-value, parent and open/closed flag in pages
// allocated on first touch, and a generation stamp so that a new query costs nothing to clear
// (no O(cells) reset). Plus the open list: a binary heap of (f, g, cell) with lazy deletion.
#pragma once

#include <algorithm>
#include <cstdint>
#include <limits>
#include <memory>
#include <vector>

namespace uavplan {

class SearchBuffers {
 public:
  struct Node {
    double g;
    std::uint32_t parent;
    std::uint32_t stamp;  // generation << 1 | closed
  };
  static constexpr std::uint32_t kNoParent = std::numeric_limits<std::uint32_t>::max();

  // Starts a query over a grid of `cells` cells (at most 2^32 - 1).
  void begin(std::int64_t cells) {
    const auto pages = static_cast<std::size_t>((cells + kPageSize - 1) / kPageSize);
    if (pages > pages_.size()) pages_.resize(pages);
    if (++generation_ >= (1u << 31)) {  // wrap: forget every page
      for (auto& p : pages_) p.reset();
      generation_ = 1;
    }
    open_.clear();
  }

  // The node of `cell`, fresh (g = inf, no parent, open) if not touched in this query.
  Node& at(std::uint32_t cell) {
    auto& page = pages_[cell >> kPageBits];
    if (!page) page = std::make_unique<Node[]>(kPageSize);  // zero stamps: untouched
    Node& n = page[cell & (kPageSize - 1)];
    if ((n.stamp >> 1) != generation_) n = {std::numeric_limits<double>::infinity(), kNoParent, generation_ << 1};
    return n;
  }
  static bool closed(const Node& n) { return n.stamp & 1u; }
  static void close(Node& n) { n.stamp |= 1u; }

  struct Entry {
    double f, g;
    std::uint32_t cell;
  };
  void push(double f, double g, std::uint32_t cell) {
    open_.push_back({f, g, cell});
    std::push_heap(open_.begin(), open_.end(), Worse{});
  }
  Entry pop() {
    std::pop_heap(open_.begin(), open_.end(), Worse{});
    const Entry e = open_.back();
    open_.pop_back();
    return e;
  }
  bool open_empty() const { return open_.empty(); }
  std::size_t open_size() const { return open_.size(); }

  std::size_t memory_bytes() const {
    std::size_t b = pages_.capacity() * sizeof(pages_[0]) + open_.capacity() * sizeof(Entry);
    for (const auto& p : pages_)
      if (p) b += kPageSize * sizeof(Node);
    return b;
  }

 private:
  static constexpr int kPageBits = 12;
  static constexpr std::int64_t kPageSize = std::int64_t{1} << kPageBits;
  // Heap order: smaller f first; among equal f, larger g (deeper) first. A function object, so
  // the heap operations inline it.
  struct Worse {
    bool operator()(const Entry& a, const Entry& b) const { return a.f != b.f ? a.f > b.f : a.g < b.g; }
  };

  std::vector<std::unique_ptr<Node[]>> pages_;
  std::vector<Entry> open_;
  std::uint32_t generation_ = 0;
};

}  // namespace uavplan
