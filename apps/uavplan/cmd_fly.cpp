// `uavplan fly`: a plan's ArduPilot export flown in ArduPilot's SITL, one ArduCopter (ArduPlane
// for a fixed wing) per UAV side by side (tools/sitl/uavplan_sitl.py drives them over MAVLink), the flown tracks read back
// on the plan's clock and verified as a plan, and flown set beside planned.
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <numbers>
#include <set>
#include <sstream>

#include "commands.h"
#include "uavplan/coordination/contract/separation.h"
#include "uavplan/core/geometry.h"
#include "uavplan/core/text.h"
#include "uavplan/evaluation/metrics.h"
#include "uavplan/evaluation/verifier.h"
#include "uavplan/experiments/results.h"
#include "uavplan/io/export.h"
#include "uavplan/io/files.h"
#include "uavplan/io/flight_export.h"
#include "uavplan/io/flight_schedule.h"
#include "uavplan/io/geo.h"
#include "uavplan/io/plan_io.h"
#include "uavplan/simulation/trajectory.h"

#include <nlohmann/json.hpp>

extern char** environ;

namespace uavplan::cli {
namespace {

namespace fs = std::filesystem;

struct FlyArgs {
  std::string scenario, plan, sitl, out_dir = "out";
  double speedup = 10.0;
  int instance = 0;  // the first SITL instance (TCP port 5760 + 10 N), one more per UAV
  bool keep_work = false;
};

// The ground for the simulators (ArduPilot's SITL flies over terrain it is sent, else over a plane
// at its home's altitude): heights above sea level on a latitude-longitude grid over the world's
// bounds and kTerrainMargin_m around them, rows from the south, at the terrain's cell size (10 m
// at the finest, 2000 x 2000 points at the most). The driver answers the autopilot's
// TERRAIN_REQUESTs from it.
std::string terrain_json(const Scenario& sc) {
  constexpr double kTerrainMargin_m = 500.0, kMetresPerDegree = 111320.0;
  const GeoFrame frame(*sc.origin);
  const Aabb& b = sc.world.bounds();
  double lat0 = 90, lat1 = -90, lon0 = 180, lon1 = -180;
  for (const double x : {b.min.x() - kTerrainMargin_m, b.max.x() + kTerrainMargin_m})
    for (const double y : {b.min.y() - kTerrainMargin_m, b.max.y() + kTerrainMargin_m}) {
      const LatLonAlt g = frame.to_wgs84(Vec3(x, y, 0.0));
      lat0 = std::min(lat0, g.lat_deg), lat1 = std::max(lat1, g.lat_deg);
      lon0 = std::min(lon0, g.lon_deg), lon1 = std::max(lon1, g.lon_deg);
    }
  const double step_m = std::max(10.0, sc.world.terrain()->cell_m());
  const double dlat = step_m / kMetresPerDegree, dlon = dlat / std::cos(0.5 * (lat0 + lat1) * std::numbers::pi / 180.0);
  const int rows = std::clamp(static_cast<int>(std::ceil((lat1 - lat0) / dlat)) + 1, 2, 2000);
  const int cols = std::clamp(static_cast<int>(std::ceil((lon1 - lon0) / dlon)) + 1, 2, 2000);
  std::vector<double> heights;
  heights.reserve(static_cast<std::size_t>(rows) * cols);
  for (int i = 0; i < rows; ++i)
    for (int j = 0; j < cols; ++j) {
      const Vec3 p = frame.to_local(lat0 + i * (lat1 - lat0) / (rows - 1), lon0 + j * (lon1 - lon0) / (cols - 1), 0.0);
      const double x = std::clamp(p.x(), b.min.x(), b.max.x()), y = std::clamp(p.y(), b.min.y(), b.max.y());
      heights.push_back(std::round(frame.to_wgs84(Vec3(x, y, sc.world.ground_z(x, y))).alt_m * 100.0) / 100.0);
    }
  const nlohmann::json j = {{"lat0", lat0}, {"lat1", lat1}, {"lon0", lon0},           {"lon1", lon1},
                            {"rows", rows}, {"cols", cols}, {"heights_amsl", heights}};
  return j.dump();
}

// One UAV's mission as flown: its file, when its mission starts on the plan's clock (its
// take-off before t = 0, or its departure) and the rows it was exported with.
struct Flight {
  const ExportedUav* exported = nullptr;
  std::string file;  // the mission file's stem
  double start_s = 0.0;
  Trajectory planned, flown;  // the exported rows (take-off and landing included), the track
  Trajectory body;            // the exported rows from its start to its goal and landing
  bool fixed_wing = false;    // flown in ArduPlane: from and to its runway
};

// A flat world's plan is flown above it (--flat-altitude): its columns stand at every height,
// so a flight is measured and checked in the world's plane.
void flatten(Trajectory& tr, const World& world) {
  if (world.bounds().max.z() > world.bounds().min.z()) return;
  for (TrajectorySample& row : tr) row.p.z() = world.bounds().min.z();
}

// The driver beside the program (build/uavplan -> tools/sitl/; bin/uavplan -> share/uavplan/).
std::string driver_path() {
  std::error_code ec;
  const fs::path exe = fs::canonical("/proc/self/exe", ec).parent_path();
  for (const fs::path& p : {exe / ".." / "tools" / "sitl" / "uavplan_sitl.py",
                            exe / ".." / "share" / "uavplan" / "tools" / "sitl" / "uavplan_sitl.py"})
    if (fs::is_regular_file(p, ec)) return p.lexically_normal().string();
  return "";
}

// Runs the command (no shell: its words are passed as they are) and returns its exit status.
int run_program(const std::vector<std::string>& words) {
  std::vector<char*> argv;
  argv.reserve(words.size() + 1);
  for (const std::string& w : words) argv.push_back(const_cast<char*>(w.c_str()));
  argv.push_back(nullptr);
  pid_t pid = 0;
  if (posix_spawnp(&pid, argv[0], nullptr, nullptr, argv.data(), environ) != 0) return 127;
  int status = 0;
  while (waitpid(pid, &status, 0) < 0)
    if (errno != EINTR) return 127;
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

// A track file `t_s,lat_deg,lon_deg,alt_amsl_m` (t_s since its mission started) on the plan's
// clock in the scenario's frame. Its clock is set by its lift-off (the first row 0.2 m above the
// first) at `lift_off_s`: a multirotor's kCopterLiftoff_s after its scheduled start as the
// schedule's model has it, a fixed wing's where its exported rows leave the runway. The moment
// the driver reads for the arming is late by the MAVLink link's delay, seconds of simulated time
// when simulators side by side share the machine.
constexpr double kLifted_m = 0.2;

Trajectory read_track(const std::string& path, const GeoFrame& frame, double start_s, double lift_off_s) {
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);  // the header
  Trajectory tr;
  while (std::getline(in, line)) {
    std::istringstream row(line);
    double v[4];
    char comma = 0;
    if (!(row >> v[0] >> comma >> v[1] >> comma >> v[2] >> comma >> v[3])) continue;
    const double t = start_s + v[0];
    if (!tr.empty() && t <= tr.back().t_s) continue;
    tr.push_back({t, frame.to_local(v[1], v[2], v[3])});
  }
  for (const TrajectorySample& s : tr)
    if (s.p.z() > tr.front().p.z() + kLifted_m) {
      const double shift_s = lift_off_s - s.t_s;
      for (TrajectorySample& row : tr) row.t_s += shift_s;
      break;
    }
  return tr;
}

// When the exported rows leave the ground (their first row above the first): a fixed wing's
// lift-off at the end of its roll.
double planned_lift_off_s(const Trajectory& rows) {
  for (const TrajectorySample& s : rows)
    if (s.p.z() > rows.front().p.z() + kLifted_m) return s.t_s;
  return rows.front().t_s;
}

// Within the body's radius of the ground (10 cm at least): on it, as far as the autopilot's
// height estimate tells.
bool near_ground(const World& world, double radius_m, const TrajectorySample& s) {
  return s.p.z() - world.ground_z(s.p.x(), s.p.y()) < std::max(radius_m, 0.1);
}

// On the ground at both ends as a plan's is: the autopilot's height there (its estimate, a few
// centimetres off) is put on the scenario's ground while it is near it.
void settle_on_ground(Trajectory& tr, const World& world, double radius_m) {
  std::size_t first = 0, last = tr.size();
  while (first < tr.size() && near_ground(world, radius_m, tr[first])) ++first;
  while (last > first && near_ground(world, radius_m, tr[last - 1])) --last;
  for (std::size_t k = 0; k < tr.size(); ++k)
    if (k < first || k >= last) tr[k].p.z() = world.ground_z(tr[k].p.x(), tr[k].p.y());
}

// Of the rows at the start that `lead` holds for and at the end that `trail` holds for, only the
// last and the first are kept: a multirotor's on the ground before it lifts off (its motors
// spooling up) and after it touches down, a fixed wing's standing before its roll and after it
// stopped (its rolls on the runway are kept). Nothing where `lead` holds for every row.
template <class Lead, class Trail>
void trim_ends(Trajectory& tr, Lead lead, Trail trail) {
  std::size_t l = 0, t = 0;
  while (l < tr.size() && lead(tr[l])) ++l;
  if (l == tr.size()) return;
  while (t < tr.size() && trail(tr[tr.size() - 1 - t])) ++t;
  if (t > 1) tr.erase(tr.end() - static_cast<std::ptrdiff_t>(t - 1), tr.end());
  if (l > 1) tr.erase(tr.begin(), tr.begin() + static_cast<std::ptrdiff_t>(l - 1));
}

// The flight as flown from lift-off (a fixed wing: from its roll) to touch-down (its stop).
void trim_to_flight(Trajectory& tr, const World& world, double radius_m, bool fixed_wing) {
  if (tr.empty()) return;
  if (!fixed_wing) {
    const auto on_ground = [&](const TrajectorySample& s) { return near_ground(world, radius_m, s); };
    trim_ends(tr, on_ground, on_ground);
    return;
  }
  constexpr double kStanding_m = 0.5;
  const TrajectorySample start = tr.front(), stop = tr.back();
  trim_ends(
      tr, [&](const TrajectorySample& s) { return (s.p - start.p).head<2>().norm() < kStanding_m; },
      [&](const TrajectorySample& s) { return (s.p - stop.p).head<2>().norm() < kStanding_m; });
}

// A fixed wing's mission starts lined up on the runway: where the plan has it parked and
// taxiing before (the ground crew's, not the autopilot's), the flight is the plan's until the
// track begins.
void ground_crew(Trajectory& flown, const Trajectory& plan) {
  if (flown.empty() || plan.empty() || plan.front().t_s >= flown.front().t_s) return;
  Trajectory before;
  for (const TrajectorySample& s : plan)
    if (s.t_s < flown.front().t_s) before.push_back(s);
  flown.insert(flown.begin(), before.begin(), before.end());
}

// The autopilot's vertical take-off and landing drift by centimetres (and its GPS positions are
// rounded to 1e-7 degrees); the contract's take-off and landing legs are vertical (the ground
// under them no collision, obstacles still are). Rows within kColumn_m horizontally of the
// exported home (touch-down), from the first row up to where it first leaves that column (back
// from the last row to where it last entered it), are put on the column.
void columns(Trajectory& tr, const Vec3& home, const Vec3& touchdown) {
  constexpr double kColumn_m = 0.5;
  const auto snap = [](auto first, auto last, const Vec3& foot) {
    for (auto it = first; it != last && std::hypot(it->p.x() - foot.x(), it->p.y() - foot.y()) <= kColumn_m; ++it) {
      it->p.x() = foot.x();
      it->p.y() = foot.y();
    }
  };
  snap(tr.begin(), tr.end(), home);
  snap(tr.rbegin(), tr.rend(), touchdown);
}

// Distances of the flown rows from its planned legs, and from where the plan has it then; both
// from the plan's t = 0 (its start point) to its planned end.
struct Deviation {
  double legs_p95_m = 0.0, legs_max_m = 0.0, clock_p95_m = 0.0, arrival_planned_s = 0.0, arrival_flown_s = 0.0;
  double gap_planned_m = 0.0, gap_flown_m = 0.0;  // the body's least distance to obstacles and terrain
};

// The body's least distance to static obstacles and terrain, off the take-off and landing legs.
double gap_m(const Scenario& sc, const UavSpec& spec, const Trajectory& tr) {
  UavPlan u;
  u.id = spec.id;
  u.trajectory = tr;
  return uav_metrics(sc, spec, u).min_clearance_m - spec.radius_m;
}

// The first row back on the ground after the last in the air (nan when it never flew).
double touchdown_s(const World& world, const Trajectory& tr) {
  for (std::size_t k = tr.size(); k-- > 1;)
    if (tr[k - 1].p.z() - world.ground_z(tr[k - 1].p.x(), tr[k - 1].p.y()) > kLifted_m) return tr[k].t_s;
  return NAN;
}

// From its start (the plan's first row) to its goal (the last row before its landing): the
// take-off and the landing are the autopilot's own (their speeds are its parameters).
Deviation deviation(const Scenario& sc, const Flight& f) {
  Deviation d;
  d.gap_planned_m = gap_m(sc, *f.exported->spec, f.planned);
  d.gap_flown_m = gap_m(sc, *f.exported->spec, f.flown);
  std::vector<double> legs, clock;
  const Trajectory& body = f.body;
  const TrajectorySample& goal = body[std::min(f.exported->body_end, body.size() - 1)];
  const double from = body.front().t_s, to = goal.t_s;
  for (const TrajectorySample& s : f.flown) {
    if (s.t_s < from || s.t_s > to) continue;
    double best = World::kInf;
    for (std::size_t k = 1; k < f.planned.size(); ++k)
      best = std::min(best, point_segment_distance(s.p, f.planned[k - 1].p, f.planned[k].p));
    legs.push_back(best);
    clock.push_back((s.p - position_at(f.planned, s.t_s)).norm());
  }
  d.legs_p95_m = quantile(legs, 0.95);
  d.legs_max_m = legs.empty() ? 0.0 : *std::max_element(legs.begin(), legs.end());
  d.clock_p95_m = quantile(clock, 0.95);
  // Arrival: the first moment within a tenth of a second's flight of its goal (10 cm at least);
  // a fixed wing's, its touch-down (it lands where it ends, its goal the runway).
  d.arrival_planned_s = to;
  d.arrival_flown_s = NAN;
  if (f.fixed_wing) {
    d.arrival_planned_s = touchdown_s(sc.world, f.planned);
    d.arrival_flown_s = touchdown_s(sc.world, f.flown);
    return d;
  }
  const double within_m = std::max(0.1, 0.1 * f.exported->spec->speed.cruise_mps);
  for (const TrajectorySample& s : f.flown)
    if ((s.p - goal.p).norm() <= within_m) {
      d.arrival_flown_s = s.t_s;
      break;
    }
  // A multirotor's gaps from its start to its goal, as the table says: the autopilot's take-off
  // and landing beside a slope pass within centimetres of the terrain there, drifting off the
  // vertical legs the metrics leave out.
  const auto between = [](const Trajectory& tr, double t0_s, double t1_s) {
    Trajectory out;
    for (const TrajectorySample& s : tr)
      if (s.t_s >= t0_s && s.t_s <= t1_s) out.push_back(s);
    return out.size() < 2 ? tr : out;
  };
  d.gap_planned_m = gap_m(sc, *f.exported->spec, between(f.planned, from, to));
  if (std::isfinite(d.arrival_flown_s))
    d.gap_flown_m = gap_m(sc, *f.exported->spec, between(f.flown, from, d.arrival_flown_s));
  return d;
}

// The smallest distance between two trajectories while both fly (exact between their rows).
double closest_m(const Trajectory& a, const Trajectory& b) {
  if (a.empty() || b.empty()) return World::kInf;
  const double from = std::max(a.front().t_s, b.front().t_s), to = std::min(a.back().t_s, b.back().t_s);
  return from <= to ? closest_approach_between(a, b, from, to).distance_m : World::kInf;
}

// Violations a flown track is held to: what keeps it and others safe. Where it starts and ends,
// its turns, climbs and speed are measured against the plan instead (the table).
bool safety(ViolationKind k) {
  switch (k) {
    case ViolationKind::bounds:
    case ViolationKind::ceiling:
    case ViolationKind::obstacle:
    case ViolationKind::moving_obstacle:
    case ViolationKind::separation:
    case ViolationKind::runway:
      return true;
    default:
      return false;
  }
}

void print_table(const Scenario& sc, const std::vector<Flight>& flights) {
  std::cout << "from each UAV's start to its goal (the take-off and the landing are the autopilot's):\n"
            << strf("%-10s %12s %12s %14s %12s %12s %10s %10s\n", "uav", "legs_p95_m", "legs_max_m", "clock_p95_m",
                    "arrival_plan", "arrival_flown", "gap_plan", "gap_flown");
  for (const Flight& f : flights) {
    const Deviation d = deviation(sc, f);
    std::cout << strf("%-10s %12.2f %12.2f %14.2f %12.1f %12.1f %10.2f %10.2f\n", f.exported->spec->id.c_str(),
                      d.legs_p95_m, d.legs_max_m, d.clock_p95_m, d.arrival_planned_s, d.arrival_flown_s,
                      d.gap_planned_m, d.gap_flown_m);
  }
  for (std::size_t i = 0; i < flights.size(); ++i)
    for (std::size_t j = i + 1; j < flights.size(); ++j) {
      const UavSpec &a = *flights[i].exported->spec, &b = *flights[j].exported->spec;
      std::cout << strf("pair %s-%s: closest %.2f m flown, %.2f m planned (required %.2f m)\n", a.id.c_str(),
                        b.id.c_str(), closest_m(flights[i].flown, flights[j].flown),
                        closest_m(flights[i].planned, flights[j].planned), required_separation_m(sc, a, b));
    }
}

// The missions flown side by side in SITL, each track read back onto its flight on the plan's
// clock; returns the driver's exit status.
int fly_missions(const FlyArgs& a, const Scenario& sc, const std::string& driver, const std::string& missions,
                 std::vector<Flight>& flights) {
  // Absolute paths: the simulators run in folders of their own.
  const fs::path work = fs::absolute(fs::path(a.out_dir) / ".sitl-work");
  fs::remove_all(work);
  fs::create_directories(work / "tracks");
  std::vector<std::string> words = {"python3",
                                    driver,
                                    "--sitl",
                                    fs::absolute(a.sitl).string(),
                                    "--missions",
                                    fs::absolute(missions).string(),
                                    "--out",
                                    (work / "tracks").string(),
                                    "--work",
                                    work.string(),
                                    "--speedup",
                                    num_text(a.speedup),
                                    "--first-instance",
                                    std::to_string(a.instance)};
  if (sc.world.terrain()) {
    std::ofstream(work / "terrain.json") << terrain_json(sc);
    words.insert(words.end(), {"--terrain", (work / "terrain.json").string()});
  }
  const int rc = run_program(words);
  const GeoFrame frame(*sc.origin);
  for (Flight& f : flights) {
    const double lift_off_s = f.fixed_wing ? planned_lift_off_s(f.planned) : f.start_s + kCopterLiftoff_s;
    f.flown = read_track((work / "tracks" / (f.file + ".csv")).string(), frame, f.start_s, lift_off_s);
    if (!f.fixed_wing) columns(f.flown, f.planned.front().p, f.planned.back().p);
    settle_on_ground(f.flown, sc.world, f.exported->spec->radius_m);
    trim_to_flight(f.flown, sc.world, f.exported->spec->radius_m, f.fixed_wing);
    if (f.fixed_wing) ground_crew(f.flown, f.exported->plan.trajectory);
    flatten(f.flown, sc.world);
  }
  if (!a.keep_work) fs::remove_all(work);
  return rc;
}

// The flight as a plan file holds it: from the plan's t = 0 on (a plan's times start there; the
// take-off flown before it is verified here, not written), a row put at t = 0 where it began
// earlier.
Plan from_plan_start(Plan flown) {
  for (UavPlan& u : flown.uavs) {
    Trajectory& tr = u.trajectory;
    if (tr.empty() || tr.front().t_s >= 0.0) continue;
    const auto first = std::find_if(tr.begin(), tr.end(), [](const TrajectorySample& s) { return s.t_s >= 0.0; });
    if (first == tr.end()) {
      tr.clear();
      u.status = Status::failed;
      continue;
    }
    const TrajectorySample at_zero{0.0, position_at(tr, 0.0)};
    tr.erase(tr.begin(), first);
    if (tr.front().t_s > 0.0) tr.insert(tr.begin(), at_zero);
  }
  return flown;
}

// What keeps a scenario from being flown here ("" when nothing does): multirotors in
// ArduCopter, fixed wings in ArduPlane, each within its simulated vehicle's speeds.
std::string fly_problem(const FlyArgs& a, const Scenario& sc) {
  const bool plane = default_vehicle(sc) == "fixedwing";
  // ArduCopter's waypoint speed (WPNAV_SPEED, and DO_CHANGE_SPEED with it) is at most 20 m/s;
  // ArduPlane's SITL plane flies 10-30 m/s (plane.parm's AIRSPEED_MIN..AIRSPEED_MAX).
  constexpr double kCopterTopSpeed_mps = 20.0, kPlaneLeast_mps = 10.0, kPlaneTop_mps = 30.0;
  for (const UavSpec& u : sc.uavs) {
    if (!plane && u.speed.cruise_mps > kCopterTopSpeed_mps)
      return a.scenario + ": fly: UAV '" + u.id + "' cruises at " + num_text(u.speed.cruise_mps) +
             " m/s; ArduCopter flies waypoints at most " + num_text(kCopterTopSpeed_mps) +
             " m/s (WPNAV_SPEED): no multirotor flies this plan's timing";
    if (plane && (u.speed.min_mps < kPlaneLeast_mps || u.speed.max_mps > kPlaneTop_mps))
      return a.scenario + ": fly: UAV '" + u.id + "' flies " + num_text(u.speed.min_mps) + "-" +
             num_text(u.speed.max_mps) + " m/s; ArduPlane's SITL plane flies " + num_text(kPlaneLeast_mps) + "-" +
             num_text(kPlaneTop_mps) + " m/s";
  }
  const std::string binary = plane ? "arduplane" : "arducopter";
  if (::access((fs::path(a.sitl) / "bin" / binary).c_str(), X_OK) != 0)
    return "fly: --sitl " + a.sitl + ": no executable bin/" + binary + " there";
  if (driver_path().empty()) return "fly: tools/sitl/uavplan_sitl.py is not installed beside this program";
  return "";
}

int run_fly(const FlyArgs& a) {
  check_output_dir(a.out_dir);
  Scenario sc;
  Plan plan;
  if (!load_scenario_and_plan(a.scenario, a.plan, sc, plan)) return kExitBadInput;
  if (const std::string why = fly_problem(a, sc); !why.empty()) {
    std::cerr << why << "\n";
    return kExitBadInput;
  }
  const std::string driver = driver_path();
  ExportArgs ex;
  ex.formats = {"wpl"};
  ex.firmware = "ardupilot";
  if (const auto problem = export_request_problem(sc, ex)) {
    std::cerr << a.scenario << ": fly: " << *problem << "\n";
    return kExitBadInput;
  }
  PreparedExport prepared;
  if (const int rc = prepare_exports(a.scenario, sc, plan, ex, prepared); rc != kExitOk) return rc;
  const VerifiedExport& flights_out = prepared.flights;
  std::vector<Flight> flights;
  for (const ExportedUav& e : flights_out.uavs) {
    Flight f;
    f.exported = &e;
    for (const ExportFile& file : prepared.files)
      if (file.uav == e.spec->id) f.file = fs::path(file.name).stem().string();
    f.planned = exported_rows(e);
    f.body = e.plan.trajectory;
    flatten(f.planned, sc.world);
    flatten(f.body, sc.world);
    flights.push_back(std::move(f));
  }
  for (std::size_t k = 0; k < flights.size(); ++k) {  // as exported: when it starts, and in what
    flights[k].start_s = prepared.schedule[k].start_s;
    flights[k].fixed_wing = prepared.schedule[k].vehicle == VehicleKind::fixed_wing;
  }
  const std::string missions = (fs::path(a.out_dir) / "missions").string();
  write_export(missions, prepared.files, {}, prepared.source);
  std::cerr << "fly: " << count_text(flights.size(), "mission") << " in " << missions
            << " (schedule.json: when each starts); flying in SITL at " << num_text(a.speedup) << "x\n";

  const int rc = fly_missions(a, sc, driver, missions, flights);
  Plan flown;
  flown.status = Status::solved;
  flown.algorithm = "flown in ArduPilot SITL";
  for (const Flight& f : flights) {
    UavPlan u;
    u.id = f.exported->spec->id;
    u.status = f.flown.size() >= 2 ? Status::solved : Status::failed;
    u.trajectory = f.flown;
    flown.uavs.push_back(std::move(u));
  }
  // The flight is held to what keeps it and others safe, its body included; the scenario's
  // clearance is the margin planned for the autopilot's tracking (gap_flown shows what is left).
  Scenario bodies = sc;
  for (UavSpec& u : bodies.uavs) u.clearance_m = 0.0;
  const std::vector<Violation> all = verify_plan(bodies, flown);
  write_export(a.out_dir, {{"flown.json", plan_to_json(from_plan_start(flown)), ""}});
  print_table(sc, flights);
  int unsafe = 0;
  std::set<std::pair<std::string, ViolationKind>> said;  // the first of each kind per UAV
  for (const Violation& v : all)
    if (safety(v.kind) && ++unsafe && said.insert({v.uav, v.kind}).second)
      std::cout << "flown: " << describe(v) << "\n";
  const bool holds = rc == 0 && unsafe == 0;
  std::cout << "flown plan written to " << a.out_dir << "/flown.json: "
            << (rc != 0  ? "a flight did not finish"
                : unsafe ? "does not hold"
                         : "holds")
            << "\n";
  return holds ? kExitOk : kExitNotSolved;
}

}  // namespace

void add_fly_command(CLI::App& app, std::function<int()>& run) {
  auto args = std::make_shared<FlyArgs>();
  CLI::App* cmd = app.add_subcommand("fly",
                                     "Fly a plan's ArduPilot export in ArduPilot's SITL (one ArduCopter or ArduPlane "
                                     "per UAV) and verify the flight");
  cmd->add_option("scenario", args->scenario, "Scenario file (with an origin)")->required();
  cmd->add_option("plan", args->plan, "Plan file (plan.json)")->required();
  cmd->add_option("--sitl", args->sitl,
                  "ArduPilot SITL folder: bin/arducopter (bin/arduplane for fixed wings), params/, python/pymavlink "
                  "(its MAVLink codec)")
      ->required();
  cmd->add_option("-o,--out", args->out_dir, "Output directory: missions/, flown.json (default: out)");
  cmd->add_option("--speedup", args->speedup, "Simulated seconds per wall second (default 10)")
      ->check(CLI::Range(1.0, 100.0));
  cmd->add_option("--instance", args->instance,
                  "First SITL instance number: UAV k is instance N + k, MAVLink on TCP 5760 + 10 (N + k) (default 0)")
      ->check(CLI::Range(0, 200));
  cmd->add_flag("--keep-work", args->keep_work, "Keep the simulators' folders (out/.sitl-work)");
  cmd->footer("Example: uavplan fly scenarios/demo.yaml out/plan.json --sitl ../shared/tools/sitl -o flown");
  cmd->callback([args, &run] { run = [args] { return run_fly(*args); }; });
}

}  // namespace uavplan::cli
