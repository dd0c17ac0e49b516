// `dynrad info FILE`: what dynrad sees in a model after cleanup; for a photometry file
// (.ies, .ldt), its summary and the tabular UGR (radiosity/design/glare.h).
#include "mesh/load.h"
#include "mesh/core/refinement.h"
#include "plugin/cli/commands.h"
#include "radiosity/sources/daylight.h"
#include "radiosity/design/glare.h"
#include "radiosity/sources/luminaire.h"
#include "radiosity/solver/settings.h"
#include "radiosity/transfer/visibility.h"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <map>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <memory>

namespace dynrad::cli {
namespace {

struct InfoOptions {
  LoadOptions load;
  bool json = false;
  double patch_size = 0;  // 0: the default for the scene
};

nlohmann::json rgb_json(const Rgb& c) { return {c.r, c.g, c.b}; }

bool is_photometry_file(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext == ".ies" || ext == ".ldt";
}

// UGR values as reports show them: one decimal, "<10" below CIE 117's scale.
std::string ugr_text(double ugr) { return ugr < 10 ? "<10" : fmt::format("{:.1f}", ugr); }
double rounded(double x, double step) { return std::round(x / step) * step; }

// `dynrad info LUMINAIRE.ies|.ldt`: the photometry and its standard UGR table.
int run_photometry_info(const InfoOptions& options) {
  const rad::Photometry p = rad::read_photometry(options.load.input);
  const rad::UgrTable table = rad::tabular_ugr(p);
  const double peak = p.candela.empty() ? 0.0 : *std::max_element(p.candela.begin(), p.candela.end());
  const double width = p.round ? std::abs(p.length) : std::abs(p.width);
  const std::string opening =
      std::max(std::abs(p.length), width) == 0
          ? "none (a point source)"
          : p.round ? fmt::format("round, diameter {:.3g} m, luminous height {:.3g} m", std::abs(p.length),
                                  std::abs(p.height))
                    : fmt::format("{:.3g} m (C0) x {:.3g} m (C90), luminous height {:.3g} m", std::abs(p.length),
                                  width, std::abs(p.height));
  if (options.json) {
    nlohmann::json j;
    j["input"] = options.load.input;
    j["format"] = p.format;
    j["name"] = p.name;
    j["flux"] = p.flux;
    j["lamp_flux"] = p.lamp_flux;
    j["stated_flux"] = p.stated_flux;
    j["symmetry"] = p.symmetry;
    j["opening"] = {{"length", std::abs(p.length)}, {"width", width}, {"height", std::abs(p.height)}, {"round", p.round}};
    j["peak_intensity"] = peak;
    j["warnings"] = p.warnings;
    nlohmann::json u;
    u["defined"] = table.defined;
    u["flux"] = table.flux;
    u["height"] = table.height;
    u["spacing"] = table.spacing;
    u["reflectances"] = nlohmann::json::array();
    for (const rad::UgrReflectances& r : table.reflectances)
      u["reflectances"].push_back({{"ceiling", r.ceiling}, {"walls", r.walls}, {"floor", r.floor}});
    u["rows"] = nlohmann::json::array();
    for (std::size_t k = 0; k < table.crosswise.size(); ++k) {
      nlohmann::json row = {{"x", table.rooms[k].x}, {"y", table.rooms[k].y}};
      for (double v : table.crosswise[k]) row["crosswise"].push_back(rounded(v, 0.1));
      for (double v : table.endwise[k]) row["endwise"].push_back(rounded(v, 0.1));
      u["rows"].push_back(row);
    }
    u["notes"] = table.notes;
    j["ugr_table"] = u;
    std::cout << j.dump(2) << "\n";
    return kExitOk;
  }
  std::cout << fmt::format("photometry      {} ({})\n", options.load.input, p.format);
  if (!p.name.empty()) std::cout << fmt::format("name            {}\n", p.name);
  std::cout << fmt::format("flux            {:.5g} lm from the distribution", p.flux);
  if (p.lamp_flux > 0) std::cout << fmt::format(", lamps {:.5g} lm", p.lamp_flux);
  std::cout << "\n";
  std::cout << fmt::format("symmetry        {}\n", p.symmetry);
  std::cout << fmt::format("opening         {}\n", opening);
  std::cout << fmt::format("peak intensity  {:.5g} cd\n", peak);
  if (!table.defined) {
    std::cout << "UGR table       none\n";
  } else {
    std::cout << fmt::format("UGR table       CIE 190 layout: H = {:.3g} m, spacing {:.3g} H, {:.5g} lm per luminaire\n",
                             table.height, table.spacing, table.flux);
    auto reflectance_line = [&](const char* label, auto member) {
      std::cout << fmt::format("  {:<12}", label);
      for (int side = 0; side < 2; ++side) {
        if (side == 1) std::cout << "   ";
        for (const rad::UgrReflectances& r : table.reflectances) std::cout << fmt::format("{:>6.2f}", r.*member);
      }
      std::cout << "\n";
    };
    std::cout << fmt::format("  {:<12}{:<33}{}\n", "", "crosswise", "endwise");
    reflectance_line("ceiling", &rad::UgrReflectances::ceiling);
    reflectance_line("walls", &rad::UgrReflectances::walls);
    reflectance_line("floor", &rad::UgrReflectances::floor);
    std::cout << "  room X x Y\n";
    for (std::size_t k = 0; k < table.rooms.size(); ++k) {
      std::cout << fmt::format("  {:>4}H {:>4}H ", table.rooms[k].x, table.rooms[k].y);
      for (double v : table.crosswise[k]) std::cout << fmt::format("{:>6}", ugr_text(v));
      std::cout << "   ";
      for (double v : table.endwise[k]) std::cout << fmt::format("{:>6}", ugr_text(v));
      std::cout << "\n";
    }
  }
  for (const std::string& note : table.notes) std::cout << "note            " << note << "\n";
  for (const auto& w : p.warnings) spdlog::warn("{}", w);
  return kExitOk;
}

int run_info(const InfoOptions& options) {
  if (is_photometry_file(options.load.input)) return run_photometry_info(options);
  const CleanupOptions cleanup = options.load.cleanup();
  SimplifyOptions simplify;
  simplify.enabled = options.load.simplify;
  LoadedScene scene = load_scene(options.load.input, cleanup, simplify, options.load.read());
  SceneMesh& mesh = *scene.mesh;
  const SimplifyReport& s = scene.simplify;
  // What the cleaned model itself holds, before simplification and patching.
  const std::size_t model_vertices = s.vertices_before, model_faces = s.faces_before;
  // The patch size `dynrad solve` would choose with no options (radiosity/solver/settings.h).
  const double patch_size =
      options.patch_size > 0 ? options.patch_size : rad::choose_settings(mesh, rad::Quality::normal).patch_size;
  const PatchingReport patching = make_patches(mesh, patch_size);
  const CleanupReport& r = scene.cleanup;
  const Bounds b = mesh.bounds();
  // Luminaires of a scene file, and what a user should know about their placement.
  const std::vector<rad::Luminaire> luminaires = rad::read_luminaires(options.load.input);
  std::vector<std::string> luminaire_warnings;
  if (!luminaires.empty()) {
    const rad::Visibility visibility(mesh);
    luminaire_warnings = rad::luminaire_warnings(visibility, luminaires);
  }
  double luminaire_flux = 0;
  for (const rad::Luminaire& l : luminaires) luminaire_flux += l.flux();
  // Daylight: the scene's sky and sun, and its glazing.
  const std::vector<rad::Luminaire> daylight = rad::read_daylight(options.load.input, scene.glazing, scene.openings);

  // Per-material statistics over the cleaned triangles.
  struct Usage {
    std::size_t faces = 0;
    double area = 0;
  };
  std::vector<Usage> usage(mesh.materials().size());
  for (auto f : mesh.mesh().faces()) {
    usage[mesh.material_id(f)].faces++;
    usage[mesh.material_id(f)].area += mesh.area(f);
  }
  // Groups (OBJ g/o, a scene's mesh files, the nodes of an IFC or glTF): faces per name.
  std::vector<std::size_t> group_faces(mesh.group_names().size(), 0);
  for (auto f : mesh.mesh().faces())
    if (mesh.group(f) < group_faces.size()) ++group_faces[mesh.group(f)];
  std::size_t groups_with_faces = 0;
  for (std::size_t count : group_faces) groups_with_faces += count > 0;
  // IFC elements (assimp names their nodes IfcType_Name_GUID): elements per type.
  std::map<std::string, std::size_t> ifc_types;
  for (std::size_t g = 0; g < group_faces.size(); ++g) {
    const std::string& name = mesh.group_names()[g];
    if (group_faces[g] == 0 || name.rfind("Ifc", 0) != 0) continue;
    ++ifc_types[name.substr(0, name.find('_'))];
  }
  const std::vector<std::pair<const char*, std::size_t>> repairs = {
      {"merged_points", r.merged_points},
      {"degenerate_polygons", r.degenerate_polygons},
      {"t_junctions", r.t_junctions},
      {"triangulated_polygons", r.triangulated_polygons},
      {"untriangulatable_polygons", r.untriangulatable_polygons},
      {"degenerate_triangles", r.degenerate_triangles},
      {"duplicate_triangles", r.duplicate_triangles},
      {"non_manifold_edges", r.non_manifold_edges},
      {"split_vertices", r.split_vertices},
      {"unused_points", r.unused_points},
      {"flattened_polygons", r.flattened_polygons},
  };

  if (options.json) {
    nlohmann::json j;
    j["input"] = options.load.input;
    j["files"] = scene.input_files;
    j["input_points"] = r.input_points;
    j["input_polygons"] = r.input_polygons;
    j["vertices"] = model_vertices;
    j["faces"] = model_faces;
    j["simplify"] = {{"enabled", simplify.enabled},
                     {"triangles_before", s.faces_before},
                     {"triangles_after", s.faces_after},
                     {"vertices_before", s.vertices_before},
                     {"vertices_after", s.vertices_after},
                     {"locked_vertices", s.locked_vertices},
                     {"worst_aspect_before", s.worst_aspect_before},
                     {"worst_aspect_after", s.worst_aspect_after},
                     {"seconds", s.seconds}};
    j["patches"] = {{"patch_size", patch_size},
                    {"count", patching.patches},
                    {"splits", patching.splits.total()},
                    {"min_angle_model_deg", patching.min_angle_before},
                    {"min_angle_patches_deg", patching.min_angle_after}};
    j["bounds"] = {{"min", {b.lo[0], b.lo[1], b.lo[2]}}, {"max", {b.hi[0], b.hi[1], b.hi[2]}}};
    j["total_area"] = mesh.total_area();
    j["emitting_area"] = mesh.emitting_area();
    j["emitted_power"] = rgb_json(mesh.emitted_power());
    for (const auto& [name, count] : repairs) j["repairs"][name] = count;
    j["repairs"]["total"] = r.repairs();
    j["warped_polygons"] = r.warped_polygons;
    j["imprint"] = {{"enabled", options.load.imprint},
                    {"imprinted_edges", r.imprinted_edges},
                    {"imprinted_facets", r.imprinted_facets},
                    {"failures", r.imprint_failures},
                    {"hidden_pieces", r.hidden_pieces},
                    {"hidden_area", r.hidden_area}};
    for (std::size_t m = 0; m < mesh.materials().size(); ++m) {
      const Material& mat = mesh.materials()[m];
      if (usage[m].faces == 0) continue;
      j["materials"].push_back({{"name", mat.name},
                                {"reflectance", rgb_json(mat.reflectance)},
                                {"emission", rgb_json(mat.emission)},
                                {"faces", usage[m].faces},
                                {"area", usage[m].area}});
    }
    j["luminaires"] = nlohmann::json::array();
    for (const rad::Luminaire& l : luminaires) {
      nlohmann::json e = {{"name", l.name},
                          {"type", l.kind == rad::Luminaire::Kind::photometric ? "photometric"
                                   : l.kind == rad::Luminaire::Kind::spot      ? "spot"
                                                                                 : "point"},
                          {"flux", l.flux()},
                          {"position", {l.position[0], l.position[1], l.position[2]}},
                          {"aim", {l.nadir[0], l.nadir[1], l.nadir[2]}},
                          {"spin", l.spin},
                          {"peak_intensity", l.peak_intensity()},
                          {"maintenance_factor", l.maintenance_factor}};
      if (l.photometry) {
        e["photometry"] = {{"file", l.photometry->file},
                           {"format", l.photometry->format},
                           {"name", l.photometry->name},
                           {"file_flux", l.photometry->flux},
                           {"symmetry", l.photometry->symmetry},
                           {"warnings", l.photometry->warnings}};
      }
      j["luminaires"].push_back(e);
    }
    j["luminaire_flux"] = luminaire_flux;
    j["ifc_types"] = ifc_types;
    j["groups"] = nlohmann::json::object();
    for (std::size_t g = 0; g < group_faces.size(); ++g)
      if (group_faces[g] > 0) j["groups"][mesh.group_names()[g]] = group_faces[g];
    j["daylight"] = nlohmann::json::array();
    for (const rad::Luminaire& l : daylight) j["daylight"].push_back(l.describe());
    j["glazing_triangles"] = scene.glazing.size();
    j["opening_triangles"] = scene.openings.size();
    j["openings"] = nlohmann::json::array();  // each triangle's corners, model units
    for (const auto& t : scene.openings) {
      nlohmann::json corners = nlohmann::json::array();
      for (const Vec3d& c : t) corners.push_back({c[0], c[1], c[2]});
      j["openings"].push_back(corners);
    }
    std::vector<std::string> warnings = scene.warnings;
    warnings.insert(warnings.end(), luminaire_warnings.begin(), luminaire_warnings.end());
    j["warnings"] = warnings;
    std::cout << j.dump(2) << "\n";
    return kExitOk;
  }

  const Vec3d size = b.extent();
  const Rgb power = mesh.emitted_power();
  std::cout << fmt::format("input           {} ({} file{})\n", options.load.input, scene.input_files,
                           scene.input_files == 1 ? "" : "s");
  std::cout << fmt::format("read            {} points, {} polygons\n", r.input_points, r.input_polygons);
  std::cout << fmt::format("mesh            {} vertices, {} triangles\n", model_vertices, model_faces);
  if (simplify.enabled)
    std::cout << fmt::format(
        "simplified      {} -> {} triangles, {} vertices locked, worst aspect {:.3g} -> {:.3g}, {:.2f} s\n",
        s.faces_before, s.faces_after, s.locked_vertices, s.worst_aspect_before, s.worst_aspect_after, s.seconds);
  std::cout << fmt::format("patches         {} at patch size {:.4g} (smallest angle {:.1f} deg, model's {:.1f})\n",
                           patching.patches, patch_size, patching.min_angle_after, patching.min_angle_before);
  std::cout << fmt::format("bounds          ({:.6g}, {:.6g}, {:.6g}) to ({:.6g}, {:.6g}, {:.6g}), size {:.6g} x {:.6g} x {:.6g}\n",
                           b.lo[0], b.lo[1], b.lo[2], b.hi[0], b.hi[1], b.hi[2], size[0], size[1], size[2]);
  std::cout << fmt::format("area            {:.6g} total, {:.6g} emitting (model units squared)\n", mesh.total_area(),
                           mesh.emitting_area());
  std::cout << fmt::format("emitted power   ({:.6g}, {:.6g}, {:.6g}) (W if the model is in metres)\n", power.r,
                           power.g, power.b);
  std::cout << fmt::format("repairs         {}\n", r.repairs());
  for (const auto& [name, count] : repairs) std::cout << fmt::format("  {:<26}{}\n", name, count);
  if (options.load.imprint)
    std::cout << fmt::format("imprint         {} imprinted_edges on {} facets, {} hidden pieces, hidden_area {:.6g}{}\n",
                             r.imprinted_edges, r.imprinted_facets, r.hidden_pieces, r.hidden_area,
                             r.imprint_failures ? fmt::format(", {} facets failed", r.imprint_failures) : "");
  else
    std::cout << "imprint         off (--no-imprint)\n";
  std::cout << "materials\n";
  for (std::size_t m = 0; m < mesh.materials().size(); ++m) {
    const Material& mat = mesh.materials()[m];
    if (usage[m].faces == 0) continue;
    std::cout << fmt::format("  {:<20} reflectance ({:.3f}, {:.3f}, {:.3f})", mat.name, mat.reflectance.r,
                             mat.reflectance.g, mat.reflectance.b);
    if (mat.emits())
      std::cout << fmt::format("  emission ({:.4g}, {:.4g}, {:.4g}) W/m2", mat.emission.r, mat.emission.g,
                               mat.emission.b);
    std::cout << fmt::format("  {} faces, area {:.6g}\n", usage[m].faces, usage[m].area);
  }
  if (!luminaires.empty()) {
    std::cout << fmt::format("luminaires      {}, {:.6g} lm in total\n", luminaires.size(), luminaire_flux);
    for (const rad::Luminaire& l : luminaires) std::cout << "  " << l.describe() << "\n";
  }
  std::cout << fmt::format("groups          {} with faces (info --json lists them)\n", groups_with_faces);
  if (!ifc_types.empty()) {
    std::cout << "IFC elements   ";
    for (const auto& [type, count] : ifc_types) std::cout << " " << type << " " << count;
    std::cout << "\n";
  }
  for (const rad::Luminaire& l : daylight) std::cout << "daylight        " << l.describe() << "\n";
  if (!scene.glazing.empty())
    std::cout << fmt::format("glazing         {} triangles (materials with a transmittance: windows, not lit)\n",
                             scene.glazing.size());
  if (!scene.openings.empty())
    std::cout << fmt::format("openings        {} triangles (holes daylight comes in through, found where the mesh's "
                             "boundary is flat and not a surface's outline)\n",
                             scene.openings.size());
  if (mesh.emitting_area() == 0 && luminaires.empty() && daylight.empty())
    std::cout << "note            no emitting faces, no luminaires and no sky: a solve would have no light.\n";
  for (const auto& w : scene.warnings) spdlog::warn("{}", w);
  for (const auto& w : luminaire_warnings) spdlog::warn("{}", w);
  return kExitOk;
}

}  // namespace

Command add_info_command(CLI::App& app) {
  auto options = std::make_shared<InfoOptions>();
  CLI::App* command = app.add_subcommand("info", "Print what dynrad reads from a model: sizes, materials, repairs");
  add_load_options(*command, options->load);
  add_simplify_flag(*command, options->load);
  command->add_flag("--json", options->json, "Print the information as JSON");
  command->add_option("--patch-size", options->patch_size,
                      "Longest patch edge, model units (default: what solve chooses with no options)")
      ->check(CLI::PositiveNumber);
  return [options] { return run_info(*options); };
}

}  // namespace dynrad::cli
