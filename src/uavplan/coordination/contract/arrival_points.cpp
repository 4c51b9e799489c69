#include "uavplan/coordination/contract/arrival_points.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <numeric>

#include "uavplan/coordination/contract/separation.h"
#include "uavplan/coordination/ground_heights.h"
#include "uavplan/core/text.h"

namespace uavplan {
namespace {

constexpr double kRingMargin = 1.01;  // chords 1 % above the spacing: planners' rounding stays clear
constexpr int kRingTurns = 24;        // 15-degree steps

std::size_t root(std::vector<std::size_t>& parent, std::size_t i) {
  while (parent[i] != i) i = parent[i] = parent[parent[i]];
  return i;
}

// A UAV can end at p: in the bounds; on the ground, its landing column clear; in the air, its
// body and clearance clear of obstacles, and (conservatively) of the terrain and floor raised by
// the planning min_agl, which the planners keep.
bool free_end(const Scenario& sc, const UavSpec& u, const Vec3& p, bool on_ground) {
  const World& w = sc.world;
  if (!w.in_bounds(p)) return false;
  if (on_ground) return ground_column_problem(sc, u, p).empty();
  const double keep = keep_off_m(u), agl = planning_min_agl_m(sc);
  if (w.segment_obstacle_clearance(p, p, keep) < keep) return false;
  if (agl <= 0.0) return w.clearance(p, keep) >= keep;
  return w.clearance(p, keep + agl) >= keep + agl && w.lowest_height_above_ground(p, p) >= keep + agl;
}

// Angles on a circle, each as near its wish as the least gap `gap_rad` between neighbours lets
// it: neighbours too close push each other apart, half each, until every gap holds.
std::vector<double> spread(std::vector<double> wish, double gap_rad) {
  const std::size_t k = wish.size();
  std::vector<std::size_t> order(k);
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return wish[a] < wish[b]; });
  std::vector<double> a(k);
  for (std::size_t n = 0; n < k; ++n) a[n] = wish[order[n]];
  for (int round = 0; round < 200; ++round) {
    bool moved = false;
    for (std::size_t n = 0; n < k; ++n) {
      const std::size_t m = (n + 1) % k;
      const double gap = m == 0 ? a[0] + 2.0 * std::numbers::pi - a[n] : a[m] - a[n];
      if (gap >= gap_rad - 1e-12) continue;
      const double push = 0.5 * (gap_rad - gap) + 1e-12;
      a[n] -= push;
      a[m] += push;
      moved = true;
    }
    if (!moved) break;
  }
  std::vector<double> out(k);
  for (std::size_t n = 0; n < k; ++n) out[order[n]] = a[n];
  return out;
}

// The arrival points of one goal group, or none when no ring is free. Each UAV's point lies
// towards its start, on a ring of radius max(chord, chord / (2 sin(pi / k))) so that UAVs coming
// from one side arrive side by side a chord apart; the ring turns in 15-degree steps either way
// until every point is free.
std::vector<Vec3> ring(const Scenario& sc, const std::vector<std::size_t>& members, double chord_m) {
  const World& w = sc.world;
  const std::size_t k = members.size();
  Vec3 c = Vec3::Zero();
  for (std::size_t i : members) c += *sc.uavs[i].goal;
  c /= static_cast<double>(k);
  const bool ground =
      std::all_of(members.begin(), members.end(), [&](std::size_t i) { return w.on_ground(*sc.uavs[i].goal); });
  const double r = std::max(chord_m, chord_m / (2.0 * std::sin(std::numbers::pi / static_cast<double>(k))));
  std::vector<double> wish;
  for (std::size_t i : members) {
    const Vec3 d = sc.uavs[i].start - c;
    wish.push_back(d.head<2>().norm() > 0.0 ? std::atan2(d.y(), d.x()) : 0.0);
  }
  const std::vector<double> angle = spread(wish, 2.0 * std::asin(std::min(1.0, chord_m / (2.0 * r))));
  for (int t = 0; t < kRingTurns; ++t) {
    const int step = (t + 1) / 2;  // 0, 1, -1, 2, -2, ... turns of the ring
    const double turn = (t % 2 ? -1.0 : 1.0) * step * 2.0 * std::numbers::pi / kRingTurns;
    std::vector<Vec3> pts(k);
    bool ok = true;
    for (std::size_t m = 0; m < k && ok; ++m) {
      Vec3 p(c.x() + r * std::cos(angle[m] + turn), c.y() + r * std::sin(angle[m] + turn), c.z());
      if (ground) p.z() = w.ground_z(p.x(), p.y());
      ok = free_end(sc, sc.uavs[members[m]], p, ground);
      pts[m] = p;
    }
    if (ok) return pts;
  }
  return {};
}

}  // namespace

double goal_spacing_m(const Scenario& sc, const UavSpec& a, const UavSpec& b) {
  // Bodies with their clearance: the planners keep that much between UAVs too.
  return std::max({sc.mission.goal_spacing_m.value_or(sc.mission.separation_m), required_separation_m(sc, a, b),
                   keep_off_m(a) + keep_off_m(b)});
}

std::vector<Arrival> arrival_points(const Scenario& sc) {
  const std::size_t n = sc.uavs.size();
  std::vector<Arrival> out(n);
  std::vector<std::size_t> parent(n);
  std::iota(parent.begin(), parent.end(), 0);
  for (std::size_t i = 0; i < n; ++i) {
    const UavSpec& u = sc.uavs[i];
    out[i].point = u.goal.value_or(u.start);
    for (std::size_t j = 0; j < i && u.goal; ++j) {
      const UavSpec& v = sc.uavs[j];
      if (v.goal && (*u.goal - *v.goal).norm() < goal_spacing_m(sc, u, v)) parent[root(parent, i)] = root(parent, j);
    }
  }
  for (std::size_t i = 0; i < n; ++i) {
    if (root(parent, i) != i) continue;
    std::vector<std::size_t> members;
    for (std::size_t j = 0; j < n; ++j)
      if (root(parent, j) == i) members.push_back(j);
    if (members.size() < 2) continue;
    double chord = 0.0;
    for (std::size_t a : members)
      for (std::size_t b : members)
        if (a < b) chord = std::max(chord, goal_spacing_m(sc, sc.uavs[a], sc.uavs[b]));
    const std::vector<Vec3> pts = ring(sc, members, chord * kRingMargin);
    std::string ids;
    for (std::size_t m : members) ids += (ids.empty() ? "" : ", ") + sc.uavs[m].id;
    for (std::size_t m = 0; m < members.size(); ++m) {
      Arrival& a = out[members[m]];
      if (pts.empty()) {
        a.problem = "the goal is shared by " + ids + " and there is no free room around it for " +
                    std::to_string(members.size()) + " arrival points " + num_text(chord) +
                    " m apart (move the goals apart, or lower mission.separation / goal_spacing)";
        continue;
      }
      a.point = pts[m];
      a.tolerance_m = (pts[m] - *sc.uavs[members[m]].goal).norm();
    }
  }
  return out;
}

double arrival_radius_m(const UavSpec& uav, const Arrival& arrival) {
  return std::max(uav.radius_m, kMinArrivalRadius_m) + arrival.tolerance_m;
}

// The last row outside the ball decides: the segment from it into the ball enters once (a ball
// is convex and the segment's end inside), at the smaller root of |a + s (b - a) - goal| = r.
namespace {

// When the segment from row k - 1 to row k enters the ball of radius within_m around goal (its
// end inside it): the smaller root of |a + s d| = r.
double entry_s(const Trajectory& tr, std::size_t k, const Vec3& goal, double within_m) {
  const Vec3 a = tr[k - 1].p - goal, d = tr[k].p - tr[k - 1].p;
  const double dd = d.squaredNorm(), ad = a.dot(d), aa = a.squaredNorm() - within_m * within_m;
  const double disc = std::max(0.0, ad * ad - dd * aa);
  const double s = dd > 0.0 ? std::clamp((-ad - std::sqrt(disc)) / dd, 0.0, 1.0) : 1.0;
  return tr[k - 1].t_s + s * (tr[k].t_s - tr[k - 1].t_s);
}

}  // namespace

double arrival_time_s(const Trajectory& tr, const Vec3& goal, double within_m) {
  if (tr.empty() || (tr.back().p - goal).norm() > within_m) return std::numeric_limits<double>::infinity();
  std::size_t k = tr.size() - 1;
  while (k > 0 && (tr[k - 1].p - goal).norm() <= within_m) --k;
  return k == 0 ? tr.front().t_s : entry_s(tr, k, goal, within_m);
}

double first_arrival_s(const Trajectory& tr, const Vec3& goal, double within_m) {
  for (std::size_t k = 0; k < tr.size(); ++k)
    if ((tr[k].p - goal).norm() <= within_m) return k == 0 ? tr.front().t_s : entry_s(tr, k, goal, within_m);
  return std::numeric_limits<double>::infinity();
}

double arrival_s(const UavSpec& uav, const Arrival& arrival, const Trajectory& trajectory) {
  if (!uav.goal) return std::numeric_limits<double>::infinity();
  if (uav.home) return first_arrival_s(trajectory, *uav.goal, arrival_radius_m(uav, arrival));
  return arrival_time_s(trajectory, *uav.goal, arrival_radius_m(uav, arrival));
}

}  // namespace uavplan
