#include "uavplan/coordination/formation_mission/consensus.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <boost/graph/adjacency_list.hpp>
#include <boost/graph/connected_components.hpp>
#include <cmath>
#include <complex>
#include <stdexcept>

namespace uavplan {
namespace {

// Both roots of s^2 + p s + q (complex p, q) with a negative real part.
bool hurwitz(std::complex<double> p, std::complex<double> q) {
  const std::complex<double> r = std::sqrt(p * p - 4.0 * q);
  return ((-p + r) / 2.0).real() < -1e-12 && ((-p - r) / 2.0).real() < -1e-12;
}

}  // namespace

Topology complete_topology(std::size_t n) {
  Topology a(n, std::vector<double>(n, 1.0));
  for (std::size_t i = 0; i < n; ++i) a[i][i] = 0.0;
  return a;
}

std::vector<AutopilotCommand> consensus_commands(const std::vector<AutopilotState>& s,
                                                 const std::vector<AutopilotParams>& params, const ConsensusTarget& t,
                                                 const Topology& a, const ConsensusGains& g) {
  const std::size_t n = s.size();
  if (params.size() != n || t.offset_m.size() != n || t.altitude_m.size() != n || a.size() != n)
    throw std::invalid_argument("consensus_commands: per-UAV inputs differ in length");
  const Vec2 v_star(t.speed_mps * std::cos(t.heading_rad), t.speed_mps * std::sin(t.heading_rad));  // eq. 17
  std::vector<AutopilotCommand> out(n);
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2 vi = s[i].speed_mps * Vec2(std::cos(s[i].heading_rad), std::sin(s[i].heading_rad));
    const Vec2 pi = s[i].position.head<2>();
    Vec2 u(-g.b_per_s * (vi.x() - v_star.x()), -g.c_per_s * (vi.y() - v_star.y()));
    double uz = -g.d_per_s2 * (s[i].position.z() - t.altitude_m[i]) - g.k_per_s * s[i].climb_rate_mps;
    for (std::size_t j = 0; j < n; ++j) {
      if (j == i || a[i][j] == 0.0) continue;
      const Vec2 vj = s[j].speed_mps * Vec2(std::cos(s[j].heading_rad), std::sin(s[j].heading_rad));
      const Vec2 e = pi - s[j].position.head<2>() - (t.offset_m[i] - t.offset_m[j]);
      u.x() -= a[i][j] * ((vi.x() - vj.x()) + g.kx_per_s * e.x());  // eq. 14
      u.y() -= a[i][j] * ((vi.y() - vj.y()) + g.ky_per_s * e.y());  // eq. 15
      const double ez = s[i].position.z() - s[j].position.z() - (t.altitude_m[i] - t.altitude_m[j]);
      uz -= a[i][j] * (ez + g.kz_s * (s[i].climb_rate_mps - s[j].climb_rate_mps));  // eq. 16
    }
    const AutopilotParams& p = params[i];
    AutopilotCommand& c = out[i];
    c.altitude_m = s[i].position.z() + p.tau_z_s / p.tau_zdot_s * s[i].climb_rate_mps + p.tau_z_s * uz;
    if (g.exact_inversion) {
      const Vec2 along(std::cos(s[i].heading_rad), std::sin(s[i].heading_rad)), normal(-along.y(), along.x());
      c.speed_mps = s[i].speed_mps + p.tau_v_s * u.dot(along);
      // Far from the shape the lateral demand is huge: turn at most a quarter turn towards it
      // (the model's turn-rate limit then saturates), never wrap round to the other side.
      const double turn = p.tau_heading_s * u.dot(normal) / std::max(s[i].speed_mps, 1.0);
      c.heading_rad = s[i].heading_rad + std::clamp(turn, -0.5 * kPi, 0.5 * kPi);
    } else {  // eq. 13 literally
      const Vec2 vc = vi + p.tau_v_s * u;
      c.speed_mps = vc.norm();
      c.heading_rad = std::atan2(vc.y(), vc.x());
    }
    const double off = std::remainder(c.heading_rad - t.heading_rad, 2.0 * kPi);
    c.heading_rad = t.heading_rad + std::clamp(off, -g.max_off_heading_rad, g.max_off_heading_rad);
  }
  return out;
}

bool topology_connected(const Topology& a) {
  boost::adjacency_list<boost::vecS, boost::vecS, boost::undirectedS> g(a.size());
  for (std::size_t i = 0; i < a.size(); ++i)
    for (std::size_t j = i + 1; j < a.size(); ++j)
      if (a[i][j] > 0.0 || a[j][i] > 0.0) boost::add_edge(i, j, g);
  std::vector<int> component(a.size());
  return a.empty() || boost::connected_components(g, component.data()) == 1;
}

bool gains_stable(const Topology& a, const ConsensusGains& g) {
  const std::size_t n = a.size();
  Eigen::MatrixXd lap = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(n), static_cast<Eigen::Index>(n));
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = 0; j < n; ++j)
      if (i != j) {
        lap(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)) -= a[i][j];
        lap(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(i)) += a[i][j];
      }
  const Eigen::VectorXcd lambdas = lap.eigenvalues();
  for (const std::complex<double> l : lambdas) {
    if (!hurwitz(g.b_per_s + l, g.kx_per_s * l) && std::abs(l) > 1e-9) return false;
    if (!hurwitz(g.c_per_s + l, g.ky_per_s * l) && std::abs(l) > 1e-9) return false;
    if (!hurwitz(g.k_per_s + g.kz_s * l, g.d_per_s2 + l)) return false;
    if (std::abs(l) <= 1e-9 && !(g.b_per_s > 0.0 && g.c_per_s > 0.0)) return false;
  }
  return true;
}

}  // namespace uavplan
