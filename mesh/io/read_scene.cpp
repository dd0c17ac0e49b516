// JSON scene files: several mesh files with transforms, plus material definitions and
// assignments by material or group name (so PLY/OFF/STL geometry can carry emitters).
// Unknown keys are errors: a misspelt key that is silently ignored costs users hours.
#include "mesh/core/error.h"
#include "mesh/io/import.h"
#include "mesh/io/io_util.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <set>

namespace dynrad {
namespace {

using json = nlohmann::json;

class SceneParser {
 public:
  SceneParser(std::string path, const ReadOptions& options) : path_(std::move(path)), options_(options) {}

  PolygonSoup parse() {
    const std::string text = detail::read_file(path_);
    json doc;
    try {
      doc = json::parse(text);
    } catch (const json::parse_error& e) {
      throw InputError(path_, line_of_byte(text, e.byte), std::string("invalid JSON: ") + e.what());
    } catch (const json::exception& e) {  // e.g. out_of_range: a number beyond double's range
      throw InputError(path_, 0, std::string("invalid JSON: ") + e.what());
    }
    if (!doc.is_object()) fail("the scene must be a JSON object with a \"meshes\" array.");
    std::set<std::string> keys = {"meshes", "materials"};
    keys.insert(options_.other_scene_keys.begin(), options_.other_scene_keys.end());
    check_keys(doc, "scene", keys);
    if (!doc.contains("meshes") || !doc["meshes"].is_array() || doc["meshes"].empty())
      fail("\"meshes\" must be a non-empty array of {\"file\": ...} entries.");

    PolygonSoup scene;
    scene.files.push_back(path_);  // index 0: the scene file itself
    for (std::size_t i = 0; i < doc["meshes"].size(); ++i)
      scene.append(load_mesh(doc["meshes"][i], "meshes[" + std::to_string(i) + "]"));

    if (doc.contains("materials")) {
      const json& materials = doc["materials"];
      if (!materials.is_object()) fail("\"materials\" must be an object mapping names to definitions.");
      for (const auto& [name, def] : materials.items()) define_material(scene, name, def);
    }
    return scene;
  }

 private:
  [[noreturn]] void fail(const std::string& what) const { throw InputError(path_, 0, what); }

  static std::size_t line_of_byte(const std::string& text, std::size_t byte) {
    return 1 + static_cast<std::size_t>(std::count(text.begin(), text.begin() + std::min(byte, text.size()), '\n'));
  }

  void check_keys(const json& object, const std::string& where, const std::set<std::string>& known) const {
    for (const auto& item : object.items()) {
      if (known.count(item.key())) continue;
      std::string list;
      for (const auto& k : known) list += (list.empty() ? "" : ", ") + k;
      fail("unknown key \"" + item.key() + "\" in " + where + " (known keys: " + list + ").");
    }
  }

  double number(const json& value, const std::string& where) const {
    if (!value.is_number()) fail(where + " must be a number.");
    const double v = value.get<double>();
    if (!std::isfinite(v)) fail(where + " must be finite.");
    return v;
  }

  // A number (grey) or an array of three numbers.
  Rgb rgb(const json& value, const std::string& where) const {
    if (value.is_number()) return Rgb(number(value, where));
    if (!value.is_array() || value.size() != 3) fail(where + " must be a number or an array of 3 numbers.");
    return Rgb(number(value[0], where + "[0]"), number(value[1], where + "[1]"), number(value[2], where + "[2]"));
  }

  Vec3d vec3(const json& value, const std::string& where) const {
    if (!value.is_array() || value.size() != 3) fail(where + " must be an array of 3 numbers.");
    return Vec3d(number(value[0], where + "[0]"), number(value[1], where + "[1]"), number(value[2], where + "[2]"));
  }

  using Matrix = std::array<std::array<double, 4>, 4>;

  static Matrix identity() {
    Matrix m{};
    for (int i = 0; i < 4; ++i) m[i][i] = 1;
    return m;
  }
  static Matrix multiply(const Matrix& a, const Matrix& b) {
    Matrix c{};
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j)
        for (int k = 0; k < 4; ++k) c[i][j] += a[i][k] * b[k][j];
    return c;
  }

  // transform: either {"matrix": 4x4 row-major} or any of scale, rotate_deg, translate,
  // applied in that order (scale first). Rotations are about x, then y, then z.
  Matrix transform(const json& t, const std::string& where) const {
    if (!t.is_object()) fail(where + " must be an object.");
    check_keys(t, where, {"matrix", "scale", "rotate_deg", "translate"});
    if (t.contains("matrix")) {
      if (t.size() != 1) fail(where + ": \"matrix\" cannot be combined with scale/rotate_deg/translate.");
      const json& m = t["matrix"];
      if (!m.is_array() || m.size() != 4) fail(where + ".matrix must be 4 rows of 4 numbers.");
      Matrix out{};
      for (int i = 0; i < 4; ++i) {
        if (!m[i].is_array() || m[i].size() != 4) fail(where + ".matrix must be 4 rows of 4 numbers.");
        for (int j = 0; j < 4; ++j) out[i][j] = number(m[i][j], where + ".matrix");
      }
      return out;
    }
    Matrix m = identity();
    if (t.contains("scale")) {
      Vec3d s =
          t["scale"].is_number() ? Vec3d(number(t["scale"], where + ".scale")) : vec3(t["scale"], where + ".scale");
      Matrix sm = identity();
      for (int i = 0; i < 3; ++i) sm[i][i] = s[i];
      m = multiply(sm, m);
    }
    if (t.contains("rotate_deg")) {
      const Vec3d r = vec3(t["rotate_deg"], where + ".rotate_deg") * (M_PI / 180.0);
      for (int axis = 0; axis < 3; ++axis) {
        const double c = std::cos(r[axis]), s = std::sin(r[axis]);
        const int a = (axis + 1) % 3, b = (axis + 2) % 3;
        Matrix rm = identity();
        rm[a][a] = c;
        rm[a][b] = -s;
        rm[b][a] = s;
        rm[b][b] = c;
        m = multiply(rm, m);
      }
    }
    if (t.contains("translate")) {
      const Vec3d d = vec3(t["translate"], where + ".translate");
      Matrix tm = identity();
      for (int i = 0; i < 3; ++i) tm[i][3] = d[i];
      m = multiply(tm, m);
    }
    return m;
  }

  std::uint32_t material_named(PolygonSoup& soup, const std::string& name, const std::string& where) const {
    int index = soup.find_material(name);
    if (index < 0) {
      Material placeholder;
      placeholder.name = name;
      placeholder.defined = false;
      placeholder.origin = path_ + " (" + where + ")";
      soup.materials.push_back(placeholder);
      index = static_cast<int>(soup.materials.size() - 1);
    }
    return static_cast<std::uint32_t>(index);
  }

  PolygonSoup load_mesh(const json& entry, const std::string& where) const {
    namespace fs = std::filesystem;
    if (!entry.is_object() || !entry.contains("file") || !entry["file"].is_string())
      fail(where + " must be an object with a \"file\" string.");
    check_keys(entry, where, {"file", "transform", "material", "materials", "groups"});
    fs::path file = entry["file"].get<std::string>();
    if (file.is_relative()) file = fs::path(path_).parent_path() / file;
    if (detail::extension_of(file.string()) == ".json") fail(where + ": scene files cannot include scene files.");
    PolygonSoup soup = read_model(file.string(), options_);

    if (entry.contains("material")) {
      if (!entry["material"].is_string()) fail(where + ".material must be a material name.");
      const std::uint32_t m = material_named(soup, entry["material"].get<std::string>(), where + ".material");
      std::fill(soup.material.begin(), soup.material.end(), m);
    }
    if (entry.contains("materials")) {
      if (!entry["materials"].is_object()) fail(where + ".materials must map material names to material names.");
      std::vector<std::uint32_t> remap(soup.materials.size());
      for (std::size_t i = 0; i < remap.size(); ++i) remap[i] = static_cast<std::uint32_t>(i);
      for (const auto& [from, to] : entry["materials"].items()) {
        const int source = soup.find_material(from);
        if (source < 0) fail(where + ".materials: " + file.string() + " has no material \"" + from + "\".");
        if (!to.is_string()) fail(where + ".materials." + from + " must be a material name.");
        remap[source] = material_named(soup, to.get<std::string>(), where + ".materials");
      }
      for (auto& m : soup.material) m = remap[m];
    }
    if (entry.contains("groups")) {
      if (!entry["groups"].is_object()) fail(where + ".groups must map group names to material names.");
      for (const auto& [group, to] : entry["groups"].items()) {
        auto it = std::find(soup.group_names.begin(), soup.group_names.end(), group);
        if (it == soup.group_names.end()) {
          std::string list;
          for (const auto& g : soup.group_names) list += (list.empty() ? "" : ", ") + g;
          fail(where + ".groups: " + file.string() + " has no group \"" + group + "\" (it has: " + list + ").");
        }
        if (!to.is_string()) fail(where + ".groups." + group + " must be a material name.");
        const auto g = static_cast<std::uint32_t>(it - soup.group_names.begin());
        const std::uint32_t m = material_named(soup, to.get<std::string>(), where + ".groups");
        for (std::size_t i = 0; i < soup.polygons.size(); ++i)
          if (soup.group[i] == g) soup.material[i] = m;
      }
    }
    if (entry.contains("transform")) {
      const Matrix m = transform(entry["transform"], where + ".transform");
      for (auto& p : soup.points) {
        Vec3d q;
        for (int i = 0; i < 3; ++i) q[i] = m[i][0] * p[0] + m[i][1] * p[1] + m[i][2] * p[2] + m[i][3];
        p = q;
      }
      const double det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
                         m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
                         m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
      if (std::abs(det) < 1e-300) fail(where + ".transform is singular (it flattens the model).");
      // A mirroring transform turns counter-clockwise loops clockwise; reverse them so
      // each face keeps the side it faced in the model.
      if (det < 0)
        for (auto& poly : soup.polygons) std::reverse(poly.begin(), poly.end());
    }
    return soup;
  }

  void define_material(PolygonSoup& scene, const std::string& name, const json& def) const {
    const std::string where = "materials." + name;
    if (!def.is_object())
      fail(where + " must be an object with \"reflectance\", \"emission\" and/or \"transmittance\".");
    check_keys(def, where, {"reflectance", "emission", "transmittance"});
    Material m;
    m.name = name;
    m.origin = path_ + " (" + where + ")";
    if (def.contains("reflectance")) m.reflectance = rgb(def["reflectance"], where + ".reflectance");
    if (def.contains("emission")) m.emission = rgb(def["emission"], where + ".emission");
    if (def.contains("transmittance")) m.transmittance = rgb(def["transmittance"], where + ".transmittance");
    // Checked here even when no face uses it: a definition that is wrong is wrong.
    if (def.contains("reflectance") || def.contains("emission") || def.contains("transmittance"))
      accept_material(m, path_, options_, scene.warnings);
    const int existing = scene.find_material(name);
    if (existing < 0) {
      scene.warnings.push_back(path_ + ": material \"" + name + "\" is defined but no face uses it.");
      scene.materials.push_back(m);
    } else {
      // A scene definition replaces the model's: that is how users fix or add emitters.
      Material& target = scene.materials[existing];
      if (!def.contains("reflectance") && target.defined) m.reflectance = target.reflectance;
      if (!def.contains("emission") && target.defined) m.emission = target.emission;
      if (!def.contains("transmittance") && target.defined) m.transmittance = target.transmittance;
      target = m;
    }
  }

  std::string path_;
  ReadOptions options_;
};

}  // namespace

PolygonSoup read_scene(const std::string& path, const ReadOptions& options) {
  return SceneParser(path, options).parse();
}

}  // namespace dynrad
