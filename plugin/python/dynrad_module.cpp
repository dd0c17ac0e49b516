// `import dynrad`: the pipeline (radiosity/pipeline/pipeline.h) for Python, with NumPy
// arrays in and out. The package (plugin/python/dynrad/__init__.py) re-exports it;
// docs/hosts.md shows its use.
#include "mesh/core/error.h"
#include "mesh/io/import.h"
#include "mesh/load.h"
#include "radiosity/pipeline/pipeline.h"
#include "radiosity/pipeline/report_json.h"
#include "radiosity/solver/settings.h"

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <spdlog/spdlog.h>

#include <cmath>
#include <limits>
#include <optional>
#include <string>

namespace py = pybind11;
using namespace dynrad;

namespace {

// The options `dynrad solve` takes that shape a result, as keyword arguments.
struct Options {
  std::string quality = "normal", method = "dynamic";
  std::optional<double> patch_size, converge, time_limit;
  std::optional<int> max_level, threads;
  std::optional<std::size_t> iterations;
  std::uint64_t seed = default_seed();
  bool imprint = true, simplify = true;
};

rad::SceneRequest make_request(const std::string& path, const Options& o) {
  rad::SceneRequest request;
  request.path = path;
  request.refine.method = rad::parse_method(o.method);  // std::invalid_argument: ValueError
  request.settings.quality = rad::parse_quality(o.quality);
  if (o.patch_size) request.settings.patch_size = *o.patch_size;
  if (o.max_level) request.settings.max_level = *o.max_level;
  if (o.converge) request.settings.converge = *o.converge;
  if (o.time_limit) request.solve.time_limit = *o.time_limit;
  if (o.iterations) request.solve.max_iterations = *o.iterations;
  if (o.threads) request.solve.threads = *o.threads;
  request.solve.seed = o.seed;
  request.solve.ambient_display = true;
  request.cleanup.imprint = o.imprint;
  request.simplify.enabled = o.simplify;
  // Ctrl-C in Python stops the solve at the next shot, and the solution so far is
  // returned (its report's stopped_by: "interrupted"), as `dynrad solve` writes it.
  request.solve.should_stop = [] {
    py::gil_scoped_acquire gil;
    if (PyErr_CheckSignals() == 0) return false;
    PyErr_Clear();
    return true;
  };
  return request;
}

template <typename T>
py::array_t<T> matrix(const std::vector<T>& values, std::size_t columns) {
  py::array_t<T> out({static_cast<py::ssize_t>(values.size() / columns), static_cast<py::ssize_t>(columns)});
  std::copy(values.begin(), values.end(), out.mutable_data());
  return out;
}

// The result as a dict of arrays: per output vertex its position, radiosity (rgb),
// irradiance (rgb; illuminance in lx is its luminance in photometric solves); per
// triangle its corners and material; per grid its points and illuminance; the report.
py::dict result_dict(rad::PreparedScene& prepared, rad::SolvedScene& solved) {
  const SceneMesh& mesh = *prepared.scene.mesh;
  const rad::Solver::Output& out = solved.output;
  std::vector<double> positions, radiosity, irradiance;
  for (std::size_t v = 0; v < out.split.size(); ++v) {
    const Vec3d& p = mesh.mesh().point(out.split.source[v]);
    positions.insert(positions.end(), {p[0], p[1], p[2]});
    radiosity.insert(radiosity.end(), {out.radiosity[v].r, out.radiosity[v].g, out.radiosity[v].b});
    irradiance.insert(irradiance.end(), {out.irradiance[v].r, out.irradiance[v].g, out.irradiance[v].b});
  }
  std::vector<std::uint32_t> triangles(out.split.corner.begin(), out.split.corner.end()), materials;
  for (auto f : mesh.mesh().faces()) materials.push_back(static_cast<std::uint32_t>(mesh.material_id(f)));
  py::dict result;
  result["positions"] = matrix(positions, 3);
  result["triangles"] = matrix(triangles, 3);
  result["triangle_materials"] = matrix(materials, 1).attr("reshape")(-1);
  result["radiosity"] = matrix(radiosity, 3);
  result["irradiance"] = matrix(irradiance, 3);
  py::dict grids;
  for (const rad::GridResult& g : solved.grids) {
    std::vector<double> points, lux;
    for (const rad::GridPointResult& q : g.points) {
      points.insert(points.end(), {q.position[0], q.position[1], q.position[2]});
      lux.push_back(q.masked ? std::numeric_limits<double>::quiet_NaN() : q.illuminance);
    }
    py::dict grid;
    grid["points"] = matrix(points, 3);
    grid["illuminance"] = matrix(lux, 1).attr("reshape")(-1);
    grids[py::str(g.spec.name)] = grid;
  }
  result["grids"] = grids;
  nlohmann::json report = rad::solve_report_json(prepared, solved, 0);
  report["input"] = prepared.request.path;
  report["grids"] = rad::grid_summary_json(solved);
  result["report"] = py::module_::import("json").attr("loads")(report.dump());
  return result;
}

py::dict solve_prepared(rad::SceneRequest request, LoadedScene* loaded) {
  rad::PreparedScene prepared = rad::prepare_scene(request, loaded);
  rad::SolvedScene solved;
  {
    py::gil_scoped_release free;  // the solve runs without the GIL (should_stop takes it)
    solved = rad::solve_scene(prepared);
  }
  return result_dict(prepared, solved);
}

Options options_from(const py::kwargs& kwargs) {
  Options o;
  for (const auto& [key, value] : kwargs) {
    const std::string k = py::str(key);
    if (k == "quality") o.quality = value.cast<std::string>();
    else if (k == "method") o.method = value.cast<std::string>();
    else if (k == "patch_size") o.patch_size = value.cast<double>();
    else if (k == "converge") o.converge = value.cast<double>();
    else if (k == "time_limit") o.time_limit = value.cast<double>();
    else if (k == "max_level") o.max_level = value.cast<int>();
    else if (k == "threads") o.threads = value.cast<int>();
    else if (k == "iterations") o.iterations = value.cast<std::size_t>();
    else if (k == "seed") o.seed = value.cast<std::uint64_t>();
    else if (k == "imprint") o.imprint = value.cast<bool>();
    else if (k == "simplify") o.simplify = value.cast<bool>();
    else
      throw py::type_error("unknown option '" + k +
                           "'; options: quality, method, patch_size, converge, time_limit, max_level, threads, "
                           "iterations, seed, imprint, simplify");
  }
  return o;
}

py::dict solve_file(const std::string& path, const py::kwargs& kwargs) {
  return solve_prepared(make_request(path, options_from(kwargs)), nullptr);
}

// A model from arrays: vertices (n, 3), faces (m, 3) vertex indices, face_materials (m)
// indices into `materials`, each a dict with "reflectance" and optionally "emission"
// (a number or [r, g, b]) and "name".
py::dict solve_arrays(py::array_t<double, py::array::c_style | py::array::forcecast> vertices,
                      py::array_t<std::int64_t, py::array::c_style | py::array::forcecast> faces,
                      py::array_t<std::int64_t, py::array::c_style | py::array::forcecast> face_materials,
                      const py::list& materials, const py::kwargs& kwargs) {
  if (vertices.ndim() != 2 || vertices.shape(1) != 3) throw py::value_error("vertices must have shape (n, 3)");
  if (faces.ndim() != 2 || faces.shape(1) != 3) throw py::value_error("faces must have shape (m, 3)");
  if (face_materials.ndim() != 1 || face_materials.shape(0) != faces.shape(0))
    throw py::value_error("face_materials must have one index per face");
  const Options o = options_from(kwargs);
  PolygonSoup soup;
  const std::string label = "arrays";
  soup.files = {label};
  soup.group_names = {"scene"};
  auto rgb = [](const py::handle& v) {
    if (py::isinstance<py::float_>(v) || py::isinstance<py::int_>(v)) return Rgb(v.cast<double>());
    const auto c = v.cast<std::vector<double>>();
    if (c.size() != 3) throw py::value_error("a colour is a number or [r, g, b]");
    return Rgb(c[0], c[1], c[2]);
  };
  for (std::size_t i = 0; i < materials.size(); ++i) {
    const py::dict m = materials[i].cast<py::dict>();
    Material material;
    material.name = m.contains("name") ? m["name"].cast<std::string>() : "material " + std::to_string(i);
    material.reflectance = m.contains("reflectance") ? rgb(m["reflectance"]) : Rgb(0.5);
    material.emission = m.contains("emission") ? rgb(m["emission"]) : Rgb();
    material.origin = "materials[" + std::to_string(i) + "]";
    check_material(material, "materials[" + std::to_string(i) + "]");
    soup.materials.push_back(std::move(material));
  }
  const auto* v = vertices.data();
  for (py::ssize_t i = 0; i < vertices.shape(0); ++i) soup.points.emplace_back(v[3 * i], v[3 * i + 1], v[3 * i + 2]);
  const auto* f = faces.data();
  const auto* fm = face_materials.data();
  for (py::ssize_t i = 0; i < faces.shape(0); ++i) {
    std::vector<std::uint32_t> loop;
    for (int k = 0; k < 3; ++k) {
      const std::int64_t index = f[3 * i + k];
      if (index < 0 || index >= vertices.shape(0))
        throw py::value_error("face " + std::to_string(i) + ": vertex index " + std::to_string(index) +
                              " is out of range");
      loop.push_back(static_cast<std::uint32_t>(index));
    }
    if (fm[i] < 0 || static_cast<std::size_t>(fm[i]) >= materials.size())
      throw py::value_error("face " + std::to_string(i) + ": material index " + std::to_string(fm[i]) +
                            " is out of range");
    soup.polygons.push_back(std::move(loop));
    soup.material.push_back(static_cast<std::uint32_t>(fm[i]));
    soup.group.push_back(0);
    soup.origin.push_back(SourceRef{0, 0, static_cast<std::uint32_t>(i)});
  }
  rad::SceneRequest request = make_request(label, o);
  LoadedScene loaded = load_soup(soup, label, request.cleanup, request.simplify);
  return solve_prepared(std::move(request), &loaded);
}

}  // namespace

PYBIND11_MODULE(_dynrad, m) {
  m.doc() = "dynrad: radiosity for architectural models (docs/hosts.md)";
  spdlog::set_level(spdlog::level::warn);  // results and errors, not the pipeline's notes
  py::register_exception<InputError>(m, "InputError", PyExc_ValueError);
  m.attr("__version__") = DYNRAD_VERSION;
  m.def("solve", &solve_file, py::arg("path"),
        "Light a model or a JSON scene file as `dynrad solve` does; keyword options: quality, method, patch_size, "
        "converge, time_limit, max_level, threads, iterations, seed, imprint, simplify. Returns a dict of NumPy "
        "arrays (positions, triangles, triangle_materials, radiosity, irradiance), grids {name: {points, "
        "illuminance}} and the report (a dict).");
  m.def("solve_arrays", &solve_arrays, py::arg("vertices"), py::arg("faces"), py::arg("face_materials"),
        py::arg("materials"),
        "Light a model given as arrays: vertices (n, 3), faces (m, 3), face_materials (m,) and materials, a list of "
        "dicts with 'reflectance' and 'emission' (a number or [r, g, b]) and 'name'. Options and result as solve().");
}
