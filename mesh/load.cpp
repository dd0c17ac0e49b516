#include "mesh/load.h"

#include "mesh/error.h"
#include "mesh/import.h"

namespace dynrad {

LoadedScene load_scene(const std::string& path, const CleanupOptions& options) {
  return load_soup(read_input(path), path, options);
}

LoadedScene load_soup(const PolygonSoup& soup, const std::string& path, const CleanupOptions& options) {
  if (!is_finite(soup.bounds().lo) || !is_finite(soup.bounds().hi))
    throw InputError(path, 0, "has coordinates that are not finite.");
  TriangleSoup clean;
  LoadedScene scene;
  scene.cleanup = cleanup(soup, clean, options);
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
  scene.mesh = std::make_unique<SceneMesh>(clean);
  return scene;
}

}  // namespace dynrad
