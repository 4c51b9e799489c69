// A hash table from 64-bit keys to counts, open addressing with linear probing, cleared in O(1)
// by a generation stamp: the space-time searches rebuild one per query from a few thousand path
// points, and look it up on every node they generate (no allocation per entry or per lookup).
#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

namespace uavplan {

class FlatCounts {
 public:
  // Empties the table, keeping room for `expected` keys without growing.
  void clear(std::size_t expected = 0) {
    if (++generation_ == 0) {  // wrapped: forget every slot
      std::fill(stamps_.begin(), stamps_.end(), 0u);
      generation_ = 1;
    }
    size_ = 0;
    std::size_t capacity = 16;
    while (capacity < 2 * expected) capacity *= 2;
    if (capacity > keys_.size()) resize(capacity);
  }
  void add(std::uint64_t key, int count = 1) {
    if (2 * (size_ + 1) > keys_.size()) grow();
    std::size_t i = slot(key);
    if (stamps_[i] != generation_) {
      stamps_[i] = generation_;
      keys_[i] = key;
      counts_[i] = 0;
      ++size_;
    }
    counts_[i] += count;
  }
  // Adds `key` once: true when it was not there.
  bool insert(std::uint64_t key) { return keep_least(key, 1); }
  // Sets `key` to `value` (above 0) when it is not there or holds more: true when it did. One probe.
  bool keep_least(std::uint64_t key, int value) {
    if (2 * (size_ + 1) > keys_.size()) grow();
    const std::size_t i = slot(key);
    if (stamps_[i] == generation_) {
      if (counts_[i] <= value) return false;
      counts_[i] = value;
      return true;
    }
    stamps_[i] = generation_;
    keys_[i] = key;
    counts_[i] = value;
    ++size_;
    return true;
  }
  int get(std::uint64_t key) const {
    if (size_ == 0) return 0;
    const std::size_t i = slot(key);
    return stamps_[i] == generation_ ? counts_[i] : 0;
  }
  std::size_t size() const { return size_; }

 private:
  // The slot holding `key`, or the empty slot where it would go.
  std::size_t slot(std::uint64_t key) const {
    const std::size_t mask = keys_.size() - 1;
    std::size_t i = static_cast<std::size_t>((key * 0x9E3779B97F4A7C15ull) >> 20) & mask;
    while (stamps_[i] == generation_ && keys_[i] != key) i = (i + 1) & mask;
    return i;
  }
  void resize(std::size_t capacity) {
    keys_.assign(capacity, 0);
    counts_.assign(capacity, 0);
    stamps_.assign(capacity, 0u);
  }
  void grow() {
    std::vector<std::uint64_t> keys;
    std::vector<int> counts;
    for (std::size_t i = 0; i < keys_.size(); ++i)
      if (stamps_[i] == generation_) {
        keys.push_back(keys_[i]);
        counts.push_back(counts_[i]);
      }
    resize(keys_.empty() ? 16 : 2 * keys_.size());
    generation_ = 1;
    size_ = 0;
    for (std::size_t k = 0; k < keys.size(); ++k) add(keys[k], counts[k]);
  }

  std::vector<std::uint64_t> keys_;
  std::vector<int> counts_;
  std::vector<std::uint32_t> stamps_;
  std::uint32_t generation_ = 0;
  std::size_t size_ = 0;
};

}  // namespace uavplan
