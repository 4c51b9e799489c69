#include "uavplan/coordination/formation_mission/formation_group.h"
#include "uavplan/core/tolerances.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace uavplan {

FormationGroup::FormationGroup(std::vector<AutopilotModel> models, std::vector<Vec3> shape, Topology topology,
                               FormationGroupOptions options, double t0_s)
    : models_(std::move(models)), shape_(std::move(shape)), topology_(std::move(topology)), o_(options), t_s_(t0_s) {
  const std::size_t n = models_.size();
  if (shape_.size() != n || topology_.size() != n)
    throw std::invalid_argument("FormationGroup: a slot and a topology row per UAV");
  for (const AutopilotModel& m : models_) params_.push_back(m.params());
  states_.resize(n);
  flying_.assign(n, 0);
  joined_.assign(n, 0);
  rows_.resize(n);
}

void FormationGroup::record(std::size_t i) {
  if (!rows_[i].empty() && rows_[i].back().t_s >= t_s_) return;
  rows_[i].push_back({t_s_, states_[i].position});
}

void FormationGroup::launch(std::size_t i, const AutopilotState& s, Launch how) {
  states_[i] = s;
  flying_[i] = 1;
  joined_[i] = how == Launch::in_formation;
  record(i);
}

void FormationGroup::release(std::size_t i) {
  record(i);
  flying_[i] = 0;
  joined_[i] = 0;
}

bool FormationGroup::anyone_in_formation() const {
  return std::any_of(joined_.begin(), joined_.end(), [](char j) { return j != 0; });
}

Vec3 FormationGroup::centroid() const {
  Vec3 c = Vec3::Zero();
  int n = 0;
  for (std::size_t i = 0; i < size(); ++i)
    if (joined_[i]) c += states_[i].position, ++n;
  return n > 0 ? Vec3(c / n) : c;
}

std::vector<Vec2> FormationGroup::offsets_m(const FormationOrder& order) const {
  const double c = std::cos(order.heading_rad), s = std::sin(order.heading_rad);
  std::vector<Vec2> out;
  for (const Vec3& r : shape_)
    out.emplace_back(order.scale * (c * r.x() - s * r.y()), order.scale * (s * r.x() + c * r.y()));
  return out;
}

double FormationGroup::shape_error_m(const FormationOrder& order) const {
  const std::vector<Vec2> off = offsets_m(order);
  Vec3 c = Vec3::Zero(), d = Vec3::Zero();
  int n = 0;
  for (std::size_t i = 0; i < size(); ++i)
    if (joined_[i]) c += states_[i].position, d += Vec3(off[i].x(), off[i].y(), order.altitude_m[i]), ++n;
  if (n == 0) return 0.0;
  c /= n, d /= n;
  double worst = 0.0;
  for (std::size_t i = 0; i < size(); ++i)
    if (joined_[i])
      worst =
          std::max(worst, ((states_[i].position - c) - (Vec3(off[i].x(), off[i].y(), order.altitude_m[i]) - d)).norm());
  return worst;
}

void FormationGroup::step(const FormationOrder& order, const std::function<AutopilotCommand(std::size_t)>& solo) {
  std::vector<std::size_t> in;
  for (std::size_t i = 0; i < size(); ++i)
    if (flying_[i] && joined_[i]) in.push_back(i);
  std::vector<AutopilotCommand> cmd(size());
  if (!in.empty()) {  // the consensus laws among those in formation
    const std::vector<Vec2> off = offsets_m(order);
    std::vector<AutopilotState> s;
    std::vector<AutopilotParams> p;
    ConsensusTarget t;
    t.speed_mps = order.speed_mps;
    t.heading_rad = order.heading_rad;
    Topology a(in.size(), std::vector<double>(in.size(), 0.0));
    for (std::size_t r = 0; r < in.size(); ++r) {
      s.push_back(states_[in[r]]);
      p.push_back(params_[in[r]]);
      t.offset_m.push_back(off[in[r]]);
      t.altitude_m.push_back(order.altitude_m[in[r]]);
      for (std::size_t q = 0; q < in.size(); ++q) a[r][q] = topology_[in[r]][in[q]];
    }
    const std::vector<AutopilotCommand> c = consensus_commands(s, p, t, a, o_.gains);
    for (std::size_t r = 0; r < in.size(); ++r) cmd[in[r]] = c[r];
  }
  for (std::size_t i = 0; i < size(); ++i)
    if (flying_[i] && !joined_[i]) cmd[i] = solo(i);
  t_s_ += o_.dt_s;
  for (std::size_t i = 0; i < size(); ++i) {
    if (!flying_[i]) continue;
    models_[i].advance(states_[i], cmd[i], o_.dt_s);
    if (rows_[i].empty() || t_s_ - rows_[i].back().t_s >= o_.record_s - kSameTime_s) record(i);
  }
}

RouteSteering::RouteSteering(std::vector<Vec3> route, std::vector<char> fly_over, double turn_radius_m, double switch_m)
    : route_(std::move(route)), fly_over_(std::move(fly_over)), radius_m_(turn_radius_m), switch_m_(switch_m) {
  fly_over_.resize(route_.size(), 0);
}

bool RouteSteering::update(const Vec3& c) {
  while (next_ < route_.size()) {
    const Vec3 &from = route_[next_ - 1], &w = route_[next_];
    const Vec2 leg = (w - from).head<2>();
    const double len = leg.norm(), along = len > 0.0 ? (c - from).head<2>().dot(leg) / len : 0.0;
    double reach = switch_m_;
    if (!fly_over_[next_] && next_ + 1 < route_.size()) {  // turn on the arc into the next leg
      const Vec2 out = (route_[next_ + 1] - w).head<2>();
      if (len > 0.0 && out.norm() > 0.0) {
        const double turn = std::acos(std::clamp(leg.dot(out) / (len * out.norm()), -1.0, 1.0));
        reach = std::max(reach, radius_m_ * std::tan(0.5 * std::min(turn, 0.5 * kPi)));
      }
    }
    if ((c - w).head<2>().norm() > reach && along < len) break;
    ++next_;
  }
  return next_ < route_.size();
}

double RouteSteering::heading_rad(const Vec3& c) const {
  const Vec3& w = route_[std::min(next_, route_.size() - 1)];
  return std::atan2(w.y() - c.y(), w.x() - c.x());
}

double RouteSteering::altitude_m(const Vec3& c) const {
  const std::size_t k = std::min(next_, route_.size() - 1);
  if (k == 0) return route_[0].z();
  const Vec3 &from = route_[k - 1], &w = route_[k];
  const Vec2 leg = (w - from).head<2>();
  const double len = leg.norm();
  const double f = len > 0.0 ? std::clamp((c - from).head<2>().dot(leg) / (len * len), 0.0, 1.0) : 1.0;
  return from.z() + f * (w.z() - from.z());
}

}  // namespace uavplan
