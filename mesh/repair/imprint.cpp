// Imprinting: where facets cross or touch, with every decision made to within a
// tolerance (see imprint.h). CGAL finds candidate triangle pairs by their boxes.
#include "mesh/repair/imprint.h"

#include <CGAL/box_intersection_d.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

namespace dynrad {
namespace {

using Box = CGAL::Box_intersection_d::Box_with_info_d<double, 3, std::uint32_t>;

// A piece of a line, from parameter `from` (point `a`) to `to` (point `b`), from > to never.
struct Piece {
  double from, to;
  std::uint32_t a, b;
};

// Joins pieces of one line that overlap or touch (gaps up to `gap`) and returns them
// as segments.
void join_pieces(std::vector<Piece>& pieces, double gap, std::vector<Segment>& out) {
  std::sort(pieces.begin(), pieces.end(),
            [](const Piece& x, const Piece& y) { return x.from < y.from || (x.from == y.from && x.to > y.to); });
  std::size_t i = 0;
  while (i < pieces.size()) {
    Piece run = pieces[i++];
    while (i < pieces.size() && pieces[i].from <= run.to + gap) {
      if (pieces[i].to > run.to) {
        run.to = pieces[i].to;
        run.b = pieces[i].b;
      }
      ++i;
    }
    if (run.a != run.b) out.push_back({run.a, run.b});
  }
}

struct Frame2 {
  Vec3d u, v;
  explicit Frame2(const Vec3d& n) {
    const Vec3d helper = std::abs(n[0]) < 0.9 ? Vec3d(1, 0, 0) : Vec3d(0, 1, 0);
    u = OpenMesh::cross(helper, n).normalized();
    v = OpenMesh::cross(n, u);
  }
  std::array<double, 2> operator()(const Vec3d& p) const { return {OpenMesh::dot(p, u), OpenMesh::dot(p, v)}; }
};

double cross2(const std::array<double, 2>& a, const std::array<double, 2>& b, const std::array<double, 2>& c) {
  return (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
}

// Area of the intersection of two counter-clockwise triangles in the plane.
double overlap_area(const std::array<std::array<double, 2>, 3>& t1, const std::array<std::array<double, 2>, 3>& t2) {
  std::vector<std::array<double, 2>> poly(t2.begin(), t2.end()), next;
  for (int k = 0; k < 3 && !poly.empty(); ++k) {
    const auto& a = t1[k];
    const auto& b = t1[(k + 1) % 3];
    next.clear();
    for (std::size_t i = 0; i < poly.size(); ++i) {
      const auto& p = poly[i];
      const auto& q = poly[(i + 1) % poly.size()];
      const double fp = cross2(a, b, p), fq = cross2(a, b, q);
      if (fp >= 0) next.push_back(p);
      if ((fp >= 0) != (fq >= 0)) {
        const double s = fp / (fp - fq);
        next.push_back({p[0] + s * (q[0] - p[0]), p[1] + s * (q[1] - p[1])});
      }
    }
    poly.swap(next);
  }
  double area = 0;
  for (std::size_t i = 0; i < poly.size(); ++i) {
    const auto& p = poly[i];
    const auto& q = poly[(i + 1) % poly.size()];
    area += 0.5 * (p[0] * q[1] - q[0] * p[1]);
  }
  return std::abs(area);
}

class Imprinter {
 public:
  Imprinter(std::vector<Vec3d>& points, const std::vector<Facet>& facets, const std::vector<Triangle>& triangles,
            const std::vector<std::uint32_t>& facet_of, double tolerance)
      : points_(points),
        facets_(facets),
        triangles_(triangles),
        facet_of_(facet_of),
        tolerance_(tolerance),
        original_points_(static_cast<std::uint32_t>(points.size())) {
    offset_.resize(facets.size());
    for (std::size_t f = 0; f < facets.size(); ++f) offset_[f] = OpenMesh::dot(facets[f].normal, facets[f].point);
    for (std::uint32_t f = 0; f < facets.size(); ++f)
      for (const Segment& e : facets[f].outline) outline_edges_.insert(edge_key(f, e[0], e[1]));
  }

  Imprints run() {
    Imprints result;
    result.touched.assign(facets_.size(), 0);
    // Facets whose boxes meet another's first (a model of one flat floor has none), then
    // the triangles of those.
    auto box_of = [&](const Bounds& b, std::uint32_t id) {
      double lo[3] = {b.lo[0] - tolerance_, b.lo[1] - tolerance_, b.lo[2] - tolerance_};
      double hi[3] = {b.hi[0] + tolerance_, b.hi[1] + tolerance_, b.hi[2] + tolerance_};
      return Box(lo, hi, id);
    };
    std::vector<Bounds> facet_bounds(facets_.size());
    for (std::uint32_t t = 0; t < triangles_.size(); ++t)
      for (auto v : triangles_[t]) facet_bounds[facet_of_[t]].extend(points_[v]);
    std::vector<Box> boxes;
    for (std::uint32_t f = 0; f < facets_.size(); ++f) boxes.push_back(box_of(facet_bounds[f], f));
    std::vector<char> near_another(facets_.size(), 0);
    CGAL::box_self_intersection_d(boxes.begin(), boxes.end(), [&](const Box& x, const Box& y) {
      near_another[x.info()] = near_another[y.info()] = 1;
    });
    boxes.clear();
    for (std::uint32_t t = 0; t < triangles_.size(); ++t) {
      if (!near_another[facet_of_[t]]) continue;
      Bounds b;
      for (auto v : triangles_[t]) b.extend(points_[v]);
      boxes.push_back(box_of(b, t));
    }
    CGAL::box_self_intersection_d(boxes.begin(), boxes.end(), [&](const Box& x, const Box& y) {
      if (facet_of_[x.info()] == facet_of_[y.info()]) return;
      ++result.candidate_pairs;
      intersect(x.info(), y.info(), result);
    });
    result.segments.resize(facets_.size());
    for (auto& [key, pieces] : line_pieces_) {
      std::vector<Segment> joined;
      join_pieces(pieces, tolerance_, joined);
      for (const Segment& s : joined) {
        result.segments[key.first].push_back(s);
        result.segments[key.second].push_back(s);
      }
    }
    for (auto& [key, pieces] : edge_pieces_) {
      const double length = (points_[key[2]] - points_[key[1]]).norm();
      join_pieces(pieces, tolerance_ / length, result.segments[key[0]]);
    }
    for (auto& segments : result.segments) {  // one copy of each, in a fixed order
      for (auto& s : segments)
        if (s[0] > s[1]) std::swap(s[0], s[1]);
      std::sort(segments.begin(), segments.end());
      segments.erase(std::unique(segments.begin(), segments.end()), segments.end());
    }
    result.overlaps.assign(overlaps_.begin(), overlaps_.end());
    return result;
  }

 private:
  using EdgeKey = std::array<std::uint32_t, 3>;  // facet, smaller end, larger end
  static EdgeKey edge_key(std::uint32_t f, std::uint32_t a, std::uint32_t b) {
    return {f, std::min(a, b), std::max(a, b)};
  }

  double distance(std::uint32_t facet, std::uint32_t v) const {
    return OpenMesh::dot(facets_[facet].normal, points_[v]) - offset_[facet];
  }

  // Prefers a point the model had over one made here, then the lower id: the same
  // choice whichever pair finds it.
  std::uint32_t prefer(std::uint32_t a, std::uint32_t b) const {
    const bool a_old = a < original_points_, b_old = b < original_points_;
    if (a_old != b_old) return a_old ? a : b;
    return std::min(a, b);
  }

  // Where edge (a, b) crosses facet f's plane; da, db are the ends' signed distances.
  std::uint32_t edge_plane_point(std::uint32_t a, std::uint32_t b, double da, double db, std::uint32_t f) {
    if (a > b) {
      std::swap(a, b);
      std::swap(da, db);
    }
    auto [it, fresh] = edge_plane_.try_emplace({a, b, f}, 0);
    if (fresh) {
      const double s = da / (da - db);
      points_.push_back(points_[a] + (points_[b] - points_[a]) * s);
      it->second = static_cast<std::uint32_t>(points_.size() - 1);
    }
    return it->second;
  }

  // Where edge (a, b) crosses edge (c, d) in a common plane, at parameter s along (a, b).
  std::uint32_t edge_edge_point(std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint32_t d, double s) {
    std::array<std::uint32_t, 4> key{std::min(a, b), std::max(a, b), std::min(c, d), std::max(c, d)};
    if (std::make_pair(key[2], key[3]) < std::make_pair(key[0], key[1])) key = {key[2], key[3], key[0], key[1]};
    auto [it, fresh] = edge_edge_.try_emplace(key, 0);
    if (fresh) {
      points_.push_back(points_[a] + (points_[b] - points_[a]) * s);
      it->second = static_cast<std::uint32_t>(points_.size() - 1);
    }
    return it->second;
  }

  void intersect(std::uint32_t t1, std::uint32_t t2, Imprints& result) {
    const std::uint32_t f1 = facet_of_[t1], f2 = facet_of_[t2];
    if (f1 == f2) return;
    const Triangle& a = triangles_[t1];
    const Triangle& b = triangles_[t2];
    int shared = 0;
    for (auto x : a)
      for (auto y : b) shared += x == y;
    if (shared == 3) {  // the same triangle twice, from two surfaces: they overlap wholly
      const bool same_facing = OpenMesh::dot(facets_[f1].normal, facets_[f2].normal) > 0;
      overlaps_.insert({std::min(f1, f2), std::max(f1, f2), same_facing});
      result.touched[f1] = result.touched[f2] = 1;
      return;
    }
    if (shared == 2) return;       // neighbours across an edge: they meet along it
    std::array<double, 3> da, db;  // a's corners from f2's plane, b's from f1's
    bool a_on = true, b_on = true;
    for (int k = 0; k < 3; ++k) {
      da[k] = distance(f2, a[k]);
      db[k] = distance(f1, b[k]);
      if (std::abs(da[k]) <= tolerance_ || std::find(b.begin(), b.end(), a[k]) != b.end()) da[k] = 0;
      if (std::abs(db[k]) <= tolerance_ || std::find(a.begin(), a.end(), b[k]) != a.end()) db[k] = 0;
      a_on = a_on && da[k] == 0;
      b_on = b_on && db[k] == 0;
    }
    if (a_on || b_on) {
      coplanar(t1, t2, result);
      return;
    }
    auto one_side = [](const std::array<double, 3>& d) {
      return (d[0] >= 0 && d[1] >= 0 && d[2] >= 0) || (d[0] <= 0 && d[1] <= 0 && d[2] <= 0);
    };
    // A triangle wholly on one side, touching the plane at one corner at most, or
    // along an edge: handled below by the crossings.
    if (one_side(da) && std::count(da.begin(), da.end(), 0.0) < 2) return;
    if (one_side(db) && std::count(db.begin(), db.end(), 0.0) < 2) return;
    std::array<std::uint32_t, 2> ca, cb;
    if (crossing(a, da, f2, ca) < 2 || crossing(b, db, f1, cb) < 2) return;
    // Both crossings lie on the line where the planes meet; its direction from the
    // facets in a fixed order, so that every pair of these facets measures alike.
    const std::uint32_t lo_f = std::min(f1, f2), hi_f = std::max(f1, f2);
    const Vec3d direction = OpenMesh::cross(facets_[lo_f].normal, facets_[hi_f].normal).normalized();
    auto along = [&](std::uint32_t p) { return OpenMesh::dot(direction, points_[p]); };
    auto order = [&](std::array<std::uint32_t, 2>& c) {
      if (along(c[0]) > along(c[1])) std::swap(c[0], c[1]);
    };
    order(ca);
    order(cb);
    const double a0 = along(ca[0]), a1 = along(ca[1]), b0 = along(cb[0]), b1 = along(cb[1]);
    const double from = std::max(a0, b0), to = std::min(a1, b1);
    if (to - from <= tolerance_) return;
    const std::uint32_t start = a0 > b0 + tolerance_ ? ca[0] : (b0 > a0 + tolerance_ ? cb[0] : prefer(ca[0], cb[0]));
    const std::uint32_t end = a1 < b1 - tolerance_ ? ca[1] : (b1 < a1 - tolerance_ ? cb[1] : prefer(ca[1], cb[1]));
    line_pieces_[{lo_f, hi_f}].push_back({from, to, start, end});
    result.touched[f1] = result.touched[f2] = 1;
  }

  // The points where triangle t meets the plane of facet f: its corners on the plane
  // (d == 0) and its edges' crossings. Returns how many (at most 2 unless t lies on it).
  int crossing(const Triangle& t, const std::array<double, 3>& d, std::uint32_t f, std::array<std::uint32_t, 2>& out) {
    int n = 0;
    for (int k = 0; k < 3 && n < 2; ++k)
      if (d[k] == 0) out[n++] = t[k];
    for (int k = 0; k < 3 && n < 2; ++k) {
      const int j = (k + 1) % 3;
      if ((d[k] < 0 && d[j] > 0) || (d[k] > 0 && d[j] < 0)) out[n++] = edge_plane_point(t[k], t[j], d[k], d[j], f);
    }
    return n;
  }

  // Two triangles in one plane: each one's facet outline, where it runs inside the
  // other triangle, is imprinted on the other facet.
  void coplanar(std::uint32_t t1, std::uint32_t t2, Imprints& result) {
    const std::uint32_t f1 = facet_of_[t1], f2 = facet_of_[t2];
    const Frame2 frame(facets_[f1].normal);
    std::array<std::array<double, 2>, 3> p1, p2;
    for (int k = 0; k < 3; ++k) {
      p1[k] = frame(points_[triangles_[t1][k]]);
      p2[k] = frame(points_[triangles_[t2][k]]);
    }
    // t1 faces f1's normal, so it runs counter-clockwise in f1's frame; t2 runs so only
    // when the two face the same way.
    const bool same_facing = OpenMesh::dot(facets_[f1].normal, facets_[f2].normal) > 0;
    std::array<std::array<double, 2>, 3> p2_ccw = p2;
    Triangle t2_ccw = triangles_[t2];
    if (!same_facing) {
      std::swap(p2_ccw[1], p2_ccw[2]);
      std::swap(t2_ccw[1], t2_ccw[2]);
    }
    clip_outline(t2, p2, triangles_[t1], p1, f1);
    clip_outline(t1, p1, t2_ccw, p2_ccw, f2);
    double longest = 0;
    for (int k = 0; k < 3; ++k) {
      longest = std::max(longest, std::hypot(p1[k][0] - p1[(k + 1) % 3][0], p1[k][1] - p1[(k + 1) % 3][1]));
      longest = std::max(longest, std::hypot(p2[k][0] - p2[(k + 1) % 3][0], p2[k][1] - p2[(k + 1) % 3][1]));
    }
    if (overlap_area(p1, p2_ccw) > tolerance_ * longest) {
      overlaps_.insert({std::min(f1, f2), std::max(f1, f2), same_facing});
      result.touched[f1] = result.touched[f2] = 1;
    }
  }

  // Imprints on facet `target` the parts of the edges of triangle `from` that are
  // edges of its facet's outline and run inside triangle `host` (its corners in
  // counter-clockwise order, at `q`; `p` are from's corners in the same frame).
  void clip_outline(std::uint32_t from, const std::array<std::array<double, 2>, 3>& p, const Triangle& host,
                    const std::array<std::array<double, 2>, 3>& q, std::uint32_t target) {
    const Triangle& t = triangles_[from];
    const std::uint32_t facet = facet_of_[from];
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t a = t[k], b = t[(k + 1) % 3];
      if (!outline_edges_.count(edge_key(facet, a, b))) continue;  // inside its facet
      const auto& pa = p[k];
      const auto& pb = p[(k + 1) % 3];
      const double length = std::hypot(pb[0] - pa[0], pb[1] - pa[1]);
      if (length <= tolerance_) continue;
      double s0 = 0, s1 = 1;
      int cut0 = -1, cut1 = -1;  // the host edge that set each bound
      bool empty = false;
      for (int e = 0; e < 3 && !empty; ++e) {
        const auto& c = q[e];
        const auto& d = q[(e + 1) % 3];
        const double edge_length = std::hypot(d[0] - c[0], d[1] - c[1]);
        // Signed distance from the host edge's line, positive inside.
        const double g0 = cross2(c, d, pa) / edge_length, g1 = cross2(c, d, pb) / edge_length;
        if (g0 >= -tolerance_ && g1 >= -tolerance_) continue;
        if (g0 < -tolerance_ && g1 < -tolerance_) {
          empty = true;
          break;
        }
        const double s = g0 / (g0 - g1);  // where the edge crosses the line
        if (g0 < -tolerance_) {
          if (s > s0) s0 = s, cut0 = e;
        } else if (s < s1) {
          s1 = s, cut1 = e;
        }
      }
      if (empty || (s1 - s0) * length <= tolerance_) continue;
      auto point_at = [&](double s, int cut, std::uint32_t end) -> std::uint32_t {
        if (cut < 0) return end;
        if (s * length <= tolerance_) return a;
        if ((1 - s) * length <= tolerance_) return b;
        return edge_edge_point(a, b, host[cut], host[(cut + 1) % 3], s);
      };
      const std::uint32_t start = point_at(s0, cut0, a), end = point_at(s1, cut1, b);
      if (start == end) continue;
      // Measured along the edge from its smaller end, as every piece of it is.
      if (a < b)
        edge_pieces_[{target, a, b}].push_back({s0, s1, start, end});
      else
        edge_pieces_[{target, b, a}].push_back({1 - s1, 1 - s0, end, start});
    }
  }

  std::vector<Vec3d>& points_;
  const std::vector<Facet>& facets_;
  const std::vector<Triangle>& triangles_;
  const std::vector<std::uint32_t>& facet_of_;
  const double tolerance_;
  const std::uint32_t original_points_;
  std::vector<double> offset_;
  std::set<EdgeKey> outline_edges_;
  std::map<std::array<std::uint32_t, 3>, std::uint32_t> edge_plane_;
  std::map<std::array<std::uint32_t, 4>, std::uint32_t> edge_edge_;
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::vector<Piece>> line_pieces_;
  std::map<std::array<std::uint32_t, 3>, std::vector<Piece>> edge_pieces_;  // target facet, edge ends
  struct OverlapLess {
    bool operator()(const Imprints::Overlap& x, const Imprints::Overlap& y) const {
      return std::tie(x.a, x.b, x.same_facing) < std::tie(y.a, y.b, y.same_facing);
    }
  };
  std::set<Imprints::Overlap, OverlapLess> overlaps_;
};

}  // namespace

Imprints find_imprints(std::vector<Vec3d>& points, const std::vector<Facet>& facets,
                       const std::vector<Triangle>& triangles, const std::vector<std::uint32_t>& facet_of,
                       double tolerance) {
  return Imprinter(points, facets, triangles, facet_of, tolerance).run();
}

std::vector<Facet> make_facets(const std::vector<Vec3d>& points, const std::vector<Triangle>& triangles,
                               const std::vector<std::uint64_t>& label, double tolerance,
                               std::vector<std::uint32_t>& facet_of) {
  auto area_vector = [&](std::uint32_t t) {
    const Triangle& c = triangles[t];
    return OpenMesh::cross(points[c[1]] - points[c[0]], points[c[2]] - points[c[0]]) * 0.5;
  };
  // (edge, triangle, corner) for every side, sorted by edge: an edge's users are a run.
  struct Side {
    std::uint64_t edge;
    std::uint32_t triangle;
    int corner;  // the side runs from this corner to the next
    bool operator<(const Side& o) const { return edge < o.edge || (edge == o.edge && triangle < o.triangle); }
  };
  std::vector<Side> sides;
  sides.reserve(triangles.size() * 3);
  for (std::uint32_t t = 0; t < triangles.size(); ++t)
    for (int k = 0; k < 3; ++k) {
      const std::uint64_t a = triangles[t][k], b = triangles[t][(k + 1) % 3];
      sides.push_back({std::min(a, b) << 32 | std::max(a, b), t, k});
    }
  std::sort(sides.begin(), sides.end());
  std::vector<std::uint32_t> parent(triangles.size());
  for (std::uint32_t t = 0; t < parent.size(); ++t) parent[t] = t;
  auto find = [&](std::uint32_t x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  };
  std::vector<char> interior(sides.size(), 0);  // the side is shared within a facet
  auto join = [&](std::size_t i, std::size_t j) {
    const Side& x = sides[i];
    const Side& y = sides[j];
    const std::uint32_t tx = x.triangle, ty = y.triangle;
    const bool opposite = triangles[tx][x.corner] == triangles[ty][(y.corner + 1) % 3];
    const Vec3d nx = area_vector(tx).normalized(), ny = area_vector(ty).normalized();
    // The other triangle's far corner on this one's plane, and the same facing.
    const std::uint32_t far = triangles[ty][(y.corner + 2) % 3];
    const double off_plane = std::abs(OpenMesh::dot(nx, points[far] - points[triangles[tx][0]]));
    if (!opposite || off_plane > tolerance || OpenMesh::dot(nx, ny) <= 1 - 1e-9) return;
    interior[i] = interior[j] = 1;
    const std::uint32_t rx = find(tx), ry = find(ty);
    if (rx != ry) parent[std::max(rx, ry)] = std::min(rx, ry);
  };
  // An edge joins the two triangles of one label that use it (other surfaces may use
  // it too: two coplanar faces cut alike where they overlap).
  std::vector<std::size_t> users;
  for (std::size_t i = 0; i < sides.size();) {
    std::size_t j = i;
    while (j < sides.size() && sides[j].edge == sides[i].edge) ++j;
    users.clear();
    for (std::size_t k = i; k < j; ++k) users.push_back(k);
    std::sort(users.begin(), users.end(),
              [&](std::size_t a, std::size_t b) { return label[sides[a].triangle] < label[sides[b].triangle]; });
    for (std::size_t k = 0; k < users.size();) {
      std::size_t m = k;
      while (m < users.size() && label[sides[users[m]].triangle] == label[sides[users[k]].triangle]) ++m;
      if (m - k == 2) join(users[k], users[k + 1]);
      k = m;
    }
    i = j;
  }
  std::vector<Facet> facets;
  facet_of.assign(triangles.size(), UINT32_MAX);
  std::vector<std::uint32_t> facet_of_root(triangles.size(), UINT32_MAX);
  for (std::uint32_t t = 0; t < triangles.size(); ++t) {
    std::uint32_t& f = facet_of_root[find(t)];
    if (f == UINT32_MAX) {
      f = static_cast<std::uint32_t>(facets.size());
      facets.emplace_back();
    }
    facets[f].triangles.push_back(t);
    facet_of[t] = f;
  }
  for (std::size_t i = 0; i < sides.size(); ++i) {
    if (interior[i]) continue;
    const Triangle& t = triangles[sides[i].triangle];
    facets[facet_of[sides[i].triangle]].outline.push_back({t[sides[i].corner], t[(sides[i].corner + 1) % 3]});
  }
  for (Facet& facet : facets) {
    Vec3d normal(0.0), centre(0.0);
    double area = 0;
    for (auto t : facet.triangles) {
      const Vec3d n = area_vector(t);
      const Triangle& c = triangles[t];
      normal += n;
      area += n.norm();
      centre += (points[c[0]] + points[c[1]] + points[c[2]]) * (n.norm() / 3);
    }
    facet.normal = normal.normalized();
    facet.point = centre / area;
    std::sort(facet.outline.begin(), facet.outline.end());  // a fixed order
  }
  return facets;
}

std::vector<Segment> split_outline(const std::vector<Vec3d>& points, const std::vector<Segment>& outline,
                                   const std::vector<Segment>& segments, double tolerance) {
  std::vector<std::uint32_t> ends;
  for (const Segment& s : segments) ends.insert(ends.end(), s.begin(), s.end());
  std::sort(ends.begin(), ends.end());
  ends.erase(std::unique(ends.begin(), ends.end()), ends.end());
  std::vector<Segment> result;
  std::vector<std::pair<double, std::uint32_t>> on_edge;
  for (const Segment& edge : outline) {
    const std::uint32_t a = edge[0], b = edge[1];
    const Vec3d d = points[b] - points[a];
    const double length2 = d.sqrnorm();
    on_edge.clear();
    for (auto e : ends) {
      if (e == a || e == b || length2 <= tolerance * tolerance) continue;
      const Vec3d w = points[e] - points[a];
      const double s = OpenMesh::dot(w, d) / length2;
      if (s <= 0 || s >= 1 || (w - d * s).sqrnorm() > tolerance * tolerance) continue;
      on_edge.emplace_back(s, e);
    }
    std::sort(on_edge.begin(), on_edge.end());
    std::uint32_t from = a;
    for (const auto& entry : on_edge) {
      result.push_back({from, entry.second});
      from = entry.second;
    }
    result.push_back({from, b});
  }
  return result;
}

}  // namespace dynrad
