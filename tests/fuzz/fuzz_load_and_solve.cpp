// libFuzzer target for one import path (DYNRAD_FUZZ_FORMAT: obj, ply, off, stl, scene
// or gltf, the last through assimp). The input bytes become a file of that format, which goes the whole way a
// user's file goes: read, cleanup, scene mesh, patches, then a short dynamic solve.
//
// InputError is the expected answer to bad input and is caught here. Anything else is
// a bug the fuzzer reports: another exception escaping, a crash, a sanitizer finding,
// a NaN in the solution or an energy balance that does not hold.
//
// Inputs come from memory but the readers take paths, so each input is written to a
// scratch directory under $TMPDIR first:
//   obj    the input up to a line "~MTL~" is model.obj, the rest (if any) model.mtl;
//   scene  the input is scene.json, next to fixed mesh files it may refer to
//          (room.obj + room.mtl, panel.off, box.ply, tri.stl, downlight.ies; see
//          write_scene_meshes).
#include "mesh/core/error.h"
#include "mesh/load.h"
#include "mesh/core/refinement.h"
#include "radiosity/sources/daylight.h"
#include "radiosity/design/emergency.h"
#include "radiosity/design/glare.h"
#include "radiosity/design/light_scenes.h"
#include "radiosity/analysis/grid_scene.h"
#include "radiosity/analysis/views.h"
#include "radiosity/sources/luminaire.h"
#include "radiosity/solver/solver.h"
#include "radiosity/pipeline/scene_sections.h"
#include "radiosity/transfer/visibility.h"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>

#ifndef DYNRAD_FUZZ_FORMAT
#error "DYNRAD_FUZZ_FORMAT must name the format: obj, ply, off, stl, scene or gltf"
#endif

namespace {

namespace fs = std::filesystem;
constexpr std::string_view kFormat = DYNRAD_FUZZ_FORMAT;
constexpr std::string_view kMtlMarker = "\n~MTL~\n";

void write_file(const fs::path& path, std::string_view bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  if (!out) {
    std::fprintf(stderr, "fuzz: cannot write %s\n", path.c_str());
    std::abort();
  }
}

// Small, valid meshes a fuzzed scene file can refer to by name.
void write_scene_meshes(const fs::path& dir) {
  write_file(dir / "room.mtl", "newmtl wall\nKd 0.6 0.6 0.6\nnewmtl light\nKd 0.5 0.5 0.5\nKe 10 10 10\n");
  write_file(dir / "room.obj",
             "mtllib room.mtl\n"
             "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
             "g floor\nusemtl wall\nf 1 2 3 4\n"
             "g walls\nf 1 5 6 2\nf 2 6 7 3\nf 3 7 8 4\nf 4 8 5 1\n"
             "g ceiling\nusemtl light\nf 5 8 7 6\n");
  write_file(dir / "panel.off", "OFF\n# a unit square facing +z\n4 1 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n");
  write_file(dir / "box.ply",
             "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
             "element face 2\nproperty list uchar int vertex_indices\nproperty uchar red\nproperty uchar green\n"
             "property uchar blue\nend_header\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2 200 100 50\n3 0 2 3 10 20 30\n");
  write_file(dir / "downlight.ies",
             "IESNA:LM-63-2002\nTILT=NONE\n1 -1 1 3 1 1 2 0.1 0.1 0\n1 1 0\n0 45 90\n0\n1000 700 0\n");
  write_file(dir / "tri.stl",
             "solid tri\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\n"
             "endfacet\nendsolid tri\n");
}

struct Scratch {
  fs::path dir;
  Scratch() {
    const char* tmp = std::getenv("TMPDIR");
    std::string pattern = (fs::path(tmp && *tmp ? tmp : "/tmp") / "dynrad-fuzz-XXXXXX").string();
    if (!::mkdtemp(pattern.data())) {
      std::perror("fuzz: mkdtemp");
      std::abort();
    }
    dir = pattern;
    if (kFormat == "scene") write_scene_meshes(dir);
  }
  ~Scratch() {
    std::error_code ec;
    fs::remove_all(dir, ec);
  }
};

// The input as the file the readers will open.
std::string stage_input(const Scratch& scratch, std::string_view bytes) {
  if (kFormat == "obj") {
    const std::size_t marker = bytes.find(kMtlMarker);
    const fs::path mtl = scratch.dir / "model.mtl";
    if (marker == std::string_view::npos) {
      std::error_code ec;
      fs::remove(mtl, ec);  // an `mtllib` line then meets a missing library
    } else {
      write_file(mtl, bytes.substr(marker + kMtlMarker.size()));
      bytes = bytes.substr(0, marker + 1);
    }
    write_file(scratch.dir / "model.obj", bytes);
    return (scratch.dir / "model.obj").string();
  }
  const std::string name = kFormat == "scene" ? "scene.json" : "model." + std::string(kFormat);
  write_file(scratch.dir / name, bytes);
  return (scratch.dir / name).string();
}

[[noreturn]] void bug(const char* what) {
  std::fprintf(stderr, "fuzz: %s\n", what);
  std::abort();
}

void load_and_solve(const std::string& path) {
  using namespace dynrad;
  ReadOptions read;
  read.other_scene_keys = rad::scene_file_sections();  // as every host reads scenes
  (void)rad::read_grids(path);
  (void)rad::read_cameras(path);
  (void)rad::read_observers(path);
  (void)rad::read_emergency_areas(path);
  LoadedScene scene = load_scene(path, {}, {}, read);
  SceneMesh& mesh = *scene.mesh;
  // Luminaires (their photometric files are the fuzz_ies and fuzz_ldt targets' job;
  // here a scene may name downlight.ies, written beside it).
  std::vector<rad::Luminaire> luminaires = rad::read_luminaires(path);
  (void)rad::read_light_scenes(path, luminaires);
  // The sky section is read and checked (its shots cost too many rays for a fuzz run).
  (void)rad::read_daylight(path, scene.glazing, scene.openings);
  if (luminaires.size() > 16) luminaires.resize(16);  // arrays: a few shots cover the paths
  if (!(mesh.emitting_area() > 0) && luminaires.empty()) return;  // the command line refuses this (exit 2)
  // Coarse patches and a few shots: the point is every code path, not accuracy.
  const double patch_size = 4 * default_patch_size(mesh);
  make_patches(mesh, patch_size);
  const RefinementOptions refinement = refinement_for_patch_size(patch_size);
  ElementHierarchy hierarchy(mesh, refinement);
  rad::SolveOptions options;
  options.max_iterations = 3;
  options.threads = 1;
  options.escape_rays = 64;
  rad::RefineSettings refine;
  refine.method = rad::Method::dynamic;
  refine.max_level = 1;
  // A small emitting patch's first shot keeps its own path (rays, push-down error) but
  // no levels beyond: with the product's 2, the obj target's fixed-seed gate ran a
  // quarter of its inputs in its 300 s (RefineSettings::primary_levels).
  refine.primary_levels = 0;
  if (!luminaires.empty()) {
    options.emission_scale = rad::kLumensPerWatt;
    options.min_reflectance = 1e-4;
    const rad::Visibility visibility(mesh);
    (void)rad::luminaire_warnings(visibility, luminaires);
  }
  rad::Solver solver(mesh, hierarchy, options, refine, luminaires);
  solver.run();
  for (const Rgb& b : solver.output().radiosity)
    if (!b.is_finite()) bug("a vertex radiosity is not finite");
  const rad::EnergyBalance& e = solver.energy();
  for (int c = 0; c < 3; ++c) {
    const double accounted = e.absorbed[c] + e.escaped[c] + e.unshot[c];
    if (!std::isfinite(accounted) || std::abs(accounted - e.emitted[c]) > 1e-6 * e.emitted[c])
      bug("energy balance does not hold: emitted != absorbed + escaped + unshot");
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const Scratch scratch;
  const std::string path = stage_input(scratch, std::string_view(reinterpret_cast<const char*>(data), size));
  try {
    load_and_solve(path);
  } catch (const dynrad::InputError&) {
    // Refused with a message: the right answer to a bad file.
  }
  return 0;
}
