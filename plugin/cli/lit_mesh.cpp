// Reading a lit PLY back (see lit_mesh.h).
#include "plugin/cli/lit_mesh.h"

#include "mesh/core/error.h"

#include <fmt/format.h>

#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>

namespace dynrad::cli {

LitMesh read_lit(const std::string& path) {
  using ReadMesh = OpenMesh::TriMesh_ArrayKernelT<>;
  ReadMesh mesh;
  OpenMesh::IO::Options io = OpenMesh::IO::Options::Custom;
  if (!std::ifstream(path)) throw InputError(path, 0, "cannot be read. Check the path.");
  if (!OpenMesh::IO::read_mesh(mesh, path, io))
    throw InputError(path, 0, "could not be read as a mesh (is it a PLY written by dynrad solve?).");
  OpenMesh::VPropHandleT<float> channel[3];
  const char* names[3] = {"radiosity_r", "radiosity_g", "radiosity_b"};
  for (int c = 0; c < 3; ++c)
    if (!mesh.get_property_handle(channel[c], names[c]))
      throw InputError(
          path, 0,
          std::string("has no '") + names[c] + "' vertex property; probe reads PLY files written by dynrad solve.");
  LitMesh lit;
  OpenMesh::VPropHandleT<float> illuminance, luminance;
  lit.photometric =
      mesh.get_property_handle(illuminance, "illuminance") && mesh.get_property_handle(luminance, "luminance");
  if (lit.photometric)
    for (auto v : mesh.vertices()) {
      lit.illuminance.push_back(mesh.property(illuminance, v));
      lit.luminance.push_back(mesh.property(luminance, v));
    }
  Bounds bounds;
  for (auto v : mesh.vertices()) {
    const auto& p = mesh.point(v);
    lit.positions.emplace_back(p[0], p[1], p[2]);
    bounds.extend(lit.positions.back());
    lit.radiosity.emplace_back(mesh.property(channel[0], v), mesh.property(channel[1], v),
                               mesh.property(channel[2], v));
  }
  for (auto f : mesh.faces()) {
    std::array<std::uint32_t, 3> t{};
    int k = 0;
    for (auto v : mesh.fv_range(f)) t[k++] = static_cast<std::uint32_t>(v.idx());
    lit.triangles.push_back(t);
  }
  if (lit.triangles.empty()) throw InputError(path, 0, "has no faces, so there is nothing to probe.");
  std::map<std::array<double, 3>, std::uint32_t> places;
  lit.place.reserve(lit.positions.size());
  for (const Vec3d& p : lit.positions)
    lit.place.push_back(places.emplace(std::array<double, 3>{p[0], p[1], p[2]}, places.size()).first->second);
  lit.around_start.assign(places.size() + 1, 0);
  for (const auto& t : lit.triangles)
    for (std::uint32_t v : t) ++lit.around_start[lit.place[v] + 1];
  for (std::size_t k = 0; k < places.size(); ++k) lit.around_start[k + 1] += lit.around_start[k];
  lit.around.resize(lit.around_start.back());
  std::vector<std::uint32_t> fill(lit.around_start.begin(), lit.around_start.end() - 1);
  for (std::uint32_t f = 0; f < lit.triangles.size(); ++f)
    for (std::uint32_t v : lit.triangles[f]) lit.around[fill[lit.place[v]]++] = f;
  lit.diagonal = bounds.diagonal();
  return lit;
}

void check_model_matches(const LitMesh& lit, const std::string& lit_path, const SceneMesh& model,
                         const std::string& model_path) {
  Bounds lit_box;
  for (const Vec3d& p : lit.positions) lit_box.extend(p);
  const Bounds model_box = model.bounds();
  if (lit_box.empty() || model_box.empty()) return;
  const double tolerance = 0.01 * lit_box.diagonal();
  if ((lit_box.lo - model_box.lo).norm() <= tolerance && (lit_box.hi - model_box.hi).norm() <= tolerance) return;
  throw InputError(model_path, 0,
                   fmt::format("this model, as read, spans ({:.4g}, {:.4g}, {:.4g}) to ({:.4g}, {:.4g}, {:.4g}), but "
                               "{} spans ({:.4g}, {:.4g}, {:.4g}) to ({:.4g}, {:.4g}, {:.4g}): it was lit from another "
                               "model, or from this one read another way. Give --model-up and --model-scale as solve "
                               "was given --up and --scale.",
                               model_box.lo[0], model_box.lo[1], model_box.lo[2], model_box.hi[0], model_box.hi[1],
                               model_box.hi[2], lit_path, lit_box.lo[0], lit_box.lo[1], lit_box.lo[2], lit_box.hi[0],
                               lit_box.hi[1], lit_box.hi[2]));
}

const Material* material_at(const SceneMesh& model, const rad::Visibility& index, const Vec3d& point,
                            const Vec3d& normal) {
  const TriMesh& mesh = model.mesh();
  const double tolerance = 1e-5 * model.bounds().diagonal();
  const rad::Visibility::Intersection hit = index.intersect(point + normal * tolerance, -normal);
  if (!hit.hit || hit.distance > 2 * tolerance) return nullptr;
  std::vector<int> candidates;
  for (auto v : mesh.fv_range(FaceHandle(hit.face)))
    for (auto f : mesh.vf_range(v)) candidates.push_back(f.idx());
  std::sort(candidates.begin(), candidates.end());
  candidates.erase(std::unique(candidates.begin(), candidates.end()), candidates.end());
  const Material* best = nullptr;
  double best_distance = tolerance;
  for (int index_f : candidates) {
    const FaceHandle f(index_f);
    const Vec3d fn = model.normal(f);
    if (OpenMesh::dot(fn, normal) < std::cos(30.0 * M_PI / 180.0)) continue;
    Vec3d c[3];
    int k = 0;
    for (auto v : mesh.fv_range(f)) c[k++] = mesh.point(v);
    const double plane = std::abs(OpenMesh::dot(point - c[0], fn));
    if (plane > best_distance) continue;
    const double area = OpenMesh::dot(OpenMesh::cross(c[1] - c[0], c[2] - c[0]), fn);
    bool inside = true;
    for (int i = 0; i < 3 && inside; ++i) {
      const double w = OpenMesh::dot(OpenMesh::cross(c[(i + 1) % 3] - point, c[(i + 2) % 3] - point), fn) / area;
      inside = w >= -tolerance / std::sqrt(std::abs(area));
    }
    if (!inside) continue;
    best = &model.material(f);
    best_distance = plane;
  }
  return best;
}

}  // namespace dynrad::cli
