// The solve's error estimate (Solver::estimate_error) against errors measured from
// something independent: the path-traced reference of the 1990 room
// (tests/data/globillum_room_reference.txt, written by tests/reference/box_reference,
// 0.1% standard error per point) and the furnace's closed form. The estimate is what
// the defaults stop by, so it must not promise more than the solve delivers.
#include "mesh/load.h"
#include "mesh/core/refinement.h"
#include "radiosity/analysis/probe.h"
#include "radiosity/solver/settings.h"
#include "radiosity/solver/solver.h"
#include "test_support.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <functional>
#include <sstream>

namespace dynrad {
namespace {

using rad::Method;
using rad::Quality;

struct ReferencePoint {
  Vec3d point, normal;
  double radiosity = 0, std_error = 0;
};

// The comparison grid without the four ceiling points on the source's corners (there
// the solver's mesh has the source's vertex, whose value is the source's).
std::vector<ReferencePoint> globillum_reference(const std::string& file = "globillum_room_reference.txt") {
  std::ifstream in(std::string(DYNRAD_TEST_DATA_DIR) + "/" + file);
  EXPECT_TRUE(in.good());
  std::vector<ReferencePoint> out;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream f(line);
    std::string surface;
    double x, y, z, b, sigma;
    f >> surface >> x >> y >> z >> b >> sigma;
    if (surface == "ceiling" && (x == 4.75 || x == 5.25) && (y == 2.75 || y == 3.25)) continue;
    // The normal into the room, from the surface's name (tests/reference/globillum_room.h).
    const Vec3d normal(surface == "wall_x0" ? 1 : surface == "wall_x10" ? -1 : 0,
                       surface == "wall_y0" ? 1 : surface == "wall_y6" ? -1 : 0,
                       surface == "floor" ? 1 : surface == "ceiling" ? -1 : 0);
    out.push_back({Vec3d(x, y, z), normal, b, sigma});
  }
  return out;
}

struct Solved {
  LoadedScene scene;
  std::unique_ptr<ElementHierarchy> hierarchy;
  std::unique_ptr<rad::Solver> solver;
  rad::SolveReport report;
};

// As `dynrad solve MODEL --quality Q` does it, with `extra` applied to the request and
// then `adjust` to the solve's options.
Solved solve_like_the_command_line(const std::string& model, Quality quality,
                                   const rad::SettingsRequest& extra = {},
                                   const std::function<void(rad::SolveOptions&)>& adjust = {}) {
  Solved s;
  SimplifyOptions simplify;
  simplify.enabled = true;
  s.scene = load_scene(model, {}, simplify);
  rad::RefineSettings refine;
  refine.method = Method::dynamic;
  rad::SolveOptions options;
  options.ambient_display = true;
  rad::SettingsRequest request = extra;
  request.quality = quality;
  const rad::AppliedSettings applied = rad::apply_settings(*s.scene.mesh, request, refine, options);
  if (adjust) adjust(options);
  make_patches(*s.scene.mesh, applied.patch_size);
  const RefinementOptions refinement = refinement_for_patch_size(applied.patch_size);
  s.hierarchy = std::make_unique<ElementHierarchy>(*s.scene.mesh, refinement);
  s.solver = std::make_unique<rad::Solver>(*s.scene.mesh, *s.hierarchy, options, refine);
  s.report = s.solver->run();
  return s;
}

// What the reference's own noise adds to a mean error measured against it: the mean of
// |a normal deviate| is sqrt(2 / pi) times its standard deviation.
double reference_noise(const std::vector<ReferencePoint>& reference) {
  double sum = 0;
  for (const ReferencePoint& p : reference) sum += p.std_error / p.radiosity;
  return std::sqrt(2 / M_PI) * sum / static_cast<double>(reference.size());
}

// What the estimate estimates: sum |B - reference| over sum reference, every point
// standing for the same area (the whole room's 0.5 m grid).
double area_weighted_error(const Solved& s, const rad::Solver::Output& out,
                           const std::vector<ReferencePoint>& reference) {
  double difference = 0, total = 0;
  for (const ReferencePoint& p : reference) {
    const auto b = rad::probe(*s.scene.mesh, out.split, out.radiosity, p.point, p.normal);
    EXPECT_TRUE(b.has_value());
    difference += b ? std::abs(b->g - p.radiosity) : p.radiosity;
    total += p.radiosity;
  }
  return difference / total;
}

double mean_error_against_reference(const Solved& s, const rad::Solver::Output& out,
                                    const std::vector<ReferencePoint>& reference, double* worst = nullptr) {
  double sum = 0, largest = 0;
  for (const ReferencePoint& p : reference) {
    const auto b = rad::probe(*s.scene.mesh, out.split, out.radiosity, p.point, p.normal);
    EXPECT_TRUE(b.has_value());
    const double e = b ? std::abs(b->g - p.radiosity) / p.radiosity : 1.0;
    sum += e;
    largest = std::max(largest, e);
  }
  if (worst) *worst = largest;
  return sum / static_cast<double>(reference.size());
}

double mean_error_against_reference(Solved& s, const std::vector<ReferencePoint>& reference, double* worst = nullptr) {
  return mean_error_against_reference(s, s.solver->output(), reference, worst);
}

// Every quality stops by its error target, delivers it, and its estimate is at least
// the error measured against the path tracer, less what the tracer's own noise adds
// (about 0.08% here): the grid's mean relative error, and what the estimate estimates,
// the area-weighted error over the whole room (walls too). That one is 0.59%, 0.21%
// and 0.10% against estimates of 2.9%, 0.97% and 0.29%: bench/results/error_estimate.md says why.
// The normal quality (the default) is within the goal of 0.5% on average (the 2.6% at single points, the ceiling's
// corners, is in bench/results/bench_defaults.md).
TEST(ErrorEstimate, BoundsTheMeasuredErrorOnThe1990RoomForEveryQuality) {
  const std::vector<ReferencePoint> reference = globillum_reference();
  ASSERT_EQ(reference.size(), 476u);
  std::vector<ReferencePoint> whole_room = reference;
  for (const ReferencePoint& p : globillum_reference("globillum_room_walls_reference.txt")) whole_room.push_back(p);
  ASSERT_EQ(whole_room.size(), 476u + 384u);
  const double noise = reference_noise(reference);
  EXPECT_LT(noise, 0.001);
  double previous = 1;
  for (Quality q : {Quality::draft, Quality::normal, Quality::high}) {
    SCOPED_TRACE(rad::quality_name(q));
    Solved s = solve_like_the_command_line(test::sample("globillum_room.obj"), q);
    const rad::Solver::Output out = s.solver->output();
    const double measured = mean_error_against_reference(s, out, reference);
    const double estimated = s.report.estimated_error.total();
    EXPECT_EQ(s.report.stopped_by, rad::StopReason::error_target);
    EXPECT_LE(estimated, rad::quality_preset(q).error_target);
    EXPECT_GE(estimated + noise, measured);
    EXPECT_GE(estimated + noise, area_weighted_error(s, out, whole_room));
    EXPECT_LT(measured, previous);  // a higher quality is more accurate
    if (q == Quality::normal) {
      EXPECT_LT(measured, 0.005);
    }
    previous = measured;
  }
}

// Stopped early, the estimate follows the light not yet shot: without the ambient
// term it is most of the error, and it still bounds it.
TEST(ErrorEstimate, BoundsTheErrorOfAnEarlyStop) {
  const std::vector<ReferencePoint> reference = globillum_reference();
  for (int shots : {50, 200}) {
    SCOPED_TRACE(shots);
    Solved s = [&] {
      Solved r;
      r.scene = load_scene(test::sample("globillum_room.obj"));
      rad::RefineSettings refine;
      refine.method = Method::dynamic;
      rad::SolveOptions options;
      options.max_iterations = static_cast<std::size_t>(shots);
      options.converge = 0;
      rad::SettingsRequest request;
      const rad::AppliedSettings applied = rad::apply_settings(*r.scene.mesh, request, refine, options);
      options.error_target = 0;
      options.converge = 0;
      make_patches(*r.scene.mesh, applied.patch_size);
      r.hierarchy = std::make_unique<ElementHierarchy>(*r.scene.mesh);
      r.solver = std::make_unique<rad::Solver>(*r.scene.mesh, *r.hierarchy, options, refine);
      r.report = r.solver->run();
      return r;
    }();
    ASSERT_EQ(s.report.iterations, static_cast<std::size_t>(shots));
    const double measured = mean_error_against_reference(s, reference);
    EXPECT_GT(measured, 0.02);  // far from converged
    EXPECT_GE(s.report.estimated_error.total(), measured);
    EXPECT_LE(s.report.estimated_error.total(), 3 * measured);  // and not uselessly loose
  }
}

// A closed box [0, 2] x [0, depth] x [0, 1] whose every face emits 1 and reflects 0.5:
// B = 2 everywhere. Returns the OBJ's path.
std::string write_furnace(test::TempDir& dir, double depth) {
  dir.write("furnace.mtl", "newmtl glow\nKd 0.5 0.5 0.5\nKe 1 1 1\n");
  const std::string d = std::to_string(depth);
  return dir.write("furnace.obj", "mtllib furnace.mtl\nusemtl glow\n"
                                  "v 0 0 0\nv 2 0 0\nv 2 " + d + " 0\nv 0 " + d + " 0\nv 0 0 1\nv 2 0 1\nv 2 " + d +
                                      " 1\nv 0 " + d + " 1\n"
                                      "f 1 4 8 5\nf 2 6 7 3\nf 1 5 6 2\nf 4 3 7 8\nf 1 2 3 4\nf 5 8 7 6\n");
}

// The furnace: B = E / (1 - rho) everywhere, whatever the mesh.
TEST(ErrorEstimate, BoundsTheMeanErrorInAFurnace) {
  test::TempDir dir;
  const std::string model = write_furnace(dir, 1);
  Solved s = solve_like_the_command_line(model, Quality::normal);
  const rad::Solver::Output out = s.solver->output();
  double mean = 0;
  for (const Rgb& b : out.radiosity) mean += std::abs(b.g - 2.0) / 2.0 / static_cast<double>(out.radiosity.size());
  EXPECT_EQ(s.report.stopped_by, rad::StopReason::error_target);
  EXPECT_GE(s.report.estimated_error.total(), mean);
  EXPECT_LT(mean, 0.005);
}

// At the defaults the solve stops with about 7% of the light unshot, which the ambient
// term spreads as one area-weighted mean. Two things left this box's edges dark:
//   - chosen by unshot power alone, the slivers along the edges (half a whole patch)
//     shot only at twice their neighbours' unshot radiosity and held the most of it at
//     the stop (SolveOptions::whole_patch_senders now chooses them as whole patches);
//   - an edge vertex takes half its light from the few patches across the edge, whose
//     unshot light is not the mean (SolveOptions::near_unshot now takes them as they are).
// Measured worst vertex: 2.9% with neither, 1.3% with the first, 0.6% with both.
TEST(ErrorEstimate, TheUnshotLightBesideAFurnacesEdgesIsWrittenAsItIs) {
  test::TempDir dir;
  const std::string model = write_furnace(dir, 1.5);
  auto worst_with = [&](bool whole, bool near) {
    Solved s = solve_like_the_command_line(model, Quality::normal, {}, [&](rad::SolveOptions& o) {
      o.whole_patch_senders = whole;
      o.near_unshot = near;
    });
    EXPECT_EQ(s.report.stopped_by, rad::StopReason::error_target);
    const rad::Solver::Output out = s.solver->output();
    double worst = 0;
    for (const Rgb& b : out.radiosity) worst = std::max(worst, std::abs(b.g - 2.0) / 2.0);
    return worst;
  };
  EXPECT_GT(worst_with(false, false), 0.025);  // the cause, measured
  EXPECT_LT(worst_with(true, false), 0.02);
  EXPECT_LT(worst_with(true, true), 0.01);
}

// An element split by a neighbour's refinement after a shot had stopped at it once took
// that shot as a line between the corners of the element it came from, never corrected
// after: beside a neighbouring wall F bends within a tenth of a metre, and this furnace,
// shot to convergence with the command line's defaults, kept a wall vertex on its
// ceiling edge 2.9% above the closed form (below it the lines from push-down and from
// splits leave about 1%). Such elements now take the shot at their own corners.
TEST(ErrorEstimate, ElementsSplitAfterAShotStoppedThereTakeItExactly) {
  test::TempDir dir;
  const std::string model = write_furnace(dir, 1.5);
  rad::SettingsRequest converged;
  converged.converge = 1e-5;
  Solved s = solve_like_the_command_line(model, Quality::normal, converged);
  const rad::Solver::Output out = s.solver->output();
  double worst_high = 0, mean = 0;
  for (const Rgb& b : out.radiosity) {
    worst_high = std::max(worst_high, (b.g - 2.0) / 2.0);
    mean += std::abs(b.g - 2.0) / 2.0 / static_cast<double>(out.radiosity.size());
  }
  EXPECT_LT(worst_high, 0.015);
  EXPECT_LT(mean, 0.002);
}


// Two ways a vertex beside an edge kept the wrong share of a shot for good, both in
// this furnace: (1) an element split from a terminal after the walk had passed (a
// neighbour's refinement reached it) and split again later in the same shot took the
// shot as a line between corners 0.75 m apart; (2) a new vertex's start was bent by
// nearby patches' F measured a step into its parent, where the parent's corner at a
// patch's corner on the edge had taken F a step into another element, across F's jump
// there. Measured: converged 1.26% at worst before, 0.58% after; high quality 1.03%
// before, 0.57% after (the 4 x 3 x 1.5 room of bench/defaults.cpp: 2.25% and 4.23%
// before, 0.49% and 0.54% after).
TEST(ErrorEstimate, EdgeVerticesOfAFurnaceKeepTheirShareOnceConvergedOrAtHighQuality) {
  test::TempDir dir;
  const std::string model = write_furnace(dir, 1.5);
  rad::SettingsRequest converged;
  converged.converge = 1e-5;
  for (const auto& [quality, request] :
       {std::pair{Quality::normal, converged}, std::pair{Quality::high, rad::SettingsRequest{}}}) {
    Solved s = solve_like_the_command_line(model, quality, request);
    const rad::Solver::Output out = s.solver->output();
    double worst = 0;
    for (const Rgb& b : out.radiosity) worst = std::max(worst, std::abs(b.g - 2.0) / 2.0);
    EXPECT_LT(worst, 0.008) << (quality == Quality::high ? "high" : "converged");
  }
}


// The per-vertex estimate (Solver::Output::error) in a furnace that is not a cube, at
// the defaults but with both edge rules off (SolveOptions::whole_patch_senders and
// near_unshot), so that the early stop leaves its error on the edges, as a solve whose
// ambient term is wrong somewhere does: its mean over the vertices is of the measured
// mean's size, and the vertices it ranks worst hold the measured worst. (With the rules
// on, the edges are as good as the faces: see the test after this one.)
TEST(ErrorEstimate, PerVertexEstimateFindsTheFurnacesWorstVertices) {
  test::TempDir dir;
  const std::string model = write_furnace(dir, 1.5);
  Solved s = solve_like_the_command_line(model, Quality::normal, {}, [](rad::SolveOptions& o) {
    o.whole_patch_senders = false;
    o.near_unshot = false;
  });
  const rad::Solver::Output out = s.solver->output();
  const std::size_t n = out.radiosity.size();
  ASSERT_EQ(out.error.size(), n);
  std::vector<double> measured(n);
  double measured_mean = 0, estimated_mean = 0;
  for (std::size_t v = 0; v < n; ++v) {
    measured[v] = std::abs(out.radiosity[v].g - 2.0) / 2.0;
    measured_mean += measured[v] / static_cast<double>(n);
    estimated_mean += out.error[v] / static_cast<double>(n);
  }
  // The estimate's rank of each of the ten worst measured vertices (0: ranked worst).
  std::vector<std::size_t> by_estimate(n), by_measure(n);
  for (std::size_t v = 0; v < n; ++v) by_estimate[v] = by_measure[v] = v;
  std::sort(by_estimate.begin(), by_estimate.end(), [&](auto a, auto b) { return out.error[a] > out.error[b]; });
  std::sort(by_measure.begin(), by_measure.end(), [&](auto a, auto b) { return measured[a] > measured[b]; });
  std::vector<std::size_t> rank(n);
  for (std::size_t r = 0; r < n; ++r) rank[by_estimate[r]] = r;
  std::printf("measured mean %.3f%%, estimated mean %.3f%%; the worst measured (%.2f%%) is ranked %zu of %zu\n",
              100 * measured_mean, 100 * estimated_mean, 100 * measured[by_measure[0]], rank[by_measure[0]], n);
  for (int i = 0; i < 10; ++i)
    std::printf("  measured %.3f%% estimated %.3f%% rank %zu\n", 100 * measured[by_measure[i]], 100 * out.error[by_measure[i]], rank[by_measure[i]]);
  EXPECT_GE(estimated_mean, measured_mean);
  EXPECT_LE(estimated_mean, 4 * measured_mean);
  // Measured: 5 of the 10 worst rank in the estimate's top 10%; the very worst (2.9%,
  // on an edge) 67th of 1382, and the estimate's top 1% holds a vertex at 2.8%. The
  // worst ten lie within 6% of each other (2.7-2.9%), so which of them the estimate puts
  // first is a toss-up; what a user needs is that the vertices it puts first are as bad
  // as the worst. Before the edge fixes of the test above the worst ranked 430th: the
  // vertex held a wrong share for good, which no surplus or unshot light shows. The
  // estimate still says about half the error there (1.5% for 2.8%): the early stop's
  // shortfall at an edge is larger than the uniform ambient's (issue 27, item 4: open).
  int found = 0;
  for (int i = 0; i < 10; ++i) found += rank[by_measure[i]] < n / 10;
  EXPECT_GE(found, 5);
  EXPECT_LT(rank[by_measure[0]], n / 10);
  double worst_of_top = 0;  // the largest measured error among the estimate's top 1%
  for (std::size_t r = 0; r < n / 100; ++r) worst_of_top = std::max(worst_of_top, measured[by_estimate[r]]);
  EXPECT_GE(worst_of_top, 0.9 * measured[by_measure[0]]);
}

// The per-vertex estimate (Solver::Output::error) in a furnace that is not a cube, at
// the defaults: no vertex is worse than its estimate says, and the mean of the
// estimate is at least the measured mean.
//
// With the edge rules on, the worst vertices are no longer the edges (2.9% dark before,
// where the estimate said 1.5%; the test before this one ranks them with the rules
// off): the worst is 0.63%, on a face, and every vertex's estimate is above its error.
// It is now too loose: 6.8 times the measured mean (item 4 of issue 27 asks at most 2):
// its unshot part still counts a quarter of the ambient term, which was measured before
// the near patches were taken apart.
TEST(ErrorEstimate, PerVertexEstimateBoundsEveryVertexOfAFurnace) {
  test::TempDir dir;
  const std::string model = write_furnace(dir, 1.5);
  Solved s = solve_like_the_command_line(model, Quality::normal);
  const rad::Solver::Output out = s.solver->output();
  const std::size_t n = out.radiosity.size();
  ASSERT_EQ(out.error.size(), n);
  double measured_mean = 0, estimated_mean = 0, worst = 0;
  std::size_t above = 0;  // vertices whose error is above their estimate
  for (std::size_t v = 0; v < n; ++v) {
    const double measured = std::abs(out.radiosity[v].g - 2.0) / 2.0;
    measured_mean += measured / static_cast<double>(n);
    estimated_mean += out.error[v] / static_cast<double>(n);
    worst = std::max(worst, measured);
    above += measured > out.error[v];
  }
  std::printf("measured mean %.3f%%, worst %.3f%%; estimated mean %.3f%%\n", 100 * measured_mean, 100 * worst,
              100 * estimated_mean);
  EXPECT_EQ(above, 0u);
  EXPECT_GE(estimated_mean, measured_mean);
  EXPECT_LT(worst, 0.01);
}

// A shadow inside an element whose corners all see the source: a 1 x 1 m floor of two
// whole patches (no refinement, no clusters) under a 0.5 m triangular source 10 m
// above (its direct light is even over the floor to within 1.5%), and a small black
// block 0.3 m above the centroid of one floor triangle, which puts that centroid in
// full shadow while the triangle's corners are lit. The surplus cannot see it (no leaf
// has a parent); the direct check does (radiosity/solver/direct_gap.cpp).
std::string write_shadow_inside_an_element(test::TempDir& dir, bool block) {
  dir.write("shadow.mtl",
            "newmtl floor\nKd 0.5 0.5 0.5\nnewmtl lamp\nKd 0 0 0\nKe 10 10 10\nnewmtl block\nKd 0 0 0\n");
  // Floor triangles (0,0)-(1,0)-(1,1) and (0,0)-(1,1)-(0,1); the first one's centroid
  // is (2/3, 1/3).
  const double cx = 2.0 / 3, cy = 1.0 / 3, h = 0.05;
  auto v = [](double x, double y, double z) {
    return "v " + std::to_string(x) + " " + std::to_string(y) + " " + std::to_string(z) + "\n";
  };
  std::string obj = "mtllib shadow.mtl\n";
  obj += v(0, 0, 0) + v(1, 0, 0) + v(1, 1, 0) + v(0, 1, 0);                    // 1-4 floor
  obj += v(0.25, 0.25, 10) + v(0.75, 0.25, 10) + v(0.5, 0.75, 10);             // 5-7 lamp
  for (double z : {0.3, 0.31})                                                   // 8-15 block
    obj += v(cx - h, cy - h, z) + v(cx + h, cy - h, z) + v(cx + h, cy + h, z) + v(cx - h, cy + h, z);
  obj += "usemtl floor\nf 1 2 3\nf 1 3 4\nusemtl lamp\nf 5 7 6\n";
  if (block)
    obj += "usemtl block\nf 8 11 10 9\nf 12 13 14 15\nf 8 9 13 12\nf 9 10 14 13\nf 10 11 15 14\nf 11 8 12 15\n";
  return dir.write(block ? "shadow.obj" : "open.obj", obj);
}

TEST(ErrorEstimate, DirectCheckSeesAShadowInsideAnElementWhoseCornersAreLit) {
  test::TempDir dir;
  rad::SettingsRequest request;
  request.patch_size = 8;  // each floor triangle is one patch
  request.max_level = 0;   // and one element
  request.clusters = false;
  auto solve = [&](bool block, bool check) {
    return solve_like_the_command_line(write_shadow_inside_an_element(dir, block), Quality::normal, request,
                                       [&](rad::SolveOptions& o) { o.direct_check = check; });
  };
  // The largest per-vertex estimate on the floor.
  auto floor_estimate = [](Solved& s) {
    const rad::Solver::Output out = s.solver->output();
    double largest = 0;
    const TriMesh& mesh = s.scene.mesh->mesh();
    for (std::size_t i = 0; i < out.split.size(); ++i)
      if (std::abs(mesh.point(out.split.source[i])[2]) < 1e-9)
        largest = std::max(largest, static_cast<double>(out.error[i]));
    return largest;
  };
  Solved blind = solve(true, false), seeing = solve(true, true), open = solve(false, true);
  const double blind_vertex = floor_estimate(blind), seeing_vertex = floor_estimate(seeing),
               open_vertex = floor_estimate(open);
  std::printf("shadows' part: shadow %.3f%%, shadow without the check %.3f%%, no block %.3f%%; largest floor "
              "vertex estimate %.1f%%, %.1f%%, %.1f%%\n",
              100 * seeing.report.estimated_error.shadows, 100 * blind.report.estimated_error.shadows,
              100 * open.report.estimated_error.shadows, 100 * seeing_vertex, 100 * blind_vertex, 100 * open_vertex);
  // Without the check the mesh part is zero: no element was ever refined.
  EXPECT_EQ(blind.report.estimated_error.discretisation, 0.0);
  EXPECT_EQ(blind.report.estimated_error.shadows, 0.0);
  EXPECT_LT(blind_vertex, 0.02);
  // With it, the shadowed triangle's corners carry two thirds of the jump at its
  // centroid, which takes no direct light: about two thirds of what they hold. Without
  // the block nothing is occluded and the check finds nothing (it looks at shadows,
  // not at how the light bends: that is the surplus's part).
  EXPECT_GT(seeing_vertex, 0.4);
  EXPECT_GT(seeing.report.estimated_error.shadows, 0.1);
  EXPECT_EQ(seeing.report.estimated_error.discretisation, 0.0);
  EXPECT_LT(open_vertex, 0.01);
  EXPECT_LT(open.report.estimated_error.shadows, 0.001);
  // The check's rays are seeded: the same answer twice.
  Solved again = solve(true, true);
  EXPECT_EQ(again.report.estimated_error.shadows, seeing.report.estimated_error.shadows);
}

// An open model: a square lamp of two triangles 10 m above a 1 m floor. Each triangle's
// shot loses nearly all its light to the outside, and the ambient term takes the
// unshot light as lost in the same share: after the first triangle the estimate said
// 0.47% with half the floor's light missing, and the solve stopped there. The estimate
// now waits until every primary source has shot (Solver::primary_sources_shot).
TEST(ErrorEstimate, AnOpenModelDoesNotStopBeforeEveryLampTriangleHasShot) {
  test::TempDir dir;
  dir.write("lamp.mtl", "newmtl floor\nKd 0.5 0.5 0.5\nnewmtl lamp\nKd 0 0 0\nKe 10 10 10\n");
  const std::string model = dir.write("lamp.obj",
                                      "mtllib lamp.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
                                      "v 0.25 0.25 10\nv 0.75 0.25 10\nv 0.75 0.75 10\nv 0.25 0.75 10\n"
                                      "usemtl floor\nf 1 2 3 4\nusemtl lamp\nf 5 8 7 6\n");
  Solved s = solve_like_the_command_line(model, Quality::normal);
  EXPECT_GE(s.report.iterations, 2u);
  EXPECT_LT(s.solver->unshot_fraction(), 0.05);
  // The floor's middle against the closed form of a small square source overhead,
  // E = M A / (pi d^2) (the source subtends 0.05 rad: the exact form for a square is
  // 0.08% less), B = rho E. Within 2%: the solve gives 1% less; with one triangle
  // shot it gave half.
  const rad::Solver::Output out = s.solver->output();
  const auto b = rad::probe(*s.scene.mesh, out.split, out.radiosity, Vec3d(0.5, 0.5, 0), Vec3d(0, 0, 1));
  ASSERT_TRUE(b.has_value());
  const double expected = 0.5 * 10 * 0.25 / (M_PI * 100);
  EXPECT_NEAR(b->g, expected, 0.02 * expected);
}

// Light does not pass through a wall into a new vertex. The obstructed 1990 room's
// partition at x = 3 (0.1 m thick, y 3..6) shades the floor to its left from the
// source; the reference (path-traced) floor is darkest along the partition's foot,
// where the partition itself takes half of the view. New vertices there once started
// with the light of the back wall on the partition's lit side, a few decimetres away
// but hidden (Solver::near_field_start had no rays): the foot came out 33% too bright
// at (2.75, 5.75) and brighter than the floor further out.
TEST(ErrorEstimate, NoLightReachesNewVerticesThroughAPartition) {
  const std::vector<ReferencePoint> reference = globillum_reference("globillum_room_obstructed_reference.txt");
  Solved s = solve_like_the_command_line(test::sample("globillum_room_obstructed.obj"), Quality::normal);
  const rad::Solver::Output out = s.solver->output();
  auto at = [&](double x, double y) {
    const auto b = rad::probe(*s.scene.mesh, out.split, out.radiosity, Vec3d(x, y, 0), Vec3d(0, 0, 1));
    EXPECT_TRUE(b.has_value());
    return b ? b->g : 0.0;
  };
  int along_the_foot = 0;
  for (const ReferencePoint& p : reference) {
    if (p.normal[2] < 0 || p.point[0] != 2.75 || p.point[1] < 3.5) continue;
    SCOPED_TRACE(p.point[1]);
    EXPECT_NEAR(at(p.point[0], p.point[1]), p.radiosity, 0.1 * p.radiosity);
    ++along_the_foot;
  }
  EXPECT_EQ(along_the_foot, 5);
  // As in the reference, the floor darkens toward the foot (0.00128 at 0.45 m from the
  // partition, 0.00105 at 1 mm).
  EXPECT_LT(at(2.949, 5.8), at(2.5, 5.8));
}

}  // namespace
}  // namespace dynrad
