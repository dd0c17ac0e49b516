// EN 12464-1 checks per room (see room_checks.h).
#include "radiosity/design/room_checks.h"

#include "radiosity/transfer/random.h"
#include "radiosity/analysis/rooms.h"

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace dynrad::rad {

namespace {

// A point of a surface to gather at, and the way it faces.
struct Sample {
  Vec3d position, normal;
};

std::vector<GridPointResult> gather(const LitScene& scene, const std::vector<Sample>& samples,
                                    const GatherOptions& options, std::uint64_t salt) {
  std::vector<GridPointResult> out(samples.size());
  tbb::parallel_for(std::size_t(0), samples.size(), [&](std::size_t k) {
    out[k] = gather_point(scene, samples[k].position, samples[k].normal, options, mix(options.seed ^ mix(salt + k)));
  });
  return out;
}

// Em and U0 of a surface as two checks.
void add_checks(std::vector<Check>& checks, const std::string& area, const PointStatistics& f, double eavg,
                double u0, const std::string& clause) {
  Check em{area, "Em", f.e_avg, f.count > 0, "lx", Check::Relation::at_least, eavg, 0, clause};
  Check uniformity{area, "U0", f.u0, f.count > 0, "", Check::Relation::at_least, u0, 0, clause};
  if (f.count == 0) em.note = uniformity.note = "no point to measure (every one inside a solid)";
  checks.push_back(em);
  checks.push_back(uniformity);
}

// Distance along `dir` from `origin` to the first surface, or 0 when none.
double distance_to_surface(const LitScene& scene, const Vec3d& origin, const Vec3d& dir) {
  const Visibility::Intersection hit = scene.visibility->intersect(origin, dir);
  return hit.hit ? hit.distance : 0.0;
}

}  // namespace

RoomResult check_room(const LitScene& scene, const GridResult& task, const std::vector<ObserverGlare>& observers,
                      const GatherOptions& options) {
  const GridSpec& spec = task.spec;
  const RoomTargets& targets = spec.room;
  RoomResult room;
  room.name = spec.name;
  const int up_axis = spec.up;
  const Vec3d up = axis_vector(up_axis);
  const auto& polygon = spec.polygon;

  // Floor and ceiling, straight down and up from the polygon's middle (its vertex mean
  // when that lies inside, else the first task point).
  double mx = 0, my = 0;
  for (const auto& p : polygon) {
    mx += p[0] / polygon.size();
    my += p[1] / polygon.size();
  }
  if (!inside_polygon(polygon, mx, my) && !task.points.empty()) {
    const auto [a, b] = plan_axes(up_axis);
    mx = task.points.front().position[a];
    my = task.points.front().position[b];
  }
  const Vec3d middle = plan_point(up_axis, mx, my, spec.height);
  const double down = distance_to_surface(scene, middle, -up), above = distance_to_surface(scene, middle, up);
  room.floor = spec.height - down;
  room.ceiling = above > 0 ? spec.height + above : 0;

  if (spec.target_eavg > 0)
    room.checks.push_back({"task area", "Em", task.e_avg, task.count > 0, "lx", Check::Relation::at_least,
                           spec.target_eavg, 0, "EN 12464-1:2021, maintained illuminance"});
  if (spec.target_u0 > 0)
    room.checks.push_back({"task area", "U0", task.u0, task.count > 0, "", Check::Relation::at_least, spec.target_u0,
                           0, "EN 12464-1:2021, uniformity"});

  // The immediate surrounding: a band between border - width and border from the edges.
  if (targets.surrounding > 0) {
    GridSpec band = spec;
    band.border = 0;
    const double width = std::min(targets.surrounding, spec.border);
    band.spacing = std::min(task.spacing > 0 ? task.spacing : automatic_spacing(1), width / 2);
    const double inner = spec.border - width;
    std::vector<Sample> samples;
    const auto [a, b] = plan_axes(up_axis);
    for (const Vec3d& p : grid_points(band)) {
      const double d = polygon_edge_distance(polygon, p[a], p[b]);
      if (d >= inner - 1e-12 && d < spec.border - 1e-12) samples.push_back({p, up});
    }
    room.surrounding = point_statistics(gather(scene, samples, options, 0x5A11ull << 20));
    const double eavg = targets.surrounding_eavg > 0 ? targets.surrounding_eavg : surrounding_illuminance(spec.target_eavg);
    if (eavg > 0)
      room.checks.push_back({"surrounding", "Em", room.surrounding.e_avg, room.surrounding.count > 0, "lx",
                             Check::Relation::at_least, eavg, 0, "EN 12464-1:2021, the surrounding's Em from the task's"});
    room.checks.push_back({"surrounding", "U0", room.surrounding.u0, room.surrounding.count > 0, "",
                           Check::Relation::at_least, targets.surrounding_u0, 0, "EN 12464-1:2021, uniformity"});
  }

  const double height = room.ceiling - room.floor;
  const double inset = 0.01;
  if ((targets.walls || targets.ceiling) && !(room.ceiling > 0)) {
    for (const char* area : {"walls", "ceiling"})
      if (std::string(area) == "walls" ? targets.walls : targets.ceiling)
        room.checks.push_back({area, "Em", 0, false, "lx", Check::Relation::at_least,
                               std::string(area) == "walls" ? targets.walls_eavg : targets.ceiling_eavg, 0,
                               "no ceiling above the grid: nothing to measure"});
  } else {
    if (targets.walls) {
      // Counter-clockwise or not: the inward side of each edge from the signed area.
      double area = 0;
      for (std::size_t i = 0, j = polygon.size() - 1; i < polygon.size(); j = i++)
        area += polygon[j][0] * polygon[i][1] - polygon[i][0] * polygon[j][1];
      const double sense = area > 0 ? 1 : -1;
      std::vector<Sample> samples;
      for (std::size_t i = 0, j = polygon.size() - 1; i < polygon.size(); j = i++) {
        const double ax = polygon[j][0], ay = polygon[j][1], dx = polygon[i][0] - ax, dy = polygon[i][1] - ay;
        const double length = std::hypot(dx, dy);
        if (!(length > 0)) continue;
        const double nx = -dy / length * sense, ny = dx / length * sense;
        const double p = automatic_spacing(std::max(length, height));
        const long nu = std::max(1L, static_cast<long>(std::ceil(length / p - 1e-9)));
        const long nv = std::max(1L, static_cast<long>(std::ceil(height / p - 1e-9)));
        const Vec3d normal = plan_point(up_axis, nx, ny, 0);
        for (long v = 0; v < nv; ++v)
          for (long u = 0; u < nu; ++u) {
            const double s = (u + 0.5) / nu;
            samples.push_back({plan_point(up_axis, ax + s * dx + inset * nx, ay + s * dy + inset * ny,
                                          room.floor + (v + 0.5) * height / nv),
                               normal});
          }
      }
      room.walls = point_statistics(gather(scene, samples, options, 0x3A115ull << 20));
      add_checks(room.checks, "walls", room.walls, targets.walls_eavg, targets.walls_u0, "EN 12464-1:2021, walls and ceiling");
    }
    if (targets.ceiling) {
      GridSpec top = spec;
      top.border = 0;
      top.height = room.ceiling - inset;
      top.spacing = 0;
      std::vector<Sample> samples;
      for (const Vec3d& p : grid_points(top)) samples.push_back({p, -up});
      room.ceiling_surface = point_statistics(gather(scene, samples, options, 0xCE11ull << 20));
      add_checks(room.checks, "ceiling", room.ceiling_surface, targets.ceiling_eavg, targets.ceiling_u0,
                 "EN 12464-1:2021, walls and ceiling");
    }
  }

  // Cylindrical illuminance and modelling over the task area at the eye's height.
  if (targets.ez > 0) {
    GridSpec eye = spec;
    eye.height = room.floor + targets.ez_height;
    const std::vector<Vec3d> points = grid_points(eye);
    std::vector<GridPointResult> ez(points.size()), eh(points.size());
    tbb::parallel_for(std::size_t(0), points.size(), [&](std::size_t k) {
      const std::uint64_t seed = mix(options.seed ^ mix((0xE2ull << 20) + k));
      eh[k] = gather_point(scene, points[k], up, options, seed);
      ez[k] = eh[k].masked ? eh[k] : gather_cylindrical(scene, points[k], up, options, mix(seed));
    });
    room.cylindrical = point_statistics(ez);
    double sum = 0;
    std::size_t n = 0;
    room.modelling_min = std::numeric_limits<double>::infinity();
    for (std::size_t k = 0; k < points.size(); ++k) {
      if (ez[k].masked || !(eh[k].illuminance > 0)) continue;
      const double m = ez[k].illuminance / eh[k].illuminance;
      sum += m;
      ++n;
      room.modelling_min = std::min(room.modelling_min, m);
      room.modelling_max = std::max(room.modelling_max, m);
    }
    if (n == 0) room.modelling_min = 0;
    room.modelling = n > 0 ? sum / n : 0;
    const std::string at = fmt::format("task area at {:g} m", targets.ez_height);
    room.checks.push_back({at, "Ez", room.cylindrical.e_avg, room.cylindrical.count > 0, "lx",
                           Check::Relation::at_least, targets.ez, 0, "EN 12464-1:2021, cylindrical illuminance"});
    room.checks.push_back({at, "U0 (Ez)", room.cylindrical.u0, room.cylindrical.count > 0, "",
                           Check::Relation::at_least, targets.ez_u0, 0, "EN 12464-1:2021, cylindrical illuminance"});
    Check modelling{at, "Ez/Eh", room.modelling, n > 0, "", Check::Relation::within, targets.modelling_low,
                    targets.modelling_high,
                    fmt::format("EN 12464-1:2021, modelling; the mean of {} points, from {:.2f} to {:.2f}", n,
                                room.modelling_min, room.modelling_max)};
    room.checks.push_back(modelling);
  }

  // Glare: the worst observer over the room's floor.
  if (targets.ugr > 0) {
    const auto [a, b] = plan_axes(up_axis);
    double worst = -std::numeric_limits<double>::infinity();
    bool any = false, all_defined = true;
    for (const ObserverGlare& o : observers) {
      if (!inside_polygon(polygon, o.eye[a], o.eye[b])) continue;
      if (room.ceiling > 0 && (o.eye[up_axis] < room.floor || o.eye[up_axis] > room.ceiling)) continue;
      room.observers.push_back(o.name);
      any = true;
      if (!o.defined) {
        all_defined = false;
        continue;
      }
      worst = std::max(worst, o.ugr);
    }
    Check ugr{"observers", "UGR", any && worst > -1e300 ? worst : 0, any && worst > -1e300, "", Check::Relation::at_most,
              targets.ugr, 0, "EN 12464-1:2021, UGR limit; the largest of the observers in the room"};
    if (!any) {
      ugr.note = "no observer stands in the room: add one to the scene's \"observers\"";
    } else if (!ugr.defined) {
      // No luminaire in anyone's view: no discomfort glare from the installation.
      ugr.defined = true;
      ugr.value = 0;
      ugr.note = "no luminaire is in view of the observers in the room (UGR below 10)";
    } else if (!all_defined) {
      ugr.note += "; some observers see no luminaire";
    }
    room.checks.push_back(ugr);
  }
  return room;
}

}  // namespace dynrad::rad
