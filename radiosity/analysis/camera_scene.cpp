// The "cameras" array of a JSON scene file (see views.h).
#include "mesh/core/error.h"
#include "radiosity/sources/scene_json.h"
#include "radiosity/analysis/views.h"

#include <cmath>
#include <set>

namespace dynrad::rad {

namespace {

using json = nlohmann::json;

Vec3d point(const std::string& path, const json& v, const std::string& where) {
  if (!v.is_array() || v.size() != 3) throw InputError(path, 0, where + " must be [x, y, z].");
  return Vec3d(scene_number(path, v[0], where + "[0]"), scene_number(path, v[1], where + "[1]"),
               scene_number(path, v[2], where + "[2]"));
}

int pixels(const std::string& path, const json& v, const std::string& where) {
  const double x = scene_number(path, v, where);
  if (x != std::floor(x) || x < 16 || x > 8192)
    throw InputError(path, 0, where + " must be a whole number of pixels from 16 to 8192.");
  return static_cast<int>(x);
}

}  // namespace

std::vector<View> read_cameras(const std::string& path) {
  const json list = scene_section(path, "cameras");
  if (list.is_null()) return {};
  auto fail = [&](const std::string& what) { throw InputError(path, 0, what); };
  if (!list.is_array()) fail("\"cameras\" must be an array of camera entries.");
  static const std::set<std::string> known = {"name", "position", "look_at", "fov", "up", "width", "height"};
  std::vector<View> out;
  std::set<std::string> names;
  for (std::size_t i = 0; i < list.size(); ++i) {
    const json& e = list[i];
    std::string where = "cameras[" + std::to_string(i) + "]";
    if (!e.is_object()) fail(where + " must be an object.");
    for (const auto& item : e.items())
      if (!known.count(item.key()))
        fail("unknown key \"" + item.key() + "\" in " + where +
             " (known keys: fov, height, look_at, name, position, up, width).");
    View v;
    v.kind = View::Kind::declared;
    v.name = "camera" + std::to_string(i + 1);
    if (e.contains("name")) {
      if (!e["name"].is_string() || e["name"].get<std::string>().empty()) fail(where + ".name must be a non-empty string.");
      v.name = e["name"].get<std::string>();
      for (char c : v.name)
        if (c == '/' || c == '\\' || static_cast<unsigned char>(c) < 32)
          fail(where + ".name must not hold '/', '\\' or control characters (it names result files).");
    }
    if (!names.insert(v.name).second) fail("two cameras are named \"" + v.name + "\"; give each its own name.");
    where += " (\"" + v.name + "\")";
    if (!e.contains("position") || !e.contains("look_at"))
      fail(where + " needs \"position\" and \"look_at\", each [x, y, z].");
    v.camera.eye = point(path, e["position"], where + ".position");
    v.camera.target = point(path, e["look_at"], where + ".look_at");
    const Vec3d forward = v.camera.target - v.camera.eye;
    if (!(forward.norm() > 0)) fail(where + ": \"look_at\" is the camera's own position; aim it at a point away from it.");
    v.camera.up = e.contains("up") ? point(path, e["up"], where + ".up") : Vec3d(0, 0, 1);
    if (!(OpenMesh::cross(forward.normalized(), v.camera.up).norm() > 1e-3 * v.camera.up.norm()))
      fail(where + " looks along its \"up\" (" + (e.contains("up") ? "as given" : "+z by default") +
           "); give an \"up\" that is not along the line of sight.");
    v.camera.fov_degrees = 60;
    if (e.contains("fov")) {
      v.camera.fov_degrees = scene_number(path, e["fov"], where + ".fov");
      if (!(v.camera.fov_degrees > 0 && v.camera.fov_degrees < 170))
        fail(where + ".fov is the vertical field of view in degrees, between 0 and 170.");
    }
    if (e.contains("width")) v.width = pixels(path, e["width"], where + ".width");
    v.height = e.contains("height") ? pixels(path, e["height"], where + ".height") : v.width * 3 / 4;
    v.description = "declared in the scene file";
    out.push_back(v);
  }
  return out;
}

}  // namespace dynrad::rad
