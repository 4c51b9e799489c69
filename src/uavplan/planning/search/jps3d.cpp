#include "uavplan/planning/search/jps3d.h"

#include <algorithm>
#include <bit>
#include <cstdlib>
#include <limits>
#include <stdexcept>

namespace uavplan {
// A named namespace, not an anonymous one: Jps3d::Expansion (declared in the header) holds these
// types, which GCC accepts from an anonymous namespace only in the main file (-Wsubobject-linkage,
// and the unity build makes this file part of another).
namespace jps3d_rules {

// A move (or a cell beside the current one) as its bit in BitGrid::free_mask: (dz+1)*9 +
// (dy+1)*3 + (dx+1); 13 is no move, and a node with it (the start, the goal) goes every way.
constexpr int kMoves = 27, kAny = 13;
struct Offset {
  int v[3];
};
Offset offset_of(int move) { return {{move % 3 - 1, move / 3 % 3 - 1, move / 9 - 1}}; }
int axes_of(int move) {
  const Offset o = offset_of(move);
  return (o.v[0] != 0) + (o.v[1] != 0) + (o.v[2] != 0);
}

// The bits of `from` + every non-empty sub-move of `m`: the bounding box a move m from `from`
// needs free. The cells lie beside the current one (asserted by construction: the throw is a
// broken table, not an input).
std::uint32_t box_bits(const Offset& from, const Offset& m) {
  std::uint32_t bits = 0;
  for (int s = 1; s < 8; ++s) {
    Offset c = from;
    bool sub = true;
    for (int a = 0; a < 3; ++a)
      if (s >> a & 1) {
        sub = sub && m.v[a] != 0;
        c.v[a] += m.v[a];
      }
    if (!sub) continue;
    for (int a = 0; a < 3; ++a)
      if (c.v[a] < -1 || c.v[a] > 1) throw std::logic_error("jps3d: a replacement path leaves the 3x3x3 block");
    bits |= 1u << ((c.v[2] + 1) * 9 + (c.v[1] + 1) * 3 + (c.v[0] + 1));
  }
  return bits;
}

bool is_sub_move(const Offset& s, const Offset& d) {  // s's components a subset of d's
  for (int a = 0; a < 3; ++a)
    if (s.v[a] != 0 && s.v[a] != d.v[a]) return false;
  return true;
}

// Move e is forced after move d when it is legal (`need` free) and its replacement from the cell
// before is not: some cell of `replace` is blocked. Cells known free (the move d itself, e's own
// box) are left out of `replace`.
struct Rule {
  std::uint32_t need, replace;
  int move;
};

struct Tables {
  std::uint32_t need[kMoves] = {};
  int sub[kMoves][7] = {}, subs[kMoves] = {};
  Rule rules[kMoves][kMoves] = {};
  int n_rules[kMoves] = {};

  Tables() {
    const Offset zero{{0, 0, 0}};
    for (int m = 0; m < kMoves; ++m)
      if (m != kAny) need[m] = box_bits(zero, offset_of(m));
    for (int d = 0; d < kMoves; ++d) {
      if (d == kAny) continue;
      const Offset dv = offset_of(d), before{{-dv.v[0], -dv.v[1], -dv.v[2]}};
      const std::uint32_t known =
          box_bits(before, dv) | 1u << ((before.v[2] + 1) * 9 + (before.v[1] + 1) * 3 + (before.v[0] + 1));
      for (int e = 0; e < kMoves; ++e) {
        if (e == kAny) continue;
        const Offset ev = offset_of(e);
        if (is_sub_move(ev, dv)) {
          sub[d][subs[d]++] = e;
          continue;
        }
        const std::uint32_t replace = replacement(before, dv, ev) & ~(need[e] | known);
        if (replace) rules[d][n_rules[d]++] = {need[e], replace, e};
      }
    }
  }

  // The cells of the path that replaces "d then e" from the cell before: e then d when d is a
  // sub-move of e (the same cost), else the canonical path to the same cell (all axes it moves
  // on, then those it moves two on), strictly shorter. Nothing when e undoes d.
  static std::uint32_t replacement(const Offset& before, const Offset& d, const Offset& e) {
    if (is_sub_move(d, e)) {
      const Offset mid{{before.v[0] + e.v[0], before.v[1] + e.v[1], before.v[2] + e.v[2]}};
      return box_bits(before, e) | box_bits(mid, d);
    }
    Offset first{}, second{};
    bool moves = false;
    for (int a = 0; a < 3; ++a) {
      const int v = d.v[a] + e.v[a];
      first.v[a] = (v > 0) - (v < 0);
      second.v[a] = std::abs(v) == 2 ? first.v[a] : 0;
      moves = moves || v != 0;
    }
    if (!moves) return 0;
    const Offset mid{{before.v[0] + first.v[0], before.v[1] + first.v[1], before.v[2] + first.v[2]}};
    return box_bits(before, first) | box_bits(mid, second);
  }

  bool legal(std::uint32_t mask, int move) const { return (mask & need[move]) == need[move]; }
  bool forced(std::uint32_t mask, const Rule& r) const {
    return (mask & r.need) == r.need && (mask & r.replace) != r.replace;
  }
  // The moves a cell with neighbourhood `mask` goes on with, reached by the moves in `reached`
  // (one bit each): every legal one for kAny, else the sub-moves and the forced moves.
  std::uint32_t continuations(std::uint32_t reached, std::uint32_t mask) const {
    if (reached >> kAny & 1u) return mask & ~(1u << kAny);  // to every free neighbour (boxes checked on the walk)
    std::uint32_t out = 0;
    for (; reached; reached &= reached - 1) {
      const int d = std::countr_zero(reached);
      for (int s = 0; s < subs[d]; ++s) out |= 1u << sub[d][s];
      for (int r = 0; r < n_rules[d]; ++r)
        if (forced(mask, rules[d][r])) out |= 1u << rules[d][r].move;
    }
    return out;
  }
  // Whether a cell reached by move d, with neighbourhood `mask`, has a forced move: a jump point.
  bool jump_point(std::uint32_t mask, int d) const {
    for (int r = 0; r < n_rules[d]; ++r)
      if (forced(mask, rules[d][r])) return true;
    return false;
  }
};

// The free_mask of the cell at bit p of the nine line reads along `axis` around it (read q holds
// the line at offsets q % 3 - 1, q / 3 - 1 on the other two axes, in x, y, z order).
std::uint32_t neighbourhood(const std::uint64_t r[9], int p, int axis) {
  std::uint32_t mask = 0;
  for (int q = 0; q < 9; ++q) {
    const auto f = static_cast<std::uint32_t>(~(r[q] >> (p - 1)) & 7u);  // before, at, after
    const int u = q % 3, w = q / 3;
    if (axis == 0) {
      mask |= f << (3 * q);
      continue;
    }
    const int stride = axis == 1 ? 3 : 9, base = axis == 1 ? w * 9 + u : w * 3 + u;
    mask |= ((f & 1u) | (f >> 1 & 1u) << stride | (f >> 2 & 1u) << 2 * stride) << base;
  }
  return mask;
}

const Tables& tables() {
  static const Tables t;
  return t;
}

}  // namespace jps3d_rules

Jps3dLines jps3d_lines(const BitGrid& grid) { return {BitLines(grid, 0), BitLines(grid, 1), BitLines(grid, 2)}; }

Jps3d::Jps3d(const BitGrid& grid, Jps3dOptions options)
    : Jps3d(grid, std::make_shared<const Jps3dLines>(jps3d_lines(grid)), options) {}

Jps3d::Jps3d(const BitGrid& grid, std::shared_ptr<const Jps3dLines> lines, Jps3dOptions options)
    : grid_(&grid), options_(options), lines_(std::move(lines)) {
  options_.slice_expansions = std::max<std::uint32_t>(options_.slice_expansions, 1);
  if (grid.size() >= std::int64_t{std::numeric_limits<std::uint32_t>::max()})
    throw std::invalid_argument("Jump Point Search in 3-D: the grid has too many cells (under 2^32 - 1)");
  (void)jps3d_rules::tables();
}

std::size_t Jps3d::line_bytes() const {
  return (*lines_)[0].memory_bytes() + (*lines_)[1].memory_bytes() + (*lines_)[2].memory_bytes();
}

int Jps3d::WalkLimit::first_over(const int c[3], int axis, int cur, int step) const {
  int at[3] = {c[0], c[1], c[2]};
  const auto over_at = [&](int t) {
    at[axis] = cur + t * step;
    return over(at);
  };
  if (over_at(0)) return 0;  // most lines off the goal's way: past the limit at once
  if (!over_at(61)) return 62;
  int lo = 1, hi = 61;  // f never falls along a line: the first cell past the limit by halving
  while (lo < hi) {
    const int m = (lo + hi) / 2;
    if (over_at(m))
      hi = m;
    else
      lo = m + 1;
  }
  return lo;
}

// Reads the nine lines around the jump 62 cells at a time; a cell whose nine neighbours along the
// line (before, at, after) are the same in all nine has no forced move (its neighbourhood is the
// same slab three times, so every replacement lies in what the move itself needs), so only cells
// where some line changes are tested exactly, on the neighbourhood those reads hold.
bool Jps3d::jump_straight(int c[3], int axis, int step, const WalkLimit& limit) const {
  using namespace jps3d_rules;
  const Tables& tb = tables();
  const int ua = axis == 0 ? 1 : 0, wa = axis == 2 ? 1 : 2;
  const BitLines& lines = (*lines_)[axis];
  int near[9];
  for (int q = 0; q < 9; ++q) near[q] = lines.line(c[ua] + q % 3 - 1, c[wa] + q / 3 - 1);
  const int* goal = limit.goal;
  const bool goal_line = goal[ua] == c[ua] && goal[wa] == c[wa];
  const int move = kAny + step * (axis == 0 ? 1 : axis == 1 ? 3 : 9);
  constexpr std::uint64_t kCells = ((std::uint64_t{1} << 62) - 1) << 1;  // bits 1..62
  int cur = c[axis] + step;
  for (;;) {
    // Bit p of a read is cell from + p; cells cur .. cur + 61 * step are bits 1..62, so each has
    // both neighbours along the line in the read.
    const std::int64_t from = step > 0 ? cur - 1 : cur - 62;
    std::uint64_t r[9], differ = 0;
    for (int q = 0; q < 9; ++q) {
      r[q] = lines.window(near[q], from);
      differ |= r[q] ^ (r[q] >> 1);
    }
    differ &= ~std::uint64_t{0} >> 1;  // bit p: cells p and p + 1 differ
    std::uint64_t test = (differ | differ << 1) & kCells;
    const auto ahead_of = [&](int p) { return step > 0 ? p - 1 : 62 - p; };
    const int cut = limit.first_over(c, axis, cur, step);  // cells ahead of cur within the limit
    const int goal_ahead = goal_line ? (goal[axis] - cur) * step : -1;
    for (;;) {
      const int p = test ? (step > 0 ? std::countr_zero(test) : 63 - std::countl_zero(test)) : -1;
      const int t = p < 0 ? 62 : ahead_of(p);
      if (goal_ahead >= 0 && goal_ahead <= std::min(t, cut) && goal_ahead < 62) {
        c[axis] = goal[axis];
        return true;
      }
      if (t <= cut && t < 62) {
        if (r[4] >> p & 1u) return false;  // the line ends
        c[axis] = cur + t * step;
        if (tb.jump_point(neighbourhood(r, p, axis), move)) return true;
        test &= ~(std::uint64_t{1} << p);
        continue;
      }
      if (cut < 62) {
        c[axis] = cur + cut * step;
        return true;
      }
      break;
    }
    cur += 62 * step;
  }
}

// A node's moves: every legal one at the start, else the sub-moves of the moves that reached it
// at its g and the forced ones, less those walked from it before. Each is walked to the nodes it
// leads to (see the header).
struct Jps3d::Expansion {
  Jps3d& self;
  Side& side;
  const StopCondition& stop;
  std::uint64_t slice_end = std::numeric_limits<std::uint64_t>::max();  // this turn ends here
  std::uint64_t other = 0;  // the other direction's expansions, for the stop condition
  bool stopped = false;     // by the stop condition, not the turn's end
  bool stop_now(std::uint64_t expanded) {
    stopped = stop_due(stop, expanded + other, 1024);
    return stopped || expanded >= slice_end;
  }

  template <class Relax>
  void expand(std::uint32_t id, const SearchBuffers::Node& n, Relax& relax) const {
    using namespace jps3d_rules;
    const Tables& t = tables();
    const BitGrid& g = *self.grid_;
    int at[3];
    g.coords(id, at[0], at[1], at[2]);
    const std::uint32_t mask = g.free_mask(at[0], at[1], at[2]);
    std::uint32_t reached = 1u << arrival(id, n.parent), walked = 0;
    MoveSets::Entry* ties = side.moves.find(id);
    if (ties && ties->g != n.g) ties = nullptr;  // a worse g's set
    if (ties) {
      reached = ties->reached;
      walked = ties->walked;
    }
    std::uint32_t todo = t.continuations(reached, mask) & ~walked;  // the moves not walked yet
    if (ties) ties->walked |= todo;  // a later expansion at this g walks only what a new tie adds
    const double g0 = n.g;
    const auto offer = [&](const int c[3], int move) { arrive(c, move, id, at, g0, relax); };
    const int* goal = side.goal;
    WalkLimit limit{{at[0], at[1], at[2]}, {goal[0], goal[1], goal[2]}, g0, 0.0};
    limit.f_max = g0 + octile_distance(goal[0] - at[0], goal[1] - at[1], goal[2] - at[2]) + 1e-9;
    for (; todo; todo &= todo - 1) {
      const int move = std::countr_zero(todo);
      if (t.legal(mask, move)) walk_move(at, move, mask, limit, offer);
    }
  }

  // The move a walk from `parent` ends with at `cell` (kAny at the start): a walk takes its moves
  // with the most axes first, so it ends along the axes it goes furthest on.
  int arrival(std::uint32_t cell, std::uint32_t parent) const {
    if (parent == SearchBuffers::kNoParent) return jps3d_rules::kAny;
    int c[3], p[3];
    self.grid_->coords(cell, c[0], c[1], c[2]);
    self.grid_->coords(parent, p[0], p[1], p[2]);
    const int far = std::max({std::abs(c[0] - p[0]), std::abs(c[1] - p[1]), std::abs(c[2] - p[2])});
    int move = jps3d_rules::kAny;
    for (int a = 0, w = 1; a < 3; ++a, w *= 3)
      if (std::abs(c[a] - p[a]) == far) move += (c[a] > p[a] ? 1 : -1) * w;
    return move;
  }

  // A walk from `parent` reached cell c by `move`. A better g goes through the search's relax; the
  // same g (to rounding) by another move adds that move to the cell's set, and a cell already
  // expanded is put back on the list for what the move adds.
  template <class Relax>
  void arrive(const int c[3], int move, std::uint32_t parent, const int from[3], double g0, Relax& relax) const {
    constexpr double kTie = 1e-9;
    const auto cell = static_cast<std::uint32_t>(self.grid_->index(c[0], c[1], c[2]));
    const double cost = g0 + octile_distance(c[0] - from[0], c[1] - from[1], c[2] - from[2]);
    SearchBuffers::Node& node = side.search.node(cell);
    if (cost < node.g - kTie) {
      relax(cell, cost, parent, GridCell{c[0], c[1], c[2]});
      return;
    }
    if (cost > node.g + kTie || cell == side.to) return;
    const int first = arrival(cell, node.parent);
    if (move == first) return;
    MoveSets::Entry& e = side.moves.at(cell);
    const bool closed = SearchBuffers::closed(node);
    if (e.g != node.g) {  // the first tie at this g: the set starts with the parent's move
      e.g = node.g;
      e.reached = 1u << first;
      e.walked = closed ? jps3d_rules::tables().continuations(e.reached, self.grid_->free_mask(c[0], c[1], c[2])) : 0;
    }
    if (e.reached >> move & 1u) return;
    e.reached |= 1u << move;
    if (!closed) return;  // still on the list: it takes the move with it
    SearchBuffers::reopen(node);
    const double h = octile_distance(side.goal[0] - c[0], side.goal[1] - c[1], side.goal[2] - c[2]);
    side.search.open().push(node.g + h, node.g, cell);
  }

  // Walks a legal move from `from` and offers the nodes it finds.
  template <class Offer>
  void walk_move(const int from[3], int move, std::uint32_t mask, const WalkLimit& limit, const Offer& offer) const {
    using namespace jps3d_rules;
    const Offset m = offset_of(move);
    if (axes_of(move) > 1) return walk_diagonal(from, move, mask, limit, offer);
    int c[3] = {from[0], from[1], from[2]};
    const int axis = m.v[0] ? 0 : m.v[1] ? 1 : 2;
    if (self.jump_straight(c, axis, m.v[axis], limit)) offer(c, move);
  }

  // A move along two or three axes: along it until the goal, the first cell past the limit or one
  // with a forced move (each a node); from every cell before, the walks of its smaller sub-moves,
  // without making the cell a node (JPS2's pruning of intermediate jump points).
  template <class Offer>
  void walk_diagonal(const int from[3], int move, std::uint32_t mask, const WalkLimit& limit,
                     const Offer& offer) const {
    using namespace jps3d_rules;
    const Tables& t = tables();
    const Offset m = offset_of(move);
    int c[3] = {from[0], from[1], from[2]};
    while (t.legal(mask, move)) {
      for (int a = 0; a < 3; ++a) c[a] += m.v[a];
      const bool goal = c[0] == side.goal[0] && c[1] == side.goal[1] && c[2] == side.goal[2];
      if (goal || limit.over(c)) return offer(c, move);
      mask = self.grid_->free_mask(c[0], c[1], c[2]);
      if (t.jump_point(mask, move)) return offer(c, move);
      for (int s = 0; s < t.subs[move]; ++s) {
        const int sub = t.sub[move][s];
        if (sub != move && t.legal(mask, sub)) walk_move(c, sub, mask, limit, offer);
      }
    }
  }
};

void Jps3d::prepare(Side& side, std::int64_t from, std::int64_t to) {
  const BitGrid& g = *grid_;
  side.from = static_cast<std::uint32_t>(from);
  side.to = static_cast<std::uint32_t>(to);
  g.coords(to, side.goal[0], side.goal[1], side.goal[2]);
  side.search.begin(g.size());
  side.moves.begin();
  side.counts = {};
  GridCell s;
  g.coords(from, s.i, s.j, s.k);
  side.search.seed(OctileToGoal{GridCell{side.goal[0], side.goal[1], side.goal[2]}, 1.0}, side.from,
                   SearchBuffers::kNoParent, s, side.counts);
}

GridSearchResult Jps3d::search(std::int64_t start, std::int64_t goal, const StopCondition& stop) {
  if (!grid_->free(start) || !grid_->free(goal)) return {};
  prepare(sides_[0], start, goal);
  if (options_.both_directions) {
    prepare(sides_[1], goal, start);
    return race(stop);
  }
  Side& side = sides_[0];
  Expansion expansion{*this, side, stop};
  const OctileToGoal h{GridCell{side.goal[0], side.goal[1], side.goal[2]}, 1.0};
  const SearchEnd end = side.search.resume(expansion, h, side.to, side.counts);
  return grid_result(side.search, end, side.counts, side.from, side.to);
}

namespace {

// A route found from the goal, turned round: its cells from the start, kept where the move
// changes, so that each step of expand_path() between two of them is one move repeated (the
// backward walks took their moves in the other order).
std::vector<std::int64_t> turned_round(const BitGrid& g, std::vector<std::int64_t> cells) {
  std::reverse(cells.begin(), cells.end());
  std::vector<std::int64_t> out{cells.front()};
  int last[3] = {0, 0, 0};
  for (std::size_t i = 1; i < cells.size(); ++i) {
    int a[3], b[3];
    g.coords(cells[i - 1], a[0], a[1], a[2]);
    g.coords(cells[i], b[0], b[1], b[2]);
    const int d[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    if (i > 1 && (d[0] != last[0] || d[1] != last[1] || d[2] != last[2])) out.push_back(cells[i - 1]);
    std::copy(d, d + 3, last);
  }
  if (cells.size() > 1) out.push_back(cells.back());
  return out;
}

}  // namespace

// Each direction expands a slice in turn until one closes its goal, runs dry (then so would the
// other: the moves are the same both ways) or the stop condition holds.
GridSearchResult Jps3d::race(const StopCondition& stop) {
  for (int turn = 0;; turn ^= 1) {
    Side& side = sides_[turn];
    Expansion expansion{*this, side, stop};
    expansion.slice_end = side.counts.expanded + options_.slice_expansions;
    expansion.other = sides_[turn ^ 1].counts.expanded;
    const OctileToGoal h{GridCell{side.goal[0], side.goal[1], side.goal[2]}, 1.0};
    const SearchEnd end = side.search.resume(expansion, h, side.to, side.counts);
    if (end == SearchEnd::stopped && !expansion.stopped) continue;
    SearchCounts both = side.counts;
    const SearchCounts& o = sides_[turn ^ 1].counts;
    both.expanded += o.expanded;
    both.generated += o.generated;
    both.opened += o.opened;
    both.open_max += o.open_max;
    GridSearchResult r = grid_result(side.search, end, both, side.from, side.to);
    if (turn == 1 && r.solved()) r.cells = turned_round(*grid_, expand_path(r.cells));
    return r;
  }
}

void Jps3d::MoveSets::begin() {
  used_ = 0;
  if (++stamp_ != 0) return;
  for (Entry& e : slots_) e.stamp = 0;  // the stamp wrapped: forget every entry
  stamp_ = 1;
}

std::size_t Jps3d::MoveSets::slot(std::uint32_t cell) const {  // Fibonacci hashing: the high bits
  const int bits = std::countr_zero(slots_.size());
  return static_cast<std::size_t>((std::uint64_t{cell} * 0x9E3779B97F4A7C15ull) >> (64 - bits));
}

Jps3d::MoveSets::Entry* Jps3d::MoveSets::find(std::uint32_t cell) {
  if (used_ == 0) return nullptr;  // no tie yet in this query
  for (std::size_t i = slot(cell);; i = (i + 1) & (slots_.size() - 1)) {
    Entry& e = slots_[i];
    if (e.stamp != stamp_) return nullptr;
    if (e.cell == cell) return &e;
  }
}

Jps3d::MoveSets::Entry& Jps3d::MoveSets::at(std::uint32_t cell) {
  if (2 * (used_ + 1) > slots_.size()) {  // keep the table at most half full
    std::vector<Entry> old(std::max<std::size_t>(1024, 2 * slots_.size()), Entry{0.0, 0, 0, 0, 0});
    old.swap(slots_);
    for (const Entry& e : old)
      if (e.stamp == stamp_) {
        std::size_t i = slot(e.cell);
        while (slots_[i].stamp == stamp_) i = (i + 1) & (slots_.size() - 1);
        slots_[i] = e;
      }
  }
  for (std::size_t i = slot(cell);; i = (i + 1) & (slots_.size() - 1)) {
    Entry& e = slots_[i];
    if (e.stamp != stamp_) {
      e = {-1.0, cell, stamp_, 0, 0};
      ++used_;
      return e;
    }
    if (e.cell == cell) return e;
  }
}

// Between two jump points the walk went along the moves with every remaining axis, then fewer:
// stepping by the sign of what is left on each axis retraces it.
std::vector<std::int64_t> Jps3d::expand_path(const std::vector<std::int64_t>& jp) const {
  std::vector<std::int64_t> cells;
  if (jp.empty()) return cells;
  cells.push_back(jp[0]);
  for (std::size_t i = 1; i < jp.size(); ++i) {
    int c[3], to[3];
    grid_->coords(jp[i - 1], c[0], c[1], c[2]);
    grid_->coords(jp[i], to[0], to[1], to[2]);
    while (c[0] != to[0] || c[1] != to[1] || c[2] != to[2]) {
      for (int a = 0; a < 3; ++a) c[a] += (to[a] > c[a]) - (to[a] < c[a]);
      cells.push_back(grid_->index(c[0], c[1], c[2]));
    }
  }
  return cells;
}

}  // namespace uavplan
