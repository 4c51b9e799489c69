#include "uavplan/coordination/formation/formation_schedule.h"
#include "uavplan/core/geometry.h"
#include "uavplan/core/tolerances.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace uavplan {
namespace {

// Slot offset (forward, left, up) turned to heading psi.
Vec3 turned(const Vec3& o, double psi) {
  const double c = std::cos(psi), s = std::sin(psi);
  return Vec3(o.x() * c - o.y() * s, o.x() * s + o.y() * c, o.z());
}

// Heading of each segment; a vertical or empty one keeps the one before (the first: the next).
std::vector<double> headings(const std::vector<Vec3>& route) {
  std::vector<double> psi(route.size() > 1 ? route.size() - 1 : 1, 0.0);
  std::vector<char> known(psi.size(), 0);
  for (std::size_t k = 0; k + 1 < route.size(); ++k) {
    const Vec3 d = route[k + 1] - route[k];
    if (d.head<2>().norm() > kSamePoint_m) {
      psi[k] = std::atan2(d.y(), d.x());
      known[k] = 1;
    }
  }
  for (std::size_t k = 1; k < psi.size(); ++k)
    if (!known[k] && known[k - 1]) psi[k] = psi[k - 1], known[k] = 1;
  for (std::size_t k = psi.size() - 1; k-- > 0;)
    if (!known[k] && known[k + 1]) psi[k] = psi[k + 1], known[k] = 1;
  return psi;
}

// The heading at which the shape (about its centroid) best matches `pts` (about theirs), in the
// least-squares sense (2-D Procrustes); `fallback` when they say nothing about it.
double fitted_heading(const std::vector<Vec3>& shape, const Vec3& centroid, const std::vector<Vec3>& pts,
                      double fallback) {
  Vec3 c = Vec3::Zero();
  for (const Vec3& p : pts) c += p / static_cast<double>(pts.size());
  double cross = 0.0, dot = 0.0;
  for (std::size_t i = 0; i < shape.size(); ++i) {
    const Vec3 a = shape[i] - centroid, b = pts[i] - c;
    cross += a.x() * b.y() - a.y() * b.x();
    dot += a.x() * b.x() + a.y() * b.y();
  }
  return std::hypot(cross, dot) > 1e-9 ? std::atan2(cross, dot) : fallback;
}

// Signed smallest turn from heading a to heading b.
double turn_between(double a, double b) { return std::remainder(b - a, 2.0 * M_PI); }

// The route cut where the approach begins, approach_m before its end (its start when it is
// shorter): the part flown in shape along the route's headings, and the points after the cut.
struct Approach {
  std::vector<Vec3> cruise;  // route[0] .. the cut
  std::vector<Vec3> rest;    // the route's points after the cut (its end last)
};
Approach split_for_approach(const std::vector<Vec3>& route, double approach_m) {
  Approach a{{route.front()}, {}};
  double left = polyline_length_m(route) - approach_m;
  std::size_t k = 0;
  for (; k + 1 < route.size() && left > kSamePoint_m; ++k) {
    const double len = (route[k + 1] - route[k]).norm();
    if (len > left + kSamePoint_m) {
      a.cruise.push_back(route[k] + (route[k + 1] - route[k]) * (left / len));
      break;
    }
    left -= len;
    a.cruise.push_back(route[k + 1]);
  }
  for (std::size_t m = k + 1; m < route.size(); ++m) a.rest.push_back(route[m]);
  if (a.rest.empty()) a.rest.push_back(route.back());
  return a;
}

// Where the reference point is and its heading.
struct Pose {
  Vec3 p = Vec3::Zero();
  double heading_rad = 0.0;
};

// A corner flown as an arc (P1's formation keeps flying through a turn): the reference point
// leaves the route `tangent_m` before the corner and rejoins it as far after, on a circle of
// radius_m, the shape turning with the arc's heading. No slot backs up when the circle is wider
// than the shape's reach on the turn's inner side (each slot then circles the same centre).
struct Arc {
  bool ok = false;
  Vec3 t1 = Vec3::Zero(), t2 = Vec3::Zero();
  Vec3 centre = Vec3::Zero();  // horizontal; z from t1 to t2
  double radius_m = 0.0, from = 0.0, turn = 0.0, side = 1.0;
  int chords = 1;
  Vec3 at(int c) const {
    const double f = static_cast<double>(c) / chords, phi = from + f * turn;
    Vec3 p = centre - side * radius_m * Vec3(-std::sin(phi), std::cos(phi), 0.0);
    p.z() = t1.z() + f * (t2.z() - t1.z());
    return p;
  }
  double heading(int c) const { return from + turn * c / chords; }
};

// The widest arc whose tangent points lie within room_m of the corner, at most twice the shape's
// reach; none (a turn on the spot) where even the narrowest arc that keeps every slot moving
// forward does not fit, or the turn is nearly a reversal.
Arc corner_arc(const Vec3& before, const Vec3& corner, const Vec3& after, double psi_in, double psi_out, double reach_m,
               double inner_m, double room) {
  Arc a;
  a.turn = turn_between(psi_in, psi_out);
  const double half = std::abs(a.turn) / 2.0;
  if (half < 1e-9 || half > 0.45 * M_PI || reach_m <= 0.0) return a;
  a.radius_m = std::min(2.0 * reach_m, room / std::tan(half));
  if (a.radius_m < std::max(1.05 * inner_m, 0.25 * reach_m)) return a;
  const double tangent = a.radius_m * std::tan(half);
  a.t1 = corner - (corner - before).normalized() * tangent;
  a.t2 = corner + (after - corner).normalized() * tangent;
  a.side = a.turn > 0.0 ? 1.0 : -1.0;
  a.from = psi_in;
  a.centre = a.t1 + a.side * a.radius_m * Vec3(-std::sin(psi_in), std::cos(psi_in), 0.0);
  a.chords = std::max(1, static_cast<int>(std::ceil(std::abs(a.turn) / (M_PI / 9.0) - kWholeNumberSlack)));
  a.ok = true;
  return a;
}

// Each interior point of the route's cruise part as an arc where one fits and every slot's
// chords are clear (`clear`), else none (the shape turns about the corner). In route
// order, a corner may take what of the segment before it the corner before left, and half of
// the segment after it (all of the last).
template <class Clear>
std::vector<Arc> corner_arcs(const std::vector<Vec3>& cruise, const std::vector<double>& psi,
                             const std::vector<Vec3>& shape, const Vec3& centroid, const Clear& clear) {
  double reach = 0.0, left = 0.0, right = 0.0;
  for (const Vec3& o : shape) {
    const Vec3 d = o - centroid;
    reach = std::max(reach, d.head<2>().norm());
    left = std::max(left, d.y()), right = std::max(right, -d.y());
  }
  std::vector<Arc> arcs(cruise.size());
  double used = 0.0;  // of the segment before the corner, by the corner before
  for (std::size_t k = 1; k + 1 < cruise.size(); ++k) {
    const double inner = turn_between(psi[k - 1], psi[k]) > 0.0 ? left : right;
    const double out = (cruise[k + 1] - cruise[k]).norm() * (k + 2 == cruise.size() ? 1.0 : 0.5);
    const double room = std::min((cruise[k] - cruise[k - 1]).norm() - used, out);
    Arc arc = corner_arc(cruise[k - 1], cruise[k], cruise[k + 1], psi[k - 1], psi[k], reach, inner, room);
    used = 0.0;
    if (!arc.ok) continue;
    std::vector<Pose> poses{{arc.t1, arc.from}};
    for (int c = 1; c <= arc.chords; ++c) poses.push_back({arc.at(c), arc.heading(c)});
    arc.ok = clear(poses);
    if (arc.ok) used = (arc.t2 - cruise[k]).norm();
    arcs[k] = arc;
  }
  return arcs;
}

// A route point within this fraction of the shape's reach of the straight line past it is a
// wiggle (a 5 m wedge: 5 cm): the shape flies straight past it instead of turning on the spot.
constexpr double kWiggleOfReach = 0.01;

// The cruise part without the route's near-collinear wiggles (a graph route's short edges, on
// which no arc fits, each a turn on the spot): a point goes where the straight line past it
// strays from it by at most `tol_m` and every slot's translate of that line is clear.
template <class Clear>
std::vector<Vec3> without_wiggles(const std::vector<Vec3>& cruise, double tol_m, const Clear& clear) {
  std::vector<Vec3> out{cruise.front()};
  std::size_t k = 0;
  while (k + 1 < cruise.size()) {
    std::size_t far = k + 1;
    for (std::size_t m = k + 2; m < cruise.size(); ++m) {
      const Vec3& a = cruise[k];
      const Vec3 d = cruise[m] - a;
      bool near = d.head<2>().norm() > kSamePoint_m;
      for (std::size_t j = k + 1; j < m && near; ++j) {
        const double f = std::clamp((cruise[j] - a).dot(d) / d.squaredNorm(), 0.0, 1.0);
        near = (a + f * d - cruise[j]).norm() <= tol_m;
      }
      if (near) {
        const double psi = std::atan2(d.y(), d.x());
        near = clear(std::vector<Pose>{{a, psi}, {cruise[m], psi}});
      }
      if (!near) break;
      far = m;
    }
    out.push_back(cruise[far]);
    k = far;
  }
  return out;
}

// Steps turning by no more than this are straight on (one pose for a straight run).
constexpr double kStraight_rad = 1e-3;

// The point at arc length s along a polyline (its segment in *k, searched from *k on).
Vec3 along_polyline(const std::vector<Vec3>& pts, const std::vector<double>& cum, double s, std::size_t* k) {
  while (*k + 2 < pts.size() && cum[*k + 1] < s) ++*k;
  const double len = cum[*k + 1] - cum[*k];
  const double f = len > 0.0 ? std::clamp((s - cum[*k]) / len, 0.0, 1.0) : 1.0;
  return pts[*k] + f * (pts[*k + 1] - pts[*k]);
}

// The cruise part as a smooth path (pure pursuit): the reference point looks radius_m ahead
// along the route and turns towards that point, never tighter than radius_m, in steps of 5 deg
// of turn at most; so a graph route's many short edges and small turns are one curve, flown
// without turning on the spot. Ends at the route's end; empty when it does not get there.
std::vector<Pose> pursued(const std::vector<Vec3>& route, double heading_rad, double radius_m) {
  if (route.size() < 2 || radius_m <= 0.0) return {};
  std::vector<double> cum{0.0};
  for (std::size_t k = 1; k < route.size(); ++k) cum.push_back(cum.back() + (route[k] - route[k - 1]).norm());
  const double total = cum.back(), step = radius_m * M_PI / 36.0;
  std::vector<Pose> out{{route.front(), heading_rad}};
  std::size_t seg = 0, look_seg = 0;
  double s = 0.0;  // how far along the route the reference is (its projection, never back)
  for (int n = 0; n < static_cast<int>(4.0 * total / step) + 100; ++n) {
    Pose next = out.back();
    if ((route.back() - next.p).norm() <= step) {
      next.p = route.back();
      const Vec3 d = next.p - out.back().p;
      if (d.head<2>().norm() > kSamePoint_m) next.heading_rad = std::atan2(d.y(), d.x());
      out.push_back(next);
      return out;
    }
    const Vec3 target = along_polyline(route, cum, std::min(total, s + radius_m), &look_seg);
    const Vec3 to = target - next.p;
    const double turn =
        std::clamp(turn_between(next.heading_rad, std::atan2(to.y(), to.x())), -M_PI / 36.0, M_PI / 36.0);
    next.heading_rad += turn;
    next.p += step * Vec3(std::cos(next.heading_rad), std::sin(next.heading_rad), 0.0);
    // The projection moves on: the nearest route point within two steps ahead.
    double best = std::numeric_limits<double>::infinity(), best_s = s;
    for (std::size_t k = seg; k + 1 < route.size() && cum[k] <= s + 2.0 * step; ++k) {
      const Vec3 d = route[k + 1] - route[k];
      const double f = d.squaredNorm() > 0.0 ? std::clamp((next.p - route[k]).dot(d) / d.squaredNorm(), 0.0, 1.0) : 0.0;
      const double at = cum[k] + f * (cum[k + 1] - cum[k]), dist = (route[k] + f * d - next.p).norm();
      if (at >= s && dist < best) best = dist, best_s = at;
    }
    s = std::max(s, best_s);
    next.p.z() = along_polyline(route, cum, s, &seg).z();  // climbing as the route climbs
    const bool straight =
        out.size() >= 2 && std::abs(turn) <= kStraight_rad &&
        std::abs(turn_between(out[out.size() - 2].heading_rad, out.back().heading_rad)) <= kStraight_rad;
    if (straight)
      out.back() = next;  // straight on: one pose
    else
      out.push_back(next);
  }
  return {};
}

}  // namespace

std::size_t FormationSchedule::interval(double tau) const {
  const auto it = std::upper_bound(knots_s.begin(), knots_s.end(), tau);
  const std::size_t k = it == knots_s.begin() ? 0 : static_cast<std::size_t>(it - knots_s.begin()) - 1;
  return std::min(k, knots_s.size() >= 2 ? knots_s.size() - 2 : 0);
}

Vec3 FormationSchedule::at(std::size_t i, double tau) const {
  if (knots_s.size() < 2 || tau <= knots_s.front()) return slots[i].front();
  if (tau >= knots_s.back()) return slots[i].back();
  const std::size_t k = interval(tau);
  const double span = knots_s[k + 1] - knots_s[k];
  const double f = span > 0.0 ? (tau - knots_s[k]) / span : 1.0;
  return slots[i][k] + f * (slots[i][k + 1] - slots[i][k]);
}

std::vector<Vec3> FormationSchedule::path(std::size_t i, double tau0, double tau1) const {
  std::vector<Vec3> out{at(i, tau0)};
  for (std::size_t k = 0; k < knots_s.size(); ++k)
    if (knots_s[k] > tau0 && knots_s[k] < tau1 && slots[i][k] != out.back()) out.push_back(slots[i][k]);
  const Vec3 end = at(i, tau1);
  if (end != out.back() || out.size() == 1) out.push_back(end);
  return out;
}

double FormationSchedule::length(std::size_t i, double tau0, double tau1) const {
  return polyline_length_m(path(i, tau0, tau1));
}

namespace {

// The schedule leg by leg: each leg to per-UAV positions as long as its longest move takes at
// the formation's speed.
class Builder {
 public:
  Builder(const std::vector<Vec3>& shape, const FormationScheduleOptions& opt) : shape_(shape), opt_(opt) {
    for (const Vec3& o : shape) centroid_ += o / static_cast<double>(shape.size());
    for (const Vec3& o : shape) reach_ = std::max(reach_, (o - centroid_).head<2>().norm());
    s_.slots.assign(shape.size(), {});
  }
  const Vec3& centroid() const { return centroid_; }
  double reach_m() const { return reach_; }
  FormationSchedule& schedule() { return s_; }
  std::vector<Vec3> slots_at(const Vec3& p, double heading) const {
    std::vector<Vec3> out;
    for (const Vec3& o : shape_) out.push_back(p + turned(o - centroid_, heading));
    return out;
  }
  void start(const std::vector<Vec3>& starts) {
    s_.knots_s.push_back(0.0);
    for (std::size_t i = 0; i < starts.size(); ++i) s_.slots[i].push_back(starts[i]);
  }
  void leg(const std::vector<Vec3>& to) {
    double longest = 0.0;
    for (std::size_t i = 0; i < to.size(); ++i) longest = std::max(longest, (to[i] - s_.slots[i].back()).norm());
    s_.knots_s.push_back(s_.knots_s.back() + longest / opt_.speed_mps);
    for (std::size_t i = 0; i < to.size(); ++i) s_.slots[i].push_back(to[i]);
  }
  void pose(const Pose& p) { leg(slots_at(p.p, p.heading_rad)); }
  // The shape turning about p as a rigid body, in chords of at most 20 deg (mates come no closer
  // than cos 10 deg of their distance): a column turning round never runs through itself.
  void turn_about(const Vec3& p, double from, double to) {
    const double turn = turn_between(from, to);
    const int chords = std::max(1, static_cast<int>(std::ceil(std::abs(turn) / (M_PI / 9.0) - kWholeNumberSlack)));
    for (int c = 1; c <= chords; ++c) leg(slots_at(p, from + turn * c / chords));
  }
  // Whether every UAV flying straight from `from` to `to` in one leg (all arriving together) is
  // clear of obstacles and keeps every pair at least its need apart.
  bool apart_and_clear(const std::vector<Vec3>& from, const std::vector<Vec3>& to) const {
    for (std::size_t i = 0; i < to.size(); ++i) {
      if (opt_.slot_clear && !opt_.slot_clear(i, from[i], to[i])) return false;
      for (std::size_t j = i + 1; j < to.size(); ++j) {  // their offset moves linearly: its least length
        const double closest_m = point_segment_distance(Vec3::Zero(), from[i] - from[j], to[i] - to[j]);
        if (closest_m < (opt_.pair_need_m ? opt_.pair_need_m(i, j) : 0.0)) return false;
      }
    }
    return true;
  }
  // Whether every slot's chord between consecutive poses is clear.
  bool clear(const std::vector<Pose>& poses) const {
    if (!opt_.slot_clear || poses.empty()) return true;
    std::vector<Vec3> prev = slots_at(poses.front().p, poses.front().heading_rad);
    for (std::size_t k = 1; k < poses.size(); ++k) {
      const std::vector<Vec3> next = slots_at(poses[k].p, poses[k].heading_rad);
      for (std::size_t i = 0; i < next.size(); ++i)
        if (!opt_.slot_clear(i, prev[i], next[i])) return false;
      prev = next;
    }
    return true;
  }

 private:
  const std::vector<Vec3>& shape_;
  const FormationScheduleOptions& opt_;
  Vec3 centroid_ = Vec3::Zero();
  double reach_ = 0.0;
  FormationSchedule s_;
};

// The cruise part: pursued (a smooth path) where every slot's chords are clear, else along the
// route itself, its corners as arcs or turns about the corner. Returns the heading at its end.
double fly_cruise(Builder& b, const std::vector<Vec3>& cruise, const std::vector<double>& psi,
                  const std::vector<Vec3>& shape) {
  const std::vector<Pose> poses = pursued(cruise, psi.front(), 2.0 * b.reach_m());
  if (!poses.empty() && b.clear(poses)) {
    for (std::size_t k = 1; k < poses.size(); ++k) b.pose(poses[k]);
    return poses.back().heading_rad;
  }
  const auto clear = [&b](const std::vector<Pose>& p) { return b.clear(p); };
  const std::vector<Arc> arcs = corner_arcs(cruise, psi, shape, b.centroid(), clear);
  for (std::size_t k = 0; k + 1 < cruise.size(); ++k) {
    if (k > 0 && arcs[k].ok) {  // the corner
      for (int c = 1; c <= arcs[k].chords; ++c) b.pose({arcs[k].at(c), arcs[k].heading(c)});
    } else if (k > 0) {
      b.turn_about(cruise[k], psi[k - 1], psi[k]);
    }
    b.pose({k + 2 < cruise.size() && arcs[k + 1].ok ? arcs[k + 1].t1 : cruise[k + 1], psi[k]});  // the segment
  }
  return cruise.size() > 1 ? psi[cruise.size() - 2] : psi.front();
}

// The approach: where it is one straight way long enough to turn to the goals' heading without
// a slot backing up (1.5 times the shape's reach per radian), turning as it goes in; else turned
// where it begins (the shape fits the route's body in any heading) and flown so along the rest
// of the route. Then the last leg into the goals.
void fly_approach(Builder& b, const Approach& a, double from, double to, const std::vector<Vec3>& goals) {
  FormationSchedule& s = b.schedule();
  const double turn = turn_between(from, to);
  const Vec3 begin = a.cruise.back(), end = a.rest.back();
  if (a.rest.size() == 1 && (end - begin).norm() >= 1.5 * b.reach_m() * std::abs(turn)) {
    s.final_knot = s.knots_s.size() - 1;
    const int pieces = std::max(1, static_cast<int>(std::ceil(std::abs(turn) / (M_PI / 36.0) - kWholeNumberSlack)));
    for (int c = 1; c < pieces; ++c) {
      const double f = static_cast<double>(c) / pieces;
      b.pose({begin + f * (end - begin), from + f * turn});
    }
  } else {
    if (std::abs(turn) > 1e-9) b.turn_about(begin, from, to);
    s.final_knot = s.knots_s.size() - 1;
    for (std::size_t k = 0; k + 1 < a.rest.size(); ++k) b.pose({a.rest[k], to});
  }
  b.leg(goals);
}

}  // namespace

FormationSchedule formation_schedule(const std::vector<Vec3>& route, const std::vector<Vec3>& shape,
                                     const std::vector<Vec3>& starts, const std::vector<Vec3>& goals,
                                     const FormationScheduleOptions& opt) {
  Builder b(shape, opt);
  const auto clear = [&b](const std::vector<Pose>& p) { return b.clear(p); };
  const std::vector<double> route_psi = headings(route);
  Approach a = split_for_approach(route, opt.approach_m);
  a.cruise = without_wiggles(a.cruise, kWiggleOfReach * b.reach_m(), clear);
  const std::vector<double> psi = a.cruise.size() > 1 ? headings(a.cruise) : std::vector<double>{route_psi.front()};
  // Form-up: straight into the slots at the route's first heading where those moves keep the
  // pairs apart and clear; else into the shape as the starts lie, then turned as a rigid body
  // (a jog into the fitted shape and a turn back reads as a reversal where it can be avoided).
  b.start(starts);
  const std::vector<Vec3> direct = b.slots_at(route.front(), psi.front());
  if (b.apart_and_clear(starts, direct)) {
    b.leg(direct);
  } else {
    const double start_heading = fitted_heading(shape, b.centroid(), starts, psi.front());
    b.pose({route.front(), start_heading});
    if (std::abs(turn_between(start_heading, psi.front())) > 1e-9)
      b.turn_about(route.front(), start_heading, psi.front());
  }
  b.schedule().form_up_knot = b.schedule().knots_s.size() - 1;
  const double cruise_heading = fly_cruise(b, a.cruise, psi, shape);
  fly_approach(b, a, cruise_heading, fitted_heading(shape, b.centroid(), goals, route_psi.back()), goals);
  return std::move(b.schedule());
}

double schedule_gap_m(const FormationSchedule& s, std::size_t i, std::size_t j, std::size_t k) {
  const Vec3 d0 = s.slots[i][k] - s.slots[j][k], d1 = s.slots[i][k + 1] - s.slots[j][k + 1];
  const Vec3 dd = d1 - d0;
  const double f = dd.squaredNorm() > 0.0 ? std::clamp(-d0.dot(dd) / dd.squaredNorm(), 0.0, 1.0) : 0.0;
  return (d0 + f * dd).norm();
}

}  // namespace uavplan
