// Polygon soup repair with CGAL. Steps, in order (each counted in CleanupReport):
//   1. merge points within a tolerance relative to the scene size (CGAL k-d tree);
//   2. drop repeated corners and polygons left with fewer than 3 points;
//   3. snap T-junctions: a point lying on another polygon's edge is inserted into it;
//   4. flatten near-planar polygons onto their best-fit planes (flatten.h);
//   5. triangulate polygons (concave too) with a constrained Delaunay triangulation in
//      the polygon's plane, falling back to CGAL's hole filling for warped loops;
//   6. drop zero-area and duplicate triangles (same corners and same facing);
//   7. imprint where surfaces cross or touch (imprint.h): the facets that meet are
//      triangulated again with those lines as edges, steps 1-3, 5 and 6 run again on the
//      result so that it is conforming, and the pieces no light can reach are removed
//      (hidden.h);
//   8. cut edges that are not manifold (more than two faces, or two faces facing
//      opposite ways) by giving each fan of faces around a point its own copy.
#include "mesh/repair/cleanup.h"

#include "mesh/repair/hidden.h"
#include "mesh/repair/imprint.h"
#include "mesh/core/polygon_triangulation.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Fuzzy_iso_box.h>
#include <CGAL/Fuzzy_sphere.h>
#include <CGAL/Kd_tree.h>
#include <CGAL/Polygon_mesh_processing/triangulate_hole.h>
#include <CGAL/Search_traits_3.h>
#include <CGAL/Search_traits_adapter.h>

#include <algorithm>
#include <numeric>
#include <set>
#include <unordered_map>
#include <unordered_set>

namespace dynrad {
namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point3 = K::Point_3;

// ---------------------------------------------------------------------------
// Spatial index over point indices (the k-d tree stores indices, positions come
// from a property map), so duplicate positions stay distinct entries.
struct IndexPointMap {
  using key_type = std::size_t;
  using value_type = Point3;
  using reference = const Point3&;
  using category = boost::readable_property_map_tag;
  const std::vector<Point3>* points = nullptr;
  friend reference get(const IndexPointMap& map, key_type i) { return (*map.points)[i]; }
};
using TreeTraits = CGAL::Search_traits_adapter<std::size_t, IndexPointMap, CGAL::Search_traits_3<K>>;
using Tree = CGAL::Kd_tree<TreeTraits>;
using Sphere = CGAL::Fuzzy_sphere<TreeTraits>;
using Box = CGAL::Fuzzy_iso_box<TreeTraits>;

struct UnionFind {
  std::vector<std::size_t> parent;
  explicit UnionFind(std::size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0); }
  std::size_t find(std::size_t x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  }
  void unite(std::size_t a, std::size_t b) {
    a = find(a);
    b = find(b);
    if (a != b) parent[std::max(a, b)] = std::min(a, b);
  }
};

// ---------------------------------------------------------------------------
// Step 5, for loops that are not planar.
bool triangulate_warped(const std::vector<Vec3d>& pts, const std::vector<std::uint32_t>& poly,
                        std::vector<Triangle>& out) {
  std::vector<Point3> loop;
  for (auto i : poly) loop.emplace_back(pts[i][0], pts[i][1], pts[i][2]);
  std::vector<CGAL::Triple<int, int, int>> patch;
  CGAL::Polygon_mesh_processing::triangulate_hole_polyline(loop, std::back_inserter(patch));
  if (patch.size() + 2 != poly.size()) return false;
  for (const auto& t : patch) out.push_back({poly[t.first], poly[t.second], poly[t.third]});
  return true;
}

// ---------------------------------------------------------------------------

class Cleaner {
 public:
  Cleaner(const PolygonSoup& in, const CleanupOptions& options, CleanupReport& report)
      : in_(in), options_(options), report_(report) {}

  void run(TriangleSoup& out) {
    report_.input_points = in_.points.size();
    report_.input_polygons = in_.polygons.size();
    const double diagonal = in_.bounds().diagonal();
    tolerance_ = options_.merge_tolerance * diagonal;
    min_area_ = options_.min_area * diagonal * diagonal;

    points_ = in_.points;
    polygons_ = in_.polygons;
    origin_.resize(polygons_.size());
    std::iota(origin_.begin(), origin_.end(), 0u);
    keep_.assign(polygons_.size(), 1);
    merge_points();
    drop_repeated_corners();
    if (options_.snap_t_junctions && tolerance_ > 0) snap_t_junctions();
    if (options_.flatten) {
      const FlattenReport flat = flatten_polygons(points_, polygons_, keep_, options_.flattening);
      report_.flattened_polygons = flat.flattened_polygons;
      report_.warped_polygons = flat.warped_polygons;
      report_.largest_flattening_move = flat.largest_move;
    }
    triangulate();
    drop_bad_triangles(options_.imprint ? Duplicates::within_a_surface : Duplicates::all);
    if (options_.imprint) imprint();
    cut_non_manifold_edges();
    emit(out);
  }

 private:
  void note_problem(std::size_t polygon) {
    if (report_.first_problem.empty()) report_.first_problem = in_.where(origin_[polygon]);
  }

  std::vector<Point3> cgal_points(const std::vector<std::size_t>& ids) const {
    std::vector<Point3> p(points_.size());
    for (auto i : ids) p[i] = Point3(points_[i][0], points_[i][1], points_[i][2]);
    return p;
  }

  // Step 1. Greedy clustering in index order: each point not yet merged absorbs the
  // unmerged points within the tolerance. Only points that some polygon uses count.
  void merge_points() {
    std::vector<char> used(points_.size(), 0);
    for (const auto& poly : polygons_)
      for (auto v : poly) used[v] = 1;
    std::vector<std::size_t> ids;
    for (std::size_t i = 0; i < points_.size(); ++i)
      if (used[i]) ids.push_back(i);
    report_.unused_points = points_.size() - ids.size();
    representative_.resize(points_.size());
    std::iota(representative_.begin(), representative_.end(), 0);
    if (ids.empty()) return;

    const auto cgal = cgal_points(ids);
    IndexPointMap map{&cgal};
    TreeTraits traits(map);
    Tree tree(ids.begin(), ids.end(), Tree::Splitter(), traits);
    std::vector<char> merged(points_.size(), 0);
    std::vector<std::size_t> near;
    for (auto i : ids) {
      if (merged[i]) continue;
      near.clear();
      if (tolerance_ > 0) {
        tree.search(std::back_inserter(near), Sphere(i, tolerance_, 0.0, traits));
      }
      for (auto j : near) {
        if (j == i || merged[j]) continue;
        merged[j] = 1;
        representative_[j] = i;
        ++report_.merged_points;
      }
      // Exact duplicates are merged even with a zero tolerance.
    }
    if (tolerance_ <= 0) {
      std::map<std::array<double, 3>, std::size_t> seen;
      for (auto i : ids) {
        auto [it, fresh] = seen.emplace(std::array<double, 3>{points_[i][0], points_[i][1], points_[i][2]}, i);
        if (!fresh) {
          representative_[i] = it->second;
          ++report_.merged_points;
        }
      }
    }
    for (auto& poly : polygons_)
      for (auto& v : poly) v = static_cast<std::uint32_t>(representative_[v]);
  }

  // Step 2.
  void drop_repeated_corners() {
    for (std::size_t p = 0; p < polygons_.size(); ++p) {
      auto& poly = polygons_[p];
      std::vector<std::uint32_t> clean;
      for (auto v : poly)
        if (clean.empty() || clean.back() != v) clean.push_back(v);
      while (clean.size() > 1 && clean.front() == clean.back()) clean.pop_back();
      poly.swap(clean);
      std::vector<std::uint32_t> distinct = poly;
      std::sort(distinct.begin(), distinct.end());
      distinct.erase(std::unique(distinct.begin(), distinct.end()), distinct.end());
      if (distinct.size() < 3 || newell_normal(points_, poly).norm() * 0.5 <= min_area_) {
        keep_[p] = 0;
        ++report_.degenerate_polygons;
        note_problem(p);
      }
    }
  }

  // Step 3. For every polygon edge, find points of other polygons lying on it (within
  // the tolerance) and insert them in order along the edge.
  void snap_t_junctions() {
    std::vector<std::size_t> ids;
    {
      std::vector<char> used(points_.size(), 0);
      for (std::size_t p = 0; p < polygons_.size(); ++p)
        if (keep_[p])
          for (auto v : polygons_[p]) used[v] = 1;
      for (std::size_t i = 0; i < points_.size(); ++i)
        if (used[i]) ids.push_back(i);
    }
    if (ids.empty()) return;
    const auto cgal = cgal_points(ids);
    IndexPointMap map{&cgal};
    TreeTraits traits(map);
    Tree tree(ids.begin(), ids.end(), Tree::Splitter(), traits);
    std::vector<std::size_t> near;
    for (std::size_t p = 0; p < polygons_.size(); ++p) {
      if (!keep_[p]) continue;
      const auto& poly = polygons_[p];
      std::vector<std::uint32_t> result;
      result.reserve(poly.size());
      const std::unordered_set<std::uint32_t> own(poly.begin(), poly.end());
      for (std::size_t k = 0; k < poly.size(); ++k) {
        const std::uint32_t a = poly[k], b = poly[(k + 1) % poly.size()];
        result.push_back(a);
        const Vec3d& pa = points_[a];
        const Vec3d& pb = points_[b];
        const Vec3d d = pb - pa;
        const double length2 = d.sqrnorm();
        if (length2 <= tolerance_ * tolerance_) continue;
        Vec3d lo = pa, hi = pa;
        lo.minimize(pb);
        hi.maximize(pb);
        near.clear();
        tree.search(std::back_inserter(near),
                    Box(Point3(lo[0] - tolerance_, lo[1] - tolerance_, lo[2] - tolerance_),
                        Point3(hi[0] + tolerance_, hi[1] + tolerance_, hi[2] + tolerance_), 0.0, traits));
        std::vector<std::pair<double, std::uint32_t>> on_edge;
        for (auto q : near) {
          if (own.count(static_cast<std::uint32_t>(q))) continue;
          const Vec3d w = points_[q] - pa;
          const double t = OpenMesh::dot(w, d) / length2;
          if (t <= 0 || t >= 1) continue;
          if ((w - d * t).sqrnorm() > tolerance_ * tolerance_) continue;
          on_edge.emplace_back(t, static_cast<std::uint32_t>(q));
        }
        std::sort(on_edge.begin(), on_edge.end());
        for (const auto& [t, q] : on_edge) {
          if (result.back() == q) continue;
          result.push_back(q);
          ++report_.t_junctions;
        }
      }
      polygons_[p].swap(result);
    }
  }

  // Step 5. Each polygon's triangles face the way the polygon does.
  void triangulate() {
    triangles_.clear();
    source_.clear();
    for (std::size_t p = 0; p < polygons_.size(); ++p) {
      if (!keep_[p]) continue;
      const auto& poly = polygons_[p];
      if (poly.size() == 3) {
        add_triangle({poly[0], poly[1], poly[2]}, p);
        continue;
      }
      ++report_.triangulated_polygons;
      std::vector<Triangle> tris;
      const Vec3d normal = newell_normal(points_, poly);
      bool ok = triangulate_polygon(points_, poly, normal, tris);
      if (!ok) {
        tris.clear();
        ok = triangulate_warped(points_, poly, tris);
      }
      if (!ok) {
        ++report_.untriangulatable_polygons;
        note_problem(p);
        continue;
      }
      for (auto t : tris) {
        // Keep the polygon's facing whatever order the triangulator produced.
        const Vec3d tn = OpenMesh::cross(points_[t[1]] - points_[t[0]], points_[t[2]] - points_[t[0]]);
        if (OpenMesh::dot(tn, normal) < 0) std::swap(t[1], t[2]);
        add_triangle(t, p);
      }
    }
  }

  // Step 7. Facets (planar polygons, or each triangle of a warped one) are imprinted with
  // the lines where others meet them and triangulated again; the whole triangle set is
  // then merged, snapped and triangulated once more, so that the points made on both
  // sides of a line are shared; last, the pieces no light reaches are removed.
  void imprint() {
    std::vector<std::uint64_t> label(triangles_.size());
    for (std::size_t i = 0; i < triangles_.size(); ++i) {
      const std::uint32_t p = origin_[source_[i]];
      label[i] = static_cast<std::uint64_t>(in_.material[p]) << 32 | in_.group[p];
    }
    std::vector<std::uint32_t> facet_of;
    const std::vector<Facet> facets = make_facets(points_, triangles_, label, tolerance_, facet_of);
    Imprints found = find_imprints(points_, facets, triangles_, facet_of, tolerance_);
    if (std::find(found.touched.begin(), found.touched.end(), 1) == found.touched.end()) return;  // nothing meets
    const std::vector<ClosedSurface> solids = closed_surfaces();  // of the model as given

    SecondPass next = retriangulate_facets(facets, facet_of, found);
    const double area_before = triangles_area();

    // Steps 1-3, 5 and 6 again, on the triangles: what they repair now was made by
    // imprinting, so the counts of the first pass stand.
    const CleanupReport first_pass = report_;
    polygons_ = std::move(next.polygons);
    origin_ = std::move(next.origin);
    keep_.assign(polygons_.size(), 1);
    merge_points();
    drop_repeated_corners();
    if (options_.snap_t_junctions && tolerance_ > 0) snap_t_junctions();
    triangulate();
    // Copies in one plane are left to the hidden-part rules, which keep the smaller
    // surface (a lamp on a ceiling), not the first.
    drop_bad_triangles(Duplicates::none);
    report_ = first_pass;

    std::vector<std::uint32_t> triangle_facet(triangles_.size());
    for (std::size_t i = 0; i < triangles_.size(); ++i) triangle_facet[i] = next.facet[source_[i]];
    std::vector<double> facet_area(facets.size(), 0.0);
    for (std::size_t i = 0; i < triangles_.size(); ++i) facet_area[triangle_facet[i]] += triangle_area(triangles_[i]);
    HiddenReport hidden;
    const std::vector<char> is_hidden = find_hidden_triangles(
        {solids, points_, triangles_, triangle_facet, found.touched, found.overlaps, facet_area, tolerance_},
        options_.hidden, hidden);
    report_.hidden_pieces =
        hidden.inside_solid_pieces + hidden.enclosed_pieces + hidden.face_to_face_pieces + hidden.covered_pieces;
    std::size_t kept = 0;
    for (std::size_t i = 0; i < triangles_.size(); ++i) {
      if (is_hidden[i]) continue;
      triangles_[kept] = triangles_[i];
      source_[kept++] = source_[i];
    }
    triangles_.resize(kept);
    source_.resize(kept);
    // What left: the hidden parts (and any sliver the second pass found to have no area).
    report_.hidden_area = std::max(0.0, area_before - triangles_area());
  }

  // The polygons for the second pass: the triangles of facets with lines on them,
  // triangulated again (each new triangle keeps the input polygon of the old triangle
  // that holds it), and the others' triangles as they were.
  struct SecondPass {
    std::vector<std::vector<std::uint32_t>> polygons;
    std::vector<std::uint32_t> origin;  // input polygon
    std::vector<std::uint32_t> facet;
  };
  SecondPass retriangulate_facets(const std::vector<Facet>& facets, const std::vector<std::uint32_t>& facet_of,
                                  Imprints& found) {
    std::vector<std::vector<Triangle>> redone(facets.size());
    std::vector<std::vector<std::uint32_t>> redone_polygon(facets.size());
    std::set<Segment> lines;
    for (std::uint32_t f = 0; f < facets.size(); ++f) {
      std::vector<Segment>& segments = found.segments[f];
      if (segments.empty()) continue;
      snap_ends_to_corners(facets[f].outline, segments);
      const auto outline = split_outline(points_, facets[f].outline, segments, tolerance_);
      std::vector<Triangle> region;
      for (auto t : facets[f].triangles) region.push_back(triangles_[t]);
      std::vector<std::uint32_t> holder;
      bool ok = false;
      try {
        ok = triangulate_region(points_, region, outline, segments, facets[f].normal, facets[f].point, redone[f],
                                holder);
      } catch (const std::exception&) {  // CGAL's checks on degenerate input: keep the facet as it is
        ok = false;
      }
      if (!ok) {
        redone[f].clear();
        if (report_.imprint_failures++ == 0)
          report_.first_imprint_failure = in_.where(origin_[source_[facets[f].triangles[0]]]);
        continue;
      }
      for (auto k : holder) redone_polygon[f].push_back(origin_[source_[facets[f].triangles[k]]]);
      ++report_.imprinted_facets;
      for (Segment s : segments) {
        if (s[0] > s[1]) std::swap(s[0], s[1]);
        lines.insert(s);
      }
    }
    report_.imprinted_edges = lines.size();
    SecondPass next;
    std::vector<char> emitted(facets.size(), 0);
    for (std::size_t i = 0; i < triangles_.size(); ++i) {
      const std::uint32_t f = facet_of[i];
      if (redone[f].empty()) {
        next.polygons.push_back({triangles_[i][0], triangles_[i][1], triangles_[i][2]});
        next.origin.push_back(origin_[source_[i]]);
        next.facet.push_back(f);
      } else if (!emitted[f]) {
        emitted[f] = 1;
        for (std::size_t k = 0; k < redone[f].size(); ++k) {
          const Triangle& t = redone[f][k];
          next.polygons.push_back({t[0], t[1], t[2]});
          next.origin.push_back(redone_polygon[f][k]);
          next.facet.push_back(f);
        }
      }
    }
    return next;
  }

  double triangle_area(const Triangle& t) const {
    return 0.5 * OpenMesh::cross(points_[t[1]] - points_[t[0]], points_[t[2]] - points_[t[0]]).norm();
  }
  double triangles_area() const {
    double sum = 0;
    for (const Triangle& t : triangles_) sum += triangle_area(t);
    return sum;
  }

  // The closed surfaces among the triangles: sets joined by shared edges in which every
  // edge is run as often one way as the other (a solid, or two solids that share an
  // edge: winding numbers add).
  std::vector<ClosedSurface> closed_surfaces() const {
    std::unordered_map<std::uint64_t, std::vector<std::uint32_t>> users;  // undirected edge -> triangles
    std::unordered_map<std::uint64_t, int> balance;                       // directed count, a < b positive
    for (std::uint32_t t = 0; t < triangles_.size(); ++t)
      for (int k = 0; k < 3; ++k) {
        const std::uint64_t a = triangles_[t][k], b = triangles_[t][(k + 1) % 3];
        const std::uint64_t key = std::min(a, b) << 32 | std::max(a, b);
        users[key].push_back(t);
        balance[key] += a < b ? 1 : -1;
      }
    UnionFind sets(triangles_.size());
    for (const auto& [key, list] : users)
      for (std::size_t i = 1; i < list.size(); ++i) sets.unite(list[0], list[i]);
    std::vector<char> open(triangles_.size(), 0);  // per set root
    for (const auto& [key, list] : users)
      if (balance.at(key) != 0) open[sets.find(list[0])] = 1;
    std::unordered_map<std::size_t, std::size_t> index;
    std::vector<ClosedSurface> surfaces;
    for (std::uint32_t t = 0; t < triangles_.size(); ++t) {
      const std::size_t root = sets.find(t);
      if (open[root]) continue;
      auto [it, fresh] = index.try_emplace(root, surfaces.size());
      if (fresh) surfaces.emplace_back();
      surfaces[it->second].push_back({points_[triangles_[t][0]], points_[triangles_[t][1]], points_[triangles_[t][2]]});
    }
    return surfaces;
  }

  // A segment's end within the tolerance of a corner of the outline is that corner.
  void snap_ends_to_corners(const std::vector<Segment>& outline, std::vector<Segment>& segments) const {
    for (Segment& s : segments)
      for (auto& end : s)
        for (const Segment& edge : outline) {
          const std::uint32_t corner = edge[0];
          if (end != corner && (points_[end] - points_[corner]).sqrnorm() <= tolerance_ * tolerance_) {
            end = corner;
            break;
          }
        }
    segments.erase(std::remove_if(segments.begin(), segments.end(), [](const Segment& s) { return s[0] == s[1]; }),
                   segments.end());
  }

  void add_triangle(const Triangle& t, std::size_t polygon) {
    triangles_.push_back(t);
    source_.push_back(static_cast<std::uint32_t>(polygon));
  }

  // Step 6.
  // Which copies of a triangle (same corners, same facing) are dropped: all but the
  // first; only those of one material and group (with imprinting, copies from two
  // surfaces are left to the hidden-part rules, which keep the smaller surface); none.
  enum class Duplicates { all, within_a_surface, none };
  void drop_bad_triangles(Duplicates duplicates) {
    struct Hash {
      std::size_t operator()(const std::pair<Triangle, std::uint64_t>& k) const {
        const Triangle& t = k.first;
        return (std::size_t(t[0]) * 73856093u) ^ (std::size_t(t[1]) * 19349663u) ^ (std::size_t(t[2]) * 83492791u) ^
               std::hash<std::uint64_t>()(k.second);
      }
    };
    std::unordered_set<std::pair<Triangle, std::uint64_t>, Hash> seen;
    std::vector<Triangle> kept;
    std::vector<std::uint32_t> kept_source;
    for (std::size_t i = 0; i < triangles_.size(); ++i) {
      const Triangle& t = triangles_[i];
      const double area = 0.5 * OpenMesh::cross(points_[t[1]] - points_[t[0]], points_[t[2]] - points_[t[0]]).norm();
      if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2] || area <= min_area_) {
        ++report_.degenerate_triangles;
        note_problem(source_[i]);
        continue;
      }
      // Canonical rotation (smallest index first) keeps the facing in the key.
      Triangle key = t;
      std::rotate(key.begin(), std::min_element(key.begin(), key.end()), key.end());
      const std::uint32_t p = origin_[source_[i]];
      const std::uint64_t surface =
          duplicates == Duplicates::all ? 0 : static_cast<std::uint64_t>(in_.material[p]) << 32 | in_.group[p];
      if (duplicates != Duplicates::none && !seen.insert({key, surface}).second) {
        ++report_.duplicate_triangles;
        continue;
      }
      kept.push_back(t);
      kept_source.push_back(source_[i]);
    }
    triangles_.swap(kept);
    source_.swap(kept_source);
  }

  // Step 8. Corners (triangle t, corner k) around a point are joined across manifold
  // edges; each resulting fan keeps or gets its own copy of the point.
  void cut_non_manifold_edges() {
    struct EdgeUse {
      std::uint32_t triangle;
      std::uint8_t corner;  // edge runs from corner to corner+1
    };
    std::unordered_map<std::uint64_t, std::vector<EdgeUse>> edges;
    edges.reserve(triangles_.size() * 2);
    auto key = [](std::uint32_t a, std::uint32_t b) {
      if (a > b) std::swap(a, b);
      return (std::uint64_t(a) << 32) | b;
    };
    for (std::uint32_t t = 0; t < triangles_.size(); ++t)
      for (std::uint8_t k = 0; k < 3; ++k) edges[key(triangles_[t][k], triangles_[t][(k + 1) % 3])].push_back({t, k});

    UnionFind corners(triangles_.size() * 3);
    for (const auto& [edge_key, uses] : edges) {
      if (uses.size() == 1) continue;
      const auto& e0 = uses[0];
      const auto& e1 = uses[uses.size() > 1 ? 1 : 0];
      const std::uint32_t a0 = triangles_[e0.triangle][e0.corner];
      const std::uint32_t a1 = triangles_[e1.triangle][e1.corner];
      if (uses.size() != 2 || a0 == a1) {  // >2 faces, or both faces run the edge the same way
        ++report_.non_manifold_edges;
        continue;
      }
      // Opposite directions: e0 runs a->b, e1 runs b->a.
      const std::uint8_t e0_next = (e0.corner + 1) % 3, e1_next = (e1.corner + 1) % 3;
      corners.unite(e0.triangle * 3 + e0.corner, e1.triangle * 3 + e1_next);
      corners.unite(e0.triangle * 3 + e0_next, e1.triangle * 3 + e1.corner);
    }
    // The first fan of each point keeps the point; later fans get copies.
    std::unordered_map<std::size_t, std::uint32_t> fan_point;  // root corner -> point
    std::vector<char> point_taken(points_.size(), 0);
    for (std::uint32_t t = 0; t < triangles_.size(); ++t) {
      for (int k = 0; k < 3; ++k) {
        const std::size_t root = corners.find(t * 3 + k);
        auto it = fan_point.find(root);
        std::uint32_t point = triangles_[t][k];
        if (it == fan_point.end()) {
          if (point_taken[point]) {
            points_.push_back(points_[point]);
            point_taken.push_back(1);
            ++report_.split_vertices;
            point = static_cast<std::uint32_t>(points_.size() - 1);
          }
          point_taken[point] = 1;
          fan_point.emplace(root, point);
        } else {
          point = it->second;
        }
        triangles_[t][k] = point;
      }
    }
  }

  void emit(TriangleSoup& out) {
    out = TriangleSoup();
    out.materials = in_.materials;
    out.group_names = in_.group_names;
    out.files = in_.files;
    out.warnings = in_.warnings;
    std::vector<std::uint32_t> remap(points_.size(), UINT32_MAX);
    for (std::size_t i = 0; i < triangles_.size(); ++i) {
      Triangle t = triangles_[i];
      for (auto& v : t) {
        if (remap[v] == UINT32_MAX) {
          remap[v] = static_cast<std::uint32_t>(out.points.size());
          out.points.push_back(points_[v]);
        }
        v = remap[v];
      }
      out.triangles.push_back(t);
      const std::uint32_t p = origin_[source_[i]];
      out.material.push_back(in_.material[p]);
      out.group.push_back(in_.group[p]);
      out.origin.push_back(in_.origin[p]);
    }
    report_.output_points = out.points.size();
    report_.output_triangles = out.triangles.size();
  }

  const PolygonSoup& in_;
  const CleanupOptions& options_;
  CleanupReport& report_;
  double tolerance_ = 0, min_area_ = 0;
  std::vector<Vec3d> points_;
  std::vector<std::vector<std::uint32_t>> polygons_;
  std::vector<char> keep_;
  std::vector<std::uint32_t> origin_;  // per entry of polygons_: the input polygon it comes from
  std::vector<std::size_t> representative_;
  std::vector<Triangle> triangles_;
  std::vector<std::uint32_t> source_;  // polygon each triangle came from
};

}  // namespace

CleanupReport cleanup(const PolygonSoup& input, TriangleSoup& output, const CleanupOptions& options) {
  CleanupReport report;
  Cleaner(input, options, report).run(output);
  return report;
}

}  // namespace dynrad
