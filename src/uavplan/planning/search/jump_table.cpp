#include "uavplan/planning/search/jump_table.h"

#include <bit>
#include <stdexcept>

namespace uavplan {

namespace {

// Bit k of the windows is cell p + k.
LineStop scan_up(const BitLines& s, int line, std::int64_t p, std::int64_t goal) {
  for (;;) {
    const std::uint64_t b = s.window(line, p), u = s.window(line - 1, p), d = s.window(line + 1, p);
    std::uint64_t stop = (b | (~u & u << 1) | (~d & d << 1)) & ~std::uint64_t{1};
    if (goal > p && goal - p < 64) stop |= std::uint64_t{1} << (goal - p);
    if (stop) {
      const int k = std::countr_zero(stop);
      return {p + k, !(b >> k & 1)};
    }
    p += 63;
  }
}

// Bit 63 - k of the windows is cell p - k.
LineStop scan_down(const BitLines& s, int line, std::int64_t p, std::int64_t goal) {
  constexpr std::uint64_t kTop = std::uint64_t{1} << 63;
  for (;;) {
    const std::int64_t from = p - 63;
    const std::uint64_t b = s.window(line, from), u = s.window(line - 1, from), d = s.window(line + 1, from);
    std::uint64_t stop = (b | (~u & u >> 1) | (~d & d >> 1)) & ~kTop;
    if (goal >= 0 && goal < p && p - goal < 64) stop |= kTop >> (p - goal);
    if (stop) {
      const int k = std::countl_zero(stop);
      return {p - k, !(b & kTop >> k)};
    }
    p -= 63;
  }
}

}  // namespace

LineStop scan_line(const BitLines& lines, int line, std::int64_t p, int step, std::int64_t goal) {
  return step > 0 ? scan_up(lines, line, p, goal) : scan_down(lines, line, p, goal);
}

JumpTable::JumpTable(const BitGrid& g, const BitLines& rows, const BitLines& cols) {
  if (!fits(g)) throw std::invalid_argument("jump table: the grid is wider or higher than 32,767 cells");
  steps_.assign(static_cast<std::size_t>(g.size()) * 8, 0);
  const int nx = g.nx(), ny = g.ny();
  auto at = [&](int x, int y, int dir) -> std::int16_t& {
    return steps_[static_cast<std::size_t>(g.index(x, y, 0)) * 8 + static_cast<std::size_t>(dir)];
  };
  for (int y = 0; y < ny; ++y)
    for (int x = 0; x < nx; ++x) {
      if (g.blocked(x, y, 0)) continue;
      for (int step = -1; step <= 1; step += 2) {
        const LineStop h = scan_line(rows, y, x, step, -1), v = scan_line(cols, x, y, step, -1);
        const auto dh = static_cast<std::int32_t>((h.at - x) * step), dv = static_cast<std::int32_t>((v.at - y) * step);
        at(x, y, direction(step, 0)) = static_cast<std::int16_t>(h.jump_point ? dh : -(dh - 1));
        at(x, y, direction(0, step)) = static_cast<std::int16_t>(v.jump_point ? dv : -(dv - 1));
      }
    }
  // A diagonal from the cell after it: sweep from the side it moves towards.
  for (int dy = -1; dy <= 1; dy += 2)
    for (int dx = -1; dx <= 1; dx += 2) {
      const int dir = direction(dx, dy);
      for (int yi = 0; yi < ny; ++yi)
        for (int xi = 0; xi < nx; ++xi) {
          const int x = dx > 0 ? nx - 1 - xi : xi, y = dy > 0 ? ny - 1 - yi : yi;
          if (g.blocked(x, y, 0) || g.blocked(x + dx, y, 0) || g.blocked(x, y + dy, 0) || g.blocked(x + dx, y + dy, 0))
            continue;  // 0: no step
          const int nxt_x = x + dx, nxt_y = y + dy;
          if (at(nxt_x, nxt_y, direction(dx, 0)) > 0 || at(nxt_x, nxt_y, direction(0, dy)) > 0) {
            at(x, y, dir) = 1;
          } else {
            const std::int32_t after = at(nxt_x, nxt_y, dir);
            at(x, y, dir) = static_cast<std::int16_t>(after > 0 ? after + 1 : after - 1);
          }
        }
    }
}

}  // namespace uavplan
