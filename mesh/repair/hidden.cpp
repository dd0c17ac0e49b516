// Hidden parts: pieces, rays from their fronts (Embree, mesh/core/ray_cast.h), and the rules
// for surfaces in one plane (see hidden.h).
#include "mesh/repair/hidden.h"

#include "mesh/core/ray_cast.h"
#include "mesh/core/winding_number.h"

#include <CGAL/box_intersection_d.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <numeric>
#include <set>
#include <tuple>
#include <unordered_map>

namespace dynrad {
namespace {

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

enum class State : std::uint8_t { visible, enclosed, face_to_face, covered };
bool closed(State s) { return s == State::enclosed || s == State::face_to_face; }

// One piece: a connected part of a facet between imprinted lines, and a point well
// inside it, on its front.
struct Piece {
  std::vector<std::uint32_t> triangles;
  Vec3d point, normal;  // the incentre of its fattest triangle
  double inradius = -1;
  bool tested = false;  // its facet was touched by imprinting
  State state = State::visible;
};

class HiddenFinder {
 public:
  HiddenFinder(const HiddenInput& in, const HiddenOptions& options, HiddenReport& report)
      : in_(in), options_(options), report_(report), state_(in.triangles.size(), State::visible) {}

  std::vector<char> run() {
    make_pieces();
    build_tree();
    find_inside_solids();
    find_enclosed();
    for (const Piece& piece : pieces_)
      for (auto t : piece.triangles) state_[t] = piece.state;
    apply_plane_rules();
    std::vector<char> hidden(in_.triangles.size(), 0);
    for (std::uint32_t t = 0; t < in_.triangles.size(); ++t) {
      if (state_[t] == State::visible) continue;
      hidden[t] = 1;
      report_.hidden_area += area(t);
    }
    return hidden;
  }

 private:
  Vec3d corner(std::uint32_t t, int k) const { return in_.points[in_.triangles[t][k]]; }
  Vec3d area_vector(std::uint32_t t) const {
    return OpenMesh::cross(corner(t, 1) - corner(t, 0), corner(t, 2) - corner(t, 0)) * 0.5;
  }
  double area(std::uint32_t t) const { return area_vector(t).norm(); }
  Vec3d incentre(std::uint32_t t, double& inradius) const {
    const Vec3d a = corner(t, 0), b = corner(t, 1), c = corner(t, 2);
    const double la = (b - c).norm(), lb = (c - a).norm(), lc = (a - b).norm();
    inradius = 2 * area(t) / (la + lb + lc);
    return (a * la + b * lb + c * lc) / (la + lb + lc);
  }

  // Pieces: a facet's triangles joined across the edges that only two triangles use. An
  // imprinted line is an edge of the surface that meets the facet too (three or more
  // users), so pieces end there.
  void make_pieces() {
    const auto& tris = in_.triangles;
    // (edge, triangle) for every triangle side, sorted by edge: an edge's users are a run.
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
      const std::uint32_t t0 = sides[i].second;
      if (j - i == 2 && in_.facet_of[t0] == in_.facet_of[sides[i + 1].second]) join.unite(t0, sides[i + 1].second);
      i = j;
    }
    std::vector<std::uint32_t> piece_of_root(tris.size(), UINT32_MAX);
    piece_of_.assign(tris.size(), UINT32_MAX);
    for (std::uint32_t t = 0; t < tris.size(); ++t) {
      std::uint32_t& id = piece_of_root[join.find(t)];
      if (id == UINT32_MAX) {
        id = static_cast<std::uint32_t>(pieces_.size());
        pieces_.emplace_back();
        pieces_.back().tested = in_.touched[in_.facet_of[t]];
      }
      Piece& piece = pieces_[id];
      piece.triangles.push_back(t);
      piece_of_[t] = id;
      double inradius;
      const Vec3d centre = incentre(t, inradius);
      if (inradius > piece.inradius) {
        piece.inradius = inradius;
        piece.point = centre;
        piece.normal = area_vector(t).normalized();
      }
    }
  }

  void build_tree() { rays_ = std::make_unique<RayCaster>(in_.points, in_.triangles); }

  // The point in front of a piece: off its plane by more than surfaces in it may
  // stray, well within the piece.
  Vec3d front_point(const Piece& piece) const {
    return piece.point + piece.normal * std::max(10 * in_.tolerance, 0.01 * piece.inradius);
  }

  // Rule 1, by winding number: the solid angle a closed surface spans seen from the
  // point, over 4 pi, is 1 inside it (facing out), 0 outside.
  void find_inside_solids() {
    // Which solids' boxes hold which tested pieces' front points, found by CGAL's box
    // intersection rather than by a pass over every solid per piece. Then, per piece and
    // in solid order, the winding number of each such solid about its point, through a
    // tree over the solid's triangles (mesh/core/winding_number.h): a closed surface spanning
    // the building, such as facades joined at corner lines storey over storey, holds
    // most pieces in its box, and summing all its triangles for each made the load grow
    // with the square of the building.
    std::vector<Box> points, solids;
    std::vector<Vec3d> front(pieces_.size());
    for (std::uint32_t p = 0; p < pieces_.size(); ++p) {
      if (!pieces_[p].tested) continue;
      front[p] = front_point(pieces_[p]);
      double at[3] = {front[p][0], front[p][1], front[p][2]};
      points.emplace_back(at, at, p);
    }
    for (std::uint32_t s = 0; s < in_.solids.size(); ++s) {
      Bounds box;
      for (const auto& t : in_.solids[s])
        for (const Vec3d& p : t) box.extend(p);
      if (in_.solids[s].empty()) continue;
      double lo[3] = {box.lo[0], box.lo[1], box.lo[2]}, hi[3] = {box.hi[0], box.hi[1], box.hi[2]};
      solids.emplace_back(lo, hi, s);
    }
    std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs;  // (piece, solid)
    CGAL::box_intersection_d(points.begin(), points.end(), solids.begin(), solids.end(),
                             [&](const Box& a, const Box& b) { pairs.emplace_back(a.info(), b.info()); });
    std::sort(pairs.begin(), pairs.end());
    // A solid with a few triangles is summed directly; a tree pays only past that.
    constexpr std::size_t kTreeFrom = 64;
    std::vector<std::unique_ptr<WindingNumber>> trees(in_.solids.size());
    for (const auto& [p, s] : pairs) {
      Piece& piece = pieces_[p];
      if (piece.state != State::visible) continue;
      const ClosedSurface& solid = in_.solids[s];
      double turns;
      if (solid.size() < kTreeFrom) {
        turns = WindingNumber::exact(solid, front[p]);
      } else {
        if (!trees[s]) trees[s] = std::make_unique<WindingNumber>(solid);
        turns = trees[s]->at(front[p]);
      }
      if (turns > 0.5) {
        piece.state = State::enclosed;
        ++report_.inside_solid_pieces;
      }
    }
  }

  // Rule 1. A ray that reaches the front of a hidden piece has stayed in the space that
  // piece faces, which is closed: it counts as closed too. So a piece is tested again
  // when one whose front it saw becomes hidden, until nothing changes.
  void find_enclosed() {
    const std::vector<Vec3d> directions = cosine_directions(options_.rays);
    std::vector<std::vector<std::uint32_t>> watchers(pieces_.size());  // who saw each piece's front
    std::vector<std::uint32_t> queue, seen;
    for (std::uint32_t p = 0; p < pieces_.size(); ++p)
      if (pieces_[p].tested) queue.push_back(p);
    report_.pieces_tested = queue.size();
    std::vector<char> queued(pieces_.size(), 0);
    while (!queue.empty()) {
      std::vector<std::uint32_t> next;
      for (auto p : queue) {
        queued[p] = 0;
        if (pieces_[p].state != State::visible) continue;
        seen.clear();
        if (enclosed(pieces_[p], directions, seen)) {
          pieces_[p].state = State::enclosed;
          ++report_.enclosed_pieces;
          for (auto w : watchers[p])
            if (!queued[w] && pieces_[w].state == State::visible) {
              queued[w] = 1;
              next.push_back(w);
            }
          watchers[p].clear();
        } else {
          for (auto h : seen) watchers[h].push_back(p);
        }
      }
      std::sort(next.begin(), next.end());  // the same order whatever found them first
      queue.swap(next);
    }
  }

  // `seen` gets the visible pieces whose fronts the rays hit.
  bool enclosed(const Piece& piece, const std::vector<Vec3d>& directions, std::vector<std::uint32_t>& seen) const {
    const Vec3d& n = piece.normal;
    const Vec3d origin = front_point(piece);
    if (!is_finite(origin) || !(piece.normal.norm() > 0.5)) return false;
    const int rays = static_cast<int>(directions.size());
    const int open_allowed = rays - static_cast<int>(std::ceil(options_.enclosed_fraction * rays));
    int open = 0;
    for (const Vec3d& local : directions) {
      const Vec3d d = about_normal(n, local);
      const long hit = rays_->first_hit(origin, d);
      if (hit >= 0) {
        const auto t = static_cast<std::uint32_t>(hit);
        if (OpenMesh::dot(area_vector(t), d) > 0) continue;  // a back
        const std::uint32_t h = piece_of_[t];
        if (closed(pieces_[h].state)) continue;
        if (std::find(seen.begin(), seen.end(), h) == seen.end()) seen.push_back(h);
      }
      if (++open > open_allowed) return false;
    }
    return true;
  }

  using Box = CGAL::Box_intersection_d::Box_with_info_d<double, 3, std::uint32_t>;
  // Triangle t's box grown by the tolerance, carrying `info`.
  Box box_of(std::uint32_t t, std::uint32_t info) const {
    Bounds b;
    for (int k = 0; k < 3; ++k) b.extend(corner(t, k));
    double lo[3], hi[3];
    for (int k = 0; k < 3; ++k) {
      lo[k] = b.lo[k] - in_.tolerance;
      hi[k] = b.hi[k] + in_.tolerance;
    }
    return Box(lo, hi, info);
  }

  // A triangle's edges as lines in its plane: dot(p, inward[k]) - offset[k] is how far p
  // lies inside edge k.
  struct EdgeLines {
    std::array<Vec3d, 3> inward;
    std::array<double, 3> offset;
  };
  EdgeLines edge_lines(std::uint32_t u) const {
    EdgeLines lines;
    const Vec3d n = area_vector(u);
    for (int k = 0; k < 3; ++k) {
      lines.inward[k] = OpenMesh::cross(n, corner(u, (k + 1) % 3) - corner(u, k)).normalized();
      lines.offset[k] = OpenMesh::dot(corner(u, k), lines.inward[k]);
    }
    return lines;
  }

  // True when triangle t lies over triangle u (both in one plane): its centroid, or a
  // point halfway from it to one of t's corners, is inside u clear of u's edges by the
  // tolerance. (The centroid alone can lie on u's edge: a square's two triangulations.)
  bool over(std::uint32_t t, const EdgeLines& u) const {
    auto inside = [&](const Vec3d& p) {
      for (int k = 0; k < 3; ++k)
        if (OpenMesh::dot(p, u.inward[k]) - u.offset[k] <= in_.tolerance) return false;
      return true;
    };
    const Vec3d c = (corner(t, 0) + corner(t, 1) + corner(t, 2)) / 3.0;
    if (inside(c)) return true;
    for (int k = 0; k < 3; ++k)
      if (inside((c + corner(t, k)) * 0.5)) return true;
    return false;
  }

  // Rules 2 and 3, triangle by triangle where two facets overlap in one plane: what
  // imprinting cut along each other's outlines lies either inside the other facet or
  // outside it.
  void apply_plane_rules() {
    // The facet pairs that overlap, keyed (smaller facet, larger): bit 1 when they face
    // apart, bit 2 when they face the same way (a pair may be listed with both).
    std::unordered_map<std::uint64_t, unsigned> facings;
    std::vector<char> in_overlap;
    for (const auto& overlap : in_.overlaps) {
      const std::uint32_t a = std::min(overlap.a, overlap.b), b = std::max(overlap.a, overlap.b);
      facings[std::uint64_t(a) << 32 | b] |= overlap.same_facing ? 2u : 1u;
      if (b >= in_overlap.size()) in_overlap.resize(b + 1, 0);
      in_overlap[a] = in_overlap[b] = 1;
    }
    struct Pair {
      std::uint32_t t, u;  // triangles, one over the other
      std::uint32_t ft, fu;
      bool same_facing;
    };
    std::vector<Pair> pairs;
    // One box search over every triangle of an overlapping facet, not one per facet
    // pair: that sorted a facet's boxes again for every facet over it, and a stack of n
    // facets in one plane has n^2 pairs. 200 random triangles, 100 stacked on one
    // plane, loaded in 25 s that way and in 14 s this way (2026-12-04).
    std::vector<Box> boxes;  // a box's info is its slot in `triangle` and `lines`
    std::vector<std::uint32_t> triangle;
    std::vector<EdgeLines> lines;
    for (std::uint32_t t = 0; t < in_.triangles.size(); ++t) {
      const std::uint32_t f = in_.facet_of[t];
      if (f >= in_overlap.size() || !in_overlap[f]) continue;
      boxes.push_back(box_of(t, static_cast<std::uint32_t>(triangle.size())));
      triangle.push_back(t);
      lines.push_back(edge_lines(t));
    }
    CGAL::box_self_intersection_d(boxes.begin(), boxes.end(), [&](const Box& x, const Box& y) {
      std::uint32_t a = x.info(), b = y.info();  // slots, the lower facet's first
      std::uint32_t ft = in_.facet_of[triangle[a]], fu = in_.facet_of[triangle[b]];
      if (ft == fu) return;
      if (ft > fu) {
        std::swap(a, b);
        std::swap(ft, fu);
      }
      const std::uint32_t t = triangle[a], u = triangle[b];
      const auto found = facings.find(std::uint64_t(ft) << 32 | fu);
      if (found == facings.end() || !(over(t, lines[b]) || over(u, lines[a]))) return;
      if (found->second & 1u) pairs.push_back({t, u, ft, fu, false});
      if (found->second & 2u) pairs.push_back({t, u, ft, fu, true});
    });
    std::sort(pairs.begin(), pairs.end(), [](const Pair& x, const Pair& y) {  // a fixed order
      return std::tie(x.t, x.u) < std::tie(y.t, y.u);
    });
    std::set<std::uint32_t> face_to_face, covered;
    // Face to face: hidden spreads across such contacts, from every hidden triangle.
    std::vector<std::vector<std::uint32_t>> contacts(in_.triangles.size());
    for (const Pair& pair : pairs) {
      if (pair.same_facing) continue;
      contacts[pair.t].push_back(pair.u);
      contacts[pair.u].push_back(pair.t);
    }
    std::vector<std::uint32_t> spread;
    for (std::uint32_t t = 0; t < in_.triangles.size(); ++t)
      if (closed(state_[t]) && !contacts[t].empty()) spread.push_back(t);
    while (!spread.empty()) {
      const std::uint32_t t = spread.back();
      spread.pop_back();
      for (auto u : contacts[t]) {
        if (closed(state_[u])) continue;
        state_[u] = State::face_to_face;
        face_to_face.insert(piece_of_[u]);
        spread.push_back(u);
      }
    }
    // Covered: of two visible triangles facing the same way, the smaller facet's stays
    // (the later one when they are equal).
    for (const Pair& pair : pairs) {
      if (!pair.same_facing || state_[pair.t] != State::visible || state_[pair.u] != State::visible) continue;
      const double at = in_.facet_area[pair.ft], au = in_.facet_area[pair.fu];
      const bool keep_t = at < au || (at == au && pair.ft > pair.fu);
      const std::uint32_t gone = keep_t ? pair.u : pair.t;
      state_[gone] = State::covered;
      covered.insert(piece_of_[gone]);
    }
    report_.face_to_face_pieces = face_to_face.size();
    report_.covered_pieces = covered.size();
  }

  const HiddenInput& in_;
  const HiddenOptions& options_;
  HiddenReport& report_;
  std::vector<Piece> pieces_;
  std::vector<std::uint32_t> piece_of_;  // per triangle
  std::vector<State> state_;             // per triangle
  std::unique_ptr<RayCaster> rays_;
};

}  // namespace

std::vector<char> find_hidden_triangles(const HiddenInput& input, const HiddenOptions& options, HiddenReport& report) {
  return HiddenFinder(input, options, report).run();
}

}  // namespace dynrad
