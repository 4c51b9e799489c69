#include "uavplan/planning/smoothing/turn_limits.h"
#include "uavplan/core/tolerances.h"

#include <algorithm>
#include <cmath>

#include "uavplan/core/text.h"
#include "uavplan/core/units.h"
#include "uavplan/vehicle/uav.h"

namespace uavplan {
namespace {

constexpr int kMaxChords = 64;
constexpr int kMaxPursuitSteps = 4000;

bool turn_ok(const Vec3& from, const Vec3& to, const TurnLimits& lim) {
  return turn_rad(from, to) <= lim.max_turn_rad + kAngleTolerance_rad;
}

Vec3 slerp(const Vec3& u1, const Vec3& u2, double t) {
  const double theta = std::acos(std::clamp(u1.dot(u2), -1.0, 1.0));
  if (theta < 1e-12) return u1;
  return (std::sin((1 - t) * theta) * u1 + std::sin(t * theta) * u2) / std::sin(theta);
}

// Inscribed polygon of the arc tangent to both legs at distance d from corner P; returns the
// points from A (on the incoming leg) to B (on the outgoing one), or nothing.
std::optional<std::vector<Vec3>> fillet(const Vec3& prev, const Vec3& p, const Vec3& next, double d,
                                        const TurnLimits& lim, const SegmentPredicate& ok) {
  const Vec3 u1 = (p - prev).normalized(), u2 = (next - p).normalized();
  const double theta = std::acos(std::clamp(u1.dot(u2), -1.0, 1.0));
  if (theta > deg_to_rad(179.0)) return std::nullopt;
  const double radius = d / std::tan(theta / 2);
  const Vec3 a = p - d * u1, b = p + d * u2;
  for (int k = std::max(1, static_cast<int>(std::ceil(theta / lim.max_turn_rad))); k <= kMaxChords; ++k) {
    const double chord = 2 * radius * std::sin(theta / (2 * k));
    std::vector<Vec3> pts{a};
    for (int m = 0; m < k; ++m) pts.push_back(pts.back() + chord * slerp(u1, u2, (m + 0.5) / k));
    pts.back() = b;
    bool turns = turn_ok(u1, pts[1] - pts[0], lim) && turn_ok(pts[k] - pts[k - 1], u2, lim);
    for (int m = 1; m < k && turns; ++m) turns = turn_ok(pts[m] - pts[m - 1], pts[m + 1] - pts[m], lim);
    if (!turns) continue;  // yaw change at pitched chords exceeds the 3-D angle: more chords
    for (int m = 0; m < k; ++m)
      if (!ok(pts[m], pts[m + 1])) return std::nullopt;
    return pts;
  }
  return std::nullopt;
}

Vec3 direction(double yaw, double pitch) {
  return {std::cos(pitch) * std::cos(yaw), std::cos(pitch) * std::sin(yaw), std::sin(pitch)};
}

// From `from` heading `dir`, turn towards `target` at most the limit per chord and climb at
// most the climb limit, until the target can be flown to straight; appends the points after
// `from`, ending with the target.
bool pursue(std::vector<Vec3>& out, Vec3 dir, const Vec3& target, const TurnLimits& lim, const SegmentPredicate& ok) {
  Vec3 p = out.back();
  // Half the limit in yaw and in pitch keeps the combined turn under the limit.
  const double step_rad = 0.49 * std::min(lim.max_turn_rad, kPi);
  for (int step = 0; step < kMaxPursuitSteps; ++step) {
    const Vec3 v = target - p;
    const double dist = v.norm();
    if (dist <= kSamePoint_m) return true;
    if (turn_ok(dir, v, lim) && std::abs(pitch_rad(v)) <= lim.max_climb_rad + kAngleTolerance_rad && ok(p, target)) {
      out.push_back(target);
      return true;
    }
    const double yaw = dir.head<2>().norm() > kSamePoint_m ? std::atan2(dir.y(), dir.x()) : std::atan2(v.y(), v.x());
    const double pitch = pitch_rad(dir);
    const double want_pitch = std::clamp(pitch_rad(v), -lim.max_climb_rad, lim.max_climb_rad);
    const double new_yaw = yaw + std::clamp(wrap_angle_rad(std::atan2(v.y(), v.x()) - yaw), -step_rad, step_rad);
    const double new_pitch = pitch + std::clamp(want_pitch - pitch, -step_rad, step_rad);
    const Vec3 nd = direction(new_yaw, std::clamp(new_pitch, -lim.max_climb_rad, lim.max_climb_rad));
    // Chords short against the distance keep the target outside the turning circle.
    double chord = std::max(dist * 0.25 * std::sin(step_rad), 1e-6);
    bool moved = false;
    for (int tries = 0; tries < 12 && !moved; ++tries, chord *= 0.5) {
      const Vec3 q = p + chord * nd;
      if (turn_ok(dir, nd, lim) && ok(p, q)) {
        out.push_back(q);
        p = q;
        dir = nd;
        moved = true;
      }
    }
    if (!moved) return false;
  }
  return false;
}

// Where pursuing `target` fails: the farthest point of the leg from out.back() to `target`, half
// its length or less (halving), that a pursuit reaches (appended to `out`); `target` where none.
Vec3 rejoin_point(std::vector<Vec3>& out, const Vec3& dir, const Vec3& target, const TurnLimits& lim,
                  const SegmentPredicate& ok) {
  const Vec3 corner = out.back();
  const std::size_t kept = out.size();
  for (double f = 0.5; f > 1.0 / 1024; f *= 0.5) {
    Vec3 q = corner + f * (target - corner);
    if ((q - corner).norm() <= kSamePoint_m) break;
    if (pursue(out, dir, q, lim, ok)) return q;
    out.resize(kept);
  }
  return target;
}

}  // namespace

TurnShaping enforce_turn_limits(std::span<const Vec3> pts, std::span<const char> pinned, std::optional<double> heading,
                                const TurnLimits& lim, const SegmentPredicate& ok) {
  TurnShaping r;
  // Drop repeated points: they have no direction.
  std::vector<Vec3> p;
  std::vector<char> pin;
  for (std::size_t i = 0; i < pts.size(); ++i) {
    if (!p.empty() && (pts[i] - p.back()).norm() <= kSamePoint_m) {
      pin.back() = pin.back() || pinned[i];
      continue;
    }
    p.push_back(pts[i]);
    pin.push_back(pinned[i]);
  }
  std::size_t n = p.size();
  r.waypoints.push_back(p.front());
  std::optional<Vec3> dir;
  if (heading) dir = heading_vector(*heading);
  for (std::size_t i = 0; i + 1 < n; ++i) {
    const Vec3& cur = r.waypoints.back();
    const Vec3 v = p[i + 1] - cur;
    if (!dir || turn_ok(*dir, v, lim)) {
      r.waypoints.push_back(p[i + 1]);
      dir = v;
      continue;
    }
    // A fillet replaces an unpinned corner that was reached straight from the previous point.
    bool done = false;
    if (i > 0 && !pin[i] && r.waypoints.size() >= 2) {
      const Vec3 prev = r.waypoints[r.waypoints.size() - 2];
      const double d_max = std::min(0.999 * (cur - prev).norm(), 0.5 * v.norm());
      for (double d = d_max; d > d_max / 64 && !done; d *= 0.5) {
        if (auto arc = fillet(prev, cur, p[i + 1], d, lim, ok)) {
          r.waypoints.pop_back();
          r.waypoints.insert(r.waypoints.end(), arc->begin(), arc->end());
          r.waypoints.push_back(p[i + 1]);
          dir = p[i + 1] - (*arc).back();
          done = true;
        }
      }
    }
    if (done) continue;
    const std::size_t kept = r.waypoints.size();
    if (!pursue(r.waypoints, *dir, p[i + 1], lim, ok)) {
      // A turn toward a far point can swing wide into what the leg itself passes: rejoin the
      // leg (clear as planned) nearer the corner, on a tighter turn, and fly on from there.
      r.waypoints.resize(kept);
      const Vec3 rejoin = rejoin_point(r.waypoints, *dir, p[i + 1], lim, ok);
      if (rejoin == p[i + 1]) {
        r.fail(Reason::no_route, "no room to turn within " + num_text(rad_to_deg(lim.max_turn_rad)) +
                                     " deg at the corner near " + point_text(p[i]) +
                                     " (directional_astar keeps the turn limit while it searches)");
        return r;
      }
      p.insert(p.begin() + static_cast<std::ptrdiff_t>(i + 1), rejoin);
      pin.insert(pin.begin() + static_cast<std::ptrdiff_t>(i + 1), 0);
      ++n;
    }
    dir = r.waypoints.back() - r.waypoints[r.waypoints.size() - 2];
  }
  r.succeed();
  return r;
}

TurnShaping shape_turns(std::span<const Vec3> points, std::span<const char> pinned, const UavSpec& uav,
                        const SegmentPredicate& ok) {
  if (uav.max_turn_rad >= kPi - kUnlimitedAngleSlack_rad && !uav.heading_rad) {
    TurnShaping as_given;
    as_given.succeed();
    as_given.waypoints.assign(points.begin(), points.end());
    return as_given;
  }
  return enforce_turn_limits(points, pinned, uav.heading_rad, {uav.max_turn_rad, uav.max_climb_rad}, ok);
}

void finish_with_turns(std::span<const Vec3> points, std::span<const char> pinned, const UavSpec& uav,
                       const SegmentPredicate& ok, PlanResult& res) {
  TurnShaping shaped = shape_turns(points, pinned, uav, ok);
  if (!shaped.solved()) {
    res.fail(shaped.reason, "turn limits: " + shaped.message);
    return;
  }
  res.route.waypoints = std::move(shaped.waypoints);
  res.status = Status::solved;
}

}  // namespace uavplan
