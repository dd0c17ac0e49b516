// Constrained Delaunay triangulation of a polygon in its plane (CGAL). A CGAL
// translation unit: slow to compile, so it holds only this.
#include "mesh/core/polygon_triangulation.h"

#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Constrained_triangulation_face_base_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <cmath>
#include <queue>

namespace dynrad {
namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;

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
// The loop alone: constraints must not cross (a crossing means a self-intersecting loop).
using LoopCdt = CGAL::Constrained_Delaunay_triangulation_2<K, Tds, CGAL::No_constraint_intersection_tag>;
// Loop and segments: segments may cross each other; CGAL inserts the crossing points.
using SegmentCdt = CGAL::Constrained_Delaunay_triangulation_2<K, Tds, CGAL::Exact_predicates_tag>;

// Marks faces by how many constraints separate them from the infinite face; faces at
// odd depth are inside the polygon. Only valid when every constraint is a loop edge.
void mark_nesting(LoopCdt& cdt) {
  for (auto f : cdt.all_face_handles()) f->info().nesting = -1;
  std::queue<std::pair<LoopCdt::Face_handle, int>> border;
  border.emplace(cdt.infinite_face(), 0);
  while (!border.empty()) {
    auto [start, level] = border.front();
    border.pop();
    if (start->info().nesting != -1) continue;
    std::queue<LoopCdt::Face_handle> region;
    region.push(start);
    start->info().nesting = level;
    while (!region.empty()) {
      auto f = region.front();
      region.pop();
      for (int i = 0; i < 3; ++i) {
        auto n = f->neighbor(i);
        if (n->info().nesting != -1) continue;
        if (cdt.is_constrained(LoopCdt::Edge(f, i))) {
          border.emplace(n, level + 1);
        } else {
          n->info().nesting = level;
          region.push(n);
        }
      }
    }
  }
}

// An orthonormal basis (u, v, n): counter-clockwise in (u, v) means facing along n.
struct Frame {
  Vec3d u, v, n;
  explicit Frame(const Vec3d& normal) : n(normal.normalized()) {
    const Vec3d helper = std::abs(n[0]) < 0.9 ? Vec3d(1, 0, 0) : Vec3d(0, 1, 0);
    u = OpenMesh::cross(helper, n).normalized();
    v = OpenMesh::cross(n, u);
  }
};

}  // namespace

Vec3d newell_normal(const std::vector<Vec3d>& pts, const std::vector<std::uint32_t>& loop) {
  Vec3d n(0.0);
  for (std::size_t i = 0; i < loop.size(); ++i) {
    const Vec3d& a = pts[loop[i]];
    const Vec3d& b = pts[loop[(i + 1) % loop.size()]];
    n[0] += (a[1] - b[1]) * (a[2] + b[2]);
    n[1] += (a[2] - b[2]) * (a[0] + b[0]);
    n[2] += (a[0] - b[0]) * (a[1] + b[1]);
  }
  return n;  // length = twice the (projected) area
}

bool triangulate_polygon(const std::vector<Vec3d>& pts, const std::vector<std::uint32_t>& given, const Vec3d& normal,
                         std::vector<Triangle>& out) {
  // A corner named twice in a row ("f 1 2 2 3", or the first corner again at the end)
  // is one corner: CGAL cannot take a constraint from a vertex to itself.
  std::vector<std::uint32_t> loop;
  loop.reserve(given.size());
  for (auto index : given)
    if (loop.empty() || loop.back() != index) loop.push_back(index);
  while (loop.size() > 1 && loop.back() == loop.front()) loop.pop_back();
  if (loop.size() < 3) return false;
  const Frame frame(normal);
  LoopCdt cdt;
  std::vector<LoopCdt::Vertex_handle> handles;
  handles.reserve(loop.size());
  try {
    for (auto index : loop) {
      const Vec3d& p = pts[index];
      auto vh = cdt.insert(K::Point_2(OpenMesh::dot(p, frame.u), OpenMesh::dot(p, frame.v)));
      auto& corner = vh->info().index_plus_one;
      if (corner != 0 && corner != index + 1) return false;  // two corners project onto one point
      corner = index + 1;
      handles.push_back(vh);
    }
    for (std::size_t i = 0; i < handles.size(); ++i)
      cdt.insert_constraint(handles[i], handles[(i + 1) % handles.size()]);
  } catch (const LoopCdt::Intersection_of_constraints_exception&) {
    return false;  // self-intersecting loop
  }
  mark_nesting(cdt);
  std::vector<Triangle> made;
  for (auto f : cdt.finite_face_handles()) {
    if (!f->info().inside()) continue;
    made.push_back({f->vertex(0)->info().index_plus_one - 1, f->vertex(1)->info().index_plus_one - 1,
                    f->vertex(2)->info().index_plus_one - 1});
  }
  if (made.size() + 2 != loop.size()) return false;  // a simple n-gon without Steiner points has n-2 triangles
  out.insert(out.end(), made.begin(), made.end());
  return true;
}

bool triangulate_region(std::vector<Vec3d>& points, const std::vector<Triangle>& region,
                        const std::vector<Segment>& outline, const std::vector<Segment>& segments, const Vec3d& normal,
                        const Vec3d& plane_point, std::vector<Triangle>& out, std::vector<std::uint32_t>& from) {
  const Frame frame(normal);
  auto to_2d = [&](const Vec3d& p) {
    const Vec3d d = p - plane_point;
    return K::Point_2(OpenMesh::dot(d, frame.u), OpenMesh::dot(d, frame.v));
  };
  SegmentCdt cdt;
  auto insert = [&](std::uint32_t index) {
    auto vh = cdt.insert(to_2d(points[index]));
    auto& id = vh->info().index_plus_one;
    if (id == 0) id = index + 1;  // two points on one spot: the first named keeps it
    return vh;
  };
  for (const auto* edges : {&outline, &segments}) {
    for (const Segment& s : *edges) {
      auto a = insert(s[0]), b = insert(s[1]);
      if (a != b) cdt.insert_constraint(a, b);
    }
  }
  // Points CGAL made where segments cross: lifted onto the plane.
  for (auto v : cdt.finite_vertex_handles()) {
    if (v->info().index_plus_one != 0) continue;
    const auto& p = v->point();
    points.push_back(plane_point + frame.u * p.x() + frame.v * p.y());
    v->info().index_plus_one = static_cast<std::uint32_t>(points.size());
  }
  // The region in the plane, for "which of its triangles holds this point".
  std::vector<std::array<K::Point_2, 3>> old;
  double region_area = 0;
  for (const Triangle& t : region) {
    old.push_back({to_2d(points[t[0]]), to_2d(points[t[1]]), to_2d(points[t[2]])});
    region_area += std::abs(CGAL::area(old.back()[0], old.back()[1], old.back()[2]));
  }
  std::vector<Triangle> made;
  std::vector<std::uint32_t> holder;
  double made_area = 0;
  for (auto f : cdt.finite_face_handles()) {
    const auto centroid = CGAL::centroid(f->vertex(0)->point(), f->vertex(1)->point(), f->vertex(2)->point());
    std::uint32_t inside = UINT32_MAX;
    for (std::uint32_t k = 0; k < old.size() && inside == UINT32_MAX; ++k) {
      const auto& o = old[k];
      const auto side = CGAL::orientation(o[0], o[1], o[2]) == CGAL::LEFT_TURN
                            ? CGAL::Triangle_2<K>(o[0], o[1], o[2]).bounded_side(centroid)
                            : CGAL::Triangle_2<K>(o[0], o[2], o[1]).bounded_side(centroid);
      if (side != CGAL::ON_UNBOUNDED_SIDE) inside = k;
    }
    if (inside == UINT32_MAX) continue;
    made.push_back({f->vertex(0)->info().index_plus_one - 1, f->vertex(1)->info().index_plus_one - 1,
                    f->vertex(2)->info().index_plus_one - 1});
    holder.push_back(inside);
    made_area += CGAL::area(f->vertex(0)->point(), f->vertex(1)->point(), f->vertex(2)->point());
  }
  if (!(std::abs(made_area - region_area) <= 1e-9 * region_area)) return false;
  // CGAL's faces are counter-clockwise in (u, v): they face along the normal.
  out.insert(out.end(), made.begin(), made.end());
  from.insert(from.end(), holder.begin(), holder.end());
  return true;
}

}  // namespace dynrad
