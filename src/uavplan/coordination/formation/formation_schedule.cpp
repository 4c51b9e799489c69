#include "uavplan/coordination/formation/formation_schedule.h"
#include "uavplan/core/geometry.h"

#include <algorithm>
#include <cmath>

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
    if (d.head<2>().norm() > 1e-9) {
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
  for (; k + 1 < route.size() && left > 1e-9; ++k) {
    const double len = (route[k + 1] - route[k]).norm();
    if (len > left + 1e-9) {
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

// The widest arc that fits in half of each segment beside the corner, at most twice the shape's
// reach; none (a turn on the spot) where even the narrowest arc that keeps every slot moving
// forward does not fit, or the turn is nearly a reversal.
Arc corner_arc(const Vec3& before, const Vec3& corner, const Vec3& after, double psi_in, double psi_out, double reach_m,
               double inner_m) {
  Arc a;
  a.turn = turn_between(psi_in, psi_out);
  const double half = std::abs(a.turn) / 2.0;
  if (half < 1e-9 || half > 0.45 * M_PI || reach_m <= 0.0) return a;
  const double room = 0.5 * std::min((corner - before).norm(), (after - corner).norm());
  a.radius_m = std::min(2.0 * reach_m, room / std::tan(half));
  if (a.radius_m < std::max(1.05 * inner_m, 0.25 * reach_m)) return a;
  const double tangent = a.radius_m * std::tan(half);
  a.t1 = corner - (corner - before).normalized() * tangent;
  a.t2 = corner + (after - corner).normalized() * tangent;
  a.side = a.turn > 0.0 ? 1.0 : -1.0;
  a.from = psi_in;
  a.centre = a.t1 + a.side * a.radius_m * Vec3(-std::sin(psi_in), std::cos(psi_in), 0.0);
  a.chords = std::max(1, static_cast<int>(std::ceil(std::abs(a.turn) / (M_PI / 9.0) - 1e-9)));
  a.ok = true;
  return a;
}

// Each interior point of the route's cruise part as an arc where one fits and every slot's
// chords are clear (opt.slot_clear), else none (the shape turns about the corner).
template <class SlotsAt>
std::vector<Arc> corner_arcs(const std::vector<Vec3>& cruise, const std::vector<double>& psi,
                             const std::vector<Vec3>& shape, const Vec3& centroid, const FormationScheduleOptions& opt,
                             const SlotsAt& slots_at) {
  double reach = 0.0, left = 0.0, right = 0.0;
  for (const Vec3& o : shape) {
    const Vec3 d = o - centroid;
    reach = std::max(reach, d.head<2>().norm());
    left = std::max(left, d.y()), right = std::max(right, -d.y());
  }
  std::vector<Arc> arcs(cruise.size());
  for (std::size_t k = 1; k + 1 < cruise.size(); ++k) {
    const double inner = turn_between(psi[k - 1], psi[k]) > 0.0 ? left : right;
    Arc arc = corner_arc(cruise[k - 1], cruise[k], cruise[k + 1], psi[k - 1], psi[k], reach, inner);
    if (!arc.ok) continue;
    std::vector<Vec3> prev = slots_at(arc.t1, arc.from);
    for (int c = 1; c <= arc.chords && arc.ok && opt.slot_clear; ++c) {
      const std::vector<Vec3> next = slots_at(arc.at(c), arc.heading(c));
      for (std::size_t i = 0; i < shape.size() && arc.ok; ++i) arc.ok = opt.slot_clear(i, prev[i], next[i]);
      prev = next;
    }
    arcs[k] = arc;
  }
  return arcs;
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

FormationSchedule formation_schedule(const std::vector<Vec3>& route, const std::vector<Vec3>& shape,
                                     const std::vector<Vec3>& starts, const std::vector<Vec3>& goals,
                                     const FormationScheduleOptions& opt) {
  const std::size_t n = shape.size();
  const double v = opt.speed_mps;
  Vec3 centroid = Vec3::Zero();
  for (const Vec3& o : shape) centroid += o / static_cast<double>(n);
  const std::vector<double> route_psi = headings(route);
  FormationSchedule s;
  s.slots.assign(n, {});
  // A leg to per-UAV positions, as long as its longest move at speed v takes.
  auto leg = [&](const std::vector<Vec3>& to) {
    double longest = 0.0;
    for (std::size_t i = 0; i < n; ++i) longest = std::max(longest, (to[i] - s.slots[i].back()).norm());
    s.knots_s.push_back(s.knots_s.back() + longest / v);
    for (std::size_t i = 0; i < n; ++i) s.slots[i].push_back(to[i]);
  };
  auto slots_at = [&](const Vec3& p, double heading) {
    std::vector<Vec3> out;
    for (const Vec3& o : shape) out.push_back(p + turned(o - centroid, heading));
    return out;
  };
  // The shape turning about p from one heading to another as a rigid body, in chords of at most
  // 20 deg (mates come no closer than cos 10 deg of their distance): a column turning round
  // never runs through itself.
  auto turn_about = [&](const Vec3& p, double from, double to) {
    const double turn = turn_between(from, to);
    const int chords = std::max(1, static_cast<int>(std::ceil(std::abs(turn) / (M_PI / 9.0) - 1e-9)));
    for (int c = 1; c <= chords; ++c) leg(slots_at(p, from + turn * c / chords));
  };
  const Approach a = split_for_approach(route, opt.approach_m);
  const std::vector<double> psi = a.cruise.size() > 1 ? headings(a.cruise) : std::vector<double>{route_psi.front()};
  s.knots_s.push_back(0.0);
  for (std::size_t i = 0; i < n; ++i) s.slots[i].push_back(starts[i]);
  // Form-up: into the shape as the starts lie, then turned to the route's first heading.
  const double start_heading = fitted_heading(shape, centroid, starts, psi.front());
  leg(slots_at(route.front(), start_heading));
  if (std::abs(turn_between(start_heading, psi.front())) > 1e-9) turn_about(route.front(), start_heading, psi.front());
  s.form_up_knot = s.knots_s.size() - 1;
  const std::vector<Arc> arcs = corner_arcs(a.cruise, psi, shape, centroid, opt, slots_at);
  for (std::size_t k = 0; k + 1 < a.cruise.size(); ++k) {
    if (k > 0 && arcs[k].ok) {  // the corner
      for (int c = 1; c <= arcs[k].chords; ++c) leg(slots_at(arcs[k].at(c), arcs[k].heading(c)));
    } else if (k > 0) {
      turn_about(a.cruise[k], psi[k - 1], psi[k]);
    }
    leg(slots_at(k + 2 < a.cruise.size() && arcs[k + 1].ok ? arcs[k + 1].t1 : a.cruise[k + 1], psi[k]));  // the segment
  }
  // The approach: turned as the goals lie where it begins (the shape fits the route's body in
  // any heading), then as that shape along the rest of the route, the last leg into the goals.
  const double cruise_heading = a.cruise.size() > 1 ? psi[a.cruise.size() - 2] : psi.front();
  const double goal_heading = fitted_heading(shape, centroid, goals, route_psi.back());
  if (std::abs(turn_between(cruise_heading, goal_heading)) > 1e-9)
    turn_about(a.cruise.back(), cruise_heading, goal_heading);
  s.final_knot = s.knots_s.size() - 1;
  for (std::size_t k = 0; k + 1 < a.rest.size(); ++k) leg(slots_at(a.rest[k], goal_heading));
  leg(goals);
  return s;
}

double schedule_gap_m(const FormationSchedule& s, std::size_t i, std::size_t j, std::size_t k) {
  const Vec3 d0 = s.slots[i][k] - s.slots[j][k], d1 = s.slots[i][k + 1] - s.slots[j][k + 1];
  const Vec3 dd = d1 - d0;
  const double f = dd.squaredNorm() > 0.0 ? std::clamp(-d0.dot(dd) / dd.squaredNorm(), 0.0, 1.0) : 0.0;
  return (d0 + f * dd).norm();
}

}  // namespace uavplan
