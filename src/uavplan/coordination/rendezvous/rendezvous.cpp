#include "uavplan/coordination/rendezvous/rendezvous.h"
#include "uavplan/coordination/rendezvous/rendezvous_mission.h"
#include "uavplan/core/text.h"
#include "uavplan/core/tolerances.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <memory>
#include <mutex>
#include <numeric>
#include <optional>
#include <thread>

#include "uavplan/core/geometry.h"
#include "uavplan/planning/segment_rule.h"
#include "uavplan/vehicle/uav.h"

namespace uavplan {

std::string_view to_string(RendezvousStep s) {
  switch (s) {
    case RendezvousStep::none:
      return "none";
    case RendezvousStep::preplanned:
      return "pre-planned";
    case RendezvousStep::multi_point:
      return "multi-point search";
    case RendezvousStep::loiter:
      return "loiter circle";
    case RendezvousStep::virtual_adjust_r:
      return "virtual threat (adjust R)";
    case RendezvousStep::virtual_move_h:
      return "virtual threat (move H)";
    case RendezvousStep::detour:
      return "detour waypoint";
  }
  return "none";
}

namespace {

// A re-planning search that has not found its route after this many expansions is dropped as a
// candidate (a pre-planning search on these worlds needs a few thousand).
constexpr std::int64_t kReplanExpansions = 20'000;
// The last-resort loiter tries this many of the longest routes found, with up to this many laps.
constexpr int kLoiterBases = 4;
constexpr int kMaxLoiterLaps = 16;
// A detour replaces at most this many consecutive route segments.
constexpr std::size_t kDetourSpan = 8;
// move-H re-centres the virtual threat at most this many times.
constexpr int kMoveCentreSteps = 15;

double length(const std::vector<Vec3>& pts) { return polyline_length_m(pts); }

std::string fmt(const char* f, double a, double b = 0.0, double c = 0.0) { return strf(f, a, b, c); }

// The loiter of P4 eq. 9-11 as a regular polygon, x0 at the middle of its first side and that
// side along the heading, so the UAV leaves and rejoins its route with its own heading: [x0,
// v1, ..., vn, x0], each vertex turning 2 pi / n, perimeter `perimeter_m`. The paper's circle is
// flown counter-clockwise, its centre to the left, O = X0 - a v'/|v'| with
// v' = [[0,1,0],[-1,0,0],[0,0,0]] v; `left` false mirrors it (clockwise, centre to the right).
std::vector<Vec3> loiter_polygon(const Vec3& x0, const Vec3& heading, double perimeter_m, int n, bool left = true) {
  const Vec3 h = Vec3(heading.x(), heading.y(), 0.0).normalized();
  const Vec3 side = left ? Vec3(-h.y(), h.x(), 0.0) : Vec3(h.y(), -h.x(), 0.0);
  const double apothem = perimeter_m / (2.0 * n * std::tan(kPi / n));
  const double circum = apothem / std::cos(kPi / n);
  const Vec3 o = x0 + apothem * side;
  const double a0 = std::atan2(-side.y(), -side.x());  // direction from the centre to x0
  const double turn = left ? 1.0 : -1.0;
  std::vector<Vec3> pts{x0};
  for (int k = 0; k < n; ++k) {
    const double a = a0 + turn * (2 * k + 1) * kPi / n;
    pts.push_back(o + circum * Vec3(std::cos(a), std::sin(a), 0.0));
  }
  pts.push_back(x0);
  return pts;
}

// What a lengthened route must keep: clear of the world after inflation (`rule`), the turn and
// climb limits of `limits` (its heading the start's), its length inside [lo, hi].
struct Lengthening {
  const SegmentRule& rule;
  const UavSpec& limits;
  double lo, hi;
  int sides;  // of the loiter polygon

  bool keeps(const std::vector<Vec3>& route) const {
    const double l = length(route);
    return l >= lo && l <= hi && check_route_limits(route, limits).empty();
  }

  // `base` with `laps` turns of a loiter of `extra` metres in all at route point `at`, entered
  // and left along the horizontal heading there (the start's own heading at the start).
  std::optional<std::vector<Vec3>> loiter(const std::vector<Vec3>& base, std::size_t at, double extra, int laps,
                                          bool left) const {
    const Vec3 heading = at > 0 ? Vec3(base[at] - base[at - 1])
                                : (limits.heading_rad ? heading_vector(*limits.heading_rad) : Vec3(base[1] - base[0]));
    if (heading.head<2>().norm() <= kSamePoint_m * heading.norm()) return std::nullopt;
    const auto loop = loiter_polygon(base[at], heading, extra / laps, sides, left);
    for (std::size_t i = 1; i < loop.size(); ++i)
      if (!rule(loop[i - 1], loop[i])) return std::nullopt;
    std::vector<Vec3> route(base.begin(), base.begin() + static_cast<std::ptrdiff_t>(at) + 1);
    for (int lap = 0; lap < laps; ++lap) route.insert(route.end(), loop.begin() + 1, loop.end() - 1);
    route.insert(route.end(), base.begin() + static_cast<std::ptrdiff_t>(at), base.end());
    if (!keeps(route)) return std::nullopt;
    return route;
  }

  // `base` with its waypoints i..j replaced by two legs through one waypoint beside the middle of
  // the chord (horizontally, on the left of i -> j or the right), offset by h so that the route
  // grows by `extra`: 2 sqrt((D/2)^2 + h^2) = (the replaced part's length) + extra.
  std::optional<std::vector<Vec3>> detour(const std::vector<Vec3>& base, std::size_t i, std::size_t j, double extra,
                                          bool left, double* offset_m) const {
    const Vec3& a = base[i];
    const Vec3& b = base[j];
    const double chord = (b - a).norm();
    double legs = extra;  // the two new legs together
    for (std::size_t k = i; k < j; ++k) legs += (base[k + 1] - base[k]).norm();
    const Vec3 across(a.y() - b.y(), b.x() - a.x(), 0.0);  // horizontal, left of a -> b
    if (across.norm() <= kSamePoint_m * chord || legs <= chord) return std::nullopt;
    const double h = std::sqrt(0.25 * legs * legs - 0.25 * chord * chord);
    const Vec3 m = 0.5 * (a + b) + (left ? h : -h) * across.normalized();
    if (!rule(a, m) || !rule(m, b)) return std::nullopt;
    std::vector<Vec3> route(base.begin(), base.begin() + static_cast<std::ptrdiff_t>(i) + 1);
    route.push_back(m);
    route.insert(route.end(), base.begin() + static_cast<std::ptrdiff_t>(j), base.end());
    if (!keeps(route)) return std::nullopt;
    *offset_m = h;
    return route;
  }
};

// Runs `qs` on one thread per engine, each thread taking the next query in index order.
// `prepare(i, q)` may tighten query i from the routes finished so far (called under the lock);
// `ends(i, route)` says whether route i ends the list: no query after the first such index is
// started. Every query before that index completes, so a choice made afterwards in index order
// does not depend on the timing or the thread count. Unstarted queries stay empty.
template <class Prepare, class Ends>
std::vector<std::optional<DirectionalRoute>> run_ordered(std::vector<DirectionalSearch>& engines, const World& world,
                                                         std::vector<DirectionalQuery> qs, Prepare&& prepare,
                                                         Ends&& ends, const StopCondition& stop) {
  std::vector<std::optional<DirectionalRoute>> routes(qs.size());
  // A query running past the end of the list is cancelled (its route is never chosen).
  const std::unique_ptr<std::atomic<bool>[]> cancel(new std::atomic<bool>[qs.size()]);
  for (std::size_t i = 0; i < qs.size(); ++i) cancel[i] = false;
  std::mutex m;
  std::size_t next = 0, end = qs.size();
  auto worker = [&](DirectionalSearch& engine) {
    for (;;) {
      std::size_t i;
      {
        const std::lock_guard lock(m);
        if (next >= end || stop.should_stop()) return;
        i = next++;
        prepare(i, qs[i], routes);
      }
      DirectionalRoute r = engine.run(world, qs[i], stop | StopCondition::cancel_flag(&cancel[i]));
      const std::lock_guard lock(m);
      if (ends(i, r) && i + 1 < end) {
        end = i + 1;
        for (std::size_t j = end; j < next; ++j) cancel[j] = true;
      }
      routes[i] = std::move(r);
    }
  };
  std::vector<std::thread> pool;
  for (std::size_t t = 1; t < std::min(engines.size(), qs.size()); ++t) pool.emplace_back(worker, std::ref(engines[t]));
  worker(engines.front());
  for (auto& th : pool) th.join();
  return routes;
}

// The searches of one rendezvous: one engine per thread (buffers, clearance cache), all on one
// set of cone tables, the first serving the sequential steps; every search is counted into the
// result.
class Searches {
 public:
  Searches(const World& world, const StopCondition& stop, RendezvousResult& res)
      : world_(world), stop_(stop), res_(res) {
    const auto cones = std::make_shared<DirectionalCones>();
    for (int t = stop.threads(8); t > 0; --t) engines_.emplace_back(cones);
  }
  int threads() const { return static_cast<int>(engines_.size()); }
  const StopCondition& stop() const { return stop_; }

  DirectionalRoute run(const DirectionalQuery& q) {
    DirectionalRoute r = engines_.front().run(world_, q, stop_);
    count(r);
    return r;
  }
  // run_ordered on every engine, the routes counted.
  template <class Prepare, class Ends>
  std::vector<std::optional<DirectionalRoute>> ordered(std::vector<DirectionalQuery> qs, Prepare&& prepare,
                                                       Ends&& ends) {
    auto routes = run_ordered(engines_, world_, std::move(qs), prepare, ends, stop_);
    for (const auto& r : routes)
      if (r) count(*r);
    return routes;
  }
  // Side by side, all of them (no query tightened, none ends the list).
  std::vector<std::optional<DirectionalRoute>> all(std::vector<DirectionalQuery> qs) {
    return ordered(std::move(qs), keep_query, [](std::size_t, const DirectionalRoute&) { return false; });
  }
  static void keep_query(std::size_t, DirectionalQuery&, const std::vector<std::optional<DirectionalRoute>>&) {}

 private:
  void count(const DirectionalRoute& r) {
    ++res_.searches;
    res_.expanded += r.expanded;
  }
  const World& world_;
  const StopCondition& stop_;
  RendezvousResult& res_;
  std::vector<DirectionalSearch> engines_;
};

// The pre-plans are independent: side by side (a UAV without a goal gets no search). Like
// every later search they keep P4's one state per lattice point; a UAV that finds no route
// that way is searched again with heading sectors in the state (DirectionalQuery::heading_states).
// One entry per UAV with a goal, in scenario order; empty where the stop came first.
std::vector<std::optional<DirectionalRoute>> preplan(const Scenario& sc, const std::vector<DirectionalQuery>& queries,
                                                     Searches& searches) {
  std::vector<DirectionalQuery> with_goal;
  for (std::size_t s = 0; s < sc.uavs.size(); ++s)
    if (sc.uavs[s].goal) {
      with_goal.push_back(queries[s]);
      with_goal.back().heading_states = false;
    }
  auto preplans = searches.all(with_goal);
  std::vector<DirectionalQuery> again;
  std::vector<std::size_t> again_of;
  for (std::size_t k = 0; k < preplans.size(); ++k)
    if (preplans[k] && !preplans[k]->solved() && preplans[k]->reason != Reason::stopped) {
      again.push_back(with_goal[k]);
      again.back().heading_states = true;
      again_of.push_back(k);
    }
  auto second = searches.all(std::move(again));
  for (std::size_t m = 0; m < second.size(); ++m)
    if (second[m]) preplans[again_of[m]] = std::move(second[m]);
  return preplans;
}

// Each UAV as pre-planned: its route, or why it has none.
std::vector<RendezvousUav> preplanned_uavs(const Scenario& sc,
                                           const std::vector<std::optional<DirectionalRoute>>& preplans) {
  std::vector<RendezvousUav> uavs;
  for (std::size_t s = 0, k = 0; s < sc.uavs.size(); ++s) {
    const UavSpec& u = sc.uavs[s];
    RendezvousUav r;
    r.id = u.id;
    if (!u.goal) {
      r.detail = "no goal given";
      r.reason = Reason::invalid;
    } else if (!preplans[k]) {
      r.detail = "stopped before a route was found";
      r.reason = Reason::stopped;
      ++k;
    } else {
      const DirectionalRoute& route = *preplans[k++];
      r.status = route.status;
      r.waypoints = route.waypoints;
      r.preplanned_m = r.final_m = route.length_m;
      r.step = route.solved() ? RendezvousStep::preplanned : RendezvousStep::none;
      if (!route.solved()) {
        r.detail = route.message;
        r.reason = route.reason;
      }
    }
    uavs.push_back(std::move(r));
  }
  return uavs;
}

// The window every route's length must fall in: [lo, hi] = [P_max - epsilon, P_max], aiming at
// its middle.
struct LengthWindow {
  double lo = 0.0, hi = 0.0, aim = 0.0, epsilon = 0.0;
  bool within(double l) const { return l >= lo && l <= hi; }
};

// The steps that bring one UAV's route into the window, in P4's order, each a method; the first
// route within the window is accepted and ends them.
class Lengthener {
 public:
  Lengthener(const Scenario& sc, std::size_t s, const DirectionalQuery& query, const DirectionalAStarOptions& opt,
             const LengthWindow& window, Searches& searches, RendezvousResult& res)
      : s_(s),
        u_(sc.uavs[s]),
        r_(res.uavs[s]),
        res_(res),
        window_(window),
        searches_(searches),
        cell_(query.cell_m),
        r_min_(opt.min_turn_radius_m > 0.0 ? opt.min_turn_radius_m : query.cell_m),
        sides_(
            std::max(12, static_cast<int>(std::ceil(2 * kPi / (0.95 * std::min(u_.max_turn_rad, query.max_yaw_rad)))))),
        rule_(sc.world, u_),
        limits_(search_limits(u_, query)),
        lengthen_{rule_, limits_, window.lo, window.hi, sides_},
        step_cells_max_(opt.step_cells_max),
        q_(replan_query(query)) {}

  void run() {
    candidates_ = {r_.waypoints};
    r_.status = Status::failed;
    if (multi_point()) return;
    if (loiter_at_start()) return;
    if (virtual_threat()) return;
    // Last: a loiter on any route found on the way, or a detour.
    if (loiter_at_start() || loiter_anywhere() || detour()) return;
    r_.detail = fmt("no step brought the length (%.1f m) within [%.1f, %.1f] m", r_.final_m, window_.lo, window_.hi);
  }

 private:
  // The limits the lengthened routes must keep (the search's, which are within the UAV's).
  static UavSpec search_limits(const UavSpec& u, const DirectionalQuery& q) {
    UavSpec limits = u;
    limits.max_turn_rad = std::min(u.max_turn_rad, q.max_yaw_rad);
    limits.max_climb_rad = std::min(u.max_climb_rad, q.max_pitch_rad);
    return limits;
  }
  // The re-planning steps run many searches; each keeps P4's one state per lattice point and a
  // route that gets stuck is simply not a candidate. Without the relaxed heuristic: its reverse
  // search costs more than these short, length-bounded searches save (each step and direction
  // count, each virtual threat, would need its own).
  static DirectionalQuery replan_query(DirectionalQuery q) {
    q.heading_states = false;
    q.relaxed_heuristic = false;
    q.max_expansions = std::min<std::int64_t>(q.max_expansions, kReplanExpansions);
    return q;
  }

  void accept(const std::vector<Vec3>& route, RendezvousStep step, std::string detail) {
    r_.waypoints = route;
    r_.final_m = length(route);
    r_.step = step;
    r_.detail = std::move(detail);
    r_.succeed();
  }

  bool multi_point();
  bool loiter_at_start();
  bool loiter_anywhere();
  bool detour();
  bool virtual_threat();
  double adjust_radius(const Vec3& h0, double rx_max);
  void move_centre(double rx_used);
  Vec3 centre_on(const std::vector<Vec3>& pts) const;
  double radius_limit(const Vec3& h) const;

  // f(base, extra) on the routes found, longest first, whose missing length `usable` takes (at
  // most `max_bases` of them); true at the first f that accepts a route.
  template <class Usable, class F>
  bool on_candidates(Usable&& usable, int max_bases, F&& f) {
    std::sort(candidates_.begin(), candidates_.end(),
              [](const auto& x, const auto& y) { return length(x) > length(y); });
    int bases = 0;
    for (const auto& base : candidates_) {
      const double extra = window_.aim - length(base);
      if (!usable(extra) || base.size() < 2) continue;
      if (++bases > max_bases) break;
      if (f(base, extra)) return true;
    }
    return false;
  }
  bool loiter_fits(double extra) const { return extra / (2 * kPi) >= r_min_; }

  std::size_t s_;
  const UavSpec& u_;
  RendezvousUav& r_;
  const RendezvousResult& res_;
  LengthWindow window_;
  Searches& searches_;
  double cell_, r_min_;
  int sides_;
  SegmentRule rule_;
  UavSpec limits_;
  Lengthening lengthen_;
  double step_cells_max_;
  DirectionalQuery q_;
  std::vector<std::vector<Vec3>> candidates_;  // every route found on the way; the loiter may extend any
  std::vector<Vec3> best_;                     // the closest to the window so far
};

// (1) Variable-step multi-point search (P4 table 1): L from 1 to L_max step 0.2, M from 3 to 6;
// the first route within the window ends the step, else the closest is kept. The searches are
// independent: they run in batches, one per thread, and are taken in their (L, M) order, so the
// result does not depend on the thread count.
bool Lengthener::multi_point() {
  best_ = r_.waypoints;
  std::vector<std::pair<double, int>> combos;
  for (int li = 0; 1.0 + 0.2 * li <= step_cells_max_ + kWholeNumberSlack; ++li)
    for (int m = 3; m <= 6; ++m) combos.emplace_back(1.0 + 0.2 * li, m);
  std::vector<DirectionalQuery> qs(combos.size(), q_);
  for (std::size_t c = 0; c < combos.size(); ++c) {
    qs[c].step_cells = combos[c].first;
    qs[c].directions = combos[c].second;
  }
  const double best0_m = length(best_);
  const double aim = window_.aim;
  const auto routes = searches_.ordered(
      std::move(qs),
      [&](std::size_t, DirectionalQuery& qi, const std::vector<std::optional<DirectionalRoute>>& done) {
        // A route longer than this can neither fall in the window nor come closer than the best
        // so far (any finished subset of the routes gives a safe bound).
        double off = std::abs(best0_m - aim);
        for (const auto& d : done)
          if (d && d->solved()) off = std::min(off, std::abs(d->length_m - aim));
        qi.max_length_m = aim + std::max(off, 0.5 * window_.epsilon);
      },
      [&](std::size_t, const DirectionalRoute& route) { return route.solved() && window_.within(route.length_m); });
  for (std::size_t c = 0; c < routes.size() && !r_.solved(); ++c) {
    if (!routes[c] || !routes[c]->solved()) continue;
    const DirectionalRoute& route = *routes[c];
    candidates_.push_back(route.waypoints);
    if (window_.within(route.length_m))
      accept(route.waypoints, RendezvousStep::multi_point,
             fmt("L = %.1f, M = %.0f", combos[c].first, combos[c].second));
    else if (std::abs(route.length_m - aim) < std::abs(length(best_) - aim))
      best_ = route.waypoints;
  }
  if (r_.solved()) return true;
  r_.waypoints = best_;
  r_.final_m = length(best_);
  return false;
}

// (2) P4's loiter (eq. 9-11): one circle at the start, on the left, R = (P_max - P_i) / (2 pi)
// >= R_min and the circle clear of every obstacle.
bool Lengthener::loiter_at_start() {
  return on_candidates([&](double extra) { return loiter_fits(extra); }, std::numeric_limits<int>::max(),
                       [&](const std::vector<Vec3>& base, double extra) {
                         auto route = lengthen_.loiter(base, 0, extra, 1, true);
                         if (route)
                           accept(*route, RendezvousStep::loiter,
                                  fmt("radius %.1f m (R_min %.1f m), %.0f sides", extra / (2 * kPi), r_min_, sides_));
                         return route.has_value();
                       });
}

// Where that circle does not fit (a boundary, a threat) and no virtual threat helped: the same
// extra length as k laps of a circle k times smaller (while R >= R_min), on either side of the
// heading, at the start or a later waypoint of the longest routes found; the first that fits in
// that order (start first, fewer laps first, left first).
bool Lengthener::loiter_anywhere() {
  return on_candidates(
      [&](double extra) { return loiter_fits(extra); }, kLoiterBases,
      [&](const std::vector<Vec3>& base, double extra) {
        for (std::size_t at = 0; at + 1 < base.size(); ++at)
          for (int laps = 1; laps <= kMaxLoiterLaps && extra / (2 * kPi * laps) >= r_min_; ++laps)
            for (const bool left : {true, false})
              if (auto route = lengthen_.loiter(base, at, extra, laps, left)) {
                accept(
                    *route, RendezvousStep::loiter,
                    fmt("radius %.1f m (R_min %.1f m), %.0f laps", extra / (2 * kPi * laps), r_min_, laps) +
                        (left ? " on the left" : " on the right") +
                        (at == 0 ? std::string(" at the start") : fmt(" at waypoint %.0f", static_cast<double>(at))));
                return true;
              }
        return false;
      });
}

// A missing length too short for a loiter (R < R_min) that the virtual threat missed: a detour
// through one waypoint beside up to kDetourSpan segments, exactly `aim` long; the longest chords
// of the longest routes found first.
bool Lengthener::detour() {
  return on_candidates([](double extra) { return extra > 0.0; }, kLoiterBases,
                       [&](const std::vector<Vec3>& base, double extra) {
                         std::vector<std::pair<std::size_t, std::size_t>> spans;
                         for (std::size_t i = 0; i + 1 < base.size(); ++i)
                           for (std::size_t j = i + 1; j < base.size() && j - i <= kDetourSpan; ++j)
                             spans.emplace_back(i, j);
                         std::stable_sort(spans.begin(), spans.end(), [&](const auto& x, const auto& y) {
                           return (base[x.second] - base[x.first]).norm() > (base[y.second] - base[y.first]).norm();
                         });
                         for (const auto& [i, j] : spans)
                           for (const bool left : {true, false}) {
                             double offset_m = 0.0;
                             if (auto route = lengthen_.detour(base, i, j, extra, left, &offset_m)) {
                               accept(*route, RendezvousStep::detour,
                                      fmt("%.1f m beside waypoints %.0f to %.0f", offset_m, static_cast<double>(i),
                                          static_cast<double>(j)) +
                                          (left ? ", on the left" : ", on the right"));
                               return true;
                             }
                           }
                         return false;
                       });
}

// The route point nearest the start-goal midpoint.
Vec3 Lengthener::centre_on(const std::vector<Vec3>& pts) const {
  const Vec3 mid = 0.5 * (u_.start + *u_.goal);
  return *std::min_element(pts.begin(), pts.end(), [&](const Vec3& x, const Vec3& y) {
    return (x - mid).squaredNorm() < (y - mid).squaredNorm();
  });
}

// A virtual threat's largest radius at h: below the distance to the other UAVs' routes, the
// start and the goal outside it.
double Lengthener::radius_limit(const Vec3& h) const {
  double lim = std::min((h - u_.start).norm(), (h - *u_.goal).norm()) - 2 * q_.inflation_m - cell_;
  for (std::size_t o = 0; o < res_.uavs.size(); ++o) {
    if (o == s_) continue;
    const auto& w = res_.uavs[o].waypoints;
    for (std::size_t i = 1; i < w.size(); ++i)
      lim = std::min(lim, point_segment_distance(h, w[i - 1], w[i]) - q_.inflation_m);
  }
  return lim;
}

// (3) Virtual threat (P4 eq. 12-13): a sphere centred on the route point nearest the start-goal
// midpoint; adjust-R grows it, move-H keeps R_x and re-centres it on each new route.
bool Lengthener::virtual_threat() {
  const Vec3 h0 = centre_on(best_);
  const double rx_used = adjust_radius(h0, radius_limit(h0));
  if (!r_.solved()) move_centre(rx_used);
  return r_.solved();
}

// adjust-R: the length grows with R_x (by steps, the lattice being discrete), so R_x doubles from
// half a cell until the route is long enough, then bisection narrows it to a quarter cell. The
// doubling radii run side by side; taken in order, they end at the first route within the
// window or too long. Returns the largest radius whose route was still too short (0: none).
double Lengthener::adjust_radius(const Vec3& h0, double rx_max) {
  double rx_used = 0.0;
  auto take_radius = [&](double rx, const DirectionalRoute& route) -> double {  // its length, or -1 without a route
    if (!route.solved()) return -1.0;
    candidates_.push_back(route.waypoints);
    if (route.length_m < window_.lo) rx_used = std::max(rx_used, rx);
    if (window_.within(route.length_m))
      accept(route.waypoints, RendezvousStep::virtual_adjust_r,
             fmt("R_x = %.1f m at (%.0f, %.0f", rx, h0.x(), h0.y()) + fmt(", %.0f)", h0.z()));
    return route.length_m;
  };
  double short_rx = 0.0, long_rx = -1.0;
  std::vector<double> radii;
  for (double rx = 0.5 * cell_; rx < rx_max; rx *= 2.0) radii.push_back(rx);
  std::vector<DirectionalQuery> qs(radii.size(), q_);
  for (std::size_t k = 0; k < radii.size(); ++k) qs[k].virtual_threats = {Sphere{h0, radii[k]}};
  const auto routes = searches_.ordered(
      std::move(qs), Searches::keep_query,
      [&](std::size_t, const DirectionalRoute& route) { return route.solved() && route.length_m >= window_.lo; });
  for (std::size_t k = 0; k < routes.size() && routes[k] && !r_.solved(); ++k) {
    const double len = take_radius(radii[k], *routes[k]);
    if (len >= 0.0 && len < window_.lo) short_rx = radii[k];
    if (len > window_.hi) {
      long_rx = radii[k];
      break;
    }
  }
  if (long_rx < 0.0 && !r_.solved() && rx_max > short_rx) long_rx = rx_max;
  DirectionalQuery q = q_;
  while (!r_.solved() && long_rx > 0.0 && long_rx - short_rx > 0.25 * cell_ && !searches_.stop().should_stop()) {
    const double rx = 0.5 * (short_rx + long_rx);
    q.virtual_threats = {Sphere{h0, rx}};
    const double len = take_radius(rx, searches_.run(q));
    if (len >= 0.0 && len < window_.lo)
      short_rx = rx;
    else
      long_rx = rx;
  }
  return rx_used;
}

// move-H: the threat of radius R_x re-centred on each new route, up to kMoveCentreSteps times.
void Lengthener::move_centre(double rx_used) {
  std::vector<Vec3> current = best_;
  DirectionalQuery q = q_;
  for (int it = 0; it < kMoveCentreSteps && !r_.solved() && rx_used > 0.0 && !searches_.stop().should_stop(); ++it) {
    const Vec3 h = centre_on(current);
    const double rx = std::min(rx_used, radius_limit(h));
    if (rx <= 0.0) break;
    q.virtual_threats = {Sphere{h, rx}};
    const DirectionalRoute route = searches_.run(q);
    if (!route.solved() || route.waypoints == current) break;
    current = route.waypoints;
    candidates_.push_back(route.waypoints);
    if (window_.within(route.length_m))
      accept(route.waypoints, RendezvousStep::virtual_move_h, fmt("R_x = %.1f m, %.0f moves", rx, it + 1));
  }
}

}  // namespace

RendezvousResult plan_rendezvous(const Scenario& sc, const DirectionalAStarPlanner& planner,
                                 const StopCondition& stop) {
  RendezvousResult res;
  Searches searches(sc.world, stop, res);
  std::vector<DirectionalQuery> queries;
  for (const UavSpec& u : sc.uavs)
    queries.push_back(planner.query_for(Problem{u, u.goal.value_or(u.start), {}}, sc.world));
  if (!queries.empty()) DirectionalAStarPlanner::require_lattice(sc.world, queries.front(), searches.threads(), stop);
  res.uavs = preplanned_uavs(sc, preplan(sc, queries, searches));
  for (const auto& r : res.uavs)
    if (r.solved()) res.target_m = std::max(res.target_m, r.final_m);
  const double cell = queries.empty() ? 1.0 : queries.front().cell_m;
  res.epsilon_m = rendezvous_section(sc).arrival_tolerance_m.value_or(cell);
  const LengthWindow window{res.target_m - res.epsilon_m, res.target_m, res.target_m - 0.5 * res.epsilon_m,
                            res.epsilon_m};
  for (std::size_t s = 0; s < res.uavs.size(); ++s) {
    if (!res.uavs[s].solved() || window.within(res.uavs[s].final_m)) continue;
    Lengthener(sc, s, queries[s], planner.options(), window, searches, res).run();
  }
  return res;
}

}  // namespace uavplan
