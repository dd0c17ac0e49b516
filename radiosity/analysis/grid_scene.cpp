// The "grids" array of a JSON scene file. Each entry:
//
//   "name"       shown in results and file names (default "grid1", "grid2", ...)
//   "polygon"    [[x, y], ...]: at least 3 corners in the plane's two axes (x and y
//                for z up), or
//   "rectangle"  [x0, y0, x1, y1]
//   "height"     of the plane along the up axis, model units (default 0.8)
//   "spacing"    model units, or "auto" (the default): 0.2 x 5^log10(d), d the longer
//                side, metres assumed
//   "border"     band along the edges left out (default 0)
//   "up"         "x", "y" or "z" (default "z")
//   "target"     the requirements to check (EN 12464-1 gives them per task; every key
//                optional):
//     "Eavg", "U0"     maintained illuminance and uniformity of the task area (the
//                      points the border leaves)
//     "surrounding"    true or {"width": 0.5, "Eavg": E, "U0": 0.4}: the immediate
//                      surrounding, a band `width` wide just outside the task area
//                      (needs a border); Eavg by default from the task's by the
//                      standard's table (design/room_checks.h)
//     "walls"          true or {"Eavg": 75, "U0": 0.1}: the room's walls, the polygon's
//                      sides from the floor to the ceiling
//     "ceiling"        true or {"Eavg": 50, "U0": 0.1}
//     "Ez"             E or {"Eavg": E, "U0": 0.1, "height": 1.2, "modelling": [0.3, 0.6]}:
//                      mean cylindrical illuminance over the task area at `height` above
//                      the floor, and modelling Ez / Eh
//     "UGR"            limit for the observers (the scene's "observers") in the polygon
//
// Unknown keys are errors.
#include "mesh/core/error.h"
#include "radiosity/analysis/grid_scene.h"
#include "radiosity/sources/scene_json.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <set>

namespace dynrad::rad {

namespace {

using json = nlohmann::json;

class GridParser {
 public:
  explicit GridParser(std::string path) : path_(std::move(path)) {}

  std::vector<GridSpec> parse(const json& list) const {
    if (!list.is_array()) fail("\"grids\" must be an array of grid entries.");
    std::vector<GridSpec> out;
    std::set<std::string> names;
    for (std::size_t i = 0; i < list.size(); ++i) {
      out.push_back(entry(list[i], i));
      if (!names.insert(out.back().name).second)
        fail("two grids are named \"" + out.back().name + "\"; give each its own name.");
    }
    return out;
  }

 private:
  [[noreturn]] void fail(const std::string& what) const { throw InputError(path_, 0, what); }

  double number(const json& v, const std::string& where) const { return scene_number(path_, v, where); }

  GridSpec entry(const json& e, std::size_t index) const {
    const std::string where = "grids[" + std::to_string(index) + "]";
    if (!e.is_object()) fail(where + " must be an object.");
    static const std::set<std::string> known = {"name", "polygon", "rectangle", "height", "spacing", "border", "up", "target"};
    for (const auto& item : e.items())
      if (!known.count(item.key()))
        fail("unknown key \"" + item.key() + "\" in " + where +
             " (known keys: border, height, name, polygon, rectangle, spacing, target, up).");
    GridSpec g;
    g.name = "grid" + std::to_string(index + 1);
    if (e.contains("name")) {
      if (!e["name"].is_string() || e["name"].get<std::string>().empty()) fail(where + ".name must be a non-empty string.");
      g.name = e["name"].get<std::string>();
      for (char c : g.name)
        if (c == '/' || c == '\\' || static_cast<unsigned char>(c) < 32)
          fail(where + ".name must not hold '/', '\\' or control characters (it names result files).");
    }
    const std::string named = where + " (\"" + g.name + "\")";
    if (e.contains("polygon") == e.contains("rectangle"))
      fail(named + " needs exactly one of \"polygon\" ([[x, y], ...]) and \"rectangle\" ([x0, y0, x1, y1]).");
    if (e.contains("rectangle")) {
      const json& r = e["rectangle"];
      if (!r.is_array() || r.size() != 4) fail(named + ".rectangle must be [x0, y0, x1, y1].");
      const double x0 = number(r[0], named + ".rectangle[0]"), y0 = number(r[1], named + ".rectangle[1]");
      const double x1 = number(r[2], named + ".rectangle[2]"), y1 = number(r[3], named + ".rectangle[3]");
      if (!(x1 > x0 && y1 > y0)) fail(named + ".rectangle needs x1 > x0 and y1 > y0.");
      g.polygon = {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}};
    } else {
      const json& p = e["polygon"];
      if (!p.is_array() || p.size() < 3 || p.size() > 100000)
        fail(named + ".polygon must be an array of at least 3 corners [x, y].");
      for (std::size_t k = 0; k < p.size(); ++k) {
        const std::string at = named + ".polygon[" + std::to_string(k) + "]";
        if (!p[k].is_array() || p[k].size() != 2) fail(at + " must be [x, y].");
        g.polygon.push_back({number(p[k][0], at + "[0]"), number(p[k][1], at + "[1]")});
      }
      double area = 0;
      for (std::size_t i = 0, j = g.polygon.size() - 1; i < g.polygon.size(); j = i++)
        area += g.polygon[j][0] * g.polygon[i][1] - g.polygon[i][0] * g.polygon[j][1];
      if (!(std::abs(area) > 0)) fail(named + ".polygon encloses no area.");
    }
    if (e.contains("height")) g.height = number(e["height"], named + ".height");
    if (e.contains("spacing")) {
      const json& s = e["spacing"];
      if (s.is_string()) {
        if (s.get<std::string>() != "auto") fail(named + ".spacing must be a number or \"auto\".");
      } else {
        g.spacing = number(s, named + ".spacing");
        if (!(g.spacing > 0)) fail(named + ".spacing must be above 0.");
      }
    }
    if (e.contains("border")) {
      g.border = number(e["border"], named + ".border");
      if (g.border < 0) fail(named + ".border must not be negative.");
    }
    if (e.contains("up")) {
      const std::string up = e["up"].is_string() ? e["up"].get<std::string>() : "";
      if (up == "x") g.up = 0;
      else if (up == "y") g.up = 1;
      else if (up == "z") g.up = 2;
      else fail(named + ".up must be \"x\", \"y\" or \"z\".");
    }
    if (e.contains("target")) {
      const json& t = e["target"];
      if (!t.is_object() || t.empty())
        fail(named + ".target must be an object such as {\"Eavg\": 500, \"U0\": 0.6}.");
      for (const auto& item : t.items()) {
        if (room_target(item.key(), item.value(), named + ".target." + item.key(), g)) continue;
        const double x = number(item.value(), named + ".target." + item.key());
        if (item.key() == "Eavg") {
          if (!(x > 0)) fail(named + ".target.Eavg must be above 0.");
          g.target_eavg = x;
        } else if (item.key() == "U0") {
          if (!(x > 0 && x <= 1)) fail(named + ".target.U0 must be above 0 and at most 1.");
          g.target_u0 = x;
        } else {
          fail("unknown key \"" + item.key() + "\" in " + named +
               ".target (known keys: Eavg, U0, surrounding, walls, ceiling, Ez, UGR).");
        }
      }
    }
    // Bounded work: a million points per grid at most (the cells are counted before
    // any is made).
    double lo[2] = {1e300, 1e300}, hi[2] = {-1e300, -1e300};
    for (const auto& p : g.polygon)
      for (int k = 0; k < 2; ++k) {
        lo[k] = std::min(lo[k], p[k]);
        hi[k] = std::max(hi[k], p[k]);
      }
    const double p = g.spacing > 0 ? g.spacing : automatic_spacing(std::max(hi[0] - lo[0], hi[1] - lo[1]));
    if ((hi[0] - lo[0]) / p * ((hi[1] - lo[1]) / p) > 4e6)
      fail(named + " would have more than a million points; give a larger \"spacing\".");
    const std::size_t count = grid_points(g).size();
    if (count > 1000000) fail(named + " would have more than a million points; give a larger \"spacing\".");
    if (count == 0) fail(named + " has no point: its border leaves nothing of the polygon.");
    if (g.room.surrounding > 0 && !(g.border > 0))
      fail(named + ".target.surrounding needs a \"border\": the surrounding band lies between the task area (the "
                   "polygon less its border) and the polygon's edge. Give the grid the room's outline as its polygon "
                   "and a border of at least the band's width (0.5 m).");
    return g;
  }

  // The room's requirements (RoomTargets); false when `key` is not one of them.
  bool room_target(const std::string& key, const json& v, const std::string& where, GridSpec& g) const {
    RoomTargets& r = g.room;
    // true, or an object of numbers with the given keys, each checked by `read`.
    auto object = [&](const std::set<std::string>& keys, auto read) {
      if (v.is_boolean()) {
        if (!v.get<bool>()) fail(where + " must be true or an object; leave it out to skip the check.");
        return;
      }
      if (!v.is_object()) fail(where + " must be true or an object.");
      for (const auto& item : v.items()) {
        if (!keys.count(item.key())) {
          std::string list;
          for (const std::string& k : keys) list += (list.empty() ? "" : ", ") + k;
          fail("unknown key \"" + item.key() + "\" in " + where + " (known keys: " + list + ").");
        }
        read(item.key(), item.value(), where + "." + item.key());
      }
    };
    auto positive = [&](const json& x, const std::string& at) {
      const double y = number(x, at);
      if (!(y > 0)) fail(at + " must be above 0.");
      return y;
    };
    auto fraction = [&](const json& x, const std::string& at) {
      const double y = number(x, at);
      if (!(y > 0 && y <= 1)) fail(at + " must be above 0 and at most 1.");
      return y;
    };
    if (key == "surrounding") {
      r.surrounding = 0.5;
      object({"width", "Eavg", "U0"}, [&](const std::string& k, const json& x, const std::string& at) {
        if (k == "width") r.surrounding = positive(x, at);
        if (k == "Eavg") r.surrounding_eavg = positive(x, at);
        if (k == "U0") r.surrounding_u0 = fraction(x, at);
      });
    } else if (key == "walls" || key == "ceiling") {
      const bool walls = key == "walls";
      (walls ? r.walls : r.ceiling) = true;
      object({"Eavg", "U0"}, [&](const std::string& k, const json& x, const std::string& at) {
        if (k == "Eavg") (walls ? r.walls_eavg : r.ceiling_eavg) = positive(x, at);
        if (k == "U0") (walls ? r.walls_u0 : r.ceiling_u0) = fraction(x, at);
      });
    } else if (key == "Ez") {
      if (v.is_number()) {
        r.ez = positive(v, where);
        return true;
      }
      if (!v.is_object() || !v.contains("Eavg")) fail(where + " must be a number (lx) or an object with \"Eavg\".");
      object({"Eavg", "U0", "height", "modelling"}, [&](const std::string& k, const json& x, const std::string& at) {
        if (k == "Eavg") r.ez = positive(x, at);
        if (k == "U0") r.ez_u0 = fraction(x, at);
        if (k == "height") r.ez_height = positive(x, at);
        if (k == "modelling") {
          if (!x.is_array() || x.size() != 2) fail(at + " must be [low, high], such as [0.3, 0.6].");
          r.modelling_low = number(x[0], at + "[0]");
          r.modelling_high = number(x[1], at + "[1]");
          if (!(r.modelling_low >= 0 && r.modelling_high > r.modelling_low))
            fail(at + " must be [low, high] with 0 <= low < high.");
        }
      });
    } else if (key == "UGR") {
      r.ugr = number(v, where);
      if (!(r.ugr > 0 && r.ugr <= 40)) fail(where + " must be a UGR limit above 0 and at most 40 (19 for offices).");
    } else {
      return false;
    }
    return true;
  }

  std::string path_;
};

}  // namespace

std::vector<GridSpec> read_grids(const std::string& scene_path) {
  const json list = scene_section(scene_path, "grids");
  if (list.is_null()) return {};
  return GridParser(scene_path).parse(list);
}

}  // namespace dynrad::rad
