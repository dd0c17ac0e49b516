// libFuzzer target for one import path (DYNRAD_FUZZ_FORMAT: obj, ply, off, stl, scene
// or gltf, the last through assimp). The input bytes become a file of that format, which goes the whole way a
// user's file goes: through the pipeline every host calls (read, repair, light sources,
// settings, patches), then a short dynamic solve.
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
#include "radiosity/pipeline/pipeline.h"

#include <algorithm>
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

// The pipeline every host calls (radiosity/pipeline/pipeline.h), asked for a short
// solve: coarse patches and a few shots, since the point is every code path, not
// accuracy.
dynrad::rad::SceneRequest short_solve(const std::string& path) {
  dynrad::rad::SceneRequest request;
  request.path = path;
  request.simplify.enabled = true;  // as `dynrad solve` and the C ABI
  request.settings.patch_scale = 4;
  request.settings.max_level = 1;
  // A small emitting patch's first shot keeps its own path (rays, push-down error) but
  // no levels beyond: with the product's 2, the obj target's fixed-seed gate ran a
  // quarter of its inputs in its 300 s (RefineSettings::primary_levels).
  request.refine.primary_levels = 0;
  request.shadow_outlines = false;  // tens of luminaires' outlines per input: too slow for a gate
  request.solve.max_iterations = 3;
  request.solve.threads = 1;
  request.solve.escape_rays = 64;
  return request;
}

void load_and_solve(const std::string& path) {
  using namespace dynrad;
  // Throws InputError (NoLightError among them: the command line refuses a scene that
  // nothing lights, exit 2) for what cannot be read or lit.
  rad::PreparedScene prepared = rad::prepare_scene(short_solve(path));
  rad::check_scene_sections(path, prepared.scene);  // cameras, observers, routes, light scenes
  // The sky and the sun are read and checked, but their shots cost too many rays for a
  // fuzz run; of an array of luminaires, a few cover the paths. Their photometric files
  // are the fuzz_ies and fuzz_ldt targets' job: here a scene may name downlight.ies,
  // written beside it. Grids are read, not gathered (48 x 48 rays a point).
  std::vector<rad::Luminaire>& luminaires = prepared.luminaires;
  luminaires.erase(std::remove_if(luminaires.begin(), luminaires.end(),
                                  [](const rad::Luminaire& l) { return l.directional(); }),
                   luminaires.end());
  if (luminaires.size() > 16) luminaires.resize(16);
  prepared.grids.clear();
  if (!(prepared.scene.mesh->emitting_area() > 0) && luminaires.empty()) return;
  const rad::SolvedScene solved = rad::solve_scene(prepared);
  for (const Rgb& b : solved.output.radiosity)
    if (!b.is_finite()) bug("a vertex radiosity is not finite");
  const rad::EnergyBalance& e = solved.solver->energy();
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
