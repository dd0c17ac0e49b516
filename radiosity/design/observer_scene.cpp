// The "observers" array of a JSON scene file: where glare (UGR) is evaluated. Each
// entry:
//
//   "name"       shown in results (default "observer1", "observer2", ...); unique
//   "position"   [x, y, z]: the eye, model units (required)
//   "direction"  [x, y, z]: the line of sight, or
//   "look_at"    [x, y, z]: a point the eye looks at; exactly one of the two. The line
//                of sight is made horizontal (z up) for UGR, so it must not be
//                vertical.
//   "UGR"        the limit to check (EN 12464-1's UGR_L for the task), above 0 and at
//                most 40; optional
//
// Unknown keys are errors.
#include "mesh/core/error.h"
#include "radiosity/design/glare.h"
#include "radiosity/sources/scene_json.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <set>

namespace dynrad::rad {

namespace {

using json = nlohmann::json;

class ObserverParser {
 public:
  explicit ObserverParser(std::string path) : path_(std::move(path)) {}

  std::vector<Observer> parse(const json& list) const {
    if (!list.is_array()) fail("\"observers\" must be an array of observer entries.");
    std::vector<Observer> out;
    std::set<std::string> names;
    for (std::size_t i = 0; i < list.size(); ++i) {
      out.push_back(entry(list[i], i));
      if (!names.insert(out.back().name).second)
        fail("observers[" + std::to_string(i) + "]: two observers are named \"" + out.back().name +
             "\"; give each its own name.");
    }
    return out;
  }

 private:
  [[noreturn]] void fail(const std::string& what) const { throw InputError(path_, 0, what); }

  Vec3d point(const json& v, const std::string& where) const {
    if (!v.is_array() || v.size() != 3) fail(where + " must be [x, y, z].");
    return Vec3d(scene_number(path_, v[0], where + "[0]"), scene_number(path_, v[1], where + "[1]"),
                 scene_number(path_, v[2], where + "[2]"));
  }

  Observer entry(const json& e, std::size_t index) const {
    const std::string where = "observers[" + std::to_string(index) + "]";
    if (!e.is_object()) fail(where + " must be an object.");
    static const std::set<std::string> known = {"name", "position", "direction", "look_at", "UGR"};
    for (const auto& item : e.items())
      if (!known.count(item.key()))
        fail("unknown key \"" + item.key() + "\" in " + where +
             " (known keys: UGR, direction, look_at, name, position).");
    Observer o;
    o.name = "observer" + std::to_string(index + 1);
    if (e.contains("name")) {
      if (!e["name"].is_string() || e["name"].get<std::string>().empty())
        fail(where + ".name must be a non-empty string.");
      o.name = e["name"].get<std::string>();
    }
    const std::string named = where + " (\"" + o.name + "\")";
    if (!e.contains("position")) fail(named + " needs \"position\": [x, y, z], the eye.");
    o.eye = point(e["position"], named + ".position");
    if (e.contains("direction") == e.contains("look_at"))
      fail(named + " needs exactly one of \"direction\" ([x, y, z], the line of sight) and \"look_at\" ([x, y, z]).");
    Vec3d view = e.contains("direction") ? point(e["direction"], named + ".direction")
                                         : point(e["look_at"], named + ".look_at") - o.eye;
    const double length = view.norm();
    if (!(length > 0))
      fail(named + ": the line of sight has no length; give a direction or a point away from the eye.");
    view /= length;
    // UGR needs a horizontal line of sight: within a degree of vertical is refused.
    if (std::hypot(view[0], view[1]) < std::sin(M_PI / 180))
      fail(named + ": the line of sight is vertical; UGR is for a horizontal one, give a direction with x or y.");
    o.view = view;
    if (e.contains("UGR")) {
      o.limit = scene_number(path_, e["UGR"], named + ".UGR");
      if (!(o.limit > 0 && o.limit <= 40))
        fail(named + ".UGR must be above 0 and at most 40 (EN 12464-1 gives 16 to 28).");
    }
    return o;
  }

  std::string path_;
};

}  // namespace

std::vector<Observer> read_observers(const std::string& scene_path) {
  const json list = scene_section(scene_path, "observers");
  if (list.is_null()) return {};
  return ObserverParser(scene_path).parse(list);
}

}  // namespace dynrad::rad
