#include "uavplan/planning/search/open_list.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "uavplan/core/rng.h"

namespace uavplan {
namespace {

// Pops, with pushes in between that may fall below the bucket being popped, must come out in
// the list's total order whatever the bucket width: compared with a sorted oracle.
std::vector<OpenList::Entry> run(double width, std::uint64_t seed) {
  Rng rng(seed);
  OpenList open;
  open.reset(10.0, width);
  std::vector<OpenList::Entry> out;
  std::uint32_t id = 0;
  auto push_some = [&](double base) {
    const int n = static_cast<int>(rng.uniform_int(0, 4));
    for (int i = 0; i < n; ++i) {
      // Mostly above the last pop, sometimes below it; repeated f and g make ties.
      const double f = std::round((base + rng.uniform(-0.5, 6.0)) * 4.0) / 4.0;
      const double g = std::round(rng.uniform(0.0, 3.0));
      open.push(f, g, id++ % 997);
    }
  };
  for (int i = 0; i < 50; ++i) push_some(10.0);
  while (!open.empty() && out.size() < 5000) {
    out.push_back(open.pop());
    push_some(out.back().f);
  }
  return out;
}

TEST(OpenList, PopsInTotalOrderWhateverTheBucketWidth) {
  for (std::uint64_t seed = 1; seed <= 3; ++seed) {
    const auto heap = run(std::numeric_limits<double>::infinity(), seed);
    ASSERT_GT(heap.size(), 1000u);
    for (const double width : {0.1, 0.5, 3.0}) {
      const auto bucketed = run(width, seed);
      ASSERT_EQ(bucketed.size(), heap.size());
      for (std::size_t i = 0; i < heap.size(); ++i) {
        EXPECT_EQ(bucketed[i].f, heap[i].f);
        EXPECT_EQ(bucketed[i].g, heap[i].g);
        ASSERT_EQ(bucketed[i].id, heap[i].id) << "pop " << i << ", width " << width;
      }
    }
  }
}

TEST(OpenList, EachPopIsTheLeastEntryLeft) {
  Rng rng(7);
  OpenList open;
  open.reset(0.0, 1.0);
  std::vector<OpenList::Entry> oracle;
  for (std::uint32_t i = 0; i < 2000; ++i) {
    const double f = std::round(rng.uniform(0.0, 40.0) * 2.0) / 2.0, g = std::round(rng.uniform(0.0, 5.0));
    open.push(f, g, i);
    oracle.push_back({f, static_cast<float>(g), i});
    if (i % 3 == 0) {
      const auto least = std::min_element(oracle.begin(), oracle.end(), OpenList::before);
      const OpenList::Entry e = open.pop();
      EXPECT_EQ(e.id, least->id);
      oracle.erase(least);
    }
  }
  EXPECT_EQ(open.size(), oracle.size());
  open.reset(5.0, 1.0);
  EXPECT_TRUE(open.empty());
  open.push(1.0, 0.0, 42);  // below f0: the first bucket
  EXPECT_EQ(open.pop().id, 42u);
}

// Entries thousands of buckets apart (a maze's detours: f jumps far between pops) come out in
// order across the words of the used-bucket bits, and a reset with entries still in far buckets
// leaves none behind for the next query.
TEST(OpenList, FarApartBucketsAndAResetWithEntriesLeft) {
  Rng rng(11);
  OpenList open;
  for (int query = 0; query < 3; ++query) {
    open.reset(0.0, 0.01);
    std::vector<OpenList::Entry> oracle;
    for (std::uint32_t i = 0; i < 300; ++i) {
      const double f = std::round(rng.uniform(0.0, 2000.0));  // every 100 buckets at least
      open.push(f, 0.0, i + 1000 * static_cast<std::uint32_t>(query));
      oracle.push_back({f, 0.0f, i + 1000 * static_cast<std::uint32_t>(query)});
    }
    std::sort(oracle.begin(), oracle.end(), OpenList::before);
    for (std::size_t k = 0; k < 200; ++k) ASSERT_EQ(open.pop().id, oracle[k].id) << "query " << query << ", pop " << k;
    EXPECT_EQ(open.size(), 100u);  // left in far buckets for the reset to clear
  }
  open.reset(0.0, 0.01);
  EXPECT_TRUE(open.empty());
  open.push(7.0, 0.0, 5);
  open.push(3.0, 0.0, 6);
  EXPECT_EQ(open.pop().id, 6u);
  EXPECT_EQ(open.pop().id, 5u);
  EXPECT_TRUE(open.empty());
}

}  // namespace
}  // namespace uavplan
