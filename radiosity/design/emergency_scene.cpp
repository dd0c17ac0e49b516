// The scene file's emergency areas (design/emergency.h):
//
//   "routes"       [{"name": "corridor", "path": [[x, y], ...], "width": 2, "floor": 0,
//                    "up": "z"}, ...]: escape routes by their centre line (at least two
//                  points, in the plan's axes) and width (default 2 m)
//   "open_areas"   [{"name": "hall", "polygon": [[x, y], ...] or "rectangle":
//                    [x0, y0, x1, y1], "floor": 0, "up": "z"}, ...]: anti-panic areas
//
// "floor" is the height of the floor along the up axis (default 0); names default to
// "route1", "area1", ... and must be unique. Unknown keys are errors.
#include "mesh/core/error.h"
#include "radiosity/design/emergency.h"
#include "radiosity/sources/scene_json.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <set>

namespace dynrad::rad {

namespace {

using json = nlohmann::json;

class EmergencyParser {
 public:
  explicit EmergencyParser(std::string path) : path_(std::move(path)) {}

  void parse(const json& list, EmergencyArea::Kind kind, std::vector<EmergencyArea>& out) {
    const bool route = kind == EmergencyArea::Kind::route;
    const std::string section = route ? "routes" : "open_areas";
    if (!list.is_array()) fail("\"" + section + "\" must be an array of objects.");
    for (std::size_t i = 0; i < list.size(); ++i) {
      const json& e = list[i];
      const std::string where = section + "[" + std::to_string(i) + "]";
      if (!e.is_object()) fail(where + " must be an object.");
      const std::set<std::string> known = route ? std::set<std::string>{"name", "path", "width", "floor", "up"}
                                                : std::set<std::string>{"name", "polygon", "rectangle", "floor", "up"};
      for (const auto& item : e.items())
        if (!known.count(item.key())) {
          std::string keys;
          for (const std::string& k : known) keys += (keys.empty() ? "" : ", ") + k;
          fail("unknown key \"" + item.key() + "\" in " + where + " (known keys: " + keys + ").");
        }
      EmergencyArea a;
      a.kind = kind;
      a.name = (route ? "route" : "area") + std::to_string(i + 1);
      if (e.contains("name")) {
        if (!e["name"].is_string() || e["name"].get<std::string>().empty()) fail(where + ".name must be a non-empty string.");
        a.name = e["name"].get<std::string>();
      }
      if (!names_.insert(a.name).second)
        fail("two emergency areas are named \"" + a.name + "\" (" + where + "); give each its own name.");
      const std::string named = where + " (\"" + a.name + "\")";
      if (e.contains("floor")) a.floor = scene_number(path_, e["floor"], named + ".floor");
      if (e.contains("up")) {
        const std::string up = e["up"].is_string() ? e["up"].get<std::string>() : "";
        if (up != "x" && up != "y" && up != "z") fail(named + ".up must be \"x\", \"y\" or \"z\".");
        a.up = up[0] - 'x';
      }
      if (route) {
        if (!e.contains("path")) fail(named + " needs a \"path\": its centre line, [[x, y], ...].");
        a.points = corners(e["path"], named + ".path", 2);
        double length = 0;
        for (std::size_t k = 0; k + 1 < a.points.size(); ++k)
          length += std::hypot(a.points[k + 1][0] - a.points[k][0], a.points[k + 1][1] - a.points[k][1]);
        if (!(length > 0)) fail(named + ".path has no length.");
        if (length > 1e5) fail(named + ".path is longer than 100 km; check its units.");
        if (e.contains("width")) {
          a.width = scene_number(path_, e["width"], named + ".width");
          if (!(a.width > 0 && a.width <= 100)) fail(named + ".width must be above 0 and at most 100.");
        }
      } else {
        if (e.contains("polygon") == e.contains("rectangle"))
          fail(named + " needs exactly one of \"polygon\" ([[x, y], ...]) and \"rectangle\" ([x0, y0, x1, y1]).");
        if (e.contains("rectangle")) {
          const json& r = e["rectangle"];
          if (!r.is_array() || r.size() != 4) fail(named + ".rectangle must be [x0, y0, x1, y1].");
          double v[4];
          for (int k = 0; k < 4; ++k) v[k] = scene_number(path_, r[k], named + ".rectangle[" + std::to_string(k) + "]");
          if (!(v[2] > v[0] && v[3] > v[1])) fail(named + ".rectangle needs x1 > x0 and y1 > y0.");
          a.points = {{v[0], v[1]}, {v[2], v[1]}, {v[2], v[3]}, {v[0], v[3]}};
        } else {
          a.points = corners(e["polygon"], named + ".polygon", 3);
        }
        double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
        for (const auto& p : a.points)
          for (int k = 0; k < 2; ++k) {
            lo[k] = std::min(lo[k], p[k]);
            hi[k] = std::max(hi[k], p[k]);
          }
        if ((hi[0] - lo[0]) * (hi[1] - lo[1]) > 1e6) fail(named + " is larger than a square kilometre; check its units.");
      }
      out.push_back(a);
    }
  }

 private:
  [[noreturn]] void fail(const std::string& what) const { throw InputError(path_, 0, what); }

  std::vector<std::array<double, 2>> corners(const json& p, const std::string& where, std::size_t least) const {
    if (!p.is_array() || p.size() < least || p.size() > 100000)
      fail(where + " must be an array of at least " + std::to_string(least) + " points [x, y].");
    std::vector<std::array<double, 2>> out;
    for (std::size_t k = 0; k < p.size(); ++k) {
      const std::string at = where + "[" + std::to_string(k) + "]";
      if (!p[k].is_array() || p[k].size() != 2) fail(at + " must be [x, y].");
      out.push_back({scene_number(path_, p[k][0], at + "[0]"), scene_number(path_, p[k][1], at + "[1]")});
    }
    return out;
  }

  std::string path_;
  std::set<std::string> names_;
};

}  // namespace

std::vector<EmergencyArea> read_emergency_areas(const std::string& scene_path) {
  std::vector<EmergencyArea> out;
  EmergencyParser parser(scene_path);
  const json routes = scene_section(scene_path, "routes");
  if (!routes.is_null()) parser.parse(routes, EmergencyArea::Kind::route, out);
  const json areas = scene_section(scene_path, "open_areas");
  if (!areas.is_null()) parser.parse(areas, EmergencyArea::Kind::open_area, out);
  return out;
}

}  // namespace dynrad::rad
