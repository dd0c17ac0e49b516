#include "mesh/io/export_gltf.h"

#include "mesh/io/atomic_file.h"
#include "mesh/core/error.h"
#include "mesh/io/io_util.h"
#include "mesh/core/scene_mesh.h"

#include <boost/qvm/mat.hpp>
#include <boost/qvm/quat.hpp>
#include <boost/qvm/quat_access.hpp>
#include <boost/qvm/quat_operations.hpp>
#include <tiny_gltf.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <map>
#include <sstream>

namespace dynrad {

namespace {

// Appends `count` floats to the buffer (4-byte aligned) and returns its view's index.
int add_view(tinygltf::Model& model, const void* data, std::size_t bytes, int target) {
  std::vector<unsigned char>& buffer = model.buffers[0].data;
  while (buffer.size() % 4) buffer.push_back(0);
  tinygltf::BufferView view;
  view.buffer = 0;
  view.byteOffset = buffer.size();
  view.byteLength = bytes;
  view.target = target;
  const auto* p = static_cast<const unsigned char*>(data);
  buffer.insert(buffer.end(), p, p + bytes);
  model.bufferViews.push_back(view);
  return static_cast<int>(model.bufferViews.size() - 1);
}

int add_accessor(tinygltf::Model& model, int view, int component, int type, std::size_t count,
                 std::vector<double> min = {}, std::vector<double> max = {}) {
  tinygltf::Accessor a;
  a.bufferView = view;
  a.componentType = component;
  a.type = type;
  a.count = count;
  a.minValues = std::move(min);
  a.maxValues = std::move(max);
  model.accessors.push_back(a);
  return static_cast<int>(model.accessors.size() - 1);
}

std::string attribute_name(const std::string& name) {
  std::string out = "_";
  for (char c : name) out += static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return out;
}

// dynrad's z up to glTF's y up: (x, y, z) -> (x, z, -y).
Vec3d y_up(const Vec3d& q) { return Vec3d(q[0], q[2], -q[1]); }

// A node holding a perspective camera at the viewpoint. glTF cameras look along their
// local -z with +y up, so the node's rotation takes (x, y, -z) to (right, up, forward).
tinygltf::Node camera_node(tinygltf::Model& model, const Viewpoint& v, double zfar) {
  tinygltf::Camera camera;
  camera.name = v.name;
  camera.type = "perspective";
  camera.perspective.yfov = v.fov_degrees * M_PI / 180;
  camera.perspective.aspectRatio = v.aspect;
  camera.perspective.znear = 0.01;
  camera.perspective.zfar = zfar;
  model.cameras.push_back(camera);

  const Vec3d forward = (y_up(v.target) - y_up(v.eye)).normalized();
  const Vec3d right = OpenMesh::cross(forward, y_up(v.up)).normalized();
  const Vec3d up = OpenMesh::cross(right, forward);
  // The rotation's matrix has columns (right, up, back); Boost.QVM makes it a quaternion.
  boost::qvm::mat<double, 3, 3> rotation;
  for (int r = 0; r < 3; ++r) {
    rotation.a[r][0] = right[r];
    rotation.a[r][1] = up[r];
    rotation.a[r][2] = -forward[r];
  }
  const auto q = boost::qvm::convert_to<boost::qvm::quat<double>>(rotation);
  tinygltf::Node node;
  node.name = v.name;
  node.camera = static_cast<int>(model.cameras.size() - 1);
  const Vec3d eye = y_up(v.eye);
  node.translation = {eye[0], eye[1], eye[2]};
  node.rotation = {boost::qvm::X(q), boost::qvm::Y(q), boost::qvm::Z(q), boost::qvm::S(q)};
  return node;
}

}  // namespace

void write_glb(const std::string& path, const SceneMesh& scene, const VertexSplit& split, const VertexValues& values,
               const WriteOptions& options) {
  const std::size_t n = split.size();
  tinygltf::Model model;
  model.asset.version = "2.0";
  model.asset.generator = "dynrad";
  model.buffers.resize(1);
  model.extensionsUsed.push_back("KHR_materials_unlit");

  // Vertex attributes, shared by every primitive.
  std::vector<float> position(3 * n), colour(3 * n), linear(3 * n);
  std::vector<double> lo(3, 1e300), hi(3, -1e300);
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3d p = y_up(scene.mesh().point(split.source[i]));
    for (int c = 0; c < 3; ++c) {
      position[3 * i + c] = static_cast<float>(p[c]);
      lo[c] = std::min(lo[c], static_cast<double>(position[3 * i + c]));
      hi[c] = std::max(hi[c], static_cast<double>(position[3 * i + c]));
      colour[3 * i + c] = static_cast<float>(detail::srgb_to_linear(values.display[i][c] / 255.0));
      linear[3 * i + c] = static_cast<float>(values.linear[i][c]);
    }
  }
  std::map<std::string, int> attributes;
  attributes["POSITION"] = add_accessor(model, add_view(model, position.data(), position.size() * 4, TINYGLTF_TARGET_ARRAY_BUFFER),
                                        TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, n, lo, hi);
  attributes["COLOR_0"] = add_accessor(model, add_view(model, colour.data(), colour.size() * 4, TINYGLTF_TARGET_ARRAY_BUFFER),
                                       TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, n);
  attributes[attribute_name(values.name)] =
      add_accessor(model, add_view(model, linear.data(), linear.size() * 4, TINYGLTF_TARGET_ARRAY_BUFFER),
                   TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, n);
  for (const auto& [name, scalar] : values.scalars)
    attributes[attribute_name(name)] =
        add_accessor(model, add_view(model, scalar.data(), scalar.size() * 4, TINYGLTF_TARGET_ARRAY_BUFFER),
                     TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_SCALAR, n);

  // Materials: base colour the reflectance, unlit.
  for (const Material& m : scene.materials()) {
    tinygltf::Material g;
    g.name = m.name;
    g.pbrMetallicRoughness.baseColorFactor = {1.0, 1.0, 1.0, 1.0};  // the vertex colours carry the light
    g.pbrMetallicRoughness.metallicFactor = 0;
    g.pbrMetallicRoughness.roughnessFactor = 1;
    g.extensions["KHR_materials_unlit"] = tinygltf::Value(tinygltf::Value::Object());
    tinygltf::Value::Object extras;
    extras["reflectance"] = tinygltf::Value(tinygltf::Value::Array{tinygltf::Value(m.reflectance.r),
                                                                   tinygltf::Value(m.reflectance.g),
                                                                   tinygltf::Value(m.reflectance.b)});
    g.extras = tinygltf::Value(extras);
    model.materials.push_back(g);
  }

  // Indices per (group, material), in face order.
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::vector<std::uint32_t>> indices;
  for (auto f : scene.mesh().faces()) {
    auto& list = indices[{scene.group(f), scene.material_id(f)}];
    for (int k = 0; k < 3; ++k) list.push_back(split.corner[3 * static_cast<std::size_t>(f.idx()) + k]);
  }
  tinygltf::Scene root;
  std::map<std::uint32_t, int> mesh_of_group;
  for (const auto& [key, list] : indices) {
    const auto [group, material] = key;
    auto found = mesh_of_group.find(group);
    if (found == mesh_of_group.end()) {
      tinygltf::Mesh mesh;
      mesh.name = group < scene.group_names().size() ? scene.group_names()[group] : "group" + std::to_string(group);
      model.meshes.push_back(mesh);
      tinygltf::Node node;
      node.name = mesh.name;
      node.mesh = static_cast<int>(model.meshes.size() - 1);
      model.nodes.push_back(node);
      root.nodes.push_back(static_cast<int>(model.nodes.size() - 1));
      found = mesh_of_group.emplace(group, node.mesh).first;
    }
    tinygltf::Primitive primitive;
    primitive.attributes = attributes;
    primitive.material = static_cast<int>(material);
    primitive.mode = TINYGLTF_MODE_TRIANGLES;
    primitive.indices =
        add_accessor(model, add_view(model, list.data(), list.size() * 4, TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER),
                     TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT, TINYGLTF_TYPE_SCALAR, list.size());
    model.meshes[static_cast<std::size_t>(found->second)].primitives.push_back(primitive);
  }
  // Glass: one primitive per transmittance, under one node.
  std::map<std::array<double, 3>, std::vector<const GlazingTriangle*>> panes;
  for (const GlazingTriangle& t : options.glass)
    panes[{t.transmittance.r, t.transmittance.g, t.transmittance.b}].push_back(&t);
  if (!panes.empty()) {
    tinygltf::Mesh glazing;
    glazing.name = "glazing";
    for (const auto& [tau, triangles] : panes) {
      std::vector<float> xyz;
      std::vector<double> glo(3, 1e300), ghi(3, -1e300);
      for (const GlazingTriangle* t : triangles)
        for (const Vec3d& corner : t->corners) {
          const Vec3d p = y_up(corner);
          for (int c = 0; c < 3; ++c) {
            xyz.push_back(static_cast<float>(p[c]));
            glo[c] = std::min(glo[c], static_cast<double>(xyz.back()));
            ghi[c] = std::max(ghi[c], static_cast<double>(xyz.back()));
          }
        }
      tinygltf::Material glass;
      glass.name = "glass";
      const double luminance = Rgb(tau[0], tau[1], tau[2]).luminance();
      glass.pbrMetallicRoughness.baseColorFactor = {tau[0], tau[1], tau[2], 0.2 + 0.5 * (1 - std::clamp(luminance, 0.0, 1.0))};
      glass.pbrMetallicRoughness.metallicFactor = 0;
      glass.pbrMetallicRoughness.roughnessFactor = 0;
      glass.alphaMode = "BLEND";
      glass.doubleSided = true;
      glass.extensions["KHR_materials_unlit"] = tinygltf::Value(tinygltf::Value::Object());
      tinygltf::Value::Object extras;
      extras["transmittance"] = tinygltf::Value(
          tinygltf::Value::Array{tinygltf::Value(tau[0]), tinygltf::Value(tau[1]), tinygltf::Value(tau[2])});
      glass.extras = tinygltf::Value(extras);
      model.materials.push_back(glass);
      tinygltf::Primitive primitive;
      primitive.attributes["POSITION"] =
          add_accessor(model, add_view(model, xyz.data(), xyz.size() * 4, TINYGLTF_TARGET_ARRAY_BUFFER),
                       TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, xyz.size() / 3, glo, ghi);
      primitive.material = static_cast<int>(model.materials.size() - 1);
      primitive.mode = TINYGLTF_MODE_TRIANGLES;
      glazing.primitives.push_back(primitive);
    }
    model.meshes.push_back(glazing);
    tinygltf::Node node;
    node.name = "glazing";
    node.mesh = static_cast<int>(model.meshes.size() - 1);
    model.nodes.push_back(node);
    root.nodes.push_back(static_cast<int>(model.nodes.size() - 1));
  }

  // Far enough to see the whole model from outside it (tinygltf writes zfar 0 otherwise,
  // which the specification does not allow).
  double diagonal = 0;
  for (int c = 0; c < 3; ++c) diagonal += n ? (hi[c] - lo[c]) * (hi[c] - lo[c]) : 0;
  const double zfar = std::max(1.0, 10 * std::sqrt(diagonal));
  for (const Viewpoint& v : options.viewpoints) {
    model.nodes.push_back(camera_node(model, v, zfar));
    root.nodes.push_back(static_cast<int>(model.nodes.size() - 1));
  }
  if (options.background.r >= 0) {
    tinygltf::Value::Object extras;
    extras["background"] = tinygltf::Value(tinygltf::Value::Array{
        tinygltf::Value(options.background.r), tinygltf::Value(options.background.g), tinygltf::Value(options.background.b)});
    root.extras = tinygltf::Value(extras);
  }
  model.scenes.push_back(root);
  model.defaultScene = 0;

  std::ostringstream bytes;
  tinygltf::TinyGLTF writer;
  if (!writer.WriteGltfSceneToStream(&model, bytes, false, true)) throw OutputError(path, "tinygltf could not write it.");
  AtomicFile file(path);
  const std::string data = bytes.str();
  file.stream().write(data.data(), static_cast<std::streamsize>(data.size()));
  file.commit();
}

}  // namespace dynrad
