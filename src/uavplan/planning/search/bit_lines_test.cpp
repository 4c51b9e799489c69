#include "uavplan/planning/search/bit_lines.h"

#include <gtest/gtest.h>

#include <tuple>

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
      const BitLines lines(g, columns ? 1 : 0);
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

void check_volume(Rng& r, int nx, int ny, int nz);

// In 3-D, the lines along each axis read the cells with that coordinate running and the other
// two fixed (line(u, w) names them; -1 outside the grid, read as blocked); sides shorter and
// longer than the 64-cell blocks the lines are transposed by.
TEST(BitLines, LinesAlongEachAxisOfAVolume) {
  Rng r(9);
  for (const auto& [nx, ny, nz] :
       {std::tuple{70, 5, 4}, std::tuple{130, 67, 3}, std::tuple{9, 3, 140}, std::tuple{65, 70, 66}})
    check_volume(r, nx, ny, nz);
}

void check_volume(Rng& r, int nx, int ny, int nz) {
  BitGrid g(nx, ny, nz);
  for (std::int64_t c = 0; c < g.size(); ++c)
    if (r.uniform01() < 0.3) g.set_blocked(c);
  const int n[3] = {g.nx(), g.ny(), g.nz()};
  for (int axis = 0; axis < 3; ++axis) {
    const BitLines lines(g, axis);
    const int a = axis == 0 ? 1 : 0, b = axis == 2 ? 1 : 2;  // the other two axes, in order
    for (int u = -1; u <= n[a]; ++u)
      for (int w = -1; w <= n[b]; ++w)
        for (std::int64_t from = -3; from <= n[axis]; from += 5) {
          const std::uint64_t bits = lines.window(lines.line(u, w), from);
          for (int q = 0; q < 64; ++q) {
            int c[3];
            c[axis] = static_cast<int>(from + q);
            c[a] = u;
            c[b] = w;
            ASSERT_EQ((bits >> q) & 1u, g.blocked(c[0], c[1], c[2]) ? 1u : 0u)
                << nx << "x" << ny << "x" << nz << " axis " << axis << " u " << u << " w " << w << " from " << from
                << " bit " << q;
          }
        }
  }
}

}  // namespace
}  // namespace uavplan
