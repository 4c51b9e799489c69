// uavplan export SCENARIO PLAN --format F -o DIR: mission and GIS files of a plan, only of what
// holds under the verifier.
#include <algorithm>
#include <iostream>

#include "commands.h"
#include "uavplan/core/text.h"
#include "uavplan/io/export.h"
#include "uavplan/io/files.h"
#include "uavplan/io/flight_schedule.h"
#include "uavplan/io/mission_items.h"
#include "uavplan/io/plan_io.h"

namespace uavplan::cli {

ExportOptions export_options_of(const Scenario& sc, const ExportArgs& a) {
  const std::string_view vehicle = !a.vehicle.empty() ? std::string_view(a.vehicle) : default_vehicle(sc);
  ExportOptions opt = export_options(a.firmware, vehicle, a.end, a.fence);  // CLI11 checked the spellings
  opt.flat_altitude_m = a.flat_altitude_m;
  opt.max_items = a.max_items;
  if (a.altitude == "home") opt.altitude = AltitudeFrame::home;
  if (a.altitude == "amsl") opt.altitude = AltitudeFrame::amsl;
  if (a.altitude == "terrain") opt.altitude = AltitudeFrame::terrain;
  opt.autopilot = std::any_of(a.formats.begin(), a.formats.end(),
                              [](const std::string& f) { return autopilot_format(*export_format_from_string(f)); });
  return opt;
}

std::optional<std::string> export_request_problem(const Scenario& sc, const ExportArgs& a) {
  if (a.formats.empty()) {
    if (a.options_given)
      return std::string(
          "--firmware, --vehicle, --end, --fence, --altitude, --flat-altitude and --force apply to --export: give the "
          "formats too");
    return std::nullopt;
  }
  std::vector<ExportFormat> formats;
  for (const std::string& f : a.formats) formats.push_back(*export_format_from_string(f));
  return uavplan::export_request_problem(sc, formats, export_options_of(sc, a));
}

void add_export_options(CLI::App& cmd, ExportArgs& a, bool formats_required) {
  auto* f = cmd.add_option("--format,--export", a.formats,
                           "Export format(s): qgc (QGroundControl .plan), wpl (QGC WPL 110), geojson, kml, csv; "
                           "repeat or separate with commas")
                ->delimiter(',')
                ->check(CLI::IsMember({"qgc", "wpl", "geojson", "kml", "csv"}));
  if (formats_required) f->required();
  const auto given = [&a](const std::string&) { a.options_given = true; };
  cmd.add_option("--firmware", a.firmware, "Autopilot of the .plan: px4 (firmwareType 12) or ardupilot (3)")
      ->check(CLI::IsMember({"px4", "ardupilot"}))
      ->each(given);
  cmd.add_option("--vehicle", a.vehicle,
                 "Vehicle type of the .plan: multirotor or fixedwing (default: fixedwing for a formation_mission, "
                 "which flies from a runway; else multirotor)")
      ->check(CLI::IsMember({"multirotor", "fixedwing"}))
      ->each(given);
  cmd.add_option("--end", a.end,
                 "How missions end: land (multirotor: straight down; fixed wing: 5-degree glide and landing pattern), "
                 "rtl (back to home, verified), loiter (at the goal) or none")
      ->check(CLI::IsMember({"land", "rtl", "loiter", "none"}))
      ->each(given);
  cmd.add_option(
         "--fence", a.fence,
         "Geofence of the .plan: none, bounds (the world's bounds and the 16 largest exclusions; default) or all")
      ->check(CLI::IsMember({"none", "bounds", "all"}))
      ->each(given);
  cmd.add_option("--altitude", a.altitude,
                 "Mission altitudes: home (above home, MAV_FRAME_GLOBAL_RELATIVE_ALT), amsl (above sea level, "
                 "MAV_FRAME_GLOBAL; the default over an elevation model) or terrain (above the ground, "
                 "MAV_FRAME_GLOBAL_TERRAIN_ALT; ArduPilot only)")
      ->check(CLI::IsMember({"home", "amsl", "terrain"}))
      ->each(given);
  cmd.add_option("--flat-altitude", a.flat_altitude_m,
                 "A flat (2-D) world's plan is flown this many metres above home (default 20): its obstacles are "
                 "columns at every height")
      ->check(CLI::Range(0.5, 10000.0))
      ->each(given);
  cmd.add_option("--max-items", a.max_items,
                 "Most mission items per UAV (default: what the firmware stores: ArduPilot 650, PX4 500); a longer "
                 "mission is flown as fewer verified chords of its flight")
      ->check(CLI::Range(8, 65535))
      ->each(given);
  cmd.add_flag("--force", a.force, "Write the UAVs that hold even when others do not (those are named on stderr)")
      ->each(given);
}

namespace {

// What an export is made from, as a fingerprint: the scenario's bytes, the plan's and the options
// (but the formats), so that formats exported one at a time from the same plan add up.
std::string export_source(const std::string& scenario_path, const Plan& plan, const ExportArgs& a) {
  std::string text;
  try {
    text = read_text_file(scenario_path);
  } catch (const std::exception&) {
    text = scenario_path;
  }
  text += '\n' + plan_to_json(plan) + '\n' + a.firmware + ' ' + a.vehicle + ' ' + a.end + ' ' + a.fence + ' ' +
          a.altitude + ' ' + num_text(a.flat_altitude_m) + (a.max_items ? ' ' + std::to_string(a.max_items) : "") +
          (a.force ? " force" : "");
  return content_fingerprint(text);
}

}  // namespace

namespace {

// schedule.json beside the mission files, and a line on stderr saying the same.
void add_schedule(const Scenario& sc, const ExportOptions& opt, PreparedExport& out) {
  out.schedule = flight_schedule(sc, out.flights, opt);
  const std::vector<ScheduledStart>& schedule = out.schedule;
  out.files.push_back(schedule_file(schedule, out.files));
  constexpr std::size_t kNamed = 8;
  std::string line = "schedule.json: start each mission at its moment of the plan's clock (its take-off included):";
  for (std::size_t k = 0; k < schedule.size() && k < kNamed; ++k)
    line += (k ? ", " : " ") + schedule[k].id + " at " + num_text(schedule[k].start_s) + " s";
  if (schedule.size() > kNamed) line += " and " + std::to_string(schedule.size() - kNamed) + " more";
  out.notes.push_back(line);
}

}  // namespace

int prepare_exports(const std::string& scenario_path, const Scenario& sc, const Plan& plan, const ExportArgs& a,
                    PreparedExport& out) {
  const ExportOptions opt = export_options_of(sc, a);
  out.source = export_source(scenario_path, plan, a);
  try {
    out.flights = verified_export(sc, plan, opt);
    const VerifiedExport& flights = out.flights;
    out.left_out = flights.left_out;
    if (flights.uavs.empty() || (!flights.holds() && !a.force)) {
      const std::size_t bad = plan.uavs.size() - flights.uavs.size();
      std::cerr << scenario_path << ": export refused: "
                << (bad ? std::to_string(bad) + " of " + count_text(plan.uavs.size(), "UAV") +
                              (bad == 1 ? " does" : " do") + " not hold"
                        : "the plan does not hold")
                << "; nothing written\n";
      for (const std::string& why : flights.left_out) std::cerr << "  " << why << "\n";
      if (!flights.uavs.empty())
        std::cerr << "  (--force writes the " << count_text(flights.uavs.size(), "UAV") << " that hold"
                  << (flights.uavs.size() == 1 ? "s" : "") << ")\n";
      return kExitNotSolved;
    }
    for (const std::string& name : a.formats) {
      auto more = export_files(sc, flights, *export_format_from_string(name), opt, &out.notes);
      out.files.insert(out.files.end(), std::make_move_iterator(more.begin()), std::make_move_iterator(more.end()));
    }
    if (opt.autopilot) add_schedule(sc, opt, out);
    for (std::string& n : frame_notes(sc, flights)) out.notes.push_back(std::move(n));
    if (const auto n = altitude_note(sc, opt); n && opt.autopilot) out.notes.push_back(*n);
    out.notes.insert(out.notes.end(), flights.notes.begin(), flights.notes.end());
  } catch (const ExportError& e) {
    std::cerr << scenario_path << ": export: " << e.what() << "\n";
    return kExitBadInput;
  }
  return kExitOk;
}

void report_exports(const std::string& dir, const PreparedExport& done, const ExportReplaced& replaced) {
  for (const ExportFile& f : done.files) {
    std::cout << "wrote " << dir << "/" << f.name;
    if (!f.uav.empty() && f.name.rfind(f.uav + ".", 0) != 0) std::cout << " (UAV '" << f.uav << "')";
    std::cout << "\n";
  }
  for (const std::string& k : replaced.kept) std::cout << "kept " << dir << "/" << k << " (the same plan's)\n";
  for (const std::string& r : replaced.removed)
    std::cerr << "note: removed " << dir << "/" << r << " (the last export's, not written again)\n";
  for (const std::string& n : done.notes) std::cerr << "note: " << n << "\n";
  for (const std::string& why : done.left_out) std::cerr << "left out of the export: " << why << "\n";
}

namespace {

struct ExportCommandArgs {
  std::string scenario, plan, out_dir = "out";
  ExportArgs exp;
};

int run_export(const ExportCommandArgs& a) {
  check_output_dir(a.out_dir);
  Scenario sc;
  Plan plan;
  if (!load_scenario_and_plan(a.scenario, a.plan, sc, plan)) return kExitBadInput;
  if (const auto problem = export_request_problem(sc, a.exp)) {
    std::cerr << a.scenario << ": export: " << *problem << "\n";
    return kExitBadInput;
  }
  // Everything is verified and built before anything is written, and written all or nothing: a
  // refusal or an error leaves the folder as it was.
  PreparedExport prepared;
  if (const int rc = prepare_exports(a.scenario, sc, plan, a.exp, prepared); rc != kExitOk) return rc;
  const ExportReplaced replaced = write_export(a.out_dir, prepared.files, {}, prepared.source);
  report_exports(a.out_dir, prepared, replaced);
  return kExitOk;
}

}  // namespace

void add_export_command(CLI::App& app, std::function<int()>& run) {
  auto args = std::make_shared<ExportCommandArgs>();
  CLI::App* cmd = app.add_subcommand(
      "export", "Export a verified plan for QGroundControl / PX4 / ArduPilot, GIS tools or spreadsheets");
  cmd->add_option("scenario", args->scenario, "Scenario file (needs an origin except for csv)")->required();
  cmd->add_option("plan", args->plan, "Plan file (plan.json)")->required();
  cmd->add_option("-o,--out", args->out_dir, "Output directory (default: out); its last export is replaced");
  add_export_options(*cmd, args->exp, true);
  cmd->footer("Example: uavplan export scenarios/demo.yaml out/plan.json --format qgc,geojson -o out");
  cmd->callback([args, &run] { run = [args] { return run_export(*args); }; });
}

}  // namespace uavplan::cli
