#include "radiosity/sources/shadow_outlines.h"

#include "mesh/core/line_insertion.h"
#include "radiosity/sources/daylight.h"
#include "radiosity/transfer/visibility.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

namespace dynrad::rad {

namespace {

// A sender as the outlines see it: a point, or a direction (the sun).
struct Sender {
  const Luminaire* luminaire = nullptr;
  bool directional = false;
  Vec3d position{0, 0, 0};
  Vec3d towards{0, 0, 1};  // unit, towards the sun (directional)
  double opening = 0;      // the luminaire's opening size (0: a point)
  std::size_t index = 0;   // in the luminaires given
};

// Where the ray from the sender past an edge point lands.
struct Landing {
  bool valid = false;
  int face = -1;
  Vec3d point{0, 0, 0};
  Vec3d normal{0, 0, 0};
  double half_width = 0;  // half the strip the outline needs here
};

class OutlineFinder {
 public:
  OutlineFinder(const SceneMesh& scene, const Visibility& visibility, const ShadowOutlineOptions& options)
      : mesh_(scene.mesh()), visibility_(visibility), options_(options) {
    const Bounds b = scene.bounds();
    eps_ = 1e-6 * (b.hi - b.lo).norm();
  }

  // True when face f is turned towards the sender (seen from point a on it).
  bool faces(const Sender& s, FaceHandle f, const Vec3d& a) const {
    const Vec3d& n = mesh_.normal(f);
    return (s.directional ? OpenMesh::dot(n, s.towards) : OpenMesh::dot(n, s.position - a)) > 0;
  }

  bool silhouette(const Sender& s, OpenMesh::EdgeHandle e) const {
    const OpenMesh::HalfedgeHandle h = mesh_.halfedge_handle(e, 0);
    const FaceHandle f0 = mesh_.face_handle(h), f1 = mesh_.opposite_face_handle(h);
    const Vec3d& a = mesh_.point(mesh_.from_vertex_handle(h));
    if (!f0.is_valid() || !f1.is_valid()) return true;  // a border: light passes beside it
    if (OpenMesh::dot(mesh_.normal(f0), mesh_.normal(f1)) > 1 - 1e-9) return false;
    return faces(s, f0, a) != faces(s, f1, a);
  }

  Landing land(const Sender& s, const Vec3d& x) const {
    Landing out;
    Vec3d d = s.directional ? -s.towards : x - s.position;
    const double distance = s.directional ? std::numeric_limits<double>::infinity() : d.norm();
    if (!(distance > eps_)) return out;
    if (!s.directional) d /= distance;
    // No light at all that way (a downlight's cut-off): no outline to draw.
    if (!s.directional && !(s.luminaire->intensity_towards(d) > 0)) return out;
    // The edge itself must be lit: nothing between the sender and x.
    const Visibility::Intersection back = visibility_.intersect(x - d * eps_, -d);
    if (back.hit && back.distance < distance - 2 * eps_) return out;
    const Visibility::Intersection ahead = visibility_.intersect(x + d * eps_, d);
    if (!ahead.hit || !ahead.front) return out;
    const double beyond = eps_ + ahead.distance;  // from the edge to the landing
    double half = options_.half_width;
    // Near enough for the solver to sample the opening: the penumbra's half width.
    if (!s.directional && s.opening > 0.2 * (distance + beyond))
      half = std::max(half, 0.5 * s.opening * beyond / distance);
    // Landing right beside the edge (a box's foot on the floor): nothing to add there.
    if (beyond < 4 * half || 2 * half > options_.widest) return out;
    out.valid = true;
    out.face = ahead.face;
    out.point = x + d * beyond;
    out.normal = mesh_.normal(FaceHandle(ahead.face));
    out.half_width = half;
    return out;
  }

  bool same_plane(const Landing& a, const Landing& b) const {
    return a.valid && b.valid && OpenMesh::dot(a.normal, b.normal) > 1 - 1e-9 &&
           std::abs(OpenMesh::dot(a.normal, b.point - a.point)) < 100 * eps_;
  }

  // The outlines of one silhouette edge a -> b, appended to `out` as (first, last, a
  // landing on it).
  struct Outline {
    Vec3d first, last;
    Landing middle;
    double half_width = 0;
  };
  void outlines(const Sender& s, const Vec3d& a, const Vec3d& b, std::vector<Outline>& out) const {
    const int n = std::clamp(static_cast<int>(std::ceil((b - a).norm() / options_.spacing)), 1, 256);
    std::vector<Landing> at(n + 1);
    for (int i = 0; i <= n; ++i) at[i] = land(s, a + (b - a) * (static_cast<double>(i) / n));
    int i = 0;
    while (i <= n) {
      if (!at[i].valid) {
        ++i;
        continue;
      }
      int j = i;
      while (j < n && same_plane(at[i], at[j + 1])) ++j;
      // The run i..j lands on one plane; its ends reach towards the samples beyond.
      const Vec3d first = i > 0 ? reach(s, a, b, at[i], static_cast<double>(i) / n, static_cast<double>(i - 1) / n)
                                : at[i].point;
      const Vec3d last = j < n ? reach(s, a, b, at[j], static_cast<double>(j) / n, static_cast<double>(j + 1) / n)
                               : at[j].point;
      const Landing& middle = at[(i + j) / 2];
      double half = 0;
      for (int k = i; k <= j; ++k) half = std::max(half, at[k].half_width);
      if ((last - first).norm() > std::max(4 * half, options_.shortest)) out.push_back({first, last, middle, half});
      i = j + 1;
    }
  }

 private:
  // The last point of the run that `end` (its landing at edge parameter `inside`) ends,
  // towards edge parameter `outside` (off the run), by bisection.
  Vec3d reach(const Sender& s, const Vec3d& a, const Vec3d& b, const Landing& end, double inside,
              double outside) const {
    Vec3d best = end.point;
    for (int k = 0; k < options_.bisections; ++k) {
      const double mid = 0.5 * (inside + outside);
      const Landing l = land(s, a + (b - a) * mid);
      if (same_plane(end, l)) {
        inside = mid;
        best = l.point;
      } else {
        outside = mid;
      }
    }
    return best;
  }

  const TriMesh& mesh_;
  const Visibility& visibility_;
  ShadowOutlineOptions options_;
  double eps_ = 0;
};

}  // namespace

ShadowOutlineOptions shadow_outline_options(double patch_size) {
  ShadowOutlineOptions o;
  o.half_width = 0.002 * patch_size;
  o.spacing = 0.25 * patch_size;
  o.widest = 0.5 * patch_size;
  o.shortest = 0.25 * patch_size;
  return o;
}

ShadowOutlineReport insert_shadow_outlines(SceneMesh& scene, const std::vector<Luminaire>& luminaires,
                                           const ShadowOutlineOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  ShadowOutlineReport report;
  if (!(options.half_width > 0) || !(options.spacing > 0)) return report;
  std::vector<Sender> senders;
  for (std::size_t index = 0; index < luminaires.size(); ++index) {
    const Luminaire& l = luminaires[index];
    if (l.kind == Luminaire::Kind::sky) continue;
    Sender s;
    s.luminaire = &l;
    s.index = index;
    if (l.kind == Luminaire::Kind::sun) {
      if (!l.daylight) continue;
      s.directional = true;
      s.towards = l.daylight->sun;
    } else {
      s.position = l.position;
      s.opening = l.opening_size();
    }
    senders.push_back(s);
  }
  report.senders = senders.size();
  if (senders.empty()) return report;

  // All outlines are found on the mesh as it is, then inserted. Each sender on its own
  // (in parallel), joined in the senders' order.
  std::vector<OutlineFinder::Outline> found;
  {
    const Visibility visibility(scene);
    const OutlineFinder finder(scene, visibility, options);
    const TriMesh& mesh = scene.mesh();
    std::vector<std::vector<OutlineFinder::Outline>> per_sender(senders.size());
    std::vector<std::size_t> silhouettes(senders.size(), 0);
    tbb::parallel_for(std::size_t(0), senders.size(), [&](std::size_t k) {
      const Sender& s = senders[k];
      auto look = [&](OpenMesh::EdgeHandle e) {
        if (!finder.silhouette(s, e)) return;
        ++silhouettes[k];
        const OpenMesh::HalfedgeHandle h = mesh.halfedge_handle(e, 0);
        finder.outlines(s, mesh.point(mesh.from_vertex_handle(h)), mesh.point(mesh.to_vertex_handle(h)), per_sender[k]);
      };
      if (options.candidate_edges)
        for (const OpenMesh::EdgeHandle e : (*options.candidate_edges)[s.index]) look(e);
      else
        for (auto e : mesh.edges()) look(e);
    });
    for (std::size_t k = 0; k < senders.size(); ++k) {
      report.silhouette_edges += silhouettes[k];
      found.insert(found.end(), per_sender[k].begin(), per_sender[k].end());
    }
  }
  report.outlines = found.size();
  for (const OutlineFinder::Outline& o : found) {
    const Vec3d& n = o.middle.normal;
    const Vec3d u = (o.last - o.first).normalized();
    const Vec3d across = OpenMesh::cross(n, u);
    LineOptions line;
    line.width = static_cast<float>(2 * o.half_width);
    line.snap = 0.25 * o.half_width;
    line.split = options.split;
    for (const double side : {-1.0, 1.0}) {
      // Each line runs the outline's length and a half width beyond its ends, so that
      // the lines of two outlines meeting at a corner cross there.
      const Vec3d offset = across * (side * o.half_width);
      const Vec3d middle = o.middle.point + offset;
      const FaceHandle face(o.middle.face);
      const InsertedLine ahead = insert_line(scene, face, middle, o.last + u * o.half_width + offset, line);
      const InsertedLine back = insert_line(scene, face, middle, o.first - u * o.half_width + offset, line);
      if (ahead.started) ++report.lines;
      report.vertices_added += ahead.vertices_added + back.vertices_added;
    }
  }
  if (!options.split) report.flips = flip_beside_lines(scene);
  report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return report;
}

}  // namespace dynrad::rad
