// Hidden parts: pieces, rays from their fronts (CGAL's AABB tree), and the rules for
// pieces in one plane (see hidden.h).
#include "mesh/hidden.h"

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>

namespace dynrad {
namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using TriangleList = std::vector<K::Triangle_3>;
using Primitive = CGAL::AABB_triangle_primitive<K, TriangleList::const_iterator>;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<K, Primitive>>;

struct Disjoint {
  std::vector<std::uint32_t> parent;
  explicit Disjoint(std::size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0u); }
  std::uint32_t find(std::uint32_t x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  }
  void unite(std::uint32_t a, std::uint32_t b) {
    a = find(a);
    b = find(b);
    if (a != b) parent[std::max(a, b)] = std::min(a, b);
  }
};

// One piece: its triangles and a point well inside it, on its front.
struct Piece {
  std::vector<std::uint32_t> triangles;
  Vec3d point, normal;  // the incentre of its fattest triangle
  double inradius = -1;
  bool tested = false;  // it holds a triangle of a touched facet
  enum class State { visible, enclosed, face_to_face, covered } state = State::visible;
};

// Directions cosine-distributed about +z: even in the projected disc's area (a spiral
// with the golden angle), so that each carries the same share of what the piece sees.
std::vector<Vec3d> cosine_directions(int count) {
  std::vector<Vec3d> directions;
  const double golden = M_PI * (3 - std::sqrt(5.0));
  for (int i = 0; i < count; ++i) {
    const double r2 = (i + 0.5) / count, phi = golden * i;
    const double r = std::sqrt(r2);
    directions.emplace_back(r * std::cos(phi), r * std::sin(phi), std::sqrt(1 - r2));
  }
  return directions;
}

bool inside_triangle(const Vec3d& p, const Vec3d& a, const Vec3d& b, const Vec3d& c, const Vec3d& normal,
                     double tolerance) {
  const Vec3d corners[3] = {a, b, c};
  for (int k = 0; k < 3; ++k) {
    const Vec3d edge = corners[(k + 1) % 3] - corners[k];
    const Vec3d inward = OpenMesh::cross(normal, edge).normalized();
    if (OpenMesh::dot(p - corners[k], inward) < -tolerance) return false;
  }
  return true;
}

class HiddenFinder {
 public:
  HiddenFinder(const HiddenInput& in, const HiddenOptions& options, HiddenReport& report)
      : in_(in), options_(options), report_(report) {}

  std::vector<char> run() {
    make_pieces();
    build_tree();
    find_links();
    const std::vector<Vec3d> directions = cosine_directions(options_.rays);
    // A ray that reaches the front of a hidden piece has stayed in the space that piece
    // faces, which is closed: it counts as closed too. So a piece is tested again when
    // one whose front it saw becomes hidden, until nothing changes.
    std::vector<std::vector<std::uint32_t>> seen(pieces_.size());
    std::vector<std::uint32_t> queue;
    for (std::uint32_t p = 0; p < pieces_.size(); ++p)
      if (pieces_[p].tested) queue.push_back(p);
    report_.pieces_tested = queue.size();
    std::vector<char> changed(pieces_.size(), 0);
    while (!queue.empty()) {
      std::vector<std::uint32_t> now_hidden;
      for (auto p : queue) {
        if (pieces_[p].state != Piece::State::visible) continue;
        seen[p].clear();
        if (enclosed(pieces_[p], directions, seen[p])) {
          pieces_[p].state = Piece::State::enclosed;
          ++report_.enclosed_pieces;
          now_hidden.push_back(p);
        }
      }
      const auto contacts = hide_face_to_face();
      now_hidden.insert(now_hidden.end(), contacts.begin(), contacts.end());
      for (auto p : now_hidden) changed[p] = 1;
      queue.clear();
      for (std::uint32_t p = 0; p < pieces_.size(); ++p) {
        if (!pieces_[p].tested || pieces_[p].state != Piece::State::visible) continue;
        if (std::any_of(seen[p].begin(), seen[p].end(), [&](std::uint32_t q) { return changed[q]; }))
          queue.push_back(p);
      }
      for (auto p : now_hidden) changed[p] = 0;
    }
    hide_covered();
    std::vector<char> hidden(in_.triangles.size(), 0);
    for (const Piece& piece : pieces_) {
      if (piece.state == Piece::State::visible) continue;
      for (auto t : piece.triangles) {
        hidden[t] = 1;
        report_.hidden_area += area(t);
      }
    }
    return hidden;
  }

 private:
  Vec3d corner(std::uint32_t t, int k) const { return in_.points[in_.triangles[t][k]]; }
  Vec3d area_vector(std::uint32_t t) const {
    return OpenMesh::cross(corner(t, 1) - corner(t, 0), corner(t, 2) - corner(t, 0)) * 0.5;
  }
  double area(std::uint32_t t) const { return area_vector(t).norm(); }

  // Pieces: triangles joined across every edge that exactly two triangles use. An
  // imprinted line is an edge of the surface that meets it too (three or more users),
  // so pieces end there; elsewhere a piece runs on across facets, around creases.
  void make_pieces() {
    const auto& tris = in_.triangles;
    // (edge, triangle) for every triangle side, sorted by edge: the users of an edge are
    // a run.
    std::vector<std::pair<std::uint64_t, std::uint32_t>> sides;
    sides.reserve(tris.size() * 3);
    for (std::uint32_t t = 0; t < tris.size(); ++t)
      for (int k = 0; k < 3; ++k) {
        const std::uint64_t a = tris[t][k], b = tris[t][(k + 1) % 3];
        sides.emplace_back(std::min(a, b) << 32 | std::max(a, b), t);
      }
    std::sort(sides.begin(), sides.end());
    Disjoint join(tris.size());
    for (std::size_t i = 0; i < sides.size();) {
      std::size_t j = i;
      while (j < sides.size() && sides[j].first == sides[i].first) ++j;
      if (j - i == 2) join.unite(sides[i].second, sides[i + 1].second);
      i = j;
    }
    std::vector<std::uint32_t> piece_of_root(tris.size(), UINT32_MAX);
    piece_of_.assign(tris.size(), UINT32_MAX);
    for (std::uint32_t t = 0; t < tris.size(); ++t) {
      std::uint32_t& piece_id = piece_of_root[join.find(t)];
      if (piece_id == UINT32_MAX) {
        piece_id = static_cast<std::uint32_t>(pieces_.size());
        pieces_.emplace_back();
      }
      Piece& piece = pieces_[piece_id];
      piece.triangles.push_back(t);
      piece.tested = piece.tested || in_.touched[in_.facet_of[t]];
      piece_of_[t] = piece_id;
      double inradius;
      const Vec3d centre = incentre(t, inradius);
      if (inradius > piece.inradius) {
        piece.inradius = inradius;
        piece.point = centre;
        piece.normal = area_vector(t).normalized();
      }
    }
  }

  Vec3d incentre(std::uint32_t t, double& inradius) const {
    const Vec3d a = corner(t, 0), b = corner(t, 1), c = corner(t, 2);
    const double la = (b - c).norm(), lb = (c - a).norm(), lc = (a - b).norm();
    inradius = 2 * area(t) / (la + lb + lc);
    return (a * la + b * lb + c * lc) / (la + lb + lc);
  }

  void build_tree() {
    triangles3_.reserve(in_.triangles.size());
    for (std::uint32_t t = 0; t < in_.triangles.size(); ++t) {
      auto p = [&](int k) {
        const Vec3d v = corner(t, k);
        return K::Point_3(v[0], v[1], v[2]);
      };
      triangles3_.emplace_back(p(0), p(1), p(2));
    }
    tree_.insert(triangles3_.begin(), triangles3_.end());
    tree_.build();
  }

  // `seen` gets the visible pieces whose fronts the rays hit.
  bool enclosed(const Piece& piece, const std::vector<Vec3d>& directions, std::vector<std::uint32_t>& seen) const {
    const Vec3d& n = piece.normal;
    const Vec3d helper = std::abs(n[0]) < 0.9 ? Vec3d(1, 0, 0) : Vec3d(0, 1, 0);
    const Vec3d u = OpenMesh::cross(helper, n).normalized(), v = OpenMesh::cross(n, u);
    // Off the piece's plane by more than surfaces in it may stray, within the piece.
    const double lift = std::max(10 * in_.tolerance, 0.01 * piece.inradius);
    const Vec3d origin = piece.point + n * lift;
    const K::Point_3 source(origin[0], origin[1], origin[2]);
    const int rays = static_cast<int>(directions.size());
    const int open_allowed = rays - static_cast<int>(std::ceil(options_.enclosed_fraction * rays));
    int open = 0;
    for (const Vec3d& local : directions) {
      const Vec3d d = u * local[0] + v * local[1] + n * local[2];
      const auto hit = tree_.first_intersected_primitive(K::Ray_3(source, K::Vector_3(d[0], d[1], d[2])));
      if (hit) {
        const auto t = static_cast<std::uint32_t>(*hit - triangles3_.begin());
        if (OpenMesh::dot(area_vector(t), d) > 0) continue;  // a back
        const std::uint32_t h = piece_of_[t];
        const auto state = pieces_[h].state;
        if (state == Piece::State::enclosed || state == Piece::State::face_to_face) continue;
        if (std::find(seen.begin(), seen.end(), h) == seen.end()) seen.push_back(h);
      }
      if (++open > open_allowed) return false;
    }
    return true;
  }

  // The piece of facet `f` under the point `p` (in f's plane), or UINT32_MAX.
  std::uint32_t piece_under(std::uint32_t f, const Vec3d& p, const Vec3d& normal) const {
    auto it = facet_triangles_.find(f);
    if (it == facet_triangles_.end()) return UINT32_MAX;
    for (auto t : it->second) {
      const Vec3d a = corner(t, 0), b = corner(t, 1), c = corner(t, 2);
      // `normal` is the facet's facing or its opposite: test in a fixed winding.
      const bool flip = OpenMesh::dot(area_vector(t), normal) < 0;
      if (inside_triangle(p, a, flip ? c : b, flip ? b : c, normal, in_.tolerance)) return piece_of_[t];
    }
    return UINT32_MAX;
  }

  // Pieces that overlap in one plane, found from a point of one inside the other's facet.
  void find_links() {
    for (std::uint32_t t = 0; t < in_.triangles.size(); ++t) facet_triangles_[in_.facet_of[t]].push_back(t);
    for (const auto& overlap : in_.overlaps) {
      for (int side = 0; side < 2; ++side) {
        const std::uint32_t f = side ? overlap.b : overlap.a, other = side ? overlap.a : overlap.b;
        // The fattest triangle of each piece within facet f gives the point.
        std::map<std::uint32_t, std::pair<double, std::uint32_t>> fattest;
        for (auto t : facet_triangles_[f]) {
          double inradius;
          incentre(t, inradius);
          auto [it, fresh] = fattest.try_emplace(piece_of_[t], inradius, t);
          if (!fresh && inradius > it->second.first) it->second = {inradius, t};
        }
        for (const auto& [p, best] : fattest) {
          double inradius;
          const Vec3d point = incentre(best.second, inradius);
          const std::uint32_t q = piece_under(other, point, area_vector(best.second));
          if (q != UINT32_MAX && q != p) links_.push_back({p, q, f, other, overlap.same_facing});
        }
      }
    }
  }

  // Face to face: hidden spreads across such contacts. Returns the pieces it hid.
  std::vector<std::uint32_t> hide_face_to_face() {
    std::vector<std::uint32_t> hid;
    for (bool changed = true; changed;) {  // a chain of contacts is short: repeat
      changed = false;
      for (const Link& link : links_) {
        if (link.same_facing) continue;
        const bool p_visible = pieces_[link.p].state == Piece::State::visible;
        if (p_visible == (pieces_[link.q].state == Piece::State::visible)) continue;
        const std::uint32_t now = p_visible ? link.p : link.q;
        pieces_[now].state = Piece::State::face_to_face;
        ++report_.face_to_face_pieces;
        hid.push_back(now);
        changed = true;
      }
    }
    return hid;
  }

  // Covered: of two visible pieces facing the same way, the smaller facet's stays (the
  // later one when they are equal).
  void hide_covered() {
    for (const Link& link : links_) {
      if (!link.same_facing) continue;
      Piece& p = pieces_[link.p];
      Piece& q = pieces_[link.q];
      if (p.state != Piece::State::visible || q.state != Piece::State::visible) continue;
      const double ap = in_.facet_area[link.fp], aq = in_.facet_area[link.fq];
      const bool keep_p = ap < aq || (ap == aq && link.fp > link.fq);
      (keep_p ? q : p).state = Piece::State::covered;
      ++report_.covered_pieces;
    }
  }

  struct Link {
    std::uint32_t p, q;    // pieces
    std::uint32_t fp, fq;  // the facets where they meet
    bool same_facing;
  };
  std::vector<Link> links_;
  const HiddenInput& in_;
  const HiddenOptions& options_;
  HiddenReport& report_;
  std::vector<Piece> pieces_;
  std::vector<std::uint32_t> piece_of_;  // per triangle
  std::map<std::uint32_t, std::vector<std::uint32_t>> facet_triangles_;
  TriangleList triangles3_;
  Tree tree_;
};

}  // namespace

std::vector<char> find_hidden_triangles(const HiddenInput& input, const HiddenOptions& options, HiddenReport& report) {
  return HiddenFinder(input, options, report).run();
}

}  // namespace dynrad
