// An RRT's tree: positions, parents and path lengths from the root in flat arrays reserved
// once, indexed for nearest-neighbour queries by nanoflann's dynamic k-d tree (a logarithmic
// set of static trees, rebuilt as points arrive; amortised O(log^2 n) per insertion).
#pragma once

#include <nanoflann.hpp>

#include <algorithm>
#include <array>
#include <cstdint>
#include <vector>

#include "uavplan/core/vec.h"

namespace uavplan {

class RrtTree {
 public:
  RrtTree(const Vec3& root, int capacity)
      : cloud_{&pos_}, index_(3, cloud_, nanoflann::KDTreeSingleIndexAdaptorParams(16),
                              static_cast<std::size_t>(std::max(capacity, 2))) {
    pos_.reserve(static_cast<std::size_t>(capacity));
    parent_.reserve(static_cast<std::size_t>(capacity));
    along_.reserve(static_cast<std::size_t>(capacity));
    add(root, -1);
  }
  RrtTree(const RrtTree&) = delete;
  RrtTree& operator=(const RrtTree&) = delete;

  int add(const Vec3& p, int parent) {
    const double along = parent < 0 ? 0.0 : along_[idx(parent)] + (p - pos_[idx(parent)]).norm();
    pos_.push_back(p);
    parent_.push_back(parent);
    along_.push_back(along);
    const auto i = static_cast<std::uint32_t>(pos_.size() - 1);
    index_.addPoints(i, i);
    return static_cast<int>(i);
  }
  // The node nearest to q.
  int nearest(const Vec3& q) const {
    std::uint32_t i = 0;
    double d2 = 0.0;
    nanoflann::KNNResultSet<double, std::uint32_t> rs(1);
    rs.init(&i, &d2);
    index_.findNeighbors(rs, q.data(), nanoflann::SearchParams());
    return static_cast<int>(i);
  }
  // The nearest of the `k` (at most 8) nodes nearest to q that `usable` accepts, or -1.
  template <class Usable>
  int nearest_usable(const Vec3& q, Usable&& usable) const {
    constexpr std::size_t k = 8;
    std::array<std::uint32_t, k> found{};
    std::array<double, k> d2{};
    nanoflann::KNNResultSet<double, std::uint32_t> rs(k);
    rs.init(found.data(), d2.data());
    index_.findNeighbors(rs, q.data(), nanoflann::SearchParams());
    for (std::size_t n = 0; n < rs.size(); ++n)
      if (usable(static_cast<int>(found[n]))) return static_cast<int>(found[n]);
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
    bool kdtree_get_bbox(Box&) const { return false; }
  };
  using Index = nanoflann::KDTreeSingleIndexDynamicAdaptor<nanoflann::L2_Simple_Adaptor<double, Cloud>, Cloud, 3,
                                                           std::uint32_t>;
  std::vector<Vec3> pos_;
  std::vector<int> parent_;
  std::vector<double> along_;
  Cloud cloud_;  // before index_, which keeps a reference to it
  Index index_;
};

}  // namespace uavplan
