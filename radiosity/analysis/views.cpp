#include "radiosity/analysis/views.h"

#include "radiosity/analysis/rooms.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <tuple>

namespace dynrad::rad {

namespace {

Vec3d plan_point(int up, const std::array<int, 2>& axes, double x, double y, double height) {
  Vec3d p(0.0);
  p[axes[0]] = x;
  p[axes[1]] = y;
  p[up] = height;
  return p;
}

// A grid of the scene whose polygon holds (x, y) at a height within the storey.
const GridSpec* grid_at(const std::vector<GridSpec>& grids, int up, const Storey& storey, double x, double y) {
  for (const GridSpec& g : grids)
    if (g.up == up && g.height >= storey.floor && g.height <= storey.floor + storey.height &&
        inside_polygon(g.polygon, x, y))
      return &g;
  return nullptr;
}

// The lit surface a view shows (best_lit_view): the summed area of the distinct planes
// met by a 48 x 48 ray sample whose radiosity is at least 1% of the display white. The
// planes are found once: triangles grouped by their normal (to 0.01) and offset (to
// 0.001 of the scene's diagonal), with their summed areas.
class LitSurfaceScore {
 public:
  LitSurfaceScore(const LitScene& scene, double exposure) : scene_(scene), lit_(0.01 * 0.9 / exposure) {
    plane_of_.resize(scene.triangles.size());
    std::map<std::tuple<long, long, long, long>, std::size_t> planes;
    for (std::size_t f = 0; f < scene.triangles.size(); ++f) {
      const auto& t = scene.triangles[f];
      const Vec3d& p0 = scene.positions[t[0]];
      Vec3d n = OpenMesh::cross(scene.positions[t[1]] - p0, scene.positions[t[2]] - p0);
      const double area = 0.5 * n.norm();
      if (area > 0) n /= 2 * area;
      const auto key = std::make_tuple(std::lround(100 * n[0]), std::lround(100 * n[1]), std::lround(100 * n[2]),
                                       std::lround(OpenMesh::dot(n, p0) / (1e-3 * scene.diagonal + 1e-300)));
      auto [it, inserted] = planes.emplace(key, plane_area_.size());
      if (inserted) plane_area_.push_back(0);
      plane_of_[f] = it->second;
      plane_area_[it->second] += area;
    }
  }

  double operator()(const View& v) const {
    std::vector<char> seen(plane_area_.size(), 0);
    double score = 0;
    const int n = 48;
    const double aspect = static_cast<double>(v.width) / v.height;
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) {
        const Ray ray = camera_ray(v.camera, aspect, (i + 0.5) / n * 2 - 1, (j + 0.5) / n * 2 - 1);
        const auto hit = scene_.visibility->intersect(ray.origin, ray.direction);
        if (!hit.hit || !hit.front) continue;
        const auto& t = scene_.triangles[static_cast<std::size_t>(hit.face)];
        const Rgb b = scene_.radiosity[t[0]] * (1 - hit.u - hit.v) + scene_.radiosity[t[1]] * hit.u +
                      scene_.radiosity[t[2]] * hit.v;
        if (b.luminance() < lit_) continue;
        const std::size_t plane = plane_of_[static_cast<std::size_t>(hit.face)];
        if (seen[plane]) continue;
        seen[plane] = 1;
        score += plane_area_[plane];
      }
    return score;
  }

 private:
  const LitScene& scene_;
  double lit_;
  std::vector<std::size_t> plane_of_;
  std::vector<double> plane_area_;
};

}  // namespace

const char* kind_name(View::Kind kind) {
  switch (kind) {
    case View::Kind::declared: return "camera";
    case View::Kind::plan: return "plan";
    case View::Kind::room: return "room";
    case View::Kind::overview: return "overview";
  }
  return "view";
}

std::vector<View> automatic_views(const LitScene& scene, const std::vector<GridSpec>& grids, const ViewOptions& options) {
  const int up = up_axis(scene);
  const auto axes = plan_axes(up);
  const Vec3d forward_down = axis_vector(up, -1);
  const Vec3d right = axis_vector(axes[0]);
  std::vector<View> out;
  std::optional<LitSurfaceScore> score;
  if (options.exposure > 0) score.emplace(scene, options.exposure);
  const std::vector<Storey> storeys = find_storeys(scene, up);
  for (std::size_t s = 0; s < storeys.size(); ++s) {
    const Storey& st = storeys[s];
    const std::string storey_name = "storey" + std::to_string(s + 1);
    const double w = st.hi[0] - st.lo[0], d = st.hi[1] - st.lo[1];
    if (options.plans && w > 0 && d > 0) {
      // Cut at 0.45 of the ceiling height (1.2 m in a 2.7 m storey), as plans are drawn.
      const double cut = st.floor + 0.45 * st.height;
      View v;
      v.kind = View::Kind::plan;
      v.name = "plan_" + storey_name;
      const double margin = 0.03 * std::max(w, d);
      const double view_w = w + 2 * margin, view_d = d + 2 * margin;
      v.camera.orthographic = true;
      v.camera.eye = plan_point(up, axes, 0.5 * (st.lo[0] + st.hi[0]), 0.5 * (st.lo[1] + st.hi[1]), cut);
      v.camera.target = v.camera.eye + forward_down;
      v.camera.up = OpenMesh::cross(right, forward_down);
      v.camera.view_height = view_d;
      v.width = std::clamp(options.width * 5 / 4, 16, 8192);
      v.height = std::clamp(static_cast<int>(std::lround(v.width * view_d / view_w)), 16, 8192);
      v.description = fmt::format("plan of storey {} (floor at {:.3g}, ceiling height {:.3g}) cut at {:.3g}", s + 1,
                                  st.floor, st.height, cut);
      out.push_back(v);
    }
    if (!options.rooms) continue;
    const std::vector<Room> rooms = find_rooms(scene, up, st);
    for (std::size_t r = 0; r < rooms.size(); ++r) {
      const Room& room = rooms[r];
      View v;
      v.kind = View::Kind::room;
      const GridSpec* g = grid_at(grids, up, st, room.middle[0], room.middle[1]);
      v.name = g ? "room_" + g->name : storey_name + "_room" + std::to_string(r + 1);
      v.camera.target = plan_point(up, axes, room.middle[0], room.middle[1], st.floor + 0.3 * st.height);
      v.camera.up = axis_vector(up);
      v.camera.fov_degrees = 60;
      v.width = options.width;
      v.height = options.width * 3 / 4;
      // Of the room's corners, the one whose view shows the most lit surface (a corner
      // behind a cupboard, or at the end of an L, sees less); without an exposure, the
      // farthest from the middle.
      double best = -1;
      for (const auto& corner : room.corners) {
        View candidate = v;
        candidate.camera.eye = plan_point(up, axes, corner[0], corner[1], st.floor + 0.6 * st.height);
        const double seen = score ? (*score)(candidate) : 0;
        if (seen > best) {
          best = seen;
          v.camera.eye = candidate.camera.eye;
        }
      }
      v.description = fmt::format("{} of storey {} ({:.3g} square units), from a corner at eye height {:.3g}",
                                  g ? "room of grid " + g->name : "room " + std::to_string(r + 1), s + 1, room.area,
                                  0.6 * st.height);
      out.push_back(v);
    }
  }
  return out;
}

std::vector<View> overview_candidates(const LitScene& scene, int width, int height) {
  Bounds b;
  for (const Vec3d& p : scene.positions) b.extend(p);
  const Vec3d centre = (b.lo + b.hi) * 0.5, extent = b.extent();
  const double size = std::max({extent[0], extent[1], extent[2]});
  const int up = up_axis(scene);
  std::vector<View> out;
  for (int axis = 0; axis < 3; ++axis) {
    if (axis == up) continue;  // never look straight up or down
    for (int sign : {1, -1}) {
      const Vec3d dir = axis_vector(axis, sign);
      const Vec3d outside = centre - dir * (0.5 * extent[axis] + 1.5 * size);
      const Vec3d near_wall = centre - dir * (0.45 * extent[axis]);
      int k = 0;
      for (const Vec3d& eye : {outside, near_wall, centre}) {
        View v;
        v.kind = View::Kind::overview;
        v.camera = Camera{eye, eye + dir, axis_vector(up), k == 0 ? 40.0 : 70.0};
        v.width = width;
        v.height = height;
        static const char* where[3] = {"outside", "near_wall", "middle"};
        static const char* axis_names = "xyz";
        v.name = fmt::format("overview_{}_{}{}", where[k], sign > 0 ? "+" : "-", axis_names[axis]);
        v.description = fmt::format("looking along {}{} from {}", sign > 0 ? "+" : "-", axis_names[axis],
                                    k == 0 ? "outside the model" : k == 1 ? "near its side" : "its middle");
        out.push_back(v);
        ++k;
      }
    }
  }
  return out;
}

std::vector<View> merge_views(const std::vector<View>& declared, const std::vector<View>& automatic) {
  std::vector<View> out = declared;
  for (const View& v : automatic)
    if (std::none_of(declared.begin(), declared.end(), [&](const View& d) { return d.name == v.name; }))
      out.push_back(v);
  return out;
}

View best_lit_view(const LitScene& scene, const std::vector<View>& candidates, double exposure) {
  const LitSurfaceScore score(scene, exposure);
  View best = candidates.front();
  double best_score = -1;
  for (const View& v : candidates) {
    const double s = score(v);
    if (s > best_score) {
      best_score = s;
      best = v;
    }
  }
  return best;
}

}  // namespace dynrad::rad
