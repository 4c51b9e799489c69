// An RRT's tree: positions, parents and path lengths from the root in flat arrays, indexed for nearest-neighbour queries by nanoflann's dynamic k-d tree (a logarithmic
// set of static trees, rebuilt as points arrive). Nodes join the index in batches of kBatch:
// the newest few are compared directly, which spares a small tree (a local replan has tens of
// nodes) most of the index's rebuilding.
#pragma once

#include <nanoflann.hpp>

#include <algorithm>
#include <array>
#include <cstdint>
#include <limits>
#include <vector>

#include "uavplan/core/vec.h"

namespace uavplan {

class RrtTree {
 public:
  RrtTree(const Vec3& root, int capacity)
      : cloud_{&pos_},
        index_(3, cloud_, nanoflann::KDTreeSingleIndexAdaptorParams(16),
               static_cast<std::size_t>(std::max(capacity, 2))) {
    // A local replan has tens of nodes: reserve for a few hundred and grow beyond (reserving the
    // whole capacity costs a fresh mapping and its page faults on every search).
    const auto first = static_cast<std::size_t>(std::clamp(capacity, 2, 512));
    pos_.reserve(first);
    parent_.reserve(first);
    along_.reserve(first);
    add(root, -1);
  }
  RrtTree(const RrtTree&) = delete;
  RrtTree& operator=(const RrtTree&) = delete;

  static constexpr std::size_t kBatch = 32;

  int add(const Vec3& p, int parent) {
    const double along = parent < 0 ? 0.0 : along_[idx(parent)] + (p - pos_[idx(parent)]).norm();
    pos_.push_back(p);
    parent_.push_back(parent);
    along_.push_back(along);
    if (pos_.size() - indexed_ >= kBatch) {
      index_.addPoints(static_cast<std::uint32_t>(indexed_), static_cast<std::uint32_t>(pos_.size() - 1));
      indexed_ = pos_.size();
    }
    return static_cast<int>(pos_.size() - 1);
  }
  // The node nearest to q.
  int nearest(const Vec3& q) const {
    std::uint32_t best = 0;
    double best_d2 = std::numeric_limits<double>::infinity();
    if (indexed_ > 0) {
      nanoflann::KNNResultSet<double, std::uint32_t> rs(1);
      rs.init(&best, &best_d2);
      index_.findNeighbors(rs, q.data(), nanoflann::SearchParams());
    }
    for (std::size_t i = indexed_; i < pos_.size(); ++i) {
      const double d2 = (pos_[i] - q).squaredNorm();
      if (d2 < best_d2) {
        best_d2 = d2;
        best = static_cast<std::uint32_t>(i);
      }
    }
    return static_cast<int>(best);
  }
  // The nearest of the kNear nodes nearest to q that `usable` accepts, or -1.
  static constexpr std::size_t kNear = 8;
  template <class Usable>
  int nearest_usable(const Vec3& q, Usable&& usable) const {
    std::array<std::uint32_t, kNear + kBatch> found{};
    std::array<double, kNear + kBatch> d2{};
    std::size_t n = 0;
    if (indexed_ > 0) {
      nanoflann::KNNResultSet<double, std::uint32_t> rs(kNear);
      rs.init(found.data(), d2.data());
      index_.findNeighbors(rs, q.data(), nanoflann::SearchParams());
      n = rs.size();
    }
    for (std::size_t i = indexed_; i < pos_.size(); ++i, ++n) {
      found[n] = static_cast<std::uint32_t>(i);
      d2[n] = (pos_[i] - q).squaredNorm();
    }
    std::array<std::size_t, kNear + kBatch> order{};
    for (std::size_t i = 0; i < n; ++i) order[i] = i;
    const std::size_t m = std::min(n, kNear);
    std::partial_sort(
        order.begin(), order.begin() + static_cast<std::ptrdiff_t>(m), order.begin() + static_cast<std::ptrdiff_t>(n),
        [&](std::size_t a, std::size_t b) { return d2[a] < d2[b] || (d2[a] == d2[b] && found[a] < found[b]); });
    for (std::size_t i = 0; i < m; ++i)
      if (usable(static_cast<int>(found[order[i]]))) return static_cast<int>(found[order[i]]);
    return -1;
  }
  const Vec3& pos(int i) const { return pos_[idx(i)]; }
  int parent(int i) const { return parent_[idx(i)]; }
  double along(int i) const { return along_[idx(i)]; }  // path length from the root
  int size() const { return static_cast<int>(pos_.size()); }
  // Root ... i.
  std::vector<Vec3> path_to(int i) const {
    std::vector<Vec3> out;
    for (; i >= 0; i = parent(i)) out.push_back(pos(i));
    std::reverse(out.begin(), out.end());
    return out;
  }

 private:
  static std::size_t idx(int i) { return static_cast<std::size_t>(i); }
  // nanoflann's dataset adaptor over the positions.
  struct Cloud {
    const std::vector<Vec3>* points;
    std::size_t kdtree_get_point_count() const { return points->size(); }
    double kdtree_get_pt(std::size_t i, std::size_t axis) const { return (*points)[i][static_cast<int>(axis)]; }
    template <class Box>
    bool kdtree_get_bbox(Box&) const {
      return false;
    }
  };
  using Index =
      nanoflann::KDTreeSingleIndexDynamicAdaptor<nanoflann::L2_Simple_Adaptor<double, Cloud>, Cloud, 3, std::uint32_t>;
  std::vector<Vec3> pos_;
  std::vector<int> parent_;
  std::vector<double> along_;
  Cloud cloud_;  // before index_, which keeps a reference to it
  Index index_;
  std::size_t indexed_ = 0;  // pos_[0, indexed_) are in the index
};

}  // namespace uavplan
