#include "uavplan/planning/pso/pso_single.h"
#include "uavplan/core/text.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "uavplan/planning/segment_rule.h"

namespace uavplan {
namespace {

struct LegCost {
  const World& world;
  const SegmentRule& rule;
  const PsoSingleOptions& o;
  double l, turn_max, dh_max;
  Vec3 from, to;
  std::optional<Vec3> in;

  void route(std::span<const double> x, std::vector<Vec3>& out) const {
    out.assign(1, from);
    for (std::size_t k = 0; k + 2 < x.size() + 1; k += 3) out.emplace_back(x[k], x[k + 1], x[k + 2]);
    out.push_back(to);
  }
  // Metres inside no-fly zones (or outside the airspace), sampled every l / 4 (a quarter step when
  // the segment touches one between the samples).
  double inside_m(const Vec3& a, const Vec3& b) const {
    const double len = (b - a).norm();
    const int n = std::max(1, static_cast<int>(std::ceil(len / (0.25 * l))));
    double inside = 0.0;
    for (int k = 0; k < n; ++k) {
      const Vec3 p = a + (k + 0.5) / n * (b - a);
      if (!rule.point_ok(p)) inside += len / n;
    }
    // An intrusion between the samples still counts, as a quarter step.
    return inside > 0.0 || rule(a, b) ? inside : 0.25 * l;
  }
  double operator()(const std::vector<Vec3>& pts, SingleStepRoute* report = nullptr) const {
    double j = 0.0, nfz = 0.0;
    std::optional<Vec3> dir = in;
    for (std::size_t k = 1; k < pts.size(); ++k) {
      const Vec3 seg = pts[k] - pts[k - 1];
      const double len = seg.norm();
      j += len + o.w_len * std::max(0.0, l - len) + o.w_climb * std::max(0.0, std::abs(seg.z()) - dh_max);
      nfz += inside_m(pts[k - 1], pts[k]);
      if (dir && len > 0.0) {
        const double turn = turn_rad(*dir, seg);
        j += o.w_turn_per_l * l * rad_to_deg(std::max(0.0, turn - turn_max));
        if (report && turn > report->worst_turn_rad) report->worst_turn_rad = turn, report->worst_turn_at = k - 1;
      }
      if (len > 0.0) dir = seg;
    }
    if (report) report->inside_nfz_m += nfz;
    return j + o.w_nfz_per_m * nfz;
  }
};

}  // namespace

PsoSingleOptions PsoSingleOptions::from_params(const Params& params) {
  ParamReader r(params, "pso_single");
  PsoSingleOptions o = read(r);
  r.finish();
  return o;
}

PsoSingleOptions PsoSingleOptions::read(ParamReader& r) {
  PsoSingleOptions o;
  o.steps.step_m = r.number("step", 0.0, 0.0, 1e7, "l, the segment length, m; 0: derived from the distance");
  o.steps.max_turn_deg =
      r.number("max_turn_deg", o.steps.max_turn_deg, 1.0, 90.0, "dphi_max, the turn between segments, deg");
  o.waypoints = r.integer("waypoints", 0, 0, 1000, "waypoints per leg; 0: floor(distance / l) - 1");
  o.pso.particles = r.integer("particles", o.pso.particles, 2, 10000, "the swarm's particles");
  o.pso.iterations = r.integer("iterations", o.pso.iterations, 0, 100000, "the swarm's iterations");
  return o;
}

SingleStepRoute pso_single_route(const Problem& pb, const World& world, const PsoSingleOptions& o,
                                 const StopCondition& stop) {
  const UavSpec& u = pb.uav;
  const SegmentRule rule(world, u);
  const PsoSteps steps = pso_steps(o.steps, u, world);
  const double l = steps.step_m;
  SingleStepRoute out;
  out.waypoints = {u.start};
  std::optional<Vec3> in;
  if (u.heading_rad) in = heading_vector(*u.heading_rad);
  std::vector<Vec3> stops = pb.via;
  stops.push_back(pb.goal);
  const Rng base(pb.seed);
  const Aabb& b = world.bounds();
  std::vector<Vec3> pts;
  for (std::size_t leg = 0; leg < stops.size() && !stop.should_stop(); ++leg) {
    const LegCost cost{world, rule, o, l, steps.max_turn_rad, steps.max_dh_m, out.waypoints.back(), stops[leg], in};
    const double d = (cost.to - cost.from).norm();
    const int n = o.waypoints > 0 ? o.waypoints : std::max(0, static_cast<int>(std::floor(d / l)) - 1);
    std::vector<double> lo, hi, seed;
    for (int k = 0; k < n; ++k) {
      const Vec3 straight = cost.from + (k + 1.0) / (n + 1.0) * (cost.to - cost.from);
      for (int c = 0; c < 3; ++c) {
        lo.push_back(b.min[c]);
        hi.push_back(c == 2 ? std::max(b.min.z(), rule.ceiling_m()) : b.max[c]);
        seed.push_back(straight[c]);
      }
    }
    if (n > 0) {
      Rng rng = base.split(leg);
      std::uint64_t evaluations = 0;
      const auto f = [&](std::span<const double> x) {
        if (stop.should_stop(++evaluations))
          return std::numeric_limits<double>::infinity();  // the swarm runs out at once
        cost.route(x, pts);
        return cost(pts);
      };
      const PsoResult r = pso_minimize(f, lo, hi, o.pso, rng, seed);
      out.evaluations += r.evaluations;
      cost.route(r.x, pts);
    } else {
      pts = {cost.from, cost.to};
    }
    out.cost += cost(pts, &out);
    if (out.worst_turn_at > 0 || leg == 0) out.worst_turn_at += out.waypoints.size() - 1;
    out.waypoints.insert(out.waypoints.end(), pts.begin() + 1, pts.end());
    if (pts.size() >= 2) in = pts.back() - pts[pts.size() - 2];
  }
  return out;
}

PlanResult PsoSinglePlanner::do_plan(const Problem& pb, const World& world, const StopCondition& stop) const {
  PlanResult res;
  SingleStepRoute r = pso_single_route(pb, world, options_, stop);
  res.stats.nodes_expanded = static_cast<std::uint64_t>(r.evaluations);
  if (stop.should_stop()) {
    res.message = "stopped before the swarm was done";
    res.reason = Reason::stopped;
    return res;
  }
  const SegmentRule rule(world, pb.uav);
  for (std::size_t k = 1; k < r.waypoints.size(); ++k)
    if (!rule(r.waypoints[k - 1], r.waypoints[k])) {
      res.message = "the swarm's best route (relaxed constraints) crosses an obstacle or the bounds on segment " +
                    std::to_string(k) + " (" + std::to_string(static_cast<int>(r.inside_nfz_m)) + " m inside)";
      return res;
    }
  const auto broken = check_route_limits(r.waypoints, pb.uav);
  const double limit = std::min(deg_to_rad(options_.steps.max_turn_deg), pb.uav.max_turn_rad);
  if (!broken.empty() || r.worst_turn_rad > limit + kAngleTolerance_rad) {
    const std::string buf =
        strf("the swarm's best route (relaxed constraints) turns %.1f deg at waypoint %zu, above %.1f deg",
             rad_to_deg(r.worst_turn_rad), r.worst_turn_at, rad_to_deg(limit));
    res.message = buf;
    return res;
  }
  res.status = Status::solved;
  res.route.waypoints = std::move(r.waypoints);
  return res;
}

}  // namespace uavplan
