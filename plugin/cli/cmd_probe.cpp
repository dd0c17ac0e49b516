// `dynrad probe LIT.ply --points points.txt`: values of a lit mesh at calculation
// points, as lighting designers ask for them.
//
// Each point comes with the normal of the surface it measures. The point is taken to
// the lit surface it faces: a ray from the point (lifted a hair along the normal)
// along -normal finds the first surface, which must face back along the normal; the
// radiosity there is interpolated linearly from the hit triangle's corners (the
// values the solver computed). A point on a surface reads that surface; a point of a
// work plane above the floor reads the first surface below it (the floor, or a desk
// top), with the distance reported. dynrad does not compute light in mid-air.
//
// Radiosity B (W/m^2) is what the lit PLY holds. Irradiance H, the light arriving,
// follows from B = E + rho H as H = (B - E) / rho, which needs the reflectance rho
// and the emission E of the surface hit. The PLY does not hold them; they come from
// the original model (--model: the material of the model face at the hit point) or
// from --reflectance for all points (E is then taken as 0, so do not use it on
// emitters). A channel with rho = 0 has no irradiance reading.
//
// Points file: one point per line, `x y z nx ny nz`, `#` starts a comment. --grid
// x0,y0,x1,y1,step,height adds a horizontal work plane facing up (--up gives the up
// axis; the grid runs over the other two, in x, y, z order). The rays go to Embree
// (rad::Visibility): 6,700 points on a lit building of 450,000 triangles take half a
// second.
#include "mesh/io/atomic_file.h"
#include "mesh/core/error.h"
#include "mesh/load.h"
#include "plugin/cli/commands.h"
#include "plugin/cli/lit_mesh.h"
#include "radiosity/transfer/visibility.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>
#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iostream>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <sstream>

namespace dynrad::cli {
namespace {

struct ProbeOptions {
  std::string lit, points, grid, model, reflectance, output;
  std::string up = "z";
  bool json = false;
  LoadOptions model_load;  // how --model is read: as for solve
};

struct CalculationPoint {
  Vec3d position, normal;
  std::string source;  // "points.txt:7" or "grid"
};

std::vector<CalculationPoint> read_points(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path, 0, "cannot be read. Check the path.");
  std::vector<CalculationPoint> points;
  std::size_t line_no = 0;
  for (std::string line; std::getline(in, line);) {
    ++line_no;
    line = line.substr(0, line.find('#'));
    std::istringstream fields(line);
    std::vector<double> values;
    for (std::string field; fields >> field;) {
      char* end = nullptr;
      const double value = std::strtod(field.c_str(), &end);
      if (end == field.c_str() || *end != '\0' || !std::isfinite(value))
        throw InputError(path, line_no, "'" + field + "' is not a finite number. Each line is x y z nx ny nz.");
      values.push_back(value);
    }
    if (values.empty()) continue;
    if (values.size() != 6)
      throw InputError(path, line_no, fmt::format("expected 6 numbers (x y z nx ny nz), found {}.", values.size()));
    const Vec3d normal(values[3], values[4], values[5]);
    if (!(normal.norm() > 0))
      throw InputError(path, line_no, "the normal (nx ny nz) is zero; give the direction the surface faces.");
    points.push_back(
        {Vec3d(values[0], values[1], values[2]), normal.normalized(), fmt::format("{}:{}", path, line_no)});
  }
  if (points.empty()) throw InputError(path, 0, "holds no points. Each line is x y z nx ny nz; # starts a comment.");
  return points;
}

std::vector<double> parse_numbers(const std::string& text, const std::string& option) {
  std::vector<double> values;
  std::istringstream in(text);
  for (std::string field; std::getline(in, field, ',');) {
    char* end = nullptr;
    const double value = std::strtod(field.c_str(), &end);
    if (field.empty() || end == field.c_str() || *end != '\0' || !std::isfinite(value))
      throw InputError(option, 0, "'" + field + "' is not a number (expected comma-separated numbers).");
    values.push_back(value);
  }
  return values;
}

std::vector<CalculationPoint> grid_points(const std::string& spec, const std::string& up) {
  const auto v = parse_numbers(spec, "--grid");
  if (v.size() != 6)
    throw InputError("--grid", 0, "expects x0,y0,x1,y1,step,height (6 numbers), got " + std::to_string(v.size()) + ".");
  const double step = v[4];
  if (!(step > 0) || v[2] < v[0] || v[3] < v[1])
    throw InputError("--grid", 0, "needs step > 0, x1 >= x0 and y1 >= y0.");
  const int up_axis = up == "x" ? 0 : up == "y" ? 1 : up == "z" ? 2 : -1;
  if (up_axis < 0) throw InputError("--up", 0, "'" + up + "' is not an axis; use x, y or z.");
  const int a = up_axis == 0 ? 1 : 0, b = up_axis == 2 ? 1 : 2;  // the other two axes, in order
  const auto count = [&](double lo, double hi) { return static_cast<long>(std::floor((hi - lo) / step + 1e-9)) + 1; };
  const long nu = count(v[0], v[2]), nv = count(v[1], v[3]);
  if (nu * nv > 1000000) throw InputError("--grid", 0, "would make more than a million points; use a larger step.");
  std::vector<CalculationPoint> points;
  Vec3d normal(0.0);
  normal[up_axis] = 1;
  for (long j = 0; j < nv; ++j)
    for (long i = 0; i < nu; ++i) {
      Vec3d p(0.0);
      p[a] = v[0] + i * step;
      p[b] = v[1] + j * step;
      p[up_axis] = v[5];
      points.push_back({p, normal, "grid"});
    }
  return points;
}

// Where a calculation point meets the lit surface, and the radiosity there.
struct Hit {
  Vec3d point;
  Vec3d face_normal;
  double distance = 0;
  Rgb radiosity;
  double illuminance = 0, luminance = 0;  // photometric PLY only
};

std::optional<Hit> find_surface(const LitMesh& lit, const rad::Visibility& index, const CalculationPoint& p,
                                std::string& problem) {
  const double lift = 1e-6 * lit.diagonal;
  const Vec3d origin = p.position + p.normal * lift, direction = -p.normal;
  // Embree finds the first triangle along the ray (either side; the side is checked
  // below); the weights and the distance are then computed in double precision.
  rad::Visibility::Intersection first = index.intersect(origin, direction);
  if (!first.hit) {
    // A ray exactly along a face's boundary edge (a work plane point on the plane of a
    // wall that stands on the floor's edge) can slip past in single precision: the same
    // ray moved a hair sideways, four ways (diagonally: off both planes of a corner
    // between axis-aligned walls), and the nearest face they meet.
    const Vec3d t1 = OpenMesh::cross(direction, std::abs(direction[0]) < 0.9 ? Vec3d(1, 0, 0) : Vec3d(0, 1, 0))
                         .normalized(),
                t2 = OpenMesh::cross(direction, t1);
    for (const Vec3d& side : {t1 + t2, t1 - t2, t2 - t1, (t1 + t2) * -1.0}) {
      const rad::Visibility::Intersection moved = index.intersect(origin + side * lift, direction);
      if (moved.hit && (!first.hit || moved.distance < first.distance)) first = moved;
    }
  }
  if (!first.hit) {
    problem = "no surface along -normal";
    return std::nullopt;
  }
  // Where the point lies on an edge or a corner that several faces share (a lamp's
  // edge in a ceiling), which of them Embree reports depends on its tree. The faces
  // around the hit face's corners (at the same places, split vertices included) are
  // tested again in double precision (Moller-Trumbore, both sides, a little slack on
  // the barycentric bounds) in number order, and the nearest wins, the lower-numbered
  // one on a tie: the same face a search of every triangle finds.
  std::vector<std::uint32_t> candidates;
  for (std::uint32_t v : lit.triangles[static_cast<std::size_t>(first.face)])
    candidates.insert(candidates.end(), lit.around.begin() + lit.around_start[lit.place[v]],
                      lit.around.begin() + lit.around_start[lit.place[v] + 1]);
  std::sort(candidates.begin(), candidates.end());
  candidates.erase(std::unique(candidates.begin(), candidates.end()), candidates.end());
  std::size_t face = static_cast<std::size_t>(first.face);
  double u = first.u, w = first.v, distance = first.distance;
  double best = std::numeric_limits<double>::infinity();
  for (std::uint32_t f : candidates) {
    const auto& t = lit.triangles[f];
    const Vec3d &a = lit.positions[t[0]], &b = lit.positions[t[1]], &c = lit.positions[t[2]];
    const Vec3d e1 = b - a, e2 = c - a, h = OpenMesh::cross(direction, e2);
    const double det = OpenMesh::dot(e1, h);
    if (std::abs(det) < 1e-300) continue;
    const Vec3d s = origin - a, q = OpenMesh::cross(s, e1);
    const double fu = OpenMesh::dot(s, h) / det, fw = OpenMesh::dot(direction, q) / det;
    const double slack = 1e-9;
    if (fu < -slack || fw < -slack || fu + fw > 1 + slack) continue;
    const double fd = OpenMesh::dot(e2, q) / det;
    if (fd <= 0 || fd >= best) continue;
    best = distance = fd;
    face = f;
    u = fu;
    w = fw;
  }
  // (none passes only where a moved ray found the face: its weights, clamped)
  const auto& t = lit.triangles[face];
  const Vec3d &a = lit.positions[t[0]], &b = lit.positions[t[1]], &c = lit.positions[t[2]];
  u = std::clamp(u, 0.0, 1.0);
  w = std::clamp(w, 0.0, 1.0 - u);
  Hit hit;
  hit.face_normal = OpenMesh::cross(b - a, c - a).normalized();
  if (OpenMesh::dot(hit.face_normal, p.normal) <= 0) {
    problem = "the first surface along -normal faces away (the point looks at its back)";
    return std::nullopt;
  }
  const double wa = 1 - u - w;
  hit.point = a * wa + b * u + c * w;
  hit.distance = std::max(0.0, distance - lift);
  hit.radiosity = lit.radiosity[t[0]] * wa + lit.radiosity[t[1]] * u + lit.radiosity[t[2]] * w;
  if (lit.photometric) {
    hit.illuminance = lit.illuminance[t[0]] * wa + lit.illuminance[t[1]] * u + lit.illuminance[t[2]] * w;
    hit.luminance = lit.luminance[t[0]] * wa + lit.luminance[t[1]] * u + lit.luminance[t[2]] * w;
  }
  return hit;
}

nlohmann::json rgb_json(const Rgb& c) { return {c.r, c.g, c.b}; }

int run_probe(const ProbeOptions& options) {
  if (options.points.empty() && options.grid.empty())
    throw InputError("probe", 0, "give calculation points: --points FILE and/or --grid x0,y0,x1,y1,step,height.");
  if (!options.model.empty() && !options.reflectance.empty())
    throw InputError("probe", 0, "give --model or --reflectance, not both (see dynrad probe --help).");
  std::optional<Rgb> constant_reflectance;
  if (!options.reflectance.empty()) {
    const auto v = parse_numbers(options.reflectance, "--reflectance");
    if (v.size() != 1 && v.size() != 3)
      throw InputError("--reflectance", 0, "expects one value or three (r,g,b), in (0, 1).");
    const Rgb rho = v.size() == 1 ? Rgb(v[0]) : Rgb(v[0], v[1], v[2]);
    if (!(rho.min_channel() > 0) || !(rho.max_channel() < 1))
      throw InputError("--reflectance", 0, "each value must lie in (0, 1): the surface's diffuse reflectance.");
    constant_reflectance = rho;
  }
  if (!options.output.empty()) check_output_writable(options.output);

  std::vector<CalculationPoint> points;
  if (!options.points.empty()) points = read_points(options.points);
  if (!options.grid.empty()) {
    const auto grid = grid_points(options.grid, options.up);
    points.insert(points.end(), grid.begin(), grid.end());
  }
  const LitMesh lit = read_lit(options.lit);
  const rad::Visibility lit_index(lit.positions, lit.triangles);
  std::unique_ptr<SceneMesh> model;
  std::unique_ptr<rad::Visibility> model_index;
  if (!options.model.empty()) {
    LoadedScene loaded = load_scene(options.model, options.model_load.cleanup(), {}, options.model_load.read());
    for (const auto& w : loaded.warnings) spdlog::warn("{}", w);  // its materials give the irradiance
    check_model_matches(lit, options.lit, *loaded.mesh, options.model);
    model = std::move(loaded.mesh);
    model_index = std::make_unique<rad::Visibility>(*model);
  }

  nlohmann::json rows = nlohmann::json::array();
  std::ostringstream table;
  const bool photometric = lit.photometric;
  // Photometric: the PLY holds illuminance itself; no model or reflectance needed.
  const bool irradiance_known = !photometric && (constant_reflectance || model);
  if (photometric)
    table << fmt::format("{:>4} {:>30} {:>9} {:>14} {:>14}", "#", "point", "distance", "E (lx)", "L (cd/m2)");
  else
    table << fmt::format("{:>4} {:>30} {:>9} {:>32} {:>10}", "#", "point", "distance", "radiosity r g b (W/m2)",
                         "B lum");
  if (irradiance_known) table << fmt::format(" {:>32} {:>10}", "irradiance r g b (W/m2)", "H lum");
  table << "\n";
  std::size_t missed = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const CalculationPoint& p = points[i];
    nlohmann::json row = {{"point", {p.position[0], p.position[1], p.position[2]}},
                          {"normal", {p.normal[0], p.normal[1], p.normal[2]}},
                          {"source", p.source}};
    std::string problem;
    const auto hit = find_surface(lit, lit_index, p, problem);
    const std::string where = fmt::format("({:.4g}, {:.4g}, {:.4g})", p.position[0], p.position[1], p.position[2]);
    table << fmt::format("{:>4} {:>30}", i + 1, where);
    if (!hit) {
      ++missed;
      row["radiosity"] = nullptr;
      row["problem"] = problem;
      table << "  " << problem << "\n";
      if (p.source != "grid") spdlog::warn("{}: {}: {}", p.source, where, problem);
      rows.push_back(row);
      continue;
    }
    row["surface_point"] = {hit->point[0], hit->point[1], hit->point[2]};
    row["distance"] = hit->distance;
    row["radiosity"] = rgb_json(hit->radiosity);
    row["radiosity_luminance"] = hit->radiosity.luminance();
    if (photometric) {
      row["illuminance"] = hit->illuminance;
      row["luminance"] = hit->luminance;
      table << fmt::format(" {:>9.4g} {:>14.5g} {:>14.5g}\n", hit->distance, hit->illuminance, hit->luminance);
      rows.push_back(row);
      continue;
    }
    table << fmt::format(" {:>9.4g} {:>10.4g} {:>10.4g} {:>10.4g} {:>10.4g}", hit->distance, hit->radiosity.r,
                         hit->radiosity.g, hit->radiosity.b, hit->radiosity.luminance());
    if (irradiance_known) {
      Rgb rho, emission;
      const Material* material = nullptr;
      if (constant_reflectance) {
        rho = *constant_reflectance;
      } else if ((material = material_at(*model, *model_index, hit->point, hit->face_normal))) {
        rho = material->reflectance;
        emission = material->emission;
        row["material"] = material->name;
      }
      if (constant_reflectance || material) {
        row["reflectance"] = rgb_json(rho);
        row["emission"] = rgb_json(emission);
        nlohmann::json h = nlohmann::json::array();
        Rgb value;
        bool all = true;
        for (int c = 0; c < 3; ++c) {
          if (rho[c] > 0) {
            const double hc = std::max(0.0, hit->radiosity[c] - emission[c]) / rho[c];
            h.push_back(hc);
            (c == 0 ? value.r : c == 1 ? value.g : value.b) = hc;
          } else {
            h.push_back(nullptr);
            all = false;
          }
        }
        row["irradiance"] = h;
        if (all) row["irradiance_luminance"] = value.luminance();
        auto cell = [&](int c) { return rho[c] > 0 ? fmt::format("{:>10.4g}", value[c]) : fmt::format("{:>10}", "-"); };
        table << fmt::format(" {} {} {} {:>10}", cell(0), cell(1), cell(2),
                             all ? fmt::format("{:.4g}", value.luminance()) : "-");
      } else {
        row["irradiance"] = nullptr;
        row["problem"] = "no face of " + options.model + " at this point";
        table << "  (no model face here)";
        spdlog::warn("{}: {}: no face of {} at the surface point found; is it the model the PLY was lit from?",
                     p.source, where, options.model);
      }
    }
    table << "\n";
    rows.push_back(row);
  }
  if (missed == points.size())
    throw InputError(options.points.empty() ? "--grid" : options.points, 0,
                     "no point found a lit surface along -normal. Check that the points use the model's units and "
                     "axes (--up for grids) and that the normals point away from the surfaces.");
  if (missed) spdlog::warn("{} of {} points found no lit surface facing them.", missed, points.size());

  std::string text;
  if (options.json) {
    nlohmann::json j = {{"lit", options.lit},
                        {"units", photometric ? "photometric: radiosity lm/m2, illuminance lx, luminance cd/m2"
                                              : "W/m2; irradiance H = (B - E) / reflectance"},
                        {"irradiance_from", model                  ? "model " + options.model
                                            : constant_reflectance ? std::string("--reflectance")
                                                                   : std::string("none")},
                        {"points", rows}};
    text = j.dump(2) + "\n";
  } else {
    text = table.str();
  }
  if (options.output.empty()) {
    std::cout << text;
  } else {
    AtomicFile file(options.output, std::ios::out);
    file.stream() << text;
    file.commit();
    spdlog::info("wrote {} ({} points)", options.output, points.size());
  }
  return kExitOk;
}

}  // namespace

Command add_probe_command(CLI::App& app) {
  auto options = std::make_shared<ProbeOptions>();
  CLI::App* command =
      app.add_subcommand("probe", "Radiosity and irradiance of a lit mesh at calculation points (see docs/commands/probe.md)");
  command->add_option("lit", options->lit, "Lit PLY written by dynrad solve")->required();
  command->add_option("--points", options->points, "File of points, one 'x y z nx ny nz' per line, # comments");
  command->add_option("--grid", options->grid,
                      "Work plane x0,y0,x1,y1,step,height facing up (axes: the two other than --up)");
  command->add_option("--up", options->up, "Up axis of --grid: x, y or z")->capture_default_str();
  command->add_option("--model", options->model,
                      "The model the PLY was lit from: its materials give irradiance H = (B - E) / reflectance");
  command->add_option("--reflectance", options->reflectance,
                      "r[,g,b]: reflectance for all points (emission taken as 0), for irradiance");
  add_cleanup_options(*command, options->model_load);  // as for solve, when reading --model
  add_model_axis_options(*command, options->model_load);
  command->add_flag("--json", options->json, "Print JSON instead of a table");
  command->add_option("-o,--output", options->output, "Write the table or JSON here instead of standard output");
  return [options] { return run_probe(*options); };
}

}  // namespace dynrad::cli
