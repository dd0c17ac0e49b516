// An independent path tracer for triangle meshes: the accuracy reference for
// illuminance in real models (an architect's house), where the box tracer
// (box_tracer.h) cannot go.
//
// It shares no code with the solver: nothing from mesh/ or radiosity/ is included or
// linked. Rays are Embree 3's; the PLY reader is its own. Units are those of the input
// (metres; lm and lx, or W and W/m^2).
//
//   mesh_tracer::Scene scene = mesh_tracer::read_ply("house_clean.ply");
//   scene.lights.push_back({{4.0, 2.1, 2.3}, 1500});        // 1500 lm, isotropic
//   const mesh_tracer::Tracer tracer(std::move(scene));
//   mesh_tracer::Estimate e = tracer.illuminance({3, 2, 0.8}, {0, 0, 1}, {});  // e.value, e.std_error
//
// What it models (the solver's conventions, so that comparisons are fair):
// - every triangle reflects diffusely (Lambert) on its front only, the side from which
//   its corners run counter-clockwise (normal (b - a) x (c - a)); light reaching a back
//   face is absorbed; light that meets nothing leaves the scene;
// - three colour channels; illuminance is the Rec. 709 luminance of the RGB irradiance;
// - point lights are white and isotropic (I = flux / 4 pi in every channel); triangles
//   may emit a Lambertian exitance from their front.
//
// How it computes (mesh_tracer.cpp has the details): the direct light of the point
// lights at the query is exact (I cos / d^2, one shadow ray each); the rest is a path
// estimate: cosine-weighted bounces, at every vertex the exact point-light term and one
// area sample of the emitting triangles (multiple importance sampling with the bounce
// direction), Russian roulette. Replicates of independent paths give the standard
// error; each point's random stream depends only on the seed and the point's index, so
// answers do not depend on the number of threads.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace dynrad_test::mesh_tracer {

struct Vec3 {
  double x = 0, y = 0, z = 0;
};

using Rgb = std::array<double, 3>;

// Rec. 709 luminance of linear RGB.
inline constexpr Rgb kLuminanceWeights{0.2126, 0.7152, 0.0722};

struct Triangle {
  std::array<Vec3, 3> corners;  // counter-clockwise seen from the front
  Rgb reflectance{};            // each channel in [0, 1]
  Rgb exitance{};               // emitted from the front, Lambertian (W/m^2 or lm/m^2)
};

struct PointLight {
  Vec3 position;
  double flux = 0;  // lm (or W) in every channel; intensity flux / (4 pi)
};

struct Scene {
  std::vector<Triangle> triangles;
  std::vector<PointLight> lights;
};

// The triangles of a PLY file as `dynrad clean` writes it: vertices with x, y, z and
// reflectance_r, reflectance_g, reflectance_b (other properties are ignored), faces as
// vertex index lists, all triangles. ASCII or binary of either byte order. A
// triangle's reflectance is the mean of its corners' (vertices are split at material
// borders, so they agree). The PLY carries no emission. Throws std::runtime_error
// starting with the path and saying what is wrong.
Scene read_ply(const std::string& path);

// A Monte Carlo answer. value = direct + indirect; direct (point lights, exact) has no
// error, indirect (everything else, emitting triangles included) has std_error.
struct Estimate {
  double value = 0;
  double std_error = 0;
  double direct = 0;
  double indirect = 0;
  std::int64_t paths = 0;
  // The share of the paths whose first ray met the back of a face: a point inside a
  // solid (or inside a wall) sees mostly backs, and gets no light through them.
  double back_share = 0;
};

struct TraceOptions {
  std::uint64_t seed = 1;
  // Trace until std_error <= target_relative_error * value (after at least
  // min_replicates replicates) or until max_paths paths.
  double target_relative_error = 3e-3;
  std::int64_t max_paths = std::int64_t{1} << 26;
  // If > 0: trace this many paths (rounded up to whole replicates, at least two) and
  // ignore the target.
  std::int64_t paths = 0;
  // Independent paths per replicate; the standard error is the spread of the
  // replicates' means, so there must be enough of them to estimate it (and to keep
  // the stopping rule, which trusts that estimate, from stopping on a lucky low one).
  int paths_per_replicate = 256;
  int min_replicates = 64;
  // Russian roulette: a path carries its throughput (the product of the reflectances
  // met, largest channel) while that is at least roulette_below; below, it survives
  // with probability throughput / roulette_below and is scaled up to make up for it.
  double roulette_below = 0.25;
  // A ray leaving a surface starts this far (times the scene's bounding-box diagonal)
  // in front of it, because Embree intersects in float; it also ignores the triangle it
  // leaves. (Rays from the query point start at the point.)
  double ray_offset = 1e-4;
  // Worker threads (0: all cores). Answers do not depend on it.
  int threads = 0;
  // Called after each round of replicates of a point (from worker threads, so it must
  // be thread-safe), with the point's index, its estimate so far and whether it is
  // finished.
  std::function<void(std::size_t point, const Estimate& so_far, bool finished)> progress;
};

// The scene put into Embree once, then queried from any number of threads.
class Tracer {
 public:
  // Checks the scene (finite coordinates, reflectance in [0, 1], exitance and flux >= 0,
  // at least one usable triangle) and throws std::invalid_argument naming the problem.
  // Triangles of zero area are left out (degenerate_triangles() counts them).
  // build_threads: Embree's threads for building its tree (0: all cores).
  explicit Tracer(Scene scene, int build_threads = 0);
  ~Tracer();
  Tracer(const Tracer&) = delete;
  Tracer& operator=(const Tracer&) = delete;

  // Illuminance at `point` on the side that `normal` faces. The point is taken to be in
  // mid-air: its rays start at it (ignoring hits nearer than 1e-7 of the scene's size),
  // so for a point on a surface, lift it off a little. `stream` picks the random stream
  // with the seed (point i of a list uses i).
  Estimate illuminance(const Vec3& point, const Vec3& normal, const TraceOptions& options,
                       std::uint64_t stream = 0) const;
  // Many points, all facing `normal`, in parallel across points (each on one thread):
  // the same answers as illuminance(points[i], normal, options, i).
  std::vector<Estimate> illuminance(const std::vector<Vec3>& points, const Vec3& normal,
                                    const TraceOptions& options) const;
  // Only the point lights' direct illuminance, exact.
  double direct_illuminance(const Vec3& point, const Vec3& normal) const;

  std::size_t triangle_count() const;  // used ones
  std::size_t degenerate_triangles() const;
  double scene_size() const;  // bounding-box diagonal of the triangles

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace dynrad_test::mesh_tracer
