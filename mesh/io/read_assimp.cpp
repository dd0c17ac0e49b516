// Models through assimp (Debian's libassimp) for the formats the hardened readers do
// not cover: IFC, glTF 2.0 (.gltf, .glb), COLLADA (.dae), 3DS, FBX and more.
//
// Every mesh of every node is placed by the node's accumulated transform; its faces
// keep their polygons (cleanup triangulates and repairs them as it does any reader's)
// and are grouped by node name. Points and lines are left out. Materials: diffuse
// colour (glTF's base colour where given) to reflectance, emissive colour to emission,
// opacity below 1 to a transmittance of 1 - opacity (glazing). Faces are numbered in
// messages per file, in the order read.
#include "mesh/core/error.h"
#include "mesh/io/import.h"
#include "mesh/io/io_util.h"

#include <assimp/Importer.hpp>
#include <assimp/material.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <cmath>
#include <functional>

namespace dynrad::detail {

namespace {

Rgb colour_of(const aiMaterial& m, const char* key, unsigned type, unsigned index, bool* found) {
  aiColor4D c;
  *found = m.Get(key, type, index, c) == AI_SUCCESS;
  return *found ? Rgb(c.r, c.g, c.b) : Rgb(0.0);
}

}  // namespace

bool assimp_reads(const std::string& extension) {
  static const Assimp::Importer importer;
  return !extension.empty() && importer.IsExtensionSupported(extension);
}

PolygonSoup read_assimp(const std::string& path, const ReadOptions& options) {
  (void)options;
  Assimp::Importer importer;
  importer.SetPropertyInteger(AI_CONFIG_PP_SBP_REMOVE, aiPrimitiveType_POINT | aiPrimitiveType_LINE);
  const aiScene* scene = importer.ReadFile(path, aiProcess_SortByPType | aiProcess_ValidateDataStructure);
  if (!scene || !scene->mRootNode || (scene->mFlags & AI_SCENE_FLAGS_INCOMPLETE))
    throw InputError(path, 0,
                     std::string("could not be read (assimp: ") + importer.GetErrorString() +
                         "). Check that the file is complete; export it again, or as OBJ, if it still fails.");
  PolygonSoup soup;
  soup.files.push_back(path);
  // Materials, by assimp's index.
  for (unsigned i = 0; i < scene->mNumMaterials; ++i) {
    const aiMaterial& am = *scene->mMaterials[i];
    Material m;
    aiString name;
    m.name = am.Get(AI_MATKEY_NAME, name) == AI_SUCCESS && name.length > 0 ? name.C_Str() : "material" + std::to_string(i);
    if (soup.find_material(m.name) >= 0) m.name += "#" + std::to_string(i);
    m.origin = path + " (material " + std::to_string(i) + ")";
    bool found = false;
    const Rgb base = colour_of(am, AI_MATKEY_BASE_COLOR, &found);
    if (found) m.reflectance = base;
    else {
      const Rgb diffuse = colour_of(am, AI_MATKEY_COLOR_DIFFUSE, &found);
      if (found) m.reflectance = diffuse;
    }
    m.emission = colour_of(am, AI_MATKEY_COLOR_EMISSIVE, &found);
    float opacity = 1;
    if (am.Get(AI_MATKEY_OPACITY, opacity) == AI_SUCCESS && std::isfinite(opacity) && opacity < 1 && opacity >= 0)
      m.transmittance = Rgb(std::min(0.999, 1.0 - opacity));
    if (!m.reflectance.is_finite() || !m.emission.is_finite())
      throw InputError(path, 0, "material '" + m.name + "' has a colour that is not a finite number.");
    m.emission = Rgb(std::max(0.0, m.emission.r), std::max(0.0, m.emission.g), std::max(0.0, m.emission.b));
    if (m.transmits()) m.emission = Rgb(0.0);  // glass does not glow
    accept_material(m, path, options, soup.warnings);
    soup.materials.push_back(m);
  }
  if (soup.materials.empty()) soup.materials.push_back(Material{"default", Rgb(0.5), Rgb(0.0), path, true});
  // Nodes, depth first, with their transforms.
  std::uint32_t face_number = 0;
  std::function<void(const aiNode&, const aiMatrix4x4&)> visit = [&](const aiNode& node, const aiMatrix4x4& parent) {
    const aiMatrix4x4 transform = parent * node.mTransformation;
    const std::string group = node.mName.length > 0 ? node.mName.C_Str() : "node";
    for (unsigned k = 0; k < node.mNumMeshes; ++k) {
      const aiMesh& mesh = *scene->mMeshes[node.mMeshes[k]];
      const std::uint32_t g = soup.find_or_add_group(mesh.mName.length > 0 && node.mNumMeshes > 1
                                                         ? group + "/" + mesh.mName.C_Str()
                                                         : group);
      const auto base = static_cast<std::uint32_t>(soup.points.size());
      for (unsigned v = 0; v < mesh.mNumVertices; ++v) {
        const aiVector3D p = transform * mesh.mVertices[v];
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
          throw InputError(path, 0,
                           "vertex " + std::to_string(v + 1) + " of mesh '" + mesh.mName.C_Str() + "' (node '" + group +
                               "') is not a finite number once placed by its node's transform.");
        soup.points.emplace_back(p.x, p.y, p.z);
      }
      const std::uint32_t material = mesh.mMaterialIndex < soup.materials.size() ? mesh.mMaterialIndex : 0;
      for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
        const aiFace& face = mesh.mFaces[f];
        ++face_number;
        if (face.mNumIndices < 3) continue;
        std::vector<std::uint32_t> loop;
        for (unsigned c = 0; c < face.mNumIndices; ++c) {
          if (face.mIndices[c] >= mesh.mNumVertices)
            throw InputError(path, 0, "face " + std::to_string(face_number) + " refers to a vertex it does not have.");
          loop.push_back(base + face.mIndices[c]);
        }
        soup.polygons.push_back(std::move(loop));
        soup.material.push_back(material);
        soup.group.push_back(g);
        soup.origin.push_back(SourceRef{0, 0, face_number - 1});
      }
    }
    for (unsigned c = 0; c < node.mNumChildren; ++c) visit(*node.mChildren[c], transform);
  };
  visit(*scene->mRootNode, aiMatrix4x4());
  return soup;
}

}  // namespace dynrad::detail
