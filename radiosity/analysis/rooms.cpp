#include "radiosity/analysis/rooms.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <deque>
#include <limits>
#include <map>

namespace dynrad::rad {

namespace {

Vec3d face_normal(const LitScene& s, std::size_t f, double* area = nullptr) {
  const auto& t = s.triangles[f];
  const Vec3d n = OpenMesh::cross(s.positions[t[1]] - s.positions[t[0]], s.positions[t[2]] - s.positions[t[0]]);
  if (area) *area = 0.5 * n.norm();
  const double length = n.norm();
  return length > 0 ? n / length : Vec3d(0.0);
}

}  // namespace

Vec3d axis_vector(int axis, double sign) {
  Vec3d v(0.0);
  v[axis] = sign;
  return v;
}

Vec3d plan_point(int up, double x, double y, double height) {
  const auto [a, b] = plan_axes(up);
  Vec3d v(0.0);
  v[a] = x;
  v[b] = y;
  v[up] = height;
  return v;
}

int up_axis(const LitScene& scene) {
  Vec3d facing(0.0);
  for (std::size_t f = 0; f < scene.triangles.size(); ++f) {
    if (scene.emission[f].is_zero()) continue;
    double area = 0;
    const Vec3d n = face_normal(scene, f, &area);
    facing += n * area;
  }
  if (facing.norm() > 0) facing.normalize();
  Vec3d aims(0.0);
  for (const Luminaire& l : scene.luminaires) aims += l.nadir;
  if (aims.norm() > 0) aims.normalize();
  const Vec3d down = facing.norm() > 0 ? facing : aims;
  for (int a = 0; a < 3; ++a)
    if (down[a] < -0.7) return a;
  return 2;
}

std::array<int, 2> plan_axes(int up) {
  if (up == 0) return {1, 2};
  if (up == 1) return {0, 2};
  return {0, 1};
}

std::vector<Storey> find_storeys(const LitScene& scene, int up) {
  Bounds bounds;
  for (const Vec3d& p : scene.positions) bounds.extend(p);
  const double extent = bounds.extent()[up];
  if (!(extent > 0)) return {};
  const double bin = extent / 1000;
  const Vec3d upward = axis_vector(up);
  // Up-facing triangles with a down-facing surface above them.
  struct Floor {
    std::size_t face;
    double level, area, clearance;
  };
  std::vector<Floor> candidates(scene.triangles.size(), Floor{0, 0, 0, -1});
  tbb::parallel_for(std::size_t(0), scene.triangles.size(), [&](std::size_t f) {
    double area = 0;
    const Vec3d n = face_normal(scene, f, &area);
    if (!(area > 0) || OpenMesh::dot(n, upward) < 0.95) return;
    const auto& t = scene.triangles[f];
    const Vec3d c = (scene.positions[t[0]] + scene.positions[t[1]] + scene.positions[t[2]]) / 3.0;
    const auto hit = scene.visibility->intersect(c + upward * (1e-6 * scene.diagonal), upward);
    if (!hit.hit || !hit.front) return;
    candidates[f] = Floor{f, c[up], area, hit.distance};
  });
  std::map<long, double> by_bin;
  for (const Floor& c : candidates)
    if (c.clearance > 0) by_bin[static_cast<long>(std::floor(c.level / bin))] += c.area;
  double largest = 0;
  for (const auto& [k, area] : by_bin) largest = std::max(largest, area);
  std::vector<Storey> storeys;
  for (const auto& [k, area] : by_bin) {
    if (area < 0.2 * largest) continue;
    // The floor level: the area-weighted mean height in the bin; the ceiling height: the
    // area-weighted median clearance of its triangles.
    std::vector<std::pair<double, double>> clearances;  // (clearance, area)
    double level = 0, sum = 0;
    Storey s;
    s.lo = {std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
    s.hi = {-s.lo[0], -s.lo[1]};
    const auto axes = plan_axes(up);
    for (const Floor& c : candidates) {
      if (c.clearance <= 0 || static_cast<long>(std::floor(c.level / bin)) != k) continue;
      level += c.level * c.area;
      sum += c.area;
      clearances.emplace_back(c.clearance, c.area);
      for (std::uint32_t corner : scene.triangles[c.face])
        for (int i = 0; i < 2; ++i) {
          s.lo[i] = std::min(s.lo[i], scene.positions[corner][axes[i]]);
          s.hi[i] = std::max(s.hi[i], scene.positions[corner][axes[i]]);
        }
    }
    s.floor = level / sum;
    std::sort(clearances.begin(), clearances.end());
    double below = 0;
    for (const auto& [clearance, share] : clearances) {
      below += share;
      if (below >= 0.5 * sum) {
        s.height = clearance;
        break;
      }
    }
    if (!storeys.empty() && s.floor <= storeys.back().floor + 0.8 * storeys.back().height) {
      // Part of the storey below (a raised floor, a bed): widen its extent only.
      for (int i = 0; i < 2; ++i) {
        storeys.back().lo[i] = std::min(storeys.back().lo[i], s.lo[i]);
        storeys.back().hi[i] = std::max(storeys.back().hi[i], s.hi[i]);
      }
      continue;
    }
    storeys.push_back(s);
  }
  return storeys;
}

std::vector<Room> find_rooms(const LitScene& scene, int up, const Storey& storey) {
  const auto axes = plan_axes(up);
  const double h = storey.height;
  const double w = storey.hi[0] - storey.lo[0], d = storey.hi[1] - storey.lo[1];
  if (!(h > 0 && w > 0 && d > 0)) return {};
  const double cell = std::max({w / 400, d / 400, h / 30});
  const long nx = std::max(1L, static_cast<long>(std::ceil(w / cell))), ny = std::max(1L, static_cast<long>(std::ceil(d / cell)));
  const double eye = storey.floor + 0.6 * h;
  auto at = [&](long i, long j) {
    Vec3d p(0.0);
    p[axes[0]] = storey.lo[0] + (i + 0.5) * cell;
    p[axes[1]] = storey.lo[1] + (j + 0.5) * cell;
    p[up] = eye;
    return p;
  };
  const Vec3d upward = axis_vector(up), downward = axis_vector(up, -1);
  const Vec3d east = axis_vector(axes[0]), north = axis_vector(axes[1]);
  const std::size_t n = static_cast<std::size_t>(nx * ny);
  std::vector<char> free(n, 0), open_east(n, 0), open_north(n, 0);
  tbb::parallel_for(0L, ny, [&](long j) {
    for (long i = 0; i < nx; ++i) {
      const Vec3d p = at(i, j);
      const auto above = scene.visibility->intersect(p, upward);
      const auto below = scene.visibility->intersect(p, downward);
      const std::size_t k = static_cast<std::size_t>(j * nx + i);
      free[k] = above.hit && above.front && above.distance < 1.5 * h && below.hit && below.front;
      const auto e = scene.visibility->intersect(p, east);
      const auto nn = scene.visibility->intersect(p, north);
      open_east[k] = !e.hit || e.distance > cell;
      open_north[k] = !nn.hit || nn.distance > cell;
    }
  });
  auto index = [&](long i, long j) { return static_cast<std::size_t>(j * nx + i); };
  // Whether one may step from (i, j) by (di, dj) (4-neighbours): both free, nothing between.
  auto passable = [&](long i, long j, int di, int dj) {
    const long i2 = i + di, j2 = j + dj;
    if (i2 < 0 || j2 < 0 || i2 >= nx || j2 >= ny) return false;
    if (!free[index(i, j)] || !free[index(i2, j2)]) return false;
    if (di == 1) return open_east[index(i, j)] != 0;
    if (di == -1) return open_east[index(i2, j2)] != 0;
    if (dj == 1) return open_north[index(i, j)] != 0;
    return open_north[index(i2, j2)] != 0;
  };
  static const int steps[4][2] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}};
  // Distance to the nearest obstacle: 0 on cells that are not free, half a cell on free
  // cells with a closed side, then two chamfer passes (1 and sqrt 2 cells).
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<double> dist(n, inf);
  for (long j = 0; j < ny; ++j)
    for (long i = 0; i < nx; ++i) {
      if (!free[index(i, j)]) {
        dist[index(i, j)] = 0;
        continue;
      }
      for (const auto& s : steps)
        if (!passable(i, j, s[0], s[1])) dist[index(i, j)] = 0.5 * cell;
    }
  const double diagonal_step = std::sqrt(2.0) * cell;
  auto relax = [&](long i, long j, long i2, long j2, double step) {
    if (i2 < 0 || j2 < 0 || i2 >= nx || j2 >= ny) return;
    dist[index(i, j)] = std::min(dist[index(i, j)], dist[index(i2, j2)] + step);
  };
  for (long j = 0; j < ny; ++j)
    for (long i = 0; i < nx; ++i) {
      relax(i, j, i - 1, j, cell);
      relax(i, j, i, j - 1, cell);
      relax(i, j, i - 1, j - 1, diagonal_step);
      relax(i, j, i + 1, j - 1, diagonal_step);
    }
  for (long j = ny - 1; j >= 0; --j)
    for (long i = nx - 1; i >= 0; --i) {
      relax(i, j, i + 1, j, cell);
      relax(i, j, i, j + 1, cell);
      relax(i, j, i + 1, j + 1, diagonal_step);
      relax(i, j, i - 1, j + 1, diagonal_step);
    }
  const double erosion = 0.2 * h;
  // Cores: connected eroded cells; then every free cell joins the core that reaches it
  // first through free space.
  std::vector<int> label(n, -1);
  std::vector<std::vector<std::size_t>> cores;
  for (long j = 0; j < ny; ++j)
    for (long i = 0; i < nx; ++i) {
      if (label[index(i, j)] >= 0 || !free[index(i, j)] || dist[index(i, j)] < erosion) continue;
      const int id = static_cast<int>(cores.size());
      cores.emplace_back();
      std::deque<std::pair<long, long>> queue{{i, j}};
      label[index(i, j)] = id;
      while (!queue.empty()) {
        const auto [ci, cj] = queue.front();
        queue.pop_front();
        cores.back().push_back(index(ci, cj));
        for (const auto& s : steps) {
          const long i2 = ci + s[0], j2 = cj + s[1];
          if (!passable(ci, cj, s[0], s[1]) || label[index(i2, j2)] >= 0 || dist[index(i2, j2)] < erosion) continue;
          label[index(i2, j2)] = id;
          queue.emplace_back(i2, j2);
        }
      }
    }
  std::deque<std::pair<long, long>> queue;
  for (long j = 0; j < ny; ++j)
    for (long i = 0; i < nx; ++i)
      if (label[index(i, j)] >= 0) queue.emplace_back(i, j);
  while (!queue.empty()) {
    const auto [ci, cj] = queue.front();
    queue.pop_front();
    for (const auto& s : steps) {
      const long i2 = ci + s[0], j2 = cj + s[1];
      if (!passable(ci, cj, s[0], s[1]) || label[index(i2, j2)] >= 0) continue;
      label[index(i2, j2)] = label[index(ci, cj)];
      queue.emplace_back(i2, j2);
    }
  }
  std::vector<Room> rooms(cores.size());
  std::vector<double> count(cores.size(), 0);
  for (long j = 0; j < ny; ++j)
    for (long i = 0; i < nx; ++i) {
      const int id = label[index(i, j)];
      if (id < 0) continue;
      rooms[id].middle[0] += storey.lo[0] + (i + 0.5) * cell;
      rooms[id].middle[1] += storey.lo[1] + (j + 0.5) * cell;
      count[id] += 1;
    }
  std::vector<Room> out;
  const double smallest = 0.1 * h * h;  // 0.73 m^2 in a 2.7 m storey
  for (std::size_t id = 0; id < cores.size(); ++id) {
    Room& r = rooms[id];
    r.area = count[id] * cell * cell;
    if (cores[id].size() < 4 || r.area < smallest) continue;
    r.middle = {r.middle[0] / count[id], r.middle[1] / count[id]};
    std::array<double, 4> farthest{-1, -1, -1, -1};
    std::array<std::array<double, 2>, 4> point{};
    for (std::size_t k : cores[id]) {
      const double x = storey.lo[0] + (static_cast<double>(k % nx) + 0.5) * cell;
      const double y = storey.lo[1] + (static_cast<double>(k / nx) + 0.5) * cell;
      const double d2 = (x - r.middle[0]) * (x - r.middle[0]) + (y - r.middle[1]) * (y - r.middle[1]);
      const int quarter = (x >= r.middle[0] ? 1 : 0) + (y >= r.middle[1] ? 2 : 0);
      if (d2 > farthest[quarter]) {
        farthest[quarter] = d2;
        point[quarter] = {x, y};
      }
    }
    std::array<int, 4> order{0, 1, 2, 3};
    std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return farthest[a] > farthest[b]; });
    for (int q : order)
      if (farthest[q] >= 0) r.corners.push_back(point[q]);
    r.corner = r.corners.front();
    out.push_back(r);
  }
  return out;
}

}  // namespace dynrad::rad
