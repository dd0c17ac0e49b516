#include "mesh/io/import.h"

#include "mesh/core/error.h"
#include "mesh/io/io_util.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace dynrad {
namespace detail {
PolygonSoup read_obj(const std::string& path, const ReadOptions& options);
PolygonSoup read_openmesh(const std::string& path, const ReadOptions& options);
PolygonSoup read_assimp(const std::string& path, const ReadOptions& options);
bool assimp_reads(const std::string& extension);
}  // namespace detail

namespace {

PolygonSoup read_by_extension(const std::string& path, const std::string& ext, const ReadOptions& options) {
  if (ext == ".obj") return detail::read_obj(path, options);
  if (ext == ".ply" || ext == ".off" || ext == ".stl") return detail::read_openmesh(path, options);
  if (ext != ".json" && detail::assimp_reads(ext)) return detail::read_assimp(path, options);
  throw InputError(path, 0,
                   "unsupported file type '" + ext + "'. dynrad reads .obj (with .mtl), .ply, .off, .stl, .json scene "
                   "files, and through assimp IFC, glTF (.gltf, .glb), COLLADA (.dae), 3DS, FBX and more.");
}

}  // namespace

PolygonSoup read_model(const std::string& path, const ReadOptions& options) {
  const std::string ext = detail::extension_of(path);
  PolygonSoup soup = read_by_extension(path, ext, options);
  // assimp hands every format over y up (it turns z-up IFC and COLLADA files itself);
  // dynrad's own readers keep the file's axes, which dynrad takes as z up.
  const bool through_assimp = ext != ".obj" && ext != ".ply" && ext != ".off" && ext != ".stl";
  const int up = options.up >= 0 ? options.up : through_assimp ? 1 : 2;
  if (!(options.scale > 0) || !std::isfinite(options.scale))
    throw InputError(path, 0, "the scale must be a positive number.");
  for (Vec3d& p : soup.points) {
    if (up == 1) p = Vec3d(p[0], -p[2], p[1]);
    p *= options.scale;
  }
  return soup;
}

namespace {
std::string format_rgb(const Rgb& c) {
  std::ostringstream out;
  out << "(" << c.r << ", " << c.g << ", " << c.b << ")";
  return out.str();
}
}  // namespace

void check_material(const Material& m, const std::string& where) {
  const std::string who = "material '" + m.name + "'" + (m.origin.empty() ? "" : " (" + m.origin + ")");
  if (!m.reflectance.is_finite() || !m.emission.is_finite())
    throw InputError(where, 0, who + " has a value that is not a finite number.");
  if (m.reflectance.max_channel() >= 1.0)
    throw InputError(where, 0,
                     who + ": reflectance " + format_rgb(m.reflectance) +
                         " must be below 1 in every channel, since a surface cannot reflect more light than "
                         "it receives. Real materials lie between about 0.02 and 0.9.");
  if (m.reflectance.min_channel() < 0.0)
    throw InputError(where, 0, who + ": reflectance " + format_rgb(m.reflectance) + " must not be negative.");
  if (m.emission.min_channel() < 0.0)
    throw InputError(where, 0, who + ": emission " + format_rgb(m.emission) + " must not be negative.");
  if (!m.transmittance.is_finite() || m.transmittance.min_channel() < 0.0 || m.transmittance.max_channel() >= 1.0)
    throw InputError(where, 0,
                     who + ": transmittance " + format_rgb(m.transmittance) +
                         " must be from 0 (opaque) to below 1 in every channel (clear glass passes about 0.8 "
                         "at normal incidence, double glazing about 0.7).");
  if (m.transmits() && m.emits())
    throw InputError(where, 0, who + " both emits and transmits; a window is not a light. Give it a "
                                     "transmittance only; the sky and the sun come through it (\"sky\" in a scene file).");
}

void accept_material(Material& m, const std::string& where, const ReadOptions& options,
                     std::vector<std::string>& warnings) {
  if (!options.strict && m.reflectance.is_finite() && m.reflectance.max_channel() >= 1.0) {
    const Rgb given = m.reflectance;
    m.reflectance =
        Rgb(std::min(given.r, kMaxReflectance), std::min(given.g, kMaxReflectance), std::min(given.b, kMaxReflectance));
    const std::string who = "material '" + m.name + "'" + (m.origin.empty() ? "" : " (" + m.origin + ")");
    warnings.push_back(who + ": reflectance " + format_rgb(given) +
                       " is 1 or more, but no surface reflects more light than it receives; lowered to " +
                       format_rgb(m.reflectance) +
                       ". Real materials lie between about 0.02 and 0.9 (--strict refuses such a material).");
  }
  check_material(m, where);
}

PolygonSoup read_input(const std::string& path, const ReadOptions& options) {
  PolygonSoup soup = detail::extension_of(path) == ".json" ? read_scene(path, options) : read_model(path, options);
  if (soup.polygons.empty())
    throw InputError(path, 0, "contains no faces, so there is nothing to light. Check that the export included geometry.");
  std::vector<char> used(soup.materials.size(), 0);
  for (auto m : soup.material) used[m] = 1;
  for (std::size_t i = 0; i < soup.materials.size(); ++i) {
    if (!used[i]) continue;
    Material& m = soup.materials[i];
    if (!m.defined) {
      const std::string advice = "Add it to the .mtl file or define it under \"materials\" in a scene file.";
      if (options.strict)
        throw InputError(path, 0,
                         "material '" + m.name + "' is used (" + m.origin + ") but defined nowhere. " + advice);
      // Materials are unique by name in a soup, so this warns once per name, at its first use.
      soup.warnings.push_back(m.origin + ": material '" + m.name + "' is used but defined nowhere; its faces get " +
                              "the default material (grey, reflectance 0.5, no emission). " + advice);
      Material fallback;  // grey 0.5, no emission
      fallback.name = m.name;
      fallback.origin = m.origin + ", defined nowhere: the default material";
      m = fallback;
    }
    accept_material(m, path, options, soup.warnings);
  }
  return soup;
}

}  // namespace dynrad
