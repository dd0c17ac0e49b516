#include "mesh/load.h"

#include "mesh/core/error.h"
#include "mesh/io/import.h"
#include "mesh/core/openings.h"
#include "mesh/core/polygon_triangulation.h"

#include <cmath>
#include <limits>
#include <sstream>
#include <unordered_set>

namespace dynrad {
namespace {

// Emitting polygons that cleanup dropped entirely (zero area, fewer than three distinct
// corners, or an exact duplicate of another face): they emit nothing, and the user
// should know, since a lamp modelled as a line or a point is a common mistake. Returns
// a warning, or "" when there is none.
std::string dropped_emitters(const PolygonSoup& soup, const TriangleSoup& clean) {
  auto key = [](const SourceRef& ref) { return (static_cast<std::uint64_t>(ref.file) << 32) | ref.face; };
  std::unordered_set<std::uint64_t> kept;
  for (const SourceRef& ref : clean.origin) kept.insert(key(ref));
  std::size_t dropped = 0;
  std::size_t first = 0;
  for (std::size_t p = 0; p < soup.polygons.size(); ++p) {
    if (!soup.materials[soup.material[p]].emits() || kept.count(key(soup.origin[p]))) continue;
    if (dropped++ == 0) first = p;
  }
  if (dropped == 0) return "";
  return std::to_string(dropped) + " emitting face" + (dropped == 1 ? " was" : "s were") +
         " dropped by cleanup (no area, or a duplicate of another face) and emit nothing (first: " + soup.where(first) +
         ", material '" + soup.materials[soup.material[first]].name + "'). Model a light as a polygon with an area.";
}

// Finite coordinates can still make sizes and powers that are not: 1e200 squared, or an
// emission of 1e308 W/m² over a square metre. The solver would then compute with inf
// and NaN; refuse such models with what overflowed.
void check_magnitudes(const std::string& path, const SceneMesh& mesh) {
  const double diagonal = mesh.bounds().diagonal(), area = mesh.total_area();
  if (!std::isfinite(diagonal) || !std::isfinite(area))
    throw InputError(path, 0,
                     "is too large to compute with (its area overflows double precision). Scale it down: the units "
                     "do not change the result.");
  std::vector<double> material_area(mesh.materials().size(), 0.0);
  for (auto f : mesh.mesh().faces()) material_area[mesh.material_id(f)] += mesh.area(f);
  Rgb total;
  for (std::size_t m = 0; m < material_area.size(); ++m) {
    const Material& material = mesh.materials()[m];
    total += material.emission * material_area[m];
    if (!(material.emission * material_area[m]).is_finite() || !total.is_finite()) {
      std::ostringstream emission;
      emission << material.emission.max_channel();
      throw InputError(path, 0,
                       "material '" + material.name + "' (" + material.origin +
                           ") emits more power than double precision can hold (emission " + emission.str() +
                           " W/m² over its area). Use a physically plausible emission.");
    }
  }
}

}  // namespace

LoadedScene load_scene(const std::string& path, const CleanupOptions& options, const SimplifyOptions& simplify,
                       const ReadOptions& read) {
  return load_soup(read_input(path, read), path, options, simplify);
}

LoadedScene load_soup(const PolygonSoup& soup, const std::string& path, const CleanupOptions& options,
                      const SimplifyOptions& simplify) {
  // Every point (the bounds alone would miss a NaN: comparisons with it are false).
  for (std::size_t i = 0; i < soup.points.size(); ++i)
    if (!is_finite(soup.points[i]))
      throw InputError(path, 0, "point " + std::to_string(i + 1) + " has a coordinate that is not a finite number.");
  // Cleanup and the solver work with areas, the size squared: it must be a normal double.
  const double size = soup.bounds().diagonal();
  if (!std::isfinite(size * size) || size * size < std::numeric_limits<double>::min()) {
    std::ostringstream across;
    across << size;
    throw InputError(path, 0,
                     "is " + across.str() + " units across, too " + (size > 1 ? "large" : "small") +
                         " to compute with in double precision. Scale it (a scene file's \"transform\" can): the "
                         "units do not change the result.");
  }
  // Windows: glass faces leave the soup before cleanup (they are not lit surfaces).
  LoadedScene scene;
  bool any_glass = false;
  for (std::uint32_t m : soup.material) any_glass = any_glass || soup.materials[m].transmits();
  PolygonSoup opaque_soup;
  const PolygonSoup* lit_soup = &soup;
  if (any_glass) {
    opaque_soup = soup;
    opaque_soup.polygons.clear();
    opaque_soup.material.clear();
    opaque_soup.group.clear();
    opaque_soup.origin.clear();
    for (std::size_t p = 0; p < soup.polygons.size(); ++p) {
      const Material& m = soup.materials[soup.material[p]];
      if (!m.transmits()) {
        opaque_soup.polygons.push_back(soup.polygons[p]);
        opaque_soup.material.push_back(soup.material[p]);
        if (p < soup.group.size()) opaque_soup.group.push_back(soup.group[p]);
        opaque_soup.origin.push_back(soup.origin[p]);
        continue;
      }
      const Vec3d normal = newell_normal(soup.points, soup.polygons[p]);
      std::vector<Triangle> triangles;
      if (!(normal.norm() > 0) || !triangulate_polygon(soup.points, soup.polygons[p], normal.normalized(), triangles))
        continue;  // no area: no window
      for (const Triangle& t : triangles)
        scene.glazing.push_back({{soup.points[t[0]], soup.points[t[1]], soup.points[t[2]]}, m.transmittance});
    }
    if (opaque_soup.polygons.empty())
      throw InputError(path, 0, "has only glass (materials with a transmittance): there is no surface to light.");
    lit_soup = &opaque_soup;
  }
  TriangleSoup clean;
  scene.cleanup = cleanup(*lit_soup, clean, options);
  scene.input_files = soup.files.size();
  scene.warnings = soup.warnings;
  if (clean.triangles.empty())
    throw InputError(path, 0,
                     "every face is degenerate (zero area or fewer than 3 distinct corners); first: " +
                         scene.cleanup.first_problem + ". Nothing is left to light.");
  if (scene.cleanup.untriangulatable_polygons > 0)
    scene.warnings.push_back(std::to_string(scene.cleanup.untriangulatable_polygons) +
                             " self-intersecting polygons could not be triangulated and were dropped (first: " +
                             scene.cleanup.first_problem + ").");
  if (scene.cleanup.imprint_failures > 0)
    scene.warnings.push_back(std::to_string(scene.cleanup.imprint_failures) +
                             " faces could not be imprinted where other surfaces meet them (first: " +
                             scene.cleanup.first_imprint_failure +
                             "); they are lit as they were. Check them for self-intersections.");
  if (const std::string warning = dropped_emitters(*lit_soup, clean); !warning.empty()) scene.warnings.push_back(warning);
  scene.mesh = std::make_unique<SceneMesh>(clean);
  check_magnitudes(path, *scene.mesh);
  scene.simplify = simplify_flat_regions(*scene.mesh, simplify);
  scene.openings = find_openings(scene.mesh->mesh());
  return scene;
}

}  // namespace dynrad
