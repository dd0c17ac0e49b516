// What users look at: the README's demo (the Cornell box with no options) must show no
// star or wedge streaks and no blotches. On a flat lit surface a light field sampled at
// vertices has extrema only where the light itself peaks, and there a vertex passes its
// neighbours by a hair (the second difference over one element); a streak or a blotch is
// a vertex well outside the range of the ring of vertices around it.
#include "radiosity/pipeline/pipeline.h"
#include "radiosity/solver/solver.h"
#include "test_support.h"

#include <gtest/gtest.h>

#include <map>
#include <set>

namespace dynrad {
namespace {

struct Outliers {
  std::size_t interior = 0;  // vertices inside flat single-material regions
  std::size_t beyond = 0;    // of those, outside their ring's range by more than 2% of their value
  // of those, outside their ring's range by more than 3% and by more than the ring
  // spans (both relative to their value): more than the light's variation around them
  // allows
  std::size_t beyond_gradient = 0;
  double worst = 0;          // the largest such excess, relative to the value
  Vec3d where{0, 0, 0};      // the vertex that has it
  bool darker = false;       // below its ring (else above)
  double spread = 0;         // its ring's range (max - min), relative to its value
};

// Over the written vertices: those whose faces all share one normal and one material and
// whose ring is closed.
Outliers ring_outliers(const SceneMesh& scene, const VertexSplit& split, const std::vector<Rgb>& values) {
  const TriMesh& mesh = scene.mesh();
  std::vector<std::set<std::uint32_t>> ring(split.size());
  std::vector<std::vector<FaceHandle>> faces(split.size());
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> edges;
  for (auto f : mesh.faces()) {
    std::uint32_t c[3];
    for (int k = 0; k < 3; ++k) c[k] = split.corner[3 * f.idx() + k];
    for (int k = 0; k < 3; ++k) {
      faces[c[k]].push_back(f);
      ring[c[k]].insert(c[(k + 1) % 3]);
      ring[c[k]].insert(c[(k + 2) % 3]);
      ++edges[{std::min(c[k], c[(k + 1) % 3]), std::max(c[k], c[(k + 1) % 3])}];
    }
  }
  std::vector<char> boundary(split.size(), 0);
  for (const auto& [e, count] : edges)
    if (count != 2) boundary[e.first] = boundary[e.second] = 1;
  Outliers out;
  for (std::size_t v = 0; v < split.size(); ++v) {
    if (boundary[v] || faces[v].empty()) continue;
    const FaceHandle first = faces[v].front();
    bool flat = true;
    for (FaceHandle f : faces[v])
      flat = flat && scene.material_id(f) == scene.material_id(first) &&
             OpenMesh::dot(scene.normal(f), scene.normal(first)) > 1 - 1e-9;
    if (!flat || scene.material(first).emits()) continue;
    ++out.interior;
    const double b = values[v].luminance();
    double lo = 1e300, hi = -1e300;
    for (std::uint32_t w : ring[v]) {
      lo = std::min(lo, values[w].luminance());
      hi = std::max(hi, values[w].luminance());
    }
    const double excess = std::max({b - hi, lo - b, 0.0}) / std::max(b, 1e-300);
    const double spread = (hi - lo) / std::max(b, 1e-300);
    if (excess > 0.02) ++out.beyond;
    if (excess > 0.03 && excess > spread) ++out.beyond_gradient;
    if (excess > out.worst) {
      out.worst = excess;
      out.darker = b < lo;
      out.spread = spread;
      const FaceHandle f = faces[v].front();
      auto fv = mesh.cfv_begin(f);
      for (int k = 0; k < 3; ++k, ++fv)
        if (split.corner[3 * f.idx() + k] == v) out.where = mesh.point(*fv);
    }
  }
  return out;
}

// The Cornell demo solved with the given seed (the rays' only source of chance), by the
// pipeline `dynrad solve --ambient` calls.
Outliers cornell_outliers(std::uint64_t seed) {
  rad::SceneRequest request;
  request.path = test::sample("cornell_box.obj");
  request.simplify.enabled = true;
  request.solve.ambient_display = true;
  request.solve.seed = seed;
  rad::PreparedScene prepared = rad::prepare_scene(request);
  const rad::SolvedScene solved = rad::solve_scene(prepared);
  return ring_outliers(*prepared.scene.mesh, solved.output.split, solved.output.radiosity);
}

// At every seed, not only the default one: a lone vertex decided by two rays that
// happened to agree inside a penumbra (both arriving, or both blocked) was up to 67%
// off its ring at seeds 4 and 5 before corners whose element had disagreeing corners
// were cast again with the full count (Solver::settle_visibility); the default seed
// showed 29% and the test held a bound of 30% fitted to it.
TEST(Pictures, TheDemoShowsNoStreaksAndAlmostNoBlotchesAtAnySeed) {
  double worst = 0;
  for (std::uint64_t seed = 1; seed <= 5; ++seed) {
    const Outliers o = cornell_outliers(seed);
    ASSERT_GT(o.interior, 500u);
    std::printf("seed %d: %zu of %zu interior vertices beyond their ring by more than 2%% (%zu by more than 3%% and than it spans); worst %.1f%% (%s, at %.1f %.1f %.1f; its ring spans %.1f%%)\n",
                static_cast<int>(seed), o.beyond, o.interior, o.beyond_gradient, 100 * o.worst, o.darker ? "darker" : "brighter",
                o.where[0], o.where[1], o.where[2], 100 * o.spread);
    EXPECT_LE(o.beyond, o.interior / 500) << "seed " << seed;
    // A smooth light field sampled at vertices a similar distance apart leaves a vertex
    // outside its ring's range by about the second difference over one element, well
    // under what the ring itself spans where the light varies; a vertex further out
    // than its ring spans is a blotch the light did not make. Below 3% the two-ray
    // visibility's noise is left alone: on a nearly even surface (clang's mesh, seed 1)
    // a vertex stood 2.5% above a ring spanning 0.9%.
    EXPECT_EQ(o.beyond_gradient, 0u) << "seed " << seed;
    worst = std::max(worst, o.worst);
  }
  // Measured (2026-12-04, gcc, seeds 1-5): 4.6, 1.6, 3.0, 2.6 and 2.5%, each under
  // 0.55 of its ring's span. Before a new vertex's start took no near-field bend from
  // a source its ancestors' push-down had not reached yet (Solver::initialise_values),
  // seeds 2 and 3 gave 9.9% and 8.2% (1.2 and 1.1 times their rings' span): a vertex
  // 1 cm up the short block's side, whose elements on one side of it had started 40%
  // above those on the other. Vertices on the right wall 14 cm below the ceiling were
  // 7-20% above their rings at every seed until a patch no longer sent light to a
  // point facing its own way: a receiver the wall's patch shared with a coplanar
  // neighbour, evaluated inside the sender, took F = 1.71 from it.
  // Before a new vertex's start took the light of the patches near it into account
  // (RefineSettings::near_field_start), vertices 1-2 cm above the floor at the short
  // block's foot were up to 20.5% darker than their rings at every seed: born between a
  // shot from the floor a little way off, which the foot sees only at grazing angles and
  // a corner 4 cm up sees well, and the shot from the floor at the foot, they started
  // from a line through those two corners and never got the difference back.
  EXPECT_LT(worst, 0.06);
}

}  // namespace
}  // namespace dynrad
