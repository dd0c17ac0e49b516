// Refinement speed and memory on a mesh of more than 100k triangles.
//
// The 1990 comparison room is cut into patches of 0.09 m (about 110k triangles), then
// 100k random leaves are refined (fixed seed), each with its conforming closure. The
// reference, in the same process, is OpenMesh's own edge split on the same mesh with
// no propagation path and no hierarchy: the ratio says what conformity and the element
// tree cost per split. Memory is the heap growth (glibc mallinfo2) of mesh plus
// hierarchy, divided by the number of elements.
//
// Usage: bench_refine [samples/globillum_room.obj]
#include "bench/median.h"
#include "mesh/load.h"
#include "mesh/core/refinement.h"

#include <malloc.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

namespace {

using Clock = std::chrono::steady_clock;
constexpr double kPatchSize = 0.09;
constexpr int kRefinements = 100000;
constexpr int kRepetitions = 5;

using dynrad::bench::median;

std::size_t heap_bytes() { return mallinfo2().uordblks; }

}  // namespace

int main(int argc, char** argv) {
  const std::string path = argc > 1 ? argv[1] : std::string(DYNRAD_SAMPLES_DIR) + "/globillum_room.obj";
  std::vector<double> ours_rate, raw_rate, bytes_per_element, bytes_per_leaf;
  std::size_t faces = 0, splits = 0, elements = 0;
  for (int rep = 0; rep < kRepetitions; ++rep) {
    // Ours: LEPP bisection with the element hierarchy.
    {
      const std::size_t heap0 = heap_bytes();
      dynrad::LoadedScene loaded = dynrad::load_scene(path);
      dynrad::make_patches(*loaded.mesh, kPatchSize);
      faces = loaded.mesh->face_count();
      dynrad::ElementHierarchy hierarchy(*loaded.mesh);
      std::mt19937 rng(42);
      dynrad::SplitCounts total;
      const auto start = Clock::now();
      for (int i = 0; i < kRefinements; ++i) {
        std::uniform_int_distribution<int> pick(0, static_cast<int>(loaded.mesh->face_count()) - 1);
        total += hierarchy.refine(hierarchy.element_of(dynrad::FaceHandle(pick(rng))));
      }
      const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
      splits = total.total();
      elements = hierarchy.element_count();
      ours_rate.push_back(static_cast<double>(total.total()) / seconds);
      const double heap = static_cast<double>(heap_bytes() - heap0);
      bytes_per_element.push_back(heap / static_cast<double>(hierarchy.element_count()));
      bytes_per_leaf.push_back(heap / static_cast<double>(hierarchy.leaf_count()));
    }
    // Reference: OpenMesh edge splits of random edges, same count, no closure needed
    // (an edge split is conforming by itself) and no hierarchy.
    {
      dynrad::LoadedScene loaded = dynrad::load_scene(path);
      dynrad::make_patches(*loaded.mesh, kPatchSize);
      dynrad::TriMesh& mesh = loaded.mesh->mesh();
      std::mt19937 rng(42);
      const auto start = Clock::now();
      for (std::size_t i = 0; i < splits; ++i) {
        std::uniform_int_distribution<int> pick(0, static_cast<int>(mesh.n_edges()) - 1);
        const int e = pick(rng);
        const OpenMesh::EdgeHandle eh(static_cast<int>(e));
        const auto h = mesh.halfedge_handle(eh, 0);
        const dynrad::Vec3d mid = (mesh.point(mesh.from_vertex_handle(h)) + mesh.point(mesh.to_vertex_handle(h))) * 0.5;
        mesh.split_copy(eh, mid);
      }
      const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
      // Each edge split cuts two faces: count face bisections like ours.
      raw_rate.push_back(2.0 * static_cast<double>(splits) / seconds);
    }
  }
  std::printf("mesh: %s cut at %.2f -> %zu triangles\n", path.c_str(), kPatchSize, faces);
  std::printf("refined %d random leaves: %zu bisections (requested + closure), %zu elements\n", kRefinements, splits,
              elements);
  std::printf("bisections per second (median of %d): %.3g\n", kRepetitions, median(ours_rate));
  std::printf("OpenMesh raw edge splits, face bisections per second (median): %.3g\n", median(raw_rate));
  std::printf("bytes per element (mesh + hierarchy, median): %.0f; per leaf: %.0f\n", median(bytes_per_element),
              median(bytes_per_leaf));
  std::printf("ratio: %.2f\n", median(ours_rate) / median(raw_rate));
  return 0;
}
