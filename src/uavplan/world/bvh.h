// Static bounding-volume hierarchy over axis-aligned boxes: the world's broad phase, so a
// query touches only the obstacles near it.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "uavplan/core/geometry.h"
#include "uavplan/core/vec.h"

namespace uavplan {

class Bvh {
 public:
  Bvh() = default;
  explicit Bvh(std::span<const Aabb> boxes);

  // Calls f(index, radius) for every box whose `radius`-inflated copy the segment crosses;
  // f may shrink `radius` (a running best distance) to prune the rest. Returns early when f
  // returns true.
  template <class F>
  void visit_segment(const Vec3& a, const Vec3& b, double& radius, F&& f) const;

  // Calls f(index, radius) for every box within `radius` of p, pruning as above.
  template <class F>
  void visit_point(const Vec3& p, double& radius, F&& f) const;

  std::size_t size() const { return indices_.size(); }

 private:
  struct Node {
    Aabb box;
    std::int32_t left = -1, right = -1;  // children, -1 for a leaf
    std::int32_t first = 0, count = 0;   // leaf range in indices_
  };
  std::int32_t build(std::span<const Aabb> boxes, std::vector<Vec3>& centers, std::int32_t first, std::int32_t count);

  std::vector<Node> nodes_;
  std::vector<std::int32_t> indices_;
};

template <class F>
void Bvh::visit_segment(const Vec3& a, const Vec3& b, double& radius, F&& f) const {
  if (nodes_.empty()) return;
  std::int32_t stack[64];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Node& n = nodes_[stack[--top]];
    double t0, t1;
    if (!clip_segment_to_box(a, b, n.box.inflated(radius), t0, t1)) continue;
    if (n.left < 0) {
      for (std::int32_t k = n.first; k < n.first + n.count; ++k)
        if (f(indices_[k], radius)) return;
    } else {
      stack[top++] = n.left;
      stack[top++] = n.right;
    }
  }
}

template <class F>
void Bvh::visit_point(const Vec3& p, double& radius, F&& f) const {
  if (nodes_.empty()) return;
  std::int32_t stack[64];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Node& n = nodes_[stack[--top]];
    if (n.box.distance(p) > radius) continue;
    if (n.left < 0) {
      for (std::int32_t k = n.first; k < n.first + n.count; ++k)
        if (f(indices_[k], radius)) return;
    } else {
      // Nearer child last, so it is visited first and shrinks the radius sooner.
      const bool left_nearer = nodes_[n.left].box.distance(p) <= nodes_[n.right].box.distance(p);
      stack[top++] = left_nearer ? n.right : n.left;
      stack[top++] = left_nearer ? n.left : n.right;
    }
  }
}

}  // namespace uavplan
