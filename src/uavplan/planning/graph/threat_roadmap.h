// P1's global layer graph: the Voronoi diagram of the radar threat points (Boost.Polygon),
// clipped to the world's bounds, in the horizontal plane at one height. Its edges run as far as
// possible from every pair of neighbouring threats; an edge that enters a hard obstacle (after
// inflation) is dropped. Stops (start, via points, goal) are joined to the nearest vertices they
// see. Edge cost is P1 eq. 1-3: J = k1 * J_threat + (1 - k1) * L, J_threat the three-point rule.
#pragma once

#include <cstdint>
#include <vector>

#include "uavplan/core/stop.h"
#include "uavplan/core/vec.h"
#include "uavplan/planning/segment_rule.h"

namespace uavplan {

struct RoadmapOptions {
  double k1 = 0.5;                // P1 eq. 3 weight of the threat cost
  double threat_prefactor = 1.0;  // multiplies J_threat (1: P1's L_i; 1/3: the midpoint rule's L_i / 3)
  int join_nearest = 4;           // a stop is joined to this many nearest vertices it sees
  double outline_spacing_m = 0;   // obstacle outlines sampled this often; 0: 1/100 of the bounds' larger side
};

struct Roadmap {
  struct Edge {
    std::uint32_t a, b;
    double length_m, cost;
  };
  std::vector<Vec3> vertices;
  std::vector<Edge> edges;
  std::vector<std::vector<std::uint32_t>> incident;  // per vertex: its edges
  std::size_t sites = 0;                             // Voronoi sites it was built from

  std::uint32_t add_vertex(const Vec3& p);
  void add_edge(std::uint32_t a, std::uint32_t b, double length_m, double cost);
  std::uint32_t other(std::uint32_t edge, std::uint32_t v) const {
    return edges[edge].a == v ? edges[edge].b : edges[edge].a;
  }
};

// P1 eq. 3 on segment [a, b]: k1 * prefactor * J_threat (eq. 1) + (1 - k1) * L (eq. 2).
double p1_edge_cost(const Vec3& a, const Vec3& b, const World& world, const RoadmapOptions& o);

// The roadmap at height plane_z. Sites: the radars (P1) and, for the hard obstacles the plane cuts,
// samples of their inflated footprint outlines (edges between two samples of one outline are not
// kept: what remains runs midway between obstacles); with fewer than three sites the bounds'
// corners are added. The clipped diagram's ends on the bounds are joined along the bounds.
// Throws Stopped (core/stop.h) when the stop condition holds while it is built.
Roadmap threat_roadmap(const World& world, const SegmentRule& rule, double plane_z, const RoadmapOptions& o,
                       const StopCondition& stop = {});

// Adds p as a vertex joined to the `join_nearest` nearest vertices it sees (and to each of
// `also` it sees); returns its index.
std::uint32_t join_stop(Roadmap& map, const Vec3& p, const SegmentRule& rule, const World& world,
                        const RoadmapOptions& o, const std::vector<std::uint32_t>& also = {});

}  // namespace uavplan
