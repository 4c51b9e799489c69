// The open list of a best-first search, under a total order (smaller f, then larger g - deeper
// first -, then smaller id), so the sequence of pops depends only on what was pushed, never on
// how the list stores it.
//
// Entries are kept in buckets of f (width `bucket_width` from `f0`); only the bucket being
// popped is a binary heap, later ones are plain arrays turned into a heap when their turn
// comes. A search whose f rarely falls (A* with a consistent heuristic: a child's f is at least
// its parent's) pushes most entries in O(1) into a later bucket, and its pops sift through a
// small heap that stays in cache instead of one holding the whole frontier. An entry below the
// current bucket joins the current heap, so every pop still returns the least entry of all. A
// bit per bucket says which hold entries: a search whose f jumps far (a maze's detours) passes
// thousands of empty buckets a word at a time, and a reset clears only those it used.
#pragma once

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

namespace uavplan {

class OpenList {
 public:
  struct Entry {
    double f;
    float g;  // for the order among equal f only
    std::uint32_t id;
  };

  // Empties the list (keeping its storage). An infinite width makes it one binary heap.
  void reset(double f0 = 0.0, double bucket_width = std::numeric_limits<double>::infinity()) {
    for (std::size_t w = 0; w < used_.size(); ++w) {
      for (std::uint64_t bits = used_[w]; bits != 0; bits &= bits - 1)
        buckets_[w * 64 + static_cast<std::size_t>(std::countr_zero(bits))].clear();
      used_[w] = 0;
    }
    if (!buckets_.empty()) buckets_[current_].clear();
    f0_ = f0;
    inv_width_ = bucket_width > 0.0 && std::isfinite(bucket_width) ? 1.0 / bucket_width : 0.0;
    current_ = 0;
    size_ = 0;
    if (buckets_.empty()) {
      buckets_.resize(64);
      used_.assign(1, 0);
    }
  }
  bool empty() const { return size_ == 0; }
  std::size_t size() const { return size_; }
  std::size_t memory_bytes() const {
    std::size_t b = buckets_.capacity() * sizeof(std::vector<Entry>) + used_.capacity() * sizeof(std::uint64_t);
    for (const auto& v : buckets_) b += v.capacity() * sizeof(Entry);
    return b;
  }

  void push(double f, double g, std::uint32_t id) {
    const Entry e{f, static_cast<float>(g), id};
    ++size_;
    const std::size_t k = bucket_of(f);
    if (k <= current_) {
      std::vector<Entry>& heap = buckets_[current_];
      heap.push_back(e);
      sift_up(heap, heap.size() - 1, e);
      return;
    }
    if (k >= buckets_.size()) {
      buckets_.resize(std::max((k / 64 + 1) * 64, 2 * buckets_.size()));
      used_.resize(buckets_.size() / 64, 0);
    }
    buckets_[k].push_back(e);
    used_[k / 64] |= std::uint64_t{1} << (k % 64);
  }

  // The least entry; the list must not be empty.
  Entry pop() {
    if (buckets_[current_].empty()) {
      current_ = next_used();
      std::vector<Entry>& next = buckets_[current_];
      for (std::size_t i = next.size() / 2; i-- > 0;) sift_down(next, i);
    }
    --size_;
    std::vector<Entry>& heap = buckets_[current_];
    const Entry top = heap.front();
    const Entry last = heap.back();
    heap.pop_back();
    const std::size_t n = heap.size();
    if (n == 0) return top;
    // Floyd: the hole goes down to a leaf along the better children, then `last` rises.
    std::size_t hole = 0;
    for (std::size_t c = 1; c < n; c = 2 * hole + 1) {
      c += static_cast<std::size_t>(c + 1 < n && before(heap[c + 1], heap[c]));
      heap[hole] = heap[c];
      hole = c;
    }
    sift_up(heap, hole, last);
    return top;
  }

  static bool before(const Entry& a, const Entry& b) {
    if (a.f != b.f) return a.f < b.f;
    if (a.g != b.g) return a.g > b.g;
    return a.id < b.id;
  }

 private:
  static constexpr std::size_t kMaxBuckets = std::size_t{1} << 20;  // beyond: the last one

  // The first bucket after the current one that holds entries (there is one: the list is not
  // empty and the current bucket is); its bit is cleared, as it becomes the current bucket.
  std::size_t next_used() {
    std::size_t w = (current_ + 1) / 64;
    std::uint64_t bits = used_[w] & (~std::uint64_t{0} << ((current_ + 1) % 64));
    while (bits == 0) bits = used_[++w];
    const std::size_t k = w * 64 + static_cast<std::size_t>(std::countr_zero(bits));
    used_[w] &= ~(std::uint64_t{1} << (k % 64));
    return k;
  }
  std::size_t bucket_of(double f) const {
    const double d = (f - f0_) * inv_width_;
    if (!(d > 0.0)) return 0;
    return d < static_cast<double>(kMaxBuckets - 1) ? static_cast<std::size_t>(d) : kMaxBuckets - 1;
  }
  static void sift_up(std::vector<Entry>& heap, std::size_t hole, const Entry e) {
    while (hole > 0) {
      const std::size_t parent = (hole - 1) / 2;
      if (!before(e, heap[parent])) break;
      heap[hole] = heap[parent];
      hole = parent;
    }
    heap[hole] = e;
  }
  static void sift_down(std::vector<Entry>& heap, std::size_t hole) {
    const Entry e = heap[hole];
    const std::size_t n = heap.size();
    for (std::size_t c = 2 * hole + 1; c < n; c = 2 * hole + 1) {
      c += static_cast<std::size_t>(c + 1 < n && before(heap[c + 1], heap[c]));
      if (!before(heap[c], e)) break;
      heap[hole] = heap[c];
      hole = c;
    }
    heap[hole] = e;
  }

  std::vector<std::vector<Entry>> buckets_;  // a multiple of 64 of them
  std::vector<std::uint64_t> used_;          // bit k: bucket k, after the current one, holds entries
  std::size_t current_ = 0, size_ = 0;
  double f0_ = 0.0, inv_width_ = 0.0;
};

}  // namespace uavplan
