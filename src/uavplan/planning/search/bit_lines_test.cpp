#include "uavplan/planning/search/bit_lines.h"

#include <gtest/gtest.h>

#include "uavplan/core/rng.h"

namespace uavplan {
namespace {

// Every window, at the edges and across them, reads what the grid says cell by cell (outside:
// blocked), by rows and by columns, on grids narrower and wider than a word.
TEST(BitLines, WindowsReadTheGridCellByCell) {
  Rng r(5);
  for (const auto& [nx, ny] : {std::pair{7, 5}, std::pair{64, 3}, std::pair{130, 67}}) {
    BitGrid g(nx, ny, 1);
    for (std::int64_t c = 0; c < g.size(); ++c)
      if (r.uniform01() < 0.3) g.set_blocked(c);
    for (const bool columns : {false, true}) {
      const BitLines lines(g, columns);
      for (int line = -1; line <= lines.lines(); ++line)
        for (std::int64_t from = -70; from <= lines.length() + 2; ++from) {
          const std::uint64_t w = lines.window(line, from);
          for (int b = 0; b < 64; ++b) {
            const std::int64_t p = from + b;
            const bool blocked =
                columns ? g.blocked(line, static_cast<int>(p), 0) : g.blocked(static_cast<int>(p), line, 0);
            ASSERT_EQ((w >> b) & 1u, blocked ? 1u : 0u)
                << nx << "x" << ny << " columns " << columns << " line " << line << " from " << from << " bit " << b;
          }
        }
    }
  }
}

}  // namespace
}  // namespace uavplan
