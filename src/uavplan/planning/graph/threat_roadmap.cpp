#include "uavplan/planning/graph/threat_roadmap.h"
#include "uavplan/core/tolerances.h"

#include <algorithm>
#include <cmath>
#include <unordered_map>

#include <boost/polygon/voronoi.hpp>

#include "uavplan/core/geometry.h"
#include "uavplan/world/threat.h"

namespace uavplan {
namespace {

struct Site {
  std::int32_t x, y;
};

}  // namespace
}  // namespace uavplan

template <>
struct boost::polygon::geometry_concept<uavplan::Site> {
  using type = point_concept;
};
template <>
struct boost::polygon::point_traits<uavplan::Site> {
  using coordinate_type = std::int32_t;
  static coordinate_type get(const uavplan::Site& s, orientation_2d o) { return o == HORIZONTAL ? s.x : s.y; }
};

namespace uavplan {
namespace {

// Boost.Polygon's Voronoi takes integer sites: the bounds map onto [0, 2^28] (a resolution of
// 4e-9 of the world's size), and back.
struct IntFrame {
  Vec2 origin;
  double scale;
  explicit IntFrame(const Aabb& b)
      : origin(b.min.x(), b.min.y()), scale(268'435'456.0 / std::max({b.extent().x(), b.extent().y(), kTinyDivisor})) {}
  Site to_int(const Vec2& p) const {
    return {static_cast<std::int32_t>(std::lround((p.x() - origin.x()) * scale)),
            static_cast<std::int32_t>(std::lround((p.y() - origin.y()) * scale))};
  }
  Vec2 from(double x, double y) const { return origin + Vec2(x, y) / scale; }
};

struct GroupedSite {
  Vec2 p;
  std::uint32_t group;  // sites of one group (one obstacle's outline) bound no edge between them
};

// A rectangle's outline sampled every spacing_m (at most max_pieces per side), corners included.
void rectangle_sites(const Vec2& lo, const Vec2& hi, double spacing_m, int max_pieces, std::uint32_t group,
                     std::vector<GroupedSite>& out) {
  const Vec2 corners[4] = {lo, Vec2(hi.x(), lo.y()), hi, Vec2(lo.x(), hi.y())};
  for (int side = 0; side < 4; ++side) {
    const Vec2 a = corners[side], c = corners[(side + 1) % 4];
    const int pieces = std::clamp(static_cast<int>(std::ceil((c - a).norm() / spacing_m)), 1, max_pieces);
    for (int k = 0; k < pieces; ++k) out.push_back({a + (c - a) * (static_cast<double>(k) / pieces), group});
  }
}

// The footprint outline of every obstacle the plane at plane_z cuts, inflated by the rule's
// margin and a little more, sampled every `spacing_m` (corners always): the diagram of these
// samples with the edges inside one outline removed is the generalized Voronoi diagram's
// approximation, running midway between obstacles as P1's runs midway between threats.
void outline_sites(const World& world, double plane_z, double inflate_m, double spacing_m,
                   std::vector<GroupedSite>& out, std::uint32_t& group) {
  for (const Obstacle& o : world.obstacles()) {
    const Aabb b = bounding_box(o);
    if (b.min.z() - inflate_m > plane_z || b.max.z() + inflate_m < plane_z) continue;
    rectangle_sites(b.min.head<2>() - Vec2::Constant(inflate_m), b.max.head<2>() + Vec2::Constant(inflate_m), spacing_m,
                    64, group++, out);
  }
}

std::vector<GroupedSite> site_points(const World& world, double plane_z, double inflate_m, const RoadmapOptions& o) {
  std::vector<GroupedSite> pts;
  std::uint32_t group = 0;
  for (const Radar& r : world.radars()) pts.push_back({Vec2(r.position.x(), r.position.y()), group++});
  const Aabb& b = world.bounds();
  const double spacing_m =
      o.outline_spacing_m > 0.0 ? o.outline_spacing_m : std::max(b.extent().x(), b.extent().y()) / 100.0;
  const std::size_t radars = pts.size();
  outline_sites(world, plane_z, inflate_m, spacing_m, pts, group);
  if (pts.size() > radars) {
    // With obstacles the bounds are an outline too: the diagram then also runs midway between an
    // obstacle and the bounds' side.
    rectangle_sites(b.min.head<2>(), b.max.head<2>(), spacing_m, 256, group++, pts);
  }
  if (pts.size() < 3)
    for (const Vec2& c : {Vec2(b.min.x(), b.min.y()), Vec2(b.max.x(), b.min.y()), Vec2(b.max.x(), b.max.y()),
                          Vec2(b.min.x(), b.max.y())})
      pts.push_back({c, group++});
  return pts;
}

// Position of a point on the box's outline, counter-clockwise from its (min, min) corner.
double perimeter_position(const Vec2& p, const Aabb& box) {
  const double w = box.extent().x(), h = box.extent().y();
  const double dx = p.x() - box.min.x(), dy = p.y() - box.min.y();
  const double to_left = std::abs(dx), to_bottom = std::abs(dy), to_right = std::abs(w - dx), to_top = std::abs(h - dy);
  const double least = std::min({to_left, to_bottom, to_right, to_top});
  if (least == to_bottom) return dx;
  if (least == to_right) return w + dy;
  if (least == to_top) return w + h + (w - dx);
  return 2 * w + h + (h - dy);
}

}  // namespace

std::uint32_t Roadmap::add_vertex(const Vec3& p) {
  vertices.push_back(p);
  incident.emplace_back();
  return static_cast<std::uint32_t>(vertices.size() - 1);
}

void Roadmap::add_edge(std::uint32_t a, std::uint32_t b, double length_m, double cost) {
  edges.push_back({a, b, length_m, cost});
  incident[a].push_back(static_cast<std::uint32_t>(edges.size() - 1));
  incident[b].push_back(static_cast<std::uint32_t>(edges.size() - 1));
}

double p1_edge_cost(const Vec3& a, const Vec3& b, const World& world, const RoadmapOptions& o) {
  return o.k1 * o.threat_prefactor * p1_threat_cost(a, b, world.radars()) + (1.0 - o.k1) * (b - a).norm();
}

Roadmap threat_roadmap(const World& world, const SegmentRule& rule, double plane_z, const RoadmapOptions& o,
                       const StopCondition& stop) {
  Roadmap map;
  const Aabb& bounds = world.bounds();
  const IntFrame frame(bounds);
  const std::vector<GroupedSite> pts = site_points(world, plane_z, rule.inflation_m() + 0.5, o);
  // Integer sites, sorted and unique (the first group wins a shared point).
  std::vector<std::pair<Site, std::uint32_t>> keyed;
  for (const GroupedSite& p : pts) keyed.push_back({frame.to_int(p.p), p.group});
  std::stable_sort(keyed.begin(), keyed.end(), [](const auto& a, const auto& b) {
    return a.first.x < b.first.x || (a.first.x == b.first.x && a.first.y < b.first.y);
  });
  keyed.erase(
      std::unique(keyed.begin(), keyed.end(),
                  [](const auto& a, const auto& b) { return a.first.x == b.first.x && a.first.y == b.first.y; }),
      keyed.end());
  std::vector<Site> sites;
  for (const auto& k : keyed) sites.push_back(k.first);
  map.sites = sites.size();
  boost::polygon::voronoi_diagram<double> vd;
  boost::polygon::construct_voronoi(sites.begin(), sites.end(), &vd);

  // Edges clipped to the bounds (a hair inside, so every vertex is in them), at plane_z.
  const Vec3 inset = 1e-9 * bounds.extent() + Vec3::Constant(1e-9);
  const Aabb box{Vec3(bounds.min.x() + inset.x(), bounds.min.y() + inset.y(), plane_z - 1.0),
                 Vec3(bounds.max.x() - inset.x(), bounds.max.y() - inset.y(), plane_z + 1.0)};
  const double far = 4.0 * std::max(bounds.extent().x(), bounds.extent().y()) + 1.0;
  std::unordered_map<const void*, std::uint32_t> index;  // Voronoi vertex -> roadmap vertex
  std::vector<std::pair<double, std::uint32_t>> rim;     // vertices on the bounds, by perimeter position
  auto vertex_of = [&](const boost::polygon::voronoi_vertex<double>* v, const Vec3& p, bool clipped) {
    if (clipped || !v) {
      const std::uint32_t id = map.add_vertex(p);
      rim.emplace_back(perimeter_position(p.head<2>(), box), id);
      return id;
    }
    const auto [it, fresh] = index.try_emplace(v, 0u);
    if (fresh) it->second = map.add_vertex(p);
    return it->second;
  };
  std::size_t seen = 0;
  for (const auto& e : vd.edges()) {
    if ((++seen & 1023) == 0) stop.throw_if_stopped();  // each edge is checked and costed (P1 eq. 1-3)
    if (e.color() != 0) continue;                       // its twin was taken
    e.twin()->color(1);
    const std::size_t c0 = e.cell()->source_index(), c1 = e.twin()->cell()->source_index();
    if (!e.is_primary() || keyed[c0].second == keyed[c1].second) continue;  // inside one obstacle's outline
    const Vec2 s0 = frame.from(sites[c0].x, sites[c0].y), s1 = frame.from(sites[c1].x, sites[c1].y);
    // An infinite edge runs along the bisector of its two sites, away from them on its open side.
    const Vec2 dir = Vec2(s0.y() - s1.y(), s1.x() - s0.x()).normalized();
    const Vec2 mid = 0.5 * (s0 + s1);
    const Vec2 a2 = e.vertex0() ? frame.from(e.vertex0()->x(), e.vertex0()->y())
                                : (e.vertex1() ? frame.from(e.vertex1()->x(), e.vertex1()->y()) : mid) - far * dir;
    const Vec2 b2 = e.vertex1() ? frame.from(e.vertex1()->x(), e.vertex1()->y()) : (e.vertex0() ? a2 : mid) + far * dir;
    const Vec3 a(a2.x(), a2.y(), plane_z), b(b2.x(), b2.y(), plane_z);
    double t0 = 0.0, t1 = 1.0;
    if ((b - a).norm() <= 0.0 || !clip_segment_to_box(a, b, box, t0, t1)) continue;
    const Vec3 pa = a + t0 * (b - a), pb = a + t1 * (b - a);
    if ((pb - pa).norm() <= kSamePoint_m || !rule(pa, pb)) continue;  // an edge through an obstacle is dropped
    const std::uint32_t va = vertex_of(e.vertex0(), pa, t0 > 0.0);
    const std::uint32_t vb = vertex_of(e.vertex1(), pb, t1 < 1.0);
    map.add_edge(va, vb, (pb - pa).norm(), p1_edge_cost(pa, pb, world, o));
  }
  // The diagram clipped to a box ends on the box: its outline joins those ends (and its corners),
  // so regions the diagram leaves apart are still joined where the bounds' edge is free.
  const Vec2 corners[4] = {box.min.head<2>(), Vec2(box.max.x(), box.min.y()), box.max.head<2>(),
                           Vec2(box.min.x(), box.max.y())};
  for (const Vec2& c : corners) {
    const Vec3 p(c.x(), c.y(), plane_z);
    if (rule.point_ok(p)) rim.emplace_back(perimeter_position(c, box), map.add_vertex(p));
  }
  std::sort(rim.begin(), rim.end());
  for (std::size_t k = 0; k < rim.size() && rim.size() > 1; ++k) {
    const std::uint32_t va = rim[k].second, vb = rim[(k + 1) % rim.size()].second;
    const Vec3 &pa = map.vertices[va], &pb = map.vertices[vb];
    if ((pb - pa).norm() > kSamePoint_m && rule(pa, pb))
      map.add_edge(va, vb, (pb - pa).norm(), p1_edge_cost(pa, pb, world, o));
  }
  return map;
}

std::uint32_t join_stop(Roadmap& map, const Vec3& p, const SegmentRule& rule, const World& world,
                        const RoadmapOptions& o, const std::vector<std::uint32_t>& also) {
  std::vector<std::pair<double, std::uint32_t>> near;
  for (std::uint32_t v = 0; v < map.vertices.size(); ++v)
    if (!map.incident[v].empty()) near.emplace_back((map.vertices[v] - p).squaredNorm(), v);
  std::sort(near.begin(), near.end());
  const std::uint32_t s = map.add_vertex(p);
  auto link = [&](std::uint32_t v) {
    const Vec3& q = map.vertices[v];
    if ((q - p).norm() <= kSamePoint_m || !rule(p, q)) return false;
    map.add_edge(s, v, (q - p).norm(), p1_edge_cost(p, q, world, o));
    return true;
  };
  int joined = 0;
  for (std::size_t k = 0;
       k < near.size() && joined < o.join_nearest && k < 64u * static_cast<std::size_t>(o.join_nearest); ++k)
    joined += link(near[k].second);
  for (const std::uint32_t v : also) link(v);
  return s;
}

}  // namespace uavplan
