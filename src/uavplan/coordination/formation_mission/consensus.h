// P5's consensus formation control (eqs. 13-16 as cleaned in papers.md P5, from P5's
// ref. [20]): leader-free, on x, y and z, over the communication topology a_ij,
//   u_xi = -b (v_xi - v_x*) - sum_j a_ij [(v_xi - v_xj) + k_x (x_i - x_j - x_ij)]
//   u_yi = -c (v_yi - v_y*) - sum_j a_ij [(v_yi - v_yj) + k_y (y_i - y_j - y_ij)]
//   u_zi = -d (z_i - z_i*) - k z'_i - sum_j a_ij [(z_i - z_j - z_ij) + k_z (z'_i - z'_j)]
// (the printed bracket sign "-" is positive feedback: papers.md P5), turned into the autopilot's
// commands: z_c = z + (tau_z / tau_zdot) z' + tau_z u_z (eq. 16, so that z'' = u_z), and the
// horizontal acceleration u by the exact inversion of eq. 1's speed and heading lags,
//   v_c = v + tau_v (u . t),  phi_c = phi + tau_heading (u . n) / v,
// or by eq. 13 literally (v_c = |v + tau_v u|, phi_c its bearing), which amplifies the cross-track
// gain by tau_v / tau_heading (papers.md P5: unstable with the default time constants).
#pragma once

#include <vector>

#include "uavplan/vehicle/autopilot.h"

namespace uavplan {

// Gains (P5 gives none; papers.md P5, stable in the linear analysis: see gains_stable).
struct ConsensusGains {
  double b_per_s = 0.5;    // x velocity tracking (b_i)
  double c_per_s = 0.5;    // y velocity tracking (c_i)
  double d_per_s2 = 0.05;  // altitude tracking (d_i)
  double k_per_s = 0.5;    // climb-rate damping (k)
  double kx_per_s = 0.25;  // x position consensus (k_x)
  double ky_per_s = 0.25;  // y position consensus (k_y)
  double kz_s = 0.5;       // climb-rate consensus (k_z)
  bool exact_inversion = true;
  // Far from the shape (km apart, as after take-off) each UAV's heading command stays within this
  // of the ordered heading phi*: the UAVs close the gap by speed on converging courses. Without it
  // two parts of the group a turn diameter apart chase each other round a circle at the
  // turn-rate limit and never meet. Inactive near the shape (the linear analysis holds there).
  double max_off_heading_rad = kPi / 3.0;
};

// a_ij, row i: whom UAV i hears (a_ii ignored).
using Topology = std::vector<std::vector<double>>;
Topology complete_topology(std::size_t n);

// What the formation is asked for at one sample: the desired velocity v* along phi* (eq. 17), each
// UAV's desired horizontal position relative to the others (x_i^d, y_i^d: only differences count)
// and its desired altitude z_i*.
struct ConsensusTarget {
  double speed_mps = 0.0;
  double heading_rad = 0.0;
  std::vector<Vec2> offset_m;
  std::vector<double> altitude_m;
};

// The autopilot commands of every UAV (eq. 13-16). `states`, `params`, `offset_m`, `altitude_m`
// and the topology's rows are per UAV, the same length.
std::vector<AutopilotCommand> consensus_commands(const std::vector<AutopilotState>& states,
                                                 const std::vector<AutopilotParams>& params,
                                                 const ConsensusTarget& target, const Topology& topology,
                                                 const ConsensusGains& gains);

// Whether every UAV hears, through the others, from every other (a_ij or a_ji > 0 joins i and j):
// otherwise the shape cannot form.
bool topology_connected(const Topology& topology);

// Whether the closed loop (each channel a double integrator once eq. 13-16 invert the lags) is
// stable for every eigenvalue lambda of the topology's Laplacian: the roots of
// s^2 + (b + lambda) s + k_x lambda (x; y alike) and s^2 + (k + k_z lambda) s + (d + lambda) (z) in
// the open left half-plane (lambda = 0, the formation's common mode, needs only b, k, d > 0).
bool gains_stable(const Topology& topology, const ConsensusGains& gains);

}  // namespace uavplan
