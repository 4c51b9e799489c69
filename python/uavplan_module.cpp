// The Python module: the library, not the command line. Scenario.load / from_dict, plan (the
// GIL released while planning), verify, Plan.load / save, trajectories as numpy arrays that view
// the plan's memory (no copy), metrics as dicts, export, planners(). Errors are exceptions with
// the CLI's one-line message: uavplan.InputError (a ValueError) for bad input, ValueError for
// bad planner parameters, uavplan.ExportError for an export that cannot be made.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstddef>
#include <future>
#include <memory>
#include <optional>
#include <sstream>

#include "uavplan/coordination/mission_planner.h"
#include "uavplan/evaluation/verifier.h"
#include "uavplan/experiments/plan_run.h"
#include "uavplan/io/export.h"
#include "uavplan/io/files.h"
#include "uavplan/io/flight_schedule.h"
#include "uavplan/io/input_error.h"
#include "uavplan/io/plan_io.h"
#include "uavplan/io/scenario_io.h"
#include "uavplan/planning/registry.h"

namespace py = pybind11;
using namespace uavplan;

namespace {

struct Verdict {
  std::vector<Violation> violations;
};

// A trajectory row is t, x, y, z: four doubles in a row, so numpy can view it in place.
static_assert(sizeof(TrajectorySample) == 4 * sizeof(double) && offsetof(TrajectorySample, p) == sizeof(double));

std::string text_of(const py::handle& v) {
  if (py::isinstance<py::bool_>(v)) return v.cast<bool>() ? "true" : "false";
  return py::str(v).cast<std::string>();
}

Overrides overrides_of(const py::dict& d) {
  Overrides o;
  for (const auto& [k, v] : d) o.emplace_back(text_of(k), text_of(v));
  return o;
}

std::shared_ptr<Plan> plan_scenario(const Scenario& sc, const std::optional<std::string>& algorithm,
                                    const std::optional<std::uint64_t>& seed, const py::dict& params,
                                    const std::optional<double>& time_limit_s, int threads,
                                    const std::optional<std::uint64_t>& max_memory_bytes) {
  PlanRequest request;  // the command line's plan: plan_and_verify, the same defaults
  request.algorithm = algorithm;
  request.seed = seed;
  for (const auto& [k, v] : overrides_of(params)) request.params[k] = v;
  if (time_limit_s) {
    if (!(*time_limit_s > 0.0)) throw py::value_error("time_limit_s must be a positive number of seconds");
    request.time_limit_s = *time_limit_s;
  }
  if (threads < 0) throw py::value_error("threads must be 0 (every core) or more");
  request.threads = threads;
  request.max_memory_bytes = max_memory_bytes;
  // Planning runs on a thread of its own while this one, holding the GIL only for a moment every
  // 50 ms, looks for Python's signals: Ctrl-C stops the plan at its next stop check and raises
  // KeyboardInterrupt then, not after the whole plan.
  auto plan = std::make_shared<Plan>();
  std::atomic<bool> cancel{false};
  request.stop = StopCondition::cancel_flag(&cancel);
  std::future<void> done;
  {
    py::gil_scoped_release release;
    done = std::async(std::launch::async, [&] { *plan = plan_and_verify(sc, request).plan; });
    while (done.wait_for(std::chrono::milliseconds(50)) != std::future_status::ready) {
      py::gil_scoped_acquire acquire;
      if (PyErr_CheckSignals() != 0) {
        cancel.store(true);
        break;
      }
    }
    done.wait();
  }
  if (cancel.load()) throw py::error_already_set();  // the KeyboardInterrupt PyErr_CheckSignals set
  done.get();                                        // what planning threw
  return plan;
}

// An obstacle as the scenario file writes it (type and geometry), for plots.
py::dict obstacle_dict(const Obstacle& o) {
  py::dict d;
  auto xy = [](const Vec2& p) { return std::vector<double>{p.x(), p.y()}; };
  auto xyz = [](const Vec3& p) { return std::vector<double>{p.x(), p.y(), p.z()}; };
  if (const auto* s = std::get_if<Sphere>(&o)) {
    d["type"] = "sphere";
    d["center"] = xyz(s->center);
    d["radius"] = s->radius_m;
  } else if (const auto* c = std::get_if<Cylinder>(&o)) {
    d["type"] = "cylinder";
    d["center"] = xy(c->center);
    d["radius"] = c->radius_m;
    d["z_min"] = c->z_min_m;
    d["z_max"] = c->z_max_m;
  } else if (const auto* b = std::get_if<Box>(&o)) {
    d["type"] = "box";
    d["min"] = xyz(b->min);
    d["max"] = xyz(b->max);
  } else if (const auto* p = std::get_if<Prism>(&o)) {
    std::vector<std::vector<double>> poly;
    for (const Vec2& v : p->polygon) poly.push_back(xy(v));
    d["type"] = "prism";
    d["polygon"] = poly;
    d["z_min"] = p->z_min_m;
    d["z_max"] = p->z_max_m;
  }
  return d;
}

py::dict violation_dict(const Violation& v) {
  py::dict d;
  d["kind"] = std::string(to_string(v.kind));
  d["uav"] = v.uav;
  d["t_s"] = v.t_s ? py::cast(*v.t_s) : py::none();
  d["where"] = v.where ? py::cast(std::vector<double>{v.where->x(), v.where->y(), v.where->z()}) : py::none();
  d["message"] = v.message;
  d["text"] = describe(v);
  return d;
}

std::vector<std::string> export_plan(const Scenario& sc, const Plan& plan, const std::vector<std::string>& formats,
                                     const std::string& dir, const std::string& firmware,
                                     const std::optional<std::string>& vehicle, const std::string& end,
                                     const std::string& fence, bool force, int max_items) {
  ExportOptions opt = export_options(firmware, vehicle ? std::string_view(*vehicle) : default_vehicle(sc), end, fence);
  if (max_items < 0 || (max_items > 0 && max_items < 8))
    throw py::value_error("max_items: 0 (the firmware's) or 8 and more");
  opt.max_items = max_items;
  check_output_dir(dir, "dir");
  if (formats.empty()) throw py::value_error("formats: name at least one of qgc, wpl, geojson, kml, csv");
  std::vector<ExportFormat> fs;
  for (const std::string& f : formats) {
    const auto ef = export_format_from_string(f);
    if (!ef) throw py::value_error("formats: unknown format '" + f + "' (qgc, wpl, geojson, kml, csv)");
    fs.push_back(*ef);
  }
  opt.autopilot = std::any_of(fs.begin(), fs.end(), autopilot_format);
  if (const auto problem = export_request_problem(sc, fs, opt)) throw ExportError(*problem);
  const VerifiedExport flights = verified_export(sc, plan, opt);
  if (flights.uavs.empty() || (!flights.holds() && !force)) {
    std::string why = "export refused: the plan does not hold";
    for (const std::string& w : flights.left_out) why += "; " + w;
    throw ExportError(why);
  }
  std::vector<ExportFile> files;
  for (const ExportFormat f : fs) {
    auto more = export_files(sc, flights, f, opt);
    files.insert(files.end(), std::make_move_iterator(more.begin()), std::make_move_iterator(more.end()));
  }
  if (opt.autopilot) files.push_back(schedule_file(flight_schedule(sc, flights, opt), files));  // as the CLI
  write_export(dir, files);
  std::vector<std::string> written;
  for (const ExportFile& f : files) written.push_back(dir + "/" + f.name);
  return written;
}

}  // namespace

PYBIND11_MODULE(uavplan, m) {
  m.doc() = "uavplan: route planning for UAVs, UAV groups and formations, with verification";
  // Trajectories are numpy arrays: say which python the module is built for rather than fail
  // later with "No module named numpy" under another one.
  try {
    py::module_::import("numpy");
  } catch (const py::error_already_set& e) {
    if (!e.matches(PyExc_ImportError)) throw;
    const auto exe = py::module_::import("sys").attr("executable").cast<std::string>();
    throw py::import_error("uavplan's Python module needs numpy, and " + exe +
                           " has none: it is built for Debian's python3 " PY_VERSION
                           " (/usr/bin/python3) with Debian's python3-numpy, which scripts/install-deps.sh installs");
  }
  py::register_exception<InputError>(m, "InputError", PyExc_ValueError);
  py::register_exception<ExportError>(m, "ExportError", PyExc_RuntimeError);
  py::register_exception<OutputError>(m, "OutputError", PyExc_OSError);

  py::class_<Scenario, std::shared_ptr<Scenario>>(m, "Scenario")
      .def_static(
          "load",
          [](const std::string& path, const py::dict& overrides) {
            return std::make_shared<Scenario>(load_scenario(path, overrides_of(overrides)));
          },
          py::arg("path"), py::arg("overrides") = py::dict(),
          "Load a scenario file (YAML or JSON); overrides as --set: {'cell_m': 4, 'uavs[0].speed': 8}")
      .def_static(
          "from_dict",
          [](const py::dict& d) {
            const std::string text = py::module_::import("json").attr("dumps")(d).cast<std::string>();
            try {
              return std::make_shared<Scenario>(parse_scenario(text, "<dict>"));
            } catch (const InputError& e) {
              // The dict was dumped on one line: its line number says nothing, its key path all
              // (one line per error: every unknown key is named).
              std::vector<std::string> lines;
              std::istringstream all(e.what());
              for (std::string why; std::getline(all, why);) {
                const auto at = why.find(": ");
                if (why.rfind("<dict>", 0) == 0 && at != std::string::npos) why = why.substr(at + 2);
                lines.push_back("Scenario.from_dict: " + why);
              }
              throw InputError(lines);
            }
          },
          py::arg("scenario"), "A scenario from a dict of the scenario file's structure")
      .def_property_readonly("name", [](const Scenario& s) { return s.name; })
      .def_property_readonly(
          "hints", [](const Scenario& s) { return s.hints; },
          "Valid values that look like a mistake of units or order, as plan and info print them")
      .def_property_readonly("uav_ids",
                             [](const Scenario& s) {
                               std::vector<std::string> ids;
                               for (const auto& u : s.uavs) ids.push_back(u.id);
                               return ids;
                             })
      .def_property_readonly("mission_type", [](const Scenario& s) { return s.mission.type; })
      .def_property_readonly("algorithm", [](const Scenario& s) { return s.planner.algorithm; })
      .def_property_readonly(
          "obstacles",
          [](const Scenario& s) {
            py::list l;
            for (const Obstacle& o : s.world.obstacles()) l.append(obstacle_dict(o));
            return l;
          },
          "The static obstacles as dicts of the scenario file's shape (buildings included)")
      .def_property_readonly("bounds",
                             [](const Scenario& s) {
                               const Aabb b = s.world.bounds();
                               return std::vector<std::vector<double>>{{b.min.x(), b.min.y(), b.min.z()},
                                                                       {b.max.x(), b.max.y(), b.max.z()}};
                             })
      .def_property_readonly("seed", [](const Scenario& s) { return s.seed; })
      .def("__repr__", [](const Scenario& s) {
        return "<uavplan.Scenario '" + s.name + "', " + std::to_string(s.uavs.size()) + " UAVs>";
      });

  py::class_<UavPlan>(m, "UavPlan")
      .def_property_readonly("id", [](const UavPlan& u) { return u.id; })
      .def_property_readonly("status", [](const UavPlan& u) { return std::string(to_string(u.status)); })
      .def_property_readonly(
          "reason", [](const UavPlan& u) { return std::string(to_string(u.reason)); },
          "Why it is not solved: none, stopped, budget, no_route, invalid, conflict or rejected")
      .def_property_readonly("message", [](const UavPlan& u) { return u.message; })
      .def_property_readonly("length_m", [](const UavPlan& u) { return u.length_m; })
      .def_property_readonly("route_length_m", [](const UavPlan& u) { return u.route_length_m; })
      .def_property_readonly("arrival_s", [](const UavPlan& u) { return u.arrival_s; })
      .def_property_readonly("metrics", [](const UavPlan& u) { return u.metrics; })
      .def_property_readonly("expansions", [](const UavPlan& u) { return u.stats.nodes_expanded; })
      .def_property_readonly(
          "trajectory",
          [](py::object self) {
            UavPlan& u = self.cast<UavPlan&>();
            const auto n = static_cast<py::ssize_t>(u.trajectory.size());
            double* data = n ? &u.trajectory.front().t_s : nullptr;
            py::array_t<double> a({n, py::ssize_t(4)},
                                  {py::ssize_t(sizeof(TrajectorySample)), py::ssize_t(sizeof(double))}, data,
                                  self);  // a view: `self` (and through it the plan) stays alive
            py::detail::array_proxy(a.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
            return a;
          },
          "N x 4 numpy array (t_s, x, y, z), a read-only view of the plan's memory")
      .def_property_readonly("waypoints",
                             [](const UavPlan& u) {
                               py::array_t<double> a({py::ssize_t(u.waypoints.size()), py::ssize_t(3)});
                               auto w = a.mutable_unchecked<2>();
                               for (std::size_t i = 0; i < u.waypoints.size(); ++i)
                                 for (int k = 0; k < 3; ++k) w(py::ssize_t(i), k) = u.waypoints[i][k];
                               return a;
                             })
      .def("__repr__", [](const UavPlan& u) {
        return "<uavplan.UavPlan '" + u.id + "' " + std::string(to_string(u.status)) + ", " +
               std::to_string(u.trajectory.size()) + " rows>";
      });

  py::class_<Plan, std::shared_ptr<Plan>>(m, "Plan")
      .def_static(
          "load", [](const std::string& path) { return std::make_shared<Plan>(load_plan(path)); }, py::arg("path"))
      .def(
          "save", [](const Plan& p, const std::string& path) { write_file_atomic(path, plan_to_json(p)); },
          py::arg("path"), "Write plan.json (the same bytes `uavplan plan` writes)")
      .def("to_json", [](const Plan& p) { return plan_to_json(p); })
      .def_property_readonly("status", [](const Plan& p) { return std::string(to_string(p.status)); })
      .def_property_readonly(
          "reason", [](const Plan& p) { return std::string(to_string(p.reason)); },
          "Why it is not solved: its first unsolved UAV's reason (rejected for a rule of the whole mission)")
      .def_property_readonly("message", [](const Plan& p) { return p.message; })
      .def_property_readonly("algorithm", [](const Plan& p) { return p.algorithm; })
      .def_property_readonly("seed", [](const Plan& p) { return p.seed; })
      .def_property_readonly("plan_ms", [](const Plan& p) { return p.plan_ms; })
      .def_property_readonly("metrics", [](const Plan& p) { return p.metrics; })
      .def_property_readonly("notes", [](const Plan& p) { return p.notes; })
      .def_property_readonly("uavs",
                             [](py::object self) {
                               Plan& p = self.cast<Plan&>();
                               py::list l;
                               for (UavPlan& u : p.uavs)
                                 l.append(py::cast(&u, py::return_value_policy::reference_internal, self));
                               return l;
                             })
      .def("uav",
           [](py::object self, const std::string& id) {
             Plan& p = self.cast<Plan&>();
             for (UavPlan& u : p.uavs)
               if (u.id == id) return py::cast(&u, py::return_value_policy::reference_internal, self);
             throw py::key_error("no UAV '" + id + "' in the plan");
           })
      .def("__repr__", [](const Plan& p) {
        return "<uavplan.Plan " + std::string(to_string(p.status)) + ", " + p.algorithm + ", " +
               std::to_string(p.uavs.size()) + " UAVs>";
      });

  py::class_<Verdict>(m, "Verdict")
      .def_property_readonly("ok", [](const Verdict& v) { return v.violations.empty(); })
      .def_property_readonly("violations",
                             [](const Verdict& v) {
                               py::list l;
                               for (const Violation& x : v.violations) l.append(violation_dict(x));
                               return l;
                             })
      .def("__bool__", [](const Verdict& v) { return v.violations.empty(); })
      .def("__repr__", [](const Verdict& v) {
        return v.violations.empty() ? std::string("<uavplan.Verdict ok>")
                                    : "<uavplan.Verdict " + std::to_string(v.violations.size()) + " violations>";
      });

  m.def("plan", &plan_scenario, py::arg("scenario"), py::arg("algorithm") = py::none(), py::arg("seed") = py::none(),
        py::arg("params") = py::dict(), py::arg("time_limit_s") = py::none(), py::arg("threads") = 0,
        py::arg("max_memory_bytes") = py::none(),
        "Plan and verify a scenario as `uavplan plan` does (the GIL is released while planning): a plan that does not "
        "hold is never solved; threads 0 uses every core; the planners' grids take at most max_memory_bytes (default "
        "half the machine's memory, 0: no cap)");
  m.def(
      "verify", [](const Scenario& sc, const Plan& p) { return Verdict{verify_plan(sc, p)}; }, py::arg("scenario"),
      py::arg("plan"), "Every violation of the plan against the scenario");
  m.def("export", &export_plan, py::arg("scenario"), py::arg("plan"), py::arg("formats"), py::arg("dir"),
        py::arg("firmware") = "px4", py::arg("vehicle") = py::none(), py::arg("end") = "land",
        py::arg("fence") = "bounds", py::arg("force") = false, py::arg("max_items") = 0,
        "Write mission files (qgc, wpl, geojson, kml, csv) of a verified plan, with schedule.json beside mission "
        "files; returns the paths");
  m.def(
      "planners",
      [] {
        py::list l;
        for (const PlannerInfo& p : planner_catalog()) {
          py::dict d;
          d["name"] = p.name;
          d["description"] = p.description;
          d["complete"] = p.complete;
          d["via_points"] = p.via_points;
          py::dict params, docs;
          for (const ParamDecl& decl : planner_parameters(p.name)) {
            params[py::str(decl.key)] = decl.default_value;
            docs[py::str(decl.key)] = decl.doc;
          }
          d["params"] = params;
          d["param_docs"] = docs;
          l.append(d);
        }
        return l;
      },
      "Every registered planner: name, description, its parameters with their defaults and their meaning");
}
