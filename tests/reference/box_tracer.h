// An independent Monte Carlo reference for radiosity in scenes of axis-aligned boxes.
//
// It shares no code with the solver (only the C++ standard library), so that the
// physics tests and benchmarks can compare the solver against something it did not
// compute. Surfaces are grey (one channel) and diffuse; units are metres and W/m^2.
//
//   BoxScene scene;
//   const int room = scene.add_room({0, 0, 0}, {10, 6, 3}, Reflectances::walls_floor_ceiling(0.5, 0.3, 0.7));
//   scene.add_emitter(room, Face::plus_z, {4.75, 2.75, 3}, {5.25, 3.25, 3}, 31.416);
//   TraceOptions options;                      // 0.1% relative standard error by default
//   Estimate b = radiosity(scene, {2.25, 1.25, 0}, {0, 0, 1}, options);   // b.value, b.std_error
//
// How it computes (box_tracer.cpp has the details):
// - irradiance H = direct + indirect. Direct light from each emitter is exact: Lambert's
//   contour integral over the part of the emitter above the receiver's horizon, minus the
//   parts that solid boxes (or the walls of other rooms) hide, cut out exactly as polygons.
// - indirect light is a path-traced estimate: cosine-weighted directions, first hit by
//   ray/box slabs, the exact direct light at each hit times its reflectance, Russian
//   roulette once the path's throughput is low. Light arriving at an
//   emitter is absorbed; an emitter's own emission is never picked up by a path (the
//   direct term counts it).
// - randomised quasi-Monte Carlo: independent replicates, each a randomly shifted and
//   shuffled Sobol' point set, so the standard error comes from the spread of the
//   replicates and is honest even though the points are stratified.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

namespace dynrad_test::reference {

struct Vec3 {
  double x = 0, y = 0, z = 0;
  double operator[](int axis) const { return axis == 0 ? x : (axis == 1 ? y : z); }
  double& operator[](int axis) { return axis == 0 ? x : (axis == 1 ? y : z); }
};

// The six faces of a box, by the axis and side they lie on. z is up: minus_z is the
// floor of a room and the bottom of a solid, plus_z the ceiling of a room and the top of
// a solid.
enum class Face { minus_x, plus_x, minus_y, plus_y, minus_z, plus_z };

// Reflectance of each face, indexed by Face, each in [0, 1).
struct Reflectances {
  std::array<double, 6> of_face{};
  static Reflectances uniform(double rho);
  // The four vertical faces `walls`, minus_z `floor`, plus_z `ceiling`.
  static Reflectances walls_floor_ceiling(double walls, double floor, double ceiling);
};

// An axis-aligned rectangle on a face of a box that emits `exitance` (W/m^2) on the
// face's side. It reflects `reflectance` (0 for a lamp), instead of the face's own.
// The rectangle is open: its edges belong to the surrounding face.
struct Emitter {
  int box = 0;
  Face face = Face::plus_z;
  Vec3 lo, hi;  // opposite corners; lo[axis] == hi[axis] == the face's plane
  double exitance = 0;
  double reflectance = 0;
};

// Boxes are either rooms (faces point inward: the scene is inside them) or solids
// (faces point outward: partitions, furniture). Only the front of a face reflects; a
// ray reaching the back of a face is absorbed. Emitters on one face may not overlap.
// Every add_ checks its arguments and throws std::invalid_argument naming the problem.
class BoxScene {
 public:
  struct Box {
    Vec3 lo, hi;
    bool room = false;
    Reflectances reflectance;
  };

  // Both return the new box's index.
  int add_room(const Vec3& lo, const Vec3& hi, const Reflectances& reflectance);
  int add_solid(const Vec3& lo, const Vec3& hi, const Reflectances& reflectance);
  // The rectangle [lo, hi] on face `face` of box `box`.
  void add_emitter(int box, Face face, const Vec3& lo, const Vec3& hi, double exitance, double reflectance = 0);
  // The whole face.
  void add_emitter(int box, Face face, double exitance, double reflectance = 0);

  const std::vector<Box>& boxes() const { return boxes_; }
  const std::vector<Emitter>& emitters() const { return emitters_; }

 private:
  int add_box(const Vec3& lo, const Vec3& hi, bool room, const Reflectances& reflectance);
  std::vector<Box> boxes_;
  std::vector<Emitter> emitters_;
};

// A Monte Carlo answer: the mean, its standard error (same units) and the number of
// paths traced (0 when the answer is exact).
struct Estimate {
  double value = 0;
  double std_error = 0;
  std::int64_t samples = 0;
};

struct TraceOptions {
  std::uint64_t seed = 1;
  // Trace until std_error <= target_relative_error * |value| (after at least
  // min_replicates replicates), or max_samples paths.
  double target_relative_error = 1e-3;
  std::int64_t max_samples = std::int64_t{1} << 28;
  // If > 0: trace this many paths (rounded up to whole replicates, at least two) and
  // ignore the target.
  std::int64_t samples = 0;
  // Paths per replicate: a power of two (a randomised Sobol' net). The standard error
  // is the spread of the replicates' means, so it needs many: with 1024 paths and 16 at
  // first, errors at 0.1% came out 10% small (the stopping rule trusts a rough error);
  // with 64 and 128, (error / reported error)^2 averaged 1.04 over 1500 seeds (1.10
  // with 256 and 32), for the same paths per second and paths to 0.1%.
  int paths_per_replicate = 64;
  int min_replicates = 128;
  // Russian roulette: a path goes on carrying its throughput (the product of the
  // reflectances it met) while that is at least roulette_below; below, it survives with
  // probability throughput / roulette_below. 1 makes the survival probability each
  // reflectance met; 0.25 (about three bounces before roulette in a room of
  // reflectance 0.5) reached 0.1% 1.5 to 3 times sooner in the globillum rooms.
  double roulette_below = 0.25;
  // Worker threads (0: all cores). Results do not depend on it.
  int threads = 0;
};

// Radiosity B = E + rho * H (W/m^2) at `point` on a surface whose front faces `normal`
// (the point must lie on a box face with that normal, else std::invalid_argument).
// Reproducible for a given seed; the random streams depend on the seed and the point,
// so errors at different points are independent.
Estimate radiosity(const BoxScene& scene, const Vec3& point, const Vec3& normal, const TraceOptions& options = {});

// Irradiance H (W/m^2) arriving at `point` on the side that `normal` faces: on a
// surface or in mid-air.
Estimate irradiance(const BoxScene& scene, const Vec3& point, const Vec3& normal, const TraceOptions& options = {});

// Only the direct part of the irradiance (W/m^2), exact: no sampling.
double direct_irradiance(const BoxScene& scene, const Vec3& point, const Vec3& normal);

// Many radiosity queries at once, in parallel across points (options.threads workers,
// each point traced on one thread): the same answers as one radiosity() call per point.
struct SurfacePoint {
  Vec3 point, normal;
};
std::vector<Estimate> radiosity(const BoxScene& scene, const std::vector<SurfacePoint>& points,
                                const TraceOptions& options = {});

}  // namespace dynrad_test::reference
