#include "uavplan/planning/cells/cellular_aco.h"
#include "uavplan/core/tolerances.h"

#include <algorithm>
#include <cmath>
#include <queue>
#include <thread>

#include "uavplan/core/rng.h"

namespace uavplan {

CellularAcoOptions CellularAcoOptions::from_params(const Params& params) {
  ParamReader r(params, "cellular_aco");
  CellularAcoOptions o = read(r);
  r.finish();
  return o;
}

CellularAcoOptions CellularAcoOptions::read(ParamReader& r) {
  CellularAcoOptions o;
  o.cells.read(r);
  o.ants = r.integer("ants", o.ants, 1, 100000, "the ants per iteration");
  o.iterations = r.integer("iterations", o.iterations, 1, 100000, "the colony's iterations");
  o.alpha = r.number("alpha", o.alpha, 0.0, 20.0, "the pheromone's weight (P2)");
  o.beta = r.number("beta", o.beta, 0.0, 20.0, "the heuristic's weight (P2)");
  o.q = r.number("q", o.q, 1e-12, 1e12, "the deposit constant (P2)");
  o.rho0 = r.number("rho0", o.rho0, 0.0, 1.0, "the initial evaporation");
  o.rho_max = r.number("rho_max", o.rho_max, 0.0, 1.0, "the evaporation's cap");
  o.tau_max =
      r.number("tau_max", o.tau_max, 1e-12, 1e12, "the pheromone's upper bound (relative: the best ant deposits 1)");
  o.tau_min = r.number("tau_min", o.tau_min, 1e-12, o.tau_max, "the pheromone's lower bound, at most tau_max");
  o.max_steps_factor = r.integer("max_steps_factor", o.max_steps_factor, 1, 1000,
                                 "an ant dies after this many times the straight-line cell count");
  o.threads =
      r.integer("threads", o.threads, 0, 1024, "threads of the colony; 0: the run's (--threads, else every core)");
  o.local_update = r.boolean("local_update", o.local_update, "the cellular automaton's update of the best route");
  return o;
}

namespace {

// v = n copies of `value`, filled a chunk at a time under the stop: on a fine map each of the
// colony's arrays is hundreds of megabytes, whose first touch alone took over a second.
template <class T>
void fill_under_stop(std::vector<T>& v, std::size_t n, T value, const StopCondition& stop) {
  constexpr std::size_t kChunk = std::size_t{1} << 22;
  v.clear();
  v.reserve(n);
  for (std::size_t done = 0; done < n; done += kChunk) {
    stop.throw_if_stopped();
    v.insert(v.end(), std::min(kChunk, n - done), value);
  }
}

struct Walk {
  std::vector<std::int64_t> path;
  double cost = World::kInf;
};

class Colony {
 public:
  // Throws Stopped (core/stop.h) when the stop holds while the estimate to go is computed.
  Colony(const CellGraph& g, std::int64_t from, std::int64_t to, const CellularAcoOptions& o, const StopCondition& stop)
      : g_(g), m_(g.map()), from_(from), to_(to), o_(o), stop_(stop) {
    fill_under_stop(tau_, static_cast<std::size_t>(m_.nodes()), 1.0, stop);
    goal_ = pos(to);
    // eta's scale: the cost of one horizontal cell at the lowest level.
    scale_ = std::max(1e-12, g.cost(m_.centre(0, 0, 0), m_.centre(0, 0, 0) + Vec3(m_.cell_m(), 0, 0)));
    int fi = 0, fj = 0, fk = 0, ti = 0, tj = 0, tk = 0;
    m_.unpack(from, fi, fj, fk);
    m_.unpack(to, ti, tj, tk);
    max_steps_ = o.max_steps_factor * (std::max({std::abs(fi - ti), std::abs(fj - tj)}) + std::abs(fk - tk)) + 64;
    distance_to_goal();
  }

  bool reachable() const { return std::isfinite(to_go_[static_cast<std::size_t>(from_)]); }

  Vec3 pos(std::int64_t v) const { return m_.centre(v); }

  // One ant: at each cell, P ~ tau^alpha eta^beta over the unvisited free neighbours (eq. 3),
  // eta = exp(improvement of the objective), the improvement being the cost of the move plus
  // the estimate to go, minus the estimate here (<= 0), in units of one cell's cost.
  Walk walk(Rng& rng, std::vector<std::uint32_t>& seen, std::uint32_t stamp, std::uint64_t& steps) const {
    Walk w;
    w.path.push_back(from_);
    seen[from_] = stamp;
    double cost = 0.0;
    std::int64_t v = from_;
    std::array<std::int64_t, CellGraph::kMoves> cand{};
    std::array<double, CellGraph::kMoves> weight{};
    while (v != to_) {
      if (static_cast<int>(w.path.size()) > max_steps_) return {};
      // A long walk on a fine map takes a while: the stop ends it (the ant counts as lost).
      if ((w.path.size() & 255) == 0 && stop_.should_stop()) return {};
      int i = 0, j = 0, k = 0;
      m_.unpack(v, i, j, k);
      const Vec3 pv = m_.centre(i, j, k);
      const double hv = to_go_[static_cast<std::size_t>(v)];
      int n = 0;
      double total = 0.0;
      for (int mv = 0; mv < CellGraph::kMoves; ++mv) {
        const std::int64_t u = g_.neighbour(i, j, k, mv);
        if (u < 0 || seen[u] == stamp || !std::isfinite(to_go_[static_cast<std::size_t>(u)])) continue;
        const Vec3 pu = pos(u);
        const double loss = (g_.cost(pv, pu) + to_go_[static_cast<std::size_t>(u)] - hv) / scale_;
        const double eta = std::exp(-std::max(0.0, loss));
        const double wgt = std::pow(tau_[u], o_.alpha) * std::pow(eta, o_.beta);
        cand[n] = u;
        weight[n] = wgt;
        total += wgt;
        ++n;
      }
      if (n == 0) return {};  // dead end: the ant dies
      double r = rng.uniform01() * total;
      int pick = n - 1;
      for (int c = 0; c < n; ++c) {
        r -= weight[c];
        if (r <= 0.0) {
          pick = c;
          break;
        }
      }
      const std::int64_t u = cand[pick];
      cost += g_.cost(pv, pos(u));
      seen[u] = stamp;
      w.path.push_back(u);
      v = u;
      ++steps;
    }
    w.cost = cost;
    return w;
  }

  double path_cost(const std::vector<std::int64_t>& p) const {
    double c = 0.0;
    for (std::size_t i = 1; i < p.size(); ++i) c += g_.cost(pos(p[i - 1]), pos(p[i]));
    return c;
  }

  // Whether b is a valid single move from a.
  bool adjacent(std::int64_t a, std::int64_t b) const {
    int ai = 0, aj = 0, ak = 0, bi = 0, bj = 0, bk = 0;
    m_.unpack(a, ai, aj, ak);
    m_.unpack(b, bi, bj, bk);
    const int mv = CellGraph::move_index(bi - ai, bj - aj, bk - ak);
    return mv >= 0 && g_.neighbour(ai, aj, ak, mv) == b;
  }

  // The cellular-automaton update of a route: a cell dies where its neighbours on the route
  // join directly at lower cost; a cell moves to a neighbour cell that lowers the cost.
  void local_update(std::vector<std::int64_t>& p) const {
    for (int pass = 0; pass < 1000; ++pass) {
      bool changed = false;
      for (std::size_t idx = 1; idx + 1 < p.size(); ++idx) {
        const std::int64_t a = p[idx - 1], c = p[idx], b = p[idx + 1];
        const Vec3 pa = pos(a), pb = pos(b);
        const double now = g_.cost(pa, pos(c)) + g_.cost(pos(c), pb);
        if (adjacent(a, b) && g_.cost(pa, pb) < now - kRelativeTie * now) {
          p.erase(p.begin() + static_cast<std::ptrdiff_t>(idx));
          changed = true;
          --idx;
          continue;
        }
        int ci = 0, cj = 0, ck = 0;
        m_.unpack(c, ci, cj, ck);
        std::int64_t best = -1;
        double best_cost = now - kRelativeTie * now;
        for (int mv = 0; mv < CellGraph::kMoves; ++mv) {
          const std::int64_t u = g_.neighbour(ci, cj, ck, mv);
          if (u < 0 || u == a || u == b || !adjacent(a, u) || !adjacent(u, b)) continue;
          const double alt = g_.cost(pa, pos(u)) + g_.cost(pos(u), pb);
          if (alt < best_cost) {
            best_cost = alt;
            best = u;
          }
        }
        if (best >= 0 && std::find(p.begin(), p.end(), best) == p.end()) {
          p[idx] = best;
          changed = true;
        }
      }
      if (!changed) return;
    }
  }

  std::vector<double>& tau() { return tau_; }

 private:
  // The estimate to go: the range term (w1 v s) of the shortest free way to the goal on the
  // graph, by one backward Dijkstra per leg. It is a lower bound of J to go (consistent), and
  // unlike the straight line it leads around concave obstacles instead of into them.
  void distance_to_goal() {
    fill_under_stop(to_go_, tau_.size(), World::kInf, stop_);
    using Item = std::pair<double, std::int64_t>;
    std::priority_queue<Item, std::vector<Item>, std::greater<>> open;
    to_go_[static_cast<std::size_t>(to_)] = 0.0;
    open.emplace(0.0, to_);
    const double k = g_.w1() * g_.speed();
    for (std::uint64_t pops = 0; !open.empty(); ++pops) {
      if ((pops & 4095) == 0) stop_.throw_if_stopped();  // the whole map, on a fine one seconds
      const auto [d, v] = open.top();
      open.pop();
      if (d > to_go_[static_cast<std::size_t>(v)]) continue;
      int i = 0, j = 0, kk = 0;
      m_.unpack(v, i, j, kk);
      const Vec3 pv = m_.centre(i, j, kk);
      for (int mv = 0; mv < CellGraph::kMoves; ++mv) {
        const std::int64_t u = g_.neighbour(i, j, kk, mv);  // moves are symmetric
        if (u < 0) continue;
        const double du = d + k * (pos(u) - pv).norm();
        if (du < to_go_[static_cast<std::size_t>(u)]) {
          to_go_[static_cast<std::size_t>(u)] = du;
          open.emplace(du, u);
        }
      }
    }
  }

  std::vector<double> to_go_;
  const CellGraph& g_;
  const CellMap& m_;
  std::int64_t from_, to_;
  const CellularAcoOptions& o_;
  const StopCondition& stop_;
  std::vector<double> tau_;
  Vec3 goal_;
  double scale_ = 1.0;
  int max_steps_ = 0;
};

}  // namespace

constexpr int kFirstArrivalIterations = 25;  // CellularAcoOptions' default iteration count

std::optional<std::vector<std::int64_t>> cellular_aco_search(const CellGraph& g, std::int64_t from, std::int64_t to,
                                                             const CellularAcoOptions& o, std::uint64_t seed, int leg,
                                                             const StopCondition& stop, PlanStats& stats,
                                                             AcoLegReport* report) {
  if (from == to) return std::vector<std::int64_t>{from};
  Colony colony(g, from, to, o, stop);
  if (!colony.reachable() || stop.should_stop()) return std::nullopt;  // a fine map's arrays take a while to fill
  const std::size_t nodes = static_cast<std::size_t>(g.map().nodes());
  const int threads = o.threads > 0 ? std::min(o.ants, o.threads) : stop.threads(o.ants);
  // Per thread, the cells its ant has visited.
  std::vector<std::vector<std::uint32_t>> seen(static_cast<std::size_t>(threads));
  try {
    for (auto& s : seen) fill_under_stop(s, nodes, std::uint32_t{0}, stop);
  } catch (const Stopped&) {
    return std::nullopt;
  }
  std::vector<std::uint32_t> stamps(static_cast<std::size_t>(threads), 0);
  std::vector<std::uint64_t> steps(static_cast<std::size_t>(threads), 0);
  const Rng base(seed);
  Walk best;
  double rho = o.rho0;
  int arrived_total = 0;
  int it = 0;
  for (; it < o.iterations; ++it) {
    if (stop.should_stop(static_cast<std::uint64_t>(it))) break;
    std::vector<Walk> walks(static_cast<std::size_t>(o.ants));
    auto run = [&](int t) {
      for (int a = t; a < o.ants; a += threads) {
        // Each ant's stream depends only on (seed, leg, iteration, ant): thread count does not matter.
        Rng rng = base.split((static_cast<std::uint64_t>(leg) << 48) ^ (static_cast<std::uint64_t>(it) << 24) ^
                             static_cast<std::uint64_t>(a));
        walks[static_cast<std::size_t>(a)] = colony.walk(rng, seen[t], ++stamps[t], steps[t]);
      }
    };
    if (threads == 1) {
      run(0);
    } else {
      std::vector<std::jthread> pool;
      pool.reserve(static_cast<std::size_t>(threads));
      for (int t = 0; t < threads; ++t) pool.emplace_back(run, t);
    }
    // Best of the iteration (lowest cost, then lowest ant index), then the CA update on it.
    for (const Walk& w : walks)
      if (std::isfinite(w.cost)) {
        ++arrived_total;
        if (w.cost < best.cost) best = w;
      }
    // Until an ant arrives nothing is deposited and every iteration walks the same odds: a colony
    // with no arrival in kFirstArrivalIterations will find none (the cells are too coarse or the
    // walks too short); more iterations would only spend the time limit.
    if (!std::isfinite(best.cost)) {
      if (it + 1 >= kFirstArrivalIterations) break;
      continue;
    }
    if (o.local_update) {
      colony.local_update(best.path);
      best.cost = colony.path_cost(best.path);
    }
    // Evaporation (eq. 4, rho by eq. 5), deposits Q / J_k (eq. 6), clamping (eq. 7). Costs are
    // measured in units of the best cost so far, so the bounds hold whatever the weights' units.
    auto& tau = colony.tau();
    for (double& t : tau) t *= (1.0 - rho);
    for (const Walk& w : walks)
      if (std::isfinite(w.cost))
        for (std::int64_t v : w.path) tau[static_cast<std::size_t>(v)] += o.q / (w.cost / best.cost) / o.ants;
    for (std::int64_t v : best.path) tau[static_cast<std::size_t>(v)] += o.q / o.ants;
    for (double& t : tau) t = std::clamp(t, o.tau_min, o.tau_max);
    rho = std::min(o.rho_max, rho * 1.05);
  }
  for (std::uint64_t s : steps) stats.nodes_expanded += s;
  if (report) *report = {it, arrived_total, best.cost};
  if (!std::isfinite(best.cost)) return std::nullopt;
  return best.path;
}

PlanResult CellularAcoPlanner::do_plan(const Problem& problem, const World& world, const StopCondition& stop) const {
  bool cut_short = false;  // a leg's colony stopped by the time limit with a route: its best so far
  PlanResult res = plan_on_cells(
      problem, world, options_.cells, stop,
      [&](const CellGraph& g, std::int64_t a, std::int64_t b, int leg, PlanStats& s, const StopCondition& leg_stop) {
        auto path = cellular_aco_search(g, a, b, options_, problem.seed, leg, leg_stop, s);
        cut_short |= path && leg_stop.should_stop();
        return path;
      });
  if (res.status == Status::solved && cut_short)
    res.message = "the time limit stopped the colony before its " + std::to_string(options_.iterations) +
                  " iterations: its best route so far";
  return res;
}

}  // namespace uavplan
