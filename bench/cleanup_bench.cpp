// Cleanup throughput on a generated polygon soup the size of a building floor.
//
// The soup is an n x n grid of unit quads where every quad has its own copies of its
// corners (as many CAD exports do), every other row is made of double-width quads
// (so each of their long edges carries a T-junction), and corners are jittered below
// the merge tolerance. The reference in the same process is building the OpenMesh
// half-edge mesh from the already clean result, so the printed ratio says what
// cleanup costs relative to merely loading a clean mesh.
#include "mesh/repair/cleanup.h"
#include "mesh/core/scene_mesh.h"

#include <benchmark/benchmark.h>

#include <random>

namespace {

// A soup with one grey material, one group and one (generated) file, and no polygons.
dynrad::PolygonSoup empty_soup(const char* group) {
  dynrad::PolygonSoup soup;
  soup.materials.push_back(dynrad::Material{"grey", dynrad::Rgb(0.5), dynrad::Rgb(0.0), "bench", true});
  soup.group_names.push_back(group);
  soup.files.push_back("generated");
  return soup;
}

// Appends a polygon whose corners are new points.
void add_polygon(dynrad::PolygonSoup& soup, const std::vector<dynrad::Vec3d>& corners) {
  std::vector<std::uint32_t> polygon;
  for (const dynrad::Vec3d& p : corners) {
    polygon.push_back(static_cast<std::uint32_t>(soup.points.size()));
    soup.points.push_back(p);
  }
  soup.polygons.push_back(polygon);
  soup.material.push_back(0);
  soup.group.push_back(0);
  soup.origin.push_back(dynrad::SourceRef{0, 0, static_cast<std::uint32_t>(soup.polygons.size() - 1)});
}

dynrad::PolygonSoup make_grid_soup(int n) {
  using dynrad::Vec3d;
  dynrad::PolygonSoup soup = empty_soup("grid");
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> jitter(-1e-7 * n, 1e-7 * n);
  auto add_quad = [&](double x0, double y0, double x1, double y1) {
    std::vector<Vec3d> corners;
    for (auto [x, y] : {std::pair{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}})
      corners.emplace_back(x + jitter(rng), y + jitter(rng), 0.0);
    add_polygon(soup, corners);
  };
  for (int j = 0; j < n; ++j) {
    if (j % 2 == 0) {
      for (int i = 0; i < n; ++i) add_quad(i, j, i + 1, j + 1);
    } else {
      for (int i = 0; i + 1 < n; i += 2) add_quad(i, j, i + 2, j + 1);
    }
  }
  return soup;
}

constexpr int kGrid = 300;  // about 135k polygons, 180k triangles after cleanup

void BM_Cleanup(benchmark::State& state) {
  const dynrad::PolygonSoup soup = make_grid_soup(kGrid);
  dynrad::CleanupReport report;
  for (auto _ : state) {
    dynrad::TriangleSoup out;
    report = dynrad::cleanup(soup, out);
    benchmark::DoNotOptimize(out.triangles.data());
  }
  state.counters["polygons_per_s"] =
      benchmark::Counter(static_cast<double>(soup.polygons.size()), benchmark::Counter::kIsIterationInvariantRate);
  state.counters["triangles_out"] = static_cast<double>(report.output_triangles);
  state.counters["t_junctions"] = static_cast<double>(report.t_junctions);
  state.counters["merged_points"] = static_cast<double>(report.merged_points);
}
BENCHMARK(BM_Cleanup)->Unit(benchmark::kMillisecond)->Repetitions(3)->ReportAggregatesOnly(true);

// A pathological soup: n random triangles, every other one lying in the plane z = 0 (a
// stack of overlapping facets, each imprinted with the others' outlines), the rest
// standing across that plane. Imprinting and the hidden-part rules for facets in one
// plane dominate; 200 such triangles took 25 s to load before those rules searched
// all triangles' boxes in one pass (2026-12-04).
dynrad::PolygonSoup make_stacked_soup(int n) {
  using dynrad::Vec3d;
  dynrad::PolygonSoup soup = empty_soup("stack");
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> at(0, 10), step(-5, 5);
  for (int i = 0; i < n; ++i) {
    std::vector<Vec3d> corners;
    if (i % 2 == 0) {
      for (int k = 0; k < 3; ++k) corners.emplace_back(at(rng), at(rng), 0.0);
    } else {
      const double x = at(rng), y = at(rng), dx = step(rng), dy = step(rng);
      corners = {Vec3d(x, y, -1.0), Vec3d(x + dx, y + dy, -1.0), Vec3d(x + dx / 2, y + dy / 2, 2.0)};
    }
    add_polygon(soup, corners);
  }
  return soup;
}

void BM_StackedCleanup(benchmark::State& state) {
  const dynrad::PolygonSoup soup = make_stacked_soup(static_cast<int>(state.range(0)));
  dynrad::CleanupReport report;
  for (auto _ : state) {
    dynrad::TriangleSoup out;
    report = dynrad::cleanup(soup, out);
    benchmark::DoNotOptimize(out.triangles.data());
  }
  state.counters["triangles_out"] = static_cast<double>(report.output_triangles);
}
BENCHMARK(BM_StackedCleanup)->Arg(100)->Arg(160)->Unit(benchmark::kMillisecond)->Repetitions(3)->ReportAggregatesOnly(true);

// Reference: build the half-edge mesh from the clean triangles.
void BM_BuildHalfEdgeMesh(benchmark::State& state) {
  dynrad::TriangleSoup clean;
  dynrad::cleanup(make_grid_soup(kGrid), clean);
  for (auto _ : state) {
    dynrad::SceneMesh mesh(clean);
    benchmark::DoNotOptimize(mesh.face_count());
  }
  state.counters["triangles_per_s"] =
      benchmark::Counter(static_cast<double>(clean.triangles.size()), benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(BM_BuildHalfEdgeMesh)->Unit(benchmark::kMillisecond)->Repetitions(3)->ReportAggregatesOnly(true);

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  // Collect medians to print the ratio after the table.
  class Reporter : public benchmark::ConsoleReporter {
   public:
    double cleanup_ms = 0, build_ms = 0;
    void ReportRuns(const std::vector<Run>& runs) override {
      ConsoleReporter::ReportRuns(runs);
      for (const auto& run : runs) {
        if (run.aggregate_name != "median") continue;
        const double ms = run.GetAdjustedRealTime();
        if (run.benchmark_name().find("BM_Cleanup") == 0) cleanup_ms = ms;
        if (run.benchmark_name().find("BM_BuildHalfEdgeMesh") == 0) build_ms = ms;
      }
    }
  } reporter;
  benchmark::RunSpecifiedBenchmarks(&reporter);
  if (reporter.build_ms > 0)
    std::printf("cleanup / half-edge build (medians): %.2f ms / %.2f ms, ratio: %.2f\n", reporter.cleanup_ms,
                reporter.build_ms, reporter.cleanup_ms / reporter.build_ms);
  benchmark::Shutdown();
  return 0;
}
