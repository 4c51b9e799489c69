// A scenario as the public contract defines it (version 1), in value types.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "uavplan/planning/params.h"
#include "uavplan/vehicle/uav.h"
#include "uavplan/world/world.h"

namespace uavplan {

// A mission type's own values, as its room defines them (a struct deriving from this, read by
// its Mission::read_section and read back with MissionSpec::section_as).
struct MissionSection {
  virtual ~MissionSection() = default;
};

// formation_mission (P5): the runway the UAVs take off from and land on. `position` is the
// runway's threshold on the ground; the runway runs runway_length_m from it along the heading.
struct Airfield {
  Vec3 position = Vec3::Zero();
  double runway_heading_rad = 0.0;  // 0 = east, pi/2 = north
  double runway_length_m = 3000.0;
};

struct MissionSpec {
  std::string type = "independent";  // a registered mission type's name (coordination/mission.h)
  double separation_m = 0.0;         // between any two UAVs at any time
  std::vector<Vec3> waypoints;       // route: via points, in order
  // The entry heading required at each via point (0 = east, pi/2 = north), by index; shorter or
  // empty: none (pso_mpc plans them; the verifier checks them within kEntryHeadingTolerance_deg).
  std::vector<std::optional<double>> waypoint_entry_heading_rad;
  double step_s = 1.0;  // sensing / control period T of flights in the loop
  // UAVs whose goals lie closer than this arrive at distinct points this far apart (0: they
  // meet at the goal); default the separation. Not for rendezvous (one goal by design).
  std::optional<double> goal_spacing_m;
  // The height above the ground the planners keep the fleet at between take-off and landing
  // (a planning preference, as the 2.5 m default it replaces: less where the scenario has less
  // room; not a rule the verifier checks).
  std::optional<double> cruise_agl_m;
  // The airfield the UAVs take off from and land on (formation_mission): the exports fly its
  // runway and the verifier's airfield rule reads it.
  std::optional<Airfield> airfield;
  // A mission type's own section (types registered outside the built-in ones keep theirs here).
  std::shared_ptr<MissionSection> section;
  template <class T>
  const T* section_as() const {
    return dynamic_cast<const T*>(section.get());
  }
  // The section as a T to change, for code that builds or edits a scenario: the one there when it
  // is a T held by this scenario alone (references to it stay valid), a copy when another
  // scenario shares it (copies of a scenario share their sections), else a new T.
  template <class T>
  T& edit_section() {
    T* now = dynamic_cast<T*>(section.get());
    if (now && section.use_count() == 1) return *now;
    auto fresh = now ? std::make_shared<T>(*now) : std::make_shared<T>();
    T& ref = *fresh;
    section = std::move(fresh);
    return ref;
  }
};

struct PlannerSpec {
  std::string algorithm = "astar";
  bool algorithm_given = false;  // the scenario names it (else the mission's own default applies)
  Params params;
};

struct GeoOrigin {
  double lat_deg = 0.0, lon_deg = 0.0, alt_m = 0.0;  // WGS84, metres above mean sea level
};

// world.terrain {file}: where the elevation model came from and how it was placed (uavplan info).
struct ElevationSource {
  std::string file;    // as the scenario names it
  std::string crs;     // the raster's coordinate system, e.g. "CH1903 / LV03 (EPSG:21781)"
  std::string driver;  // GDAL's format name, e.g. "GTiff"
  int raster_nx = 0, raster_ny = 0;
  double raster_cell_m = 0.0;                                 // the raster's pixel on the ground (smaller side)
  double min_amsl_m = 0.0, max_amsl_m = 0.0;                  // heights of the world's cells
  Vec2 extent_min = Vec2::Zero(), extent_max = Vec2::Zero();  // the raster's footprint's box, local frame
  double cell_m = 0.0;                                        // the world's terrain cells
  std::size_t nodata_filled = 0;                              // cells without a height, filled from their neighbours
};

// A zone of world.airspace as its file gave it, in WGS84, kept so that an export writes the fence
// back as it was read: a polygon (corners lat, lon) or a circle.
struct FenceZone {
  bool inclusion = false;
  std::vector<Vec2> polygon_latlon;  // [lat, lon] corners, no closing corner; empty for a circle
  Vec2 center_latlon = Vec2::Zero();
  double radius_m = 0.0;
  std::optional<double> floor_amsl_m, ceiling_amsl_m;  // GeoJSON/KML height limits, else all heights
  std::vector<std::size_t> obstacles;                  // the world's obstacles it became
};

struct Scenario {
  int version = 1;
  std::string name;
  std::optional<std::uint64_t> seed;
  std::optional<GeoOrigin> origin;
  World world;
  std::vector<UavSpec> uavs;
  MissionSpec mission;
  PlannerSpec planner;
  std::optional<ElevationSource> elevation;  // world.terrain from a file
  std::vector<FenceZone> airspace;           // world.airspace's zones in file order
  // The height above the ground planners keep where the scenario sets no min_agl and a UAV takes
  // off or lands (planning_view.h: default_min_agl_m; set by the scenario reader). Planning only:
  // the verifier checks the min_agl a scenario sets.
  double default_min_agl_m = 0.0;
  // Values that are valid but look like a mistake of units or order (a turn limit in radians, a
  // speed in km/h, lat and lon swapped), each "file:line: place: what"; printed, never an error.
  std::vector<std::string> hints;

  const UavSpec* find_uav(std::string_view id) const {
    for (const auto& u : uavs)
      if (u.id == id) return &u;
    return nullptr;
  }
};

}  // namespace uavplan
