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
                                     const std::vector<Vec3>& starts, const std::vector<Vec3>& goals, double v) {
  const std::size_t n = shape.size();
  Vec3 centroid = Vec3::Zero();
  for (const Vec3& o : shape) centroid += o / static_cast<double>(n);
  const std::vector<double> psi = headings(route);
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
  s.knots_s.push_back(0.0);
  for (std::size_t i = 0; i < n; ++i) s.slots[i].push_back(starts[i]);
  // Form-up: into the shape as the starts lie, then turned to the route's first heading.
  const double start_heading = fitted_heading(shape, centroid, starts, psi.front());
  leg(slots_at(route.front(), start_heading));
  if (std::abs(turn_between(start_heading, psi.front())) > 1e-9) turn_about(route.front(), start_heading, psi.front());
  s.form_up_knot = s.knots_s.size() - 1;
  for (std::size_t k = 0; k + 1 < route.size(); ++k) {
    if (k > 0) turn_about(route[k], psi[k - 1], psi[k]);  // the corner
    leg(slots_at(route[k + 1], psi[k]));                  // the segment
  }
  // End: turned as the goals lie, then into them.
  const double goal_heading = fitted_heading(shape, centroid, goals, psi.back());
  if (std::abs(turn_between(psi.back(), goal_heading)) > 1e-9) turn_about(route.back(), psi.back(), goal_heading);
  s.final_knot = s.knots_s.size() - 1;
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
