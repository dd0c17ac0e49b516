// Polygon soup repair with CGAL. Steps, in order (each counted in CleanupReport):
//   1. merge points within a tolerance relative to the scene size (CGAL k-d tree);
//   2. drop repeated corners and polygons left with fewer than 3 points;
//   3. snap T-junctions: a point lying on another polygon's edge is inserted into it;
//   4. triangulate polygons (concave too) with a constrained Delaunay triangulation in
//      the polygon's plane, falling back to CGAL's hole filling for warped loops;
//   5. drop zero-area and duplicate triangles (same corners and same facing);
//   6. cut edges that are not manifold (more than two faces, or two faces facing
//      opposite ways) by giving each fan of faces around a point its own copy.
#include "mesh/cleanup.h"

#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Constrained_triangulation_face_base_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Fuzzy_iso_box.h>
#include <CGAL/Fuzzy_sphere.h>
#include <CGAL/Kd_tree.h>
#include <CGAL/Polygon_mesh_processing/triangulate_hole.h>
#include <CGAL/Search_traits_3.h>
#include <CGAL/Search_traits_adapter.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <algorithm>
#include <numeric>
#include <queue>
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

Vec3d newell_normal(const std::vector<Vec3d>& pts, const std::vector<std::uint32_t>& poly) {
  Vec3d n(0.0);
  for (std::size_t i = 0; i < poly.size(); ++i) {
    const Vec3d& a = pts[poly[i]];
    const Vec3d& b = pts[poly[(i + 1) % poly.size()]];
    n[0] += (a[1] - b[1]) * (a[2] + b[2]);
    n[1] += (a[2] - b[2]) * (a[0] + b[0]);
    n[2] += (a[0] - b[0]) * (a[1] + b[1]);
  }
  return n;  // length = twice the (projected) area
}

// ---------------------------------------------------------------------------
// Step 4: triangulation of one polygon.
struct FaceInfo {
  int nesting = -1;
  bool inside() const { return nesting % 2 == 1; }
};
// CGAL default-initialises vertex info, which leaves a bare integer with whatever the
// memory held; a struct with an initialiser starts at 0 ("unset") every time.
struct CornerInfo {
  std::uint32_t index_plus_one = 0;
};
using Vb = CGAL::Triangulation_vertex_base_with_info_2<CornerInfo, K>;
using Fbi = CGAL::Triangulation_face_base_with_info_2<FaceInfo, K>;
using Fb = CGAL::Constrained_triangulation_face_base_2<K, Fbi>;
using Tds = CGAL::Triangulation_data_structure_2<Vb, Fb>;
using Cdt = CGAL::Constrained_Delaunay_triangulation_2<K, Tds, CGAL::No_constraint_intersection_tag>;

// Marks faces by how many constraints separate them from the infinite face; faces at
// odd depth are inside the polygon.
void mark_nesting(Cdt& cdt) {
  for (auto f : cdt.all_face_handles()) f->info().nesting = -1;
  std::queue<std::pair<Cdt::Face_handle, int>> border;
  border.emplace(cdt.infinite_face(), 0);
  while (!border.empty()) {
    auto [start, level] = border.front();
    border.pop();
    if (start->info().nesting != -1) continue;
    std::queue<Cdt::Face_handle> region;
    region.push(start);
    start->info().nesting = level;
    while (!region.empty()) {
      auto f = region.front();
      region.pop();
      for (int i = 0; i < 3; ++i) {
        auto n = f->neighbor(i);
        if (n->info().nesting != -1) continue;
        if (cdt.is_constrained(Cdt::Edge(f, i))) {
          border.emplace(n, level + 1);
        } else {
          n->info().nesting = level;
          region.push(n);
        }
      }
    }
  }
}

using Triangle = std::array<std::uint32_t, 3>;

bool triangulate_planar(const std::vector<Vec3d>& pts, const std::vector<std::uint32_t>& poly, const Vec3d& normal,
                        std::vector<Triangle>& out) {
  // Orthonormal basis (u, v, n): counter-clockwise in (u, v) means facing along n.
  const Vec3d n = normal.normalized();
  const Vec3d helper = std::abs(n[0]) < 0.9 ? Vec3d(1, 0, 0) : Vec3d(0, 1, 0);
  const Vec3d u = OpenMesh::cross(helper, n).normalized();
  const Vec3d v = OpenMesh::cross(n, u);
  Cdt cdt;
  std::vector<Cdt::Vertex_handle> handles;
  handles.reserve(poly.size());
  try {
    for (auto index : poly) {
      const Vec3d& p = pts[index];
      auto vh = cdt.insert(K::Point_2(OpenMesh::dot(p, u), OpenMesh::dot(p, v)));
      auto& corner = vh->info().index_plus_one;
      if (corner != 0 && corner != index + 1) return false;  // two corners project onto one point
      corner = index + 1;
      handles.push_back(vh);
    }
    for (std::size_t i = 0; i < handles.size(); ++i) cdt.insert_constraint(handles[i], handles[(i + 1) % handles.size()]);
  } catch (const Cdt::Intersection_of_constraints_exception&) {
    return false;  // self-intersecting loop
  }
  mark_nesting(cdt);
  std::size_t produced = 0;
  for (auto f : cdt.finite_face_handles()) {
    if (!f->info().inside()) continue;
    Triangle t{f->vertex(0)->info().index_plus_one - 1, f->vertex(1)->info().index_plus_one - 1,
               f->vertex(2)->info().index_plus_one - 1};
    out.push_back(t);
    ++produced;
  }
  return produced + 2 == poly.size();  // a simple n-gon without Steiner points has n-2 triangles
}

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
    keep_.assign(polygons_.size(), 1);
    merge_points();
    drop_repeated_corners();
    if (options_.snap_t_junctions && tolerance_ > 0) snap_t_junctions();
    triangulate();
    drop_bad_triangles();
    cut_non_manifold_edges();
    emit(out);
  }

 private:
  void note_problem(std::size_t polygon) {
    if (report_.first_problem.empty()) report_.first_problem = in_.where(polygon);
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

  // Step 4.
  void triangulate() {
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
      bool ok = triangulate_planar(points_, poly, normal, tris);
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

  void add_triangle(const Triangle& t, std::size_t polygon) {
    triangles_.push_back(t);
    source_.push_back(static_cast<std::uint32_t>(polygon));
  }

  // Step 5.
  void drop_bad_triangles() {
    struct Hash {
      std::size_t operator()(const Triangle& t) const {
        return (std::size_t(t[0]) * 73856093u) ^ (std::size_t(t[1]) * 19349663u) ^ (std::size_t(t[2]) * 83492791u);
      }
    };
    std::unordered_set<Triangle, Hash> seen;
    std::vector<Triangle> kept;
    std::vector<std::uint32_t> kept_source;
    for (std::size_t i = 0; i < triangles_.size(); ++i) {
      const Triangle& t = triangles_[i];
      const double area =
          0.5 * OpenMesh::cross(points_[t[1]] - points_[t[0]], points_[t[2]] - points_[t[0]]).norm();
      if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2] || area <= min_area_) {
        ++report_.degenerate_triangles;
        note_problem(source_[i]);
        continue;
      }
      // Canonical rotation (smallest index first) keeps the facing in the key.
      Triangle key = t;
      std::rotate(key.begin(), std::min_element(key.begin(), key.end()), key.end());
      if (!seen.insert(key).second) {
        ++report_.duplicate_triangles;
        continue;
      }
      kept.push_back(t);
      kept_source.push_back(source_[i]);
    }
    triangles_.swap(kept);
    source_.swap(kept_source);
  }

  // Step 6. Corners (triangle t, corner k) around a point are joined across manifold
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
      const std::uint32_t p = source_[i];
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
