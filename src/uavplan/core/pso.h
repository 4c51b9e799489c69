// A small particle swarm optimiser for P5's problems (one waypoint's (dphi, dh), solved thousands
// of times per route; all waypoints at once for the single-step baseline): Shi & Eberhart's
// inertia-weight PSO (the reference P5 gives for its settings), inertia falling linearly,
// velocities clamped to each variable's range, positions clamped to the box, infeasible points
// +inf (death penalty). Written here rather than taken from pagmo2: docs/decisions/0009-own-pso.md
// has the measurement. Seeded: the same seed gives the same answer. The swarm is allocated once
// per solve, nothing per evaluation.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <span>
#include <vector>

#include "uavplan/core/rng.h"

namespace uavplan {

struct PsoOptions {
  int particles = 30;
  int iterations = 100;
  double w_start = 0.9, w_end = 0.4;  // inertia, linearly over the iterations
  double c1 = 2.0, c2 = 2.0;          // cognitive and social weights
  // Stop early once the swarm's best has not improved by more than stall_tolerance * (|f| + 1)
  // for this many iterations; 0: run every iteration.
  int stall_iterations = 0;
  double stall_tolerance = 1e-9;
  // Give up once this many iterations found no feasible point at all; 0: never.
  int infeasible_iterations = 0;
};

struct PsoResult {
  std::vector<double> x;
  double f = std::numeric_limits<double>::infinity();
  int evaluations = 0;
};

// Minimises f(std::span<const double>) -> double over [lo, hi]; `seeds` (row-major, any number of
// whole points) are the first particles, so a known good point is never lost.
template <class F>
PsoResult pso_minimize(F&& f, std::span<const double> lo, std::span<const double> hi, const PsoOptions& o, Rng& rng,
                       std::span<const double> seeds = {}) {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  const std::size_t dims = lo.size(), n = static_cast<std::size_t>(o.particles > 0 ? o.particles : 1);
  std::vector<double> x(n * dims), v(n * dims), best(n * dims), best_f(n);
  PsoResult g;
  g.x.assign(dims, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    double* xi = &x[i * dims];
    for (std::size_t d = 0; d < dims; ++d) {
      const double span = hi[d] - lo[d];
      xi[d] = (i + 1) * dims <= seeds.size() ? seeds[i * dims + d] : lo[d] + span * rng.uniform01();
      v[i * dims + d] = 0.2 * span * (rng.uniform01() - 0.5);
      best[i * dims + d] = xi[d];
    }
    best_f[i] = f(std::span<const double>(xi, dims));
    ++g.evaluations;
    if (best_f[i] < g.f) g.f = best_f[i], g.x.assign(xi, xi + dims);
  }
  double last_f = g.f;
  int stall = 0;
  for (int it = 0; it < o.iterations; ++it) {
    const double w = o.iterations > 1 ? o.w_start + (o.w_end - o.w_start) * it / (o.iterations - 1) : o.w_start;
    for (std::size_t i = 0; i < n; ++i) {
      double* xi = &x[i * dims];
      double* vi = &v[i * dims];
      const double* bi = &best[i * dims];
      for (std::size_t d = 0; d < dims; ++d) {
        const double span = hi[d] - lo[d];
        const double r1 = rng.uniform01(), r2 = rng.uniform01();
        vi[d] = std::clamp(w * vi[d] + o.c1 * r1 * (bi[d] - xi[d]) + o.c2 * r2 * (g.x[d] - xi[d]), -span, span);
        xi[d] = std::clamp(xi[d] + vi[d], lo[d], hi[d]);
      }
      const double fi = f(std::span<const double>(xi, dims));
      ++g.evaluations;
      if (fi < best_f[i]) best_f[i] = fi, std::copy(xi, xi + dims, &best[i * dims]);
      if (fi < g.f) g.f = fi, g.x.assign(xi, xi + dims);
    }
    if (o.infeasible_iterations > 0 && g.f == kInf && it + 1 >= o.infeasible_iterations) break;
    if (o.stall_iterations > 0) {
      const bool improved = last_f == kInf ? g.f < kInf : g.f < last_f - o.stall_tolerance * (std::abs(last_f) + 1.0);
      stall = improved ? 0 : stall + 1;
      last_f = g.f;
      if (g.f < kInf && stall >= o.stall_iterations) break;
    }
  }
  return g;
}

}  // namespace uavplan
