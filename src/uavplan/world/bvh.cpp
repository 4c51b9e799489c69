#include "uavplan/world/bvh.h"

#include <algorithm>
#include <numeric>

namespace uavplan {
namespace {
constexpr std::int32_t kLeafSize = 4;
}

Bvh::Bvh(std::span<const Aabb> boxes) {
  if (boxes.empty()) return;
  indices_.resize(boxes.size());
  std::iota(indices_.begin(), indices_.end(), 0);
  std::vector<Vec3> centers(boxes.size());
  for (std::size_t i = 0; i < boxes.size(); ++i) centers[i] = boxes[i].center();
  nodes_.reserve(2 * boxes.size() / kLeafSize + 2);
  build(boxes, centers, 0, static_cast<std::int32_t>(boxes.size()));
}

// Median split on the longest axis of the centres: depth stays about log2(n / kLeafSize),
// well inside the fixed traversal stack.
std::int32_t Bvh::build(std::span<const Aabb> boxes, std::vector<Vec3>& centers, std::int32_t first,
                        std::int32_t count) {
  const auto id = static_cast<std::int32_t>(nodes_.size());
  nodes_.emplace_back();
  Aabb box, cbox;
  for (std::int32_t k = first; k < first + count; ++k) {
    box.extend(boxes[indices_[k]]);
    cbox.extend(centers[indices_[k]]);
  }
  nodes_[id].box = box;
  if (count <= kLeafSize) {
    nodes_[id].first = first;
    nodes_[id].count = count;
    return id;
  }
  int axis = 0;
  cbox.extent().maxCoeff(&axis);
  const std::int32_t mid = first + count / 2;
  std::nth_element(indices_.begin() + first, indices_.begin() + mid, indices_.begin() + first + count,
                   [&](std::int32_t x, std::int32_t y) { return centers[x][axis] < centers[y][axis]; });
  const std::int32_t left = build(boxes, centers, first, mid - first);
  const std::int32_t right = build(boxes, centers, mid, first + count - mid);
  nodes_[id].left = left;
  nodes_[id].right = right;
  return id;
}

}  // namespace uavplan
