#include "mesh/io/read_glb.h"

#include "mesh/core/error.h"
#include "mesh/io/io_util.h"

#include <tiny_gltf.h>

#include <cmath>
#include <cstring>
#include <set>

namespace dynrad {

namespace {

// The page shows only what the file holds: no image is decoded and no file beside it is
// read (a .glb's buffer is inside it).
bool skip_image(tinygltf::Image*, const int, std::string*, std::string*, int, int, const unsigned char*, int, void*) {
  return true;
}
bool no_file_exists(const std::string&, void*) { return false; }
std::string same_path(const std::string& path, void*) { return path; }
bool no_file_read(std::vector<unsigned char>*, std::string* err, const std::string& path, void*) {
  if (err) *err += "refers to the outside file '" + path + "'; a .glb for the viewer must hold all its data. ";
  return false;
}
bool no_file_write(std::string*, const std::string&, const std::vector<unsigned char>&, void*) { return false; }

class Checker {
 public:
  Checker(const tinygltf::Model& model, const std::string& name) : model_(model), name_(name) {}

  [[noreturn]] void fail(const std::string& what) const { throw InputError(name_, 0, what); }

  const tinygltf::Accessor& accessor(int index, const std::string& role) const {
    if (index < 0 || static_cast<std::size_t>(index) >= model_.accessors.size())
      fail(role + " names accessor " + std::to_string(index) + ", which does not exist. Export the model again.");
    return model_.accessors[static_cast<std::size_t>(index)];
  }

  // The accessor's elements, as bytes of its buffer, after checking they lie inside it.
  // Returns a pointer to the first element and its stride.
  const unsigned char* elements(int index, const std::string& role, int& stride) const {
    const tinygltf::Accessor& a = accessor(index, role);
    const std::string where = role + " (accessor " + std::to_string(index) + ")";
    if (a.sparse.isSparse) fail(where + " is sparse, which the viewer does not read. Export without sparse accessors.");
    if (a.bufferView < 0 || static_cast<std::size_t>(a.bufferView) >= model_.bufferViews.size())
      fail(where + " has no buffer view. Export the model again.");
    const tinygltf::BufferView& view = model_.bufferViews[static_cast<std::size_t>(a.bufferView)];
    if (view.buffer < 0 || static_cast<std::size_t>(view.buffer) >= model_.buffers.size())
      fail(where + "'s buffer view names no buffer. Export the model again.");
    const tinygltf::Buffer& buffer = model_.buffers[static_cast<std::size_t>(view.buffer)];
    if (view.byteOffset > buffer.data.size() || view.byteLength > buffer.data.size() - view.byteOffset)
      fail(where + "'s buffer view runs past the end of its buffer. The file is damaged or truncated.");
    stride = a.ByteStride(view);
    const int element = tinygltf::GetComponentSizeInBytes(static_cast<std::uint32_t>(a.componentType)) *
                        tinygltf::GetNumComponentsInType(static_cast<std::uint32_t>(a.type));
    if (stride <= 0 || element <= 0) fail(where + " has an unknown component type or stride.");
    if (a.count == 0) fail(where + " is empty.");
    const std::size_t need = a.byteOffset + (a.count - 1) * static_cast<std::size_t>(stride) + element;
    if (a.byteOffset > view.byteLength || need > view.byteLength || need < a.byteOffset)
      fail(where + " runs past the end of its buffer view. The file is damaged or truncated.");
    return buffer.data.data() + view.byteOffset + a.byteOffset;
  }

  // A float attribute's values, `components` per vertex, all finite.
  std::vector<float> floats(int index, const std::string& role, int components) const {
    int stride = 0;
    const unsigned char* p = elements(index, role, stride);
    const tinygltf::Accessor& a = model_.accessors[static_cast<std::size_t>(index)];
    if (a.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT || tinygltf::GetNumComponentsInType(a.type) != components)
      fail(role + " (accessor " + std::to_string(index) + ") is not " +
           (components == 1 ? "a float scalar" : "float VEC" + std::to_string(components)) + ".");
    std::vector<float> out(a.count * static_cast<std::size_t>(components));
    for (std::size_t i = 0; i < a.count; ++i)
      std::memcpy(&out[i * static_cast<std::size_t>(components)], p + i * static_cast<std::size_t>(stride), sizeof(float) * components);
    for (float v : out)
      if (!std::isfinite(v)) fail(role + " (accessor " + std::to_string(index) + ") holds a value that is not finite.");
    return out;
  }

  std::vector<std::uint32_t> indices(int index, const std::string& role) const {
    int stride = 0;
    const unsigned char* p = elements(index, role, stride);
    const tinygltf::Accessor& a = model_.accessors[static_cast<std::size_t>(index)];
    std::vector<std::uint32_t> out(a.count);
    for (std::size_t i = 0; i < a.count; ++i) {
      const unsigned char* e = p + i * static_cast<std::size_t>(stride);
      switch (a.componentType) {
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: out[i] = *e; break;
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: { std::uint16_t v; std::memcpy(&v, e, 2); out[i] = v; break; }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: std::memcpy(&out[i], e, 4); break;
        default: fail(role + " (accessor " + std::to_string(index) + ") is not of unsigned integers.");
      }
    }
    if (a.type != TINYGLTF_TYPE_SCALAR) fail(role + " (accessor " + std::to_string(index) + ") is not scalar.");
    return out;
  }

 private:
  const tinygltf::Model& model_;
  const std::string& name_;
};

}  // namespace

GlbSummary glb_summary_from_memory(const std::string& bytes, const std::string& name) {
  if (bytes.size() < 12 || std::memcmp(bytes.data(), "glTF", 4) != 0)
    throw InputError(name, 0, "is not binary glTF (it does not start with 'glTF'). Give the .glb that `dynrad solve -o` wrote.");
  tinygltf::TinyGLTF loader;
  loader.SetImageLoader(skip_image, nullptr);
  loader.SetFsCallbacks(tinygltf::FsCallbacks{no_file_exists, same_path, no_file_read, no_file_write, nullptr});
  tinygltf::Model model;
  std::string err, warn;
  if (!loader.LoadBinaryFromMemory(&model, &err, &warn, reinterpret_cast<const unsigned char*>(bytes.data()),
                                   static_cast<unsigned int>(bytes.size())))
    throw InputError(name, 0, "cannot be read as glTF: " + (err.empty() ? std::string("no reason given") : err));

  const Checker check(model, name);
  GlbSummary summary;
  std::set<int> counted;  // accessors whose values are in the summary already
  for (std::size_t m = 0; m < model.meshes.size(); ++m) {
    const tinygltf::Mesh& mesh = model.meshes[m];
    const std::string mesh_name = "mesh " + std::to_string(m) + (mesh.name.empty() ? "" : " '" + mesh.name + "'");
    ++summary.meshes;
    for (std::size_t k = 0; k < mesh.primitives.size(); ++k) {
      const tinygltf::Primitive& prim = mesh.primitives[k];
      const std::string where = mesh_name + ", primitive " + std::to_string(k);
      if (prim.mode != TINYGLTF_MODE_TRIANGLES && prim.mode != -1) continue;  // points and lines are not lit surfaces
      const auto position = prim.attributes.find("POSITION");
      if (position == prim.attributes.end()) check.fail(where + " has no POSITION.");
      const std::vector<float> xyz = check.floats(position->second, where + " POSITION", 3);
      const std::size_t n = xyz.size() / 3;
      const bool new_vertices = counted.insert(position->second).second;
      if (new_vertices) {
        summary.vertices += n;
        for (std::size_t i = 0; i < n; ++i) summary.bounds.extend(Vec3d(xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]));
      }
      bool colour = false;
      for (const auto& [attribute, accessor] : prim.attributes) {
        if (attribute == "COLOR_0") {
          const int components =
              tinygltf::GetNumComponentsInType(static_cast<std::uint32_t>(check.accessor(accessor, where + " COLOR_0").type));
          if (components != 3 && components != 4) check.fail(where + " COLOR_0 is neither VEC3 nor VEC4.");
          if (check.floats(accessor, where + " COLOR_0", components).size() != n * components)
            check.fail(where + " COLOR_0 has not one value per vertex.");
          colour = true;
        } else if (!attribute.empty() && attribute[0] == '_' &&
                   check.accessor(accessor, where + " " + attribute).componentType == TINYGLTF_COMPONENT_TYPE_FLOAT) {
          const int components = tinygltf::GetNumComponentsInType(
              static_cast<std::uint32_t>(check.accessor(accessor, where + " " + attribute).type));
          if (components < 1) check.fail(where + " " + attribute + " has an unknown type.");
          std::vector<float> values = check.floats(accessor, where + " " + attribute, components);
          if (values.size() != n * components) check.fail(where + " " + attribute + " has not one value per vertex.");
          if (components == 1 && counted.insert(accessor).second) {
            auto& list = summary.scalars[attribute];
            list.insert(list.end(), values.begin(), values.end());
          }
        }
      }
      if (colour) ++summary.coloured_primitives;
      std::size_t corners = n;
      if (prim.indices >= 0) {
        const std::vector<std::uint32_t> list = check.indices(prim.indices, where + " indices");
        for (std::uint32_t i : list)
          if (i >= n) check.fail(where + " indices name vertex " + std::to_string(i) + " of " + std::to_string(n) + ".");
        corners = list.size();
      }
      if (corners % 3) check.fail(where + " has " + std::to_string(corners) + " corners, not a whole number of triangles.");
      summary.triangles += corners / 3;
      ++summary.primitives;
    }
  }
  if (summary.triangles == 0) check.fail("holds no triangles. Give the .glb of a lit model (`dynrad solve -o OUT.glb`).");
  for (const tinygltf::Node& node : model.nodes)
    if (node.camera >= 0 && static_cast<std::size_t>(node.camera) < model.cameras.size() &&
        model.cameras[static_cast<std::size_t>(node.camera)].type == "perspective")
      summary.cameras.push_back(node.name);
  return summary;
}

GlbSummary read_glb_summary(const std::string& path) { return glb_summary_from_memory(detail::read_file(path), path); }

}  // namespace dynrad
