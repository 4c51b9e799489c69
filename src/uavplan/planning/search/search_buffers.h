// Search state reused across queries: per-cell g-value, parent and open/closed flag in pages
// allocated on first touch, and a generation stamp so that a new query costs nothing to clear
// (no O(cells) reset). The open list is apart (open_list.h); best_first.h joins the two.
#pragma once

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
  static void reopen(Node& n) { n.stamp &= ~1u; }  // to be expanded again (3-D JPS: a new move at a tie)

  std::size_t memory_bytes() const {
    std::size_t b = pages_.capacity() * sizeof(pages_[0]);
    for (const auto& p : pages_)
      if (p) b += kPageSize * sizeof(Node);
    return b;
  }

 private:
  static constexpr int kPageBits = 12;
  static constexpr std::int64_t kPageSize = std::int64_t{1} << kPageBits;
  std::vector<std::unique_ptr<Node[]>> pages_;
  std::uint32_t generation_ = 0;
};

}  // namespace uavplan
