// Helpers for tests: scratch directories, running the dynrad binary, sample paths.
#pragma once

#include "mesh/core/soup.h"

#include <cstdint>
#include <string>
#include <vector>

namespace dynrad::test {

// A fresh directory under the system temp dir, removed with its contents afterwards.
class TempDir {
 public:
  TempDir();
  ~TempDir();
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  std::string path(const std::string& name) const;
  // Writes `content` to `name` (binary-exact) and returns its path.
  std::string write(const std::string& name, const std::string& content) const;

 private:
  std::string dir_;
};

struct CommandResult {
  int exit_code = -1;
  std::string output;  // stdout and stderr together
};

// Runs the dynrad executable with the given (shell-quoted) arguments.
CommandResult run_dynrad(const std::string& arguments);
// Runs any shell command line.
CommandResult run_shell(const std::string& command);
// Starts `dynrad ARGUMENTS` (a solve) in the background, waits until its log holds
// `ready` (by default the line that counts the patches: it has loaded the model and
// started solving), lets it solve for `seconds`, sends `signal_name` (INT, TERM, KILL)
// and waits for it. The output ends with "exit=N". Waiting for the log rather than a fixed time keeps this right on slow
// (sanitizer) builds: a SIGINT that arrives while a background process still ignores
// it would be lost.
CommandResult run_dynrad_and_signal(const std::string& arguments, double seconds, const std::string& signal_name,
                                    const std::string& ready = " patches");

// An 8-bit PNG as RGB, top row first; empty (width 0) when it cannot be read.
struct Picture {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgb;
  const std::uint8_t* at(int x, int y) const { return &rgb[3 * (static_cast<std::size_t>(y) * width + x)]; }
};
Picture read_png(const std::string& path);

// A closed box room, x in [0, w], y in [0, d], z in [0, h], its faces towards the inside,
// as OBJ text with material `wall` from room.mtl.
std::string box_room_obj(double w, double d, double h);
// Writes a scene to `dir`: that room 4 x 3 x 2.8 m of reflectance 0.6 with a 300 cd
// point lamp at (2, 1.5, 2.7), and `grids` (a JSON array) as its "grids"; returns the
// scene file's path.
std::string write_lamp_room(const TempDir& dir, const std::string& grids);

std::string sample(const std::string& name);
std::string read_text(const std::string& path);
bool file_exists(const std::string& path);

// Total area of a polygon soup (each polygon by its Newell normal).
double polygon_area(const PolygonSoup& soup);

// Form factor from a point facing up to a parallel rectangle [x0, x1] x [y0, y1] facing
// it at height h above (Hottel's corner formula, written independently of the solver).
double parallel_rectangle(double px, double py, double x0, double y0, double x1, double y1, double h);

}  // namespace dynrad::test

namespace dynrad {
class SceneMesh;
}
namespace dynrad::test {
// Number of (vertex, edge) pairs where a vertex lies strictly inside an edge it is not
// an end of: T-vertices. A conforming mesh has none.
std::size_t count_t_vertices(const SceneMesh& mesh, double relative_tolerance = 1e-9);
}  // namespace dynrad::test
