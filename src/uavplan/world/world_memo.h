// What the layers above derive from one World and reuse while it lives (a planner's voxel grid
// for a cell size and a body, the bit lines a jump point search reads): every UAV of a mission
// and every plan of a batch on the same world builds it once. Shared by the copies of a World
// (they are the same world); thread-safe: a value is made once, under the lock, and shared.
#pragma once

#include <cstddef>
#include <list>
#include <memory>
#include <mutex>
#include <string>
#include <utility>

namespace uavplan {

class WorldMemo {
 public:
  // The last this many values are kept (a voxel grid of 90 M cells and its lines take 45 MB).
  static constexpr std::size_t kMaxValues = 4;

  // The value kept under `key` (the caller names every input of make() in it), else make()'s,
  // kept. An exception from make() keeps nothing.
  template <class T, class Make>
  std::shared_ptr<const T> get(const std::string& key, Make&& make) const {
    const std::lock_guard<std::mutex> lock(mutex_);
    for (auto it = values_.begin(); it != values_.end(); ++it)
      if (it->first == key) {
        values_.splice(values_.begin(), values_, it);  // most recently used first
        return std::static_pointer_cast<const T>(values_.front().second);
      }
    std::shared_ptr<const T> made = std::make_shared<const T>(make());
    values_.emplace_front(key, made);
    if (values_.size() > kMaxValues) values_.pop_back();
    return made;
  }

 private:
  mutable std::mutex mutex_;
  mutable std::list<std::pair<std::string, std::shared_ptr<const void>>> values_;
};

}  // namespace uavplan
