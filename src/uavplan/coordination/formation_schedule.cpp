#include "uavplan/coordination/formation_schedule.h"

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
  const std::vector<Vec3> p = path(i, tau0, tau1);
  double l = 0.0;
  for (std::size_t k = 1; k < p.size(); ++k) l += (p[k] - p[k - 1]).norm();
  return l;
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
  s.knots_s.push_back(0.0);
  for (std::size_t i = 0; i < n; ++i) s.slots[i].push_back(starts[i]);
  leg(slots_at(route.front(), psi.front()));  // form-up
  s.form_up_knot = 1;
  for (std::size_t k = 0; k + 1 < route.size(); ++k) {
    if (k > 0) leg(slots_at(route[k], psi[k]));  // the corner's chord
    leg(slots_at(route[k + 1], psi[k]));         // the segment
  }
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
