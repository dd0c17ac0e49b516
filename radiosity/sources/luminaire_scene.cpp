// The "luminaires" array of a JSON scene file. Each entry:
//
//   "type"                "photometric" (the default when "photometry" is given),
//                         "point" or "spot"
//   "name"                shown by `info` and in warnings (default "L1", "L2", ... by
//                         position in the array)
//   "position"            [x, y, z], model units
//   "aim"                 [dx, dy, dz]: where the nadir (gamma 0) points (default down,
//                         [0, 0, -1]); not used by a point source
//   "spin"                degrees about the aim (default 0; see luminaire.h)
//   photometric:
//   "photometry"          an .ies or .ldt file, relative to the scene file
//   "lumens"              rescale the file's distribution to this flux (default: the
//                         file's own)
//   point and spot:
//   "intensity"           cd; or "lumens" (point: I = lumens / 4 pi; spot: the
//                         intensity that gives that flux within its cone)
//   "cone"                spot: [inner, outer] degrees from the aim (full intensity
//                         within inner, none beyond outer)
//   any:
//   "maintenance_factor"  in (0, 1], multiplies the flux (default 1)
//   "colour" / "color"    [r, g, b]: a tint, scaled to luminance 1 (default white)
//   "group"               control group name (light scenes dim groups)
//   "watts"               electrical power, for the luminaire schedule
//   "emergency"           also an emergency luminaire (EN 1838): true (its full flux
//                         on emergency supply), a factor in (0, 1] (the emergency
//                         ballast lumen factor) or {"lumens": flux on emergency supply}
//   "positions"           [[x, y, z], ...] instead of "position": one luminaire at each,
//                         named "<name>.1", "<name>.2", ...
//   "array"               {"count": [n1, n2], "step": [[dx, dy, dz], [ex, ey, ez]]}:
//                         n1 x n2 copies from "position", named "<name>.i.j"
//
// Unknown keys are errors, as in the rest of the scene file.
#include "mesh/core/error.h"
#include "radiosity/sources/luminaire.h"
#include "radiosity/sources/scene_json.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <map>
#include <set>

namespace dynrad::rad {

namespace {

using json = nlohmann::json;

class LuminaireParser {
 public:
  explicit LuminaireParser(std::string path) : path_(std::move(path)) {}

  std::vector<Luminaire> parse(const json& list) {
    if (!list.is_array()) fail("\"luminaires\" must be an array of luminaire entries.");
    std::vector<Luminaire> out;
    for (std::size_t i = 0; i < list.size(); ++i) add_entry(list[i], i, out);
    std::set<std::string> names;
    for (const Luminaire& l : out)
      if (!names.insert(l.name).second) fail("two luminaires are named \"" + l.name + "\"; give each its own name.");
    return out;
  }

 private:
  [[noreturn]] void fail(const std::string& what) const { throw InputError(path_, 0, what); }

  double number(const json& v, const std::string& where) const { return scene_number(path_, v, where); }

  Vec3d vec3(const json& v, const std::string& where) const {
    if (!v.is_array() || v.size() != 3) fail(where + " must be an array of 3 numbers.");
    return Vec3d(number(v[0], where + "[0]"), number(v[1], where + "[1]"), number(v[2], where + "[2]"));
  }

  void add_entry(const json& e, std::size_t index, std::vector<Luminaire>& out) {
    const std::string where = "luminaires[" + std::to_string(index) + "]";
    if (!e.is_object()) fail(where + " must be an object.");
    static const std::set<std::string> known = {"type",   "name",   "position", "aim",       "spin",
                                                "photometry", "lumens", "intensity", "cone", "maintenance_factor",
                                                "colour", "color",  "positions", "array", "group", "watts",
                                                "emergency"};
    for (const auto& item : e.items())
      if (!known.count(item.key())) {
        std::string list;
        for (const auto& k : known) list += (list.empty() ? "" : ", ") + k;
        fail("unknown key \"" + item.key() + "\" in " + where + " (known keys: " + list + ").");
      }
    Luminaire l;
    l.name = "L" + std::to_string(index + 1);
    if (e.contains("name")) {
      if (!e["name"].is_string() || e["name"].get<std::string>().empty())
        fail(where + ".name must be a non-empty string.");
      l.name = e["name"].get<std::string>();
    }
    const std::string named = where + " (\"" + l.name + "\")";
    std::string type = e.contains("photometry") ? "photometric" : "";
    if (e.contains("type")) {
      if (!e["type"].is_string()) fail(named + ".type must be \"photometric\", \"point\" or \"spot\".");
      type = e["type"].get<std::string>();
    }
    if (type == "photometric") {
      l.kind = Luminaire::Kind::photometric;
    } else if (type == "point") {
      l.kind = Luminaire::Kind::point;
    } else if (type == "spot") {
      l.kind = Luminaire::Kind::spot;
    } else if (type.empty()) {
      fail(named + " needs a \"photometry\" file (.ies or .ldt), or \"type\": \"point\" or \"spot\" with an "
                   "\"intensity\" in cd.");
    } else {
      fail(named + ".type is \"" + type + "\"; it must be \"photometric\", \"point\" or \"spot\".");
    }
    const Vec3d aim = e.contains("aim") ? vec3(e["aim"], named + ".aim") : Vec3d(0, 0, -1);
    const double spin = e.contains("spin") ? number(e["spin"], named + ".spin") : 0.0;
    try {
      aim_luminaire(l, aim, spin);
    } catch (const std::invalid_argument&) {
      fail(named + ".aim must be a non-zero direction (where the luminaire's nadir points).");
    }
    if (e.contains("maintenance_factor")) {
      l.maintenance_factor = number(e["maintenance_factor"], named + ".maintenance_factor");
      if (!(l.maintenance_factor > 0 && l.maintenance_factor <= 1))
        fail(named + ".maintenance_factor must lie in (0, 1] (typical: 0.8).");
    }
    for (const char* key : {"colour", "color"})
      if (e.contains(key)) {
        const Vec3d c = vec3(e[key], named + "." + key);
        const Rgb tint(c[0], c[1], c[2]);
        if (c[0] < 0 || c[1] < 0 || c[2] < 0 || !(tint.luminance() > 0))
          fail(named + "." + key + " must have no negative channel and a luminance above 0.");
        l.colour = tint * (1.0 / tint.luminance());
      }
    const bool has_lumens = e.contains("lumens");
    const double lumens = has_lumens ? number(e["lumens"], named + ".lumens") : 0.0;
    if (has_lumens && !(lumens > 0)) fail(named + ".lumens must be above 0.");
    if (l.kind == Luminaire::Kind::photometric) {
      if (!e.contains("photometry") || !e["photometry"].is_string())
        fail(named + " needs \"photometry\": the path of an .ies or .ldt file.");
      for (const char* key : {"intensity", "cone"})
        if (e.contains(key)) fail(named + "." + key + " is for point and spot sources; a photometric file gives it.");
      l.photometry = photometry(e["photometry"].get<std::string>());
      const double file_flux = l.photometry->flux;
      if (!(file_flux > 0)) fail(named + ": " + l.photometry->file + " sends no light (every intensity is 0).");
      l.scale = (has_lumens ? lumens / file_flux : 1.0) * l.maintenance_factor * l.photometry->tilt_factor(l.tilt);
    } else {
      if (e.contains("photometry")) fail(named + ".photometry is for photometric luminaires (leave \"type\" out).");
      if (l.kind == Luminaire::Kind::spot) {
        if (!e.contains("cone")) fail(named + " is a spot: it needs \"cone\": [inner, outer] in degrees from the aim.");
        const json& cone = e["cone"];
        if (!cone.is_array() || cone.size() != 2) fail(named + ".cone must be [inner, outer] in degrees.");
        l.inner = number(cone[0], named + ".cone[0]");
        l.outer = number(cone[1], named + ".cone[1]");
        if (!(l.inner >= 0 && l.inner <= l.outer && l.outer > 0 && l.outer <= 180))
          fail(named + ".cone must satisfy 0 <= inner <= outer <= 180 with outer above 0.");
      } else if (e.contains("cone")) {
        fail(named + ".cone is for spots (\"type\": \"spot\").");
      }
      if (e.contains("intensity") == has_lumens)
        fail(named + " needs exactly one of \"intensity\" (cd) and \"lumens\".");
      if (has_lumens) {
        l.intensity = 1;
        l.intensity = lumens / l.flux();
      } else {
        l.intensity = number(e["intensity"], named + ".intensity");
        if (!(l.intensity > 0)) fail(named + ".intensity must be above 0 (candela).");
      }
      l.intensity *= l.maintenance_factor;
    }
    if (e.contains("group")) {
      if (!e["group"].is_string() || e["group"].get<std::string>().empty())
        fail(named + ".group must be a non-empty string (the control group's name).");
      l.group = e["group"].get<std::string>();
    }
    if (e.contains("watts")) {
      l.watts = number(e["watts"], named + ".watts");
      if (!(l.watts > 0)) fail(named + ".watts must be above 0.");
    }
    if (e.contains("emergency")) {
      const json& m = e["emergency"];
      const std::string usage = named + ".emergency must be true, a factor in (0, 1] of the flux, or {\"lumens\": F}.";
      if (m.is_boolean()) {
        l.emergency = m.get<bool>() ? 1.0 : 0.0;
      } else if (m.is_number()) {
        l.emergency = number(m, named + ".emergency");
        if (!(l.emergency > 0 && l.emergency <= 1)) fail(usage);
      } else if (m.is_object() && m.size() == 1 && m.contains("lumens")) {
        const double supply = number(m["lumens"], named + ".emergency.lumens");
        const double flux = l.flux();
        if (!(supply > 0)) fail(named + ".emergency.lumens must be above 0.");
        if (!(supply <= flux * (1 + 1e-9)))
          fail(named + ".emergency.lumens is above the luminaire's flux (" + std::to_string(flux) + " lm).");
        l.emergency = supply / flux;
      } else {
        fail(usage);
      }
    }
    // Where: one position, a list, or an array from the position.
    const int ways = e.contains("position") + e.contains("positions");
    if (ways != 1) fail(named + " needs exactly one of \"position\" and \"positions\".");
    if (e.contains("position")) {
      l.position = vec3(e["position"], named + ".position");
      if (!e.contains("array")) {
        out.push_back(l);
        return;
      }
      const json& a = e["array"];
      if (!a.is_object() || !a.contains("count") || !a.contains("step") || a.size() != 2)
        fail(named + ".array must be {\"count\": [n1, n2], \"step\": [[dx, dy, dz], [ex, ey, ez]]}.");
      const json& count = a["count"];
      const json& step = a["step"];
      if (!count.is_array() || count.size() != 2 || !step.is_array() || step.size() != 2)
        fail(named + ".array must be {\"count\": [n1, n2], \"step\": [[dx, dy, dz], [ex, ey, ez]]}.");
      int n[2];
      for (int k = 0; k < 2; ++k) {
        const double v = number(count[k], named + ".array.count[" + std::to_string(k) + "]");
        if (!(v >= 1 && v <= 10000 && v == std::floor(v)))
          fail(named + ".array.count must hold whole numbers from 1 to 10000.");
        n[k] = static_cast<int>(v);
      }
      if (static_cast<std::size_t>(n[0]) * n[1] + out.size() > 100000)
        fail(named + ".array makes more than 100000 luminaires.");
      const Vec3d s0 = vec3(step[0], named + ".array.step[0]"), s1 = vec3(step[1], named + ".array.step[1]");
      const Vec3d origin = l.position;
      const std::string base = l.name;
      for (int i = 0; i < n[0]; ++i)
        for (int j = 0; j < n[1]; ++j) {
          l.position = origin + s0 * i + s1 * j;
          l.name = base + "." + std::to_string(i + 1) + "." + std::to_string(j + 1);
          out.push_back(l);
        }
      return;
    }
    if (e.contains("array")) fail(named + ".array goes with \"position\" (the first copy), not \"positions\".");
    const json& list = e["positions"];
    if (!list.is_array() || list.empty()) fail(named + ".positions must be a non-empty array of [x, y, z].");
    if (list.size() + out.size() > 100000) fail(named + ".positions makes more than 100000 luminaires.");
    const std::string base = l.name;
    for (std::size_t k = 0; k < list.size(); ++k) {
      l.position = vec3(list[k], named + ".positions[" + std::to_string(k) + "]");
      l.name = base + "." + std::to_string(k + 1);
      out.push_back(l);
    }
  }

  // Each file is read once, however many luminaires use it.
  std::shared_ptr<const Photometry> photometry(const std::string& file) {
    std::filesystem::path p(file);
    if (p.is_relative()) p = std::filesystem::path(path_).parent_path() / p;
    const std::string resolved = p.lexically_normal().string();
    auto it = files_.find(resolved);
    if (it != files_.end()) return it->second;
    auto read = std::make_shared<const Photometry>(read_photometry(resolved));
    files_.emplace(resolved, read);
    return read;
  }

  std::string path_;
  std::map<std::string, std::shared_ptr<const Photometry>> files_;
};

}  // namespace

std::vector<Luminaire> read_luminaires(const std::string& scene_path) {
  const json list = scene_section(scene_path, "luminaires");
  if (list.is_null()) return {};
  return LuminaireParser(scene_path).parse(list);
}

}  // namespace dynrad::rad
