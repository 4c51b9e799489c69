// Route and mission metrics used by the papers.
#pragma once

#include <span>
#include <string>

#include "uavplan/coordination/contract/plan.h"
#include "uavplan/coordination/contract/scenario.h"

namespace uavplan {

// P1's edge cost summed over the route's segments: J = k1 * J_threat + (1 - k1) * J_fuel with
// J_threat the three-point rule of P1 eq. 1 over the world's radars and J_fuel = L.
double p1_route_cost(std::span<const Vec3> waypoints, const World& world, double k1 = 0.5);

// P3's path score (lower is better). Y1 = length; Y2 = sum over path points of sum over static
// obstacles of 1/d (d to the obstacle's surface, at least 1 mm); Y3 = sum over interior points
// of (1/theta - 1/pi), theta = angle ABC (pi when straight). P3 leaves the normalisation open;
// ours: S1 = Y1 / |goal - start| (1 for a straight route), S2 = Y2 / m (mean danger per point,
// 1/m), S3 = Y3 (already dimensionless); SC = K1 S1 + K2 S2 + K3 S3 with K1 = K2 = K3 = 1.
struct P3Score {
  double y1 = 0.0, y2 = 0.0, y3 = 0.0;
  double s1 = 0.0, s2 = 0.0, s3 = 0.0;
  double sc = 0.0;
};
struct P3Weights {
  double k1 = 1.0, k2 = 1.0, k3 = 1.0;
};
P3Score p3_score(std::span<const Vec3> points, const World& world, const P3Weights& w = {});

struct UavMetrics {
  double length_m = 0.0;
  double departure_s = 0.0;    // its first movement on the plan's clock (a wait on the ground before)
  double flight_time_s = 0.0;  // from departure to its last movement
  // Off the take-off and landing legs (ground_legs.h), as the verifier checks them:
  double max_turn_deg = 0.0;
  double max_climb_deg = 0.0;
  double min_clearance_m = 0.0;  // to static obstacles and terrain (+inf when there are none)
  double min_agl_m = 0.0;        // lowest height above the ground (+inf in a flat world)
  double p1_cost = 0.0;
  P3Score p3;
  int reversals = 0;  // count_reversals
};
UavMetrics uav_metrics(const Scenario& sc, const UavSpec& spec, const UavPlan& plan);

// Flight quality. A reversal: the direction of flight turns by more than `over_deg` within
// `within_s` seconds (a UAV shuttling back and forth, or backing up at a corner); each counted
// once, from where it begins. Rows where the UAV does not move are skipped (a hover between two
// legs is not a turn, but the window runs on in time).
inline constexpr double kReversalTurn_deg = 120.0;
inline constexpr double kReversalWindow_s = 3.0;
int count_reversals(const Trajectory& trajectory, double over_deg = kReversalTurn_deg,
                    double within_s = kReversalWindow_s);
// Of a UAV in a group, between from_s and to_s: the distance it flies against the group's
// direction of travel (the mean of the group's displacements over each of its trajectory's
// pieces), counted only while the group moves at 10 % of the UAV's own speed or more.
double backing_up_m(const Trajectory& own, std::span<const Trajectory* const> group, double from_s, double to_s);
// Of a formation UAV: where it flies in shape, from the form-up's end to its arrival (or the
// start of the "dismiss" phase, P5); and the time it holds its slot there (less its breaks).
struct ShapeWindow {
  double from_s = 0.0, to_s = 0.0;
};
ShapeWindow shape_window(const FormationLog& log, double arrival_s);
double time_in_shape_s(const FormationLog& log, const std::string& uav, const ShapeWindow& window);

// Fills plan.metrics (min_separation_m, arrival_spread_s, length_spread_m, total_length_m,
// p3_group_score) and each UAV's metrics.
void compute_metrics(const Scenario& sc, Plan& plan);

}  // namespace uavplan
