#include "uavplan/coordination/rendezvous/rendezvous_mission.h"
#include "uavplan/core/text.h"

#include <algorithm>
#include <cstdio>

#include "uavplan/coordination/rendezvous/rendezvous.h"
#include "uavplan/coordination/timing.h"

namespace uavplan {

// A UAV that would come closer than the separation to one timed before it (outside their meeting
// at the goal) departs later instead, in delay_step_s steps, by at most its slack: the time its
// cruise takes over what its length may still grow within the tolerance (shortest + epsilon -
// own), so at equal speeds it arrives within epsilon / speed of the earliest arrival. UAVs are
// timed from the least slack up (scenario order among equals).
// UAVs sharing a stretch of route or converging on the goal then pass one after the other; a
// UAV with no such delay fails with the conflict.
void RendezvousMission::plan(const Scenario& sc, const MissionContext& ctx, Plan& plan) const {
  const MissionOptions& opt = ctx.options;
  const DirectionalAStarPlanner planner(DirectionalAStarOptions::from_params(ctx.params));
  const RendezvousResult rr = plan_rendezvous(sc, planner, opt.stop);
  const std::size_t n = sc.uavs.size();
  std::vector<UavPlan> planned(n);  // sized once: `committed` points into it
  std::vector<std::string> messages(n);
  std::vector<double> slack_s(n, 0.0);
  std::vector<std::size_t> order;
  for (std::size_t i = 0; i < n; ++i) {
    const RendezvousUav& r = rr.uavs[i];
    const std::string buf =
        strf("rendezvous: %s, pre-planned %.1f m, final %.1f m (target %.1f m, epsilon %.1f m)",
             std::string(to_string(r.step)).c_str(), r.preplanned_m, r.final_m, rr.target_m, rr.epsilon_m);
    messages[i] = std::string(buf) + (r.detail.empty() ? "" : "; " + r.detail);
    if (r.solved()) {
      order.push_back(i);
      continue;
    }
    planned[i] = flown_plan(r.id, false, messages[i], {}, {});
    planned[i].reason = r.reason;
  }
  double shortest_m = World::kInf;
  for (const std::size_t i : order) shortest_m = std::min(shortest_m, rr.uavs[i].final_m);
  for (const std::size_t i : order)
    slack_s[i] = std::max(0.0, shortest_m + rr.epsilon_m - rr.uavs[i].final_m) / sc.uavs[i].speed.cruise_mps;
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return slack_s[a] < slack_s[b]; });
  Committed committed;
  for (const std::size_t i : order) {
    const RendezvousUav& r = rr.uavs[i];
    const UavSpec& u = sc.uavs[i];
    Departure d =
        earliest_departure(sc, u, r.waypoints, slack_s[i], committed, opt.delay_step_s, opt.max_sample_dt_s, opt.stop);
    if (d.stopped) {
      planned[i] = flown_plan(r.id, false, messages[i] + "; " + kStoppedMessage, {}, {});
      planned[i].reason = Reason::stopped;
      continue;
    }
    if (!d.placed) {
      planned[i] = flown_plan(r.id, false,
                              messages[i] + "; conflicts with " + d.first.what +
                                  strf(" for every departure delay up to %.1f s (its arrival slack)", slack_s[i]),
                              {}, {});
      planned[i].reason = Reason::conflict;
      continue;
    }
    if (d.delay_s > 0.0) messages[i] += strf("; departs %.1f s late to keep the separation", d.delay_s);
    planned[i] = flown_plan(r.id, true, messages[i], r.waypoints, std::move(d.trajectory));
    committed.emplace_back(&u, &planned[i]);
  }
  for (std::size_t i = 0; i < n; ++i) {
    plan.uavs.push_back(std::move(planned[i]));
    if (opt.progress) opt.progress(i + 1, n);
  }
}

}  // namespace uavplan
