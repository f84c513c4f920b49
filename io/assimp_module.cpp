// The quiver_assimp module: Assimp's importers behind the plain function
// table of io/assimp_module.h. Built as a shared module that quiver dlopens
// on first use; nothing here throws.
#include "io/assimp_module.h"

#include <assimp/material.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <assimp/Importer.hpp>
#include <cstring>
#include <exception>
#include <memory>
#include <new>
#include <string>
#include <vector>

#include "io/module_message.h"

namespace quiver {

namespace {

static_assert(sizeof(aiVector3D) == 3 * sizeof(float), "quiver reads Assimp's vectors as float triples");

// What one import owns: Assimp's scene and the arrays made from it.
struct Import {
  Assimp::Importer importer;
  std::vector<std::vector<std::uint32_t>> indices;
  std::vector<ImportedPart> parts;
  std::vector<ImportedMaterial> materials;
};

ImportedMaterial material_of(const aiScene& scene, const aiMaterial& m) {
  ImportedMaterial out{};
  aiColor4D color;
  if (m.Get(AI_MATKEY_BASE_COLOR, color) == aiReturn_SUCCESS ||
      m.Get(AI_MATKEY_COLOR_DIFFUSE, color) == aiReturn_SUCCESS) {
    out.color[0] = color.r;
    out.color[1] = color.g;
    out.color[2] = color.b;
    out.has_color = 1;
  }
  int two_sided = 0;
  if (m.Get(AI_MATKEY_TWOSIDED, two_sided) == aiReturn_SUCCESS) out.two_sided = two_sided != 0 ? 1 : 0;
  aiString texture;
  if (m.GetTexture(aiTextureType_BASE_COLOR, 0, &texture) == aiReturn_SUCCESS ||
      m.GetTexture(aiTextureType_DIFFUSE, 0, &texture) == aiReturn_SUCCESS) {
    copy_message(std::string_view(texture.data, texture.length), out.texture, sizeof out.texture);
    if (const aiTexture* embedded = scene.GetEmbeddedTexture(texture.C_Str())) {
      if (embedded->mHeight == 0) {  // a compressed file of mWidth bytes
        out.embedded = reinterpret_cast<const unsigned char*>(embedded->pcData);
        out.embedded_size = embedded->mWidth;
      } else {
        out.embedded_raw = 1;
      }
    }
  }
  return out;
}

// The scene's triangle meshes as parts; other primitives (after
// aiProcess_SortByPType a mesh holds one kind) are counted and left out.
void collect(const aiScene& scene, Import& import, ImportedMesh& mesh) {
  mesh = {};
  for (unsigned i = 0; i < scene.mNumMaterials; ++i) import.materials.push_back(material_of(scene, *scene.mMaterials[i]));
  for (unsigned i = 0; i < scene.mNumMeshes; ++i) {
    const aiMesh& m = *scene.mMeshes[i];
    // The flags beside the kinds (aiPrimitiveType_NGONEncodingFlag) do not matter.
    constexpr unsigned kOthers = aiPrimitiveType_POINT | aiPrimitiveType_LINE | aiPrimitiveType_POLYGON;
    if ((m.mPrimitiveTypes & aiPrimitiveType_TRIANGLE) == 0 || (m.mPrimitiveTypes & kOthers) != 0) {
      mesh.dropped_points_and_lines += m.mNumFaces;
      continue;
    }
    std::vector<std::uint32_t>& indices = import.indices.emplace_back();
    indices.reserve(std::size_t{3} * m.mNumFaces);
    for (unsigned f = 0; f < m.mNumFaces; ++f) {
      const aiFace& face = m.mFaces[f];
      indices.insert(indices.end(), face.mIndices, face.mIndices + 3);  // triangulated: 3 each
    }
    ImportedPart part{};
    part.vertex_count = m.mNumVertices;
    part.positions = &m.mVertices[0].x;
    part.normals = m.mNormals != nullptr ? &m.mNormals[0].x : nullptr;
    if (m.mTextureCoords[0] != nullptr) {
      part.uvs = &m.mTextureCoords[0][0].x;
      part.uv_stride = 3;
    }
    part.triangle_count = m.mNumFaces;
    part.indices = indices.data();
    part.material = m.mMaterialIndex < scene.mNumMaterials ? m.mMaterialIndex : 0;
    import.parts.push_back(part);
  }
  if (import.materials.empty()) import.materials.push_back(ImportedMaterial{});
  mesh.part_count = import.parts.size();
  mesh.parts = import.parts.data();
  mesh.material_count = import.materials.size();
  mesh.materials = import.materials.data();
}

void* import_mesh(const char* path, const void* data, std::size_t size, const char* hint, ImportedMesh* mesh,
                  char* error, std::size_t error_size) {
  try {
    auto import = std::make_unique<Import>();
    constexpr unsigned kSteps = aiProcess_Triangulate | aiProcess_SortByPType | aiProcess_PreTransformVertices |
                                aiProcess_ValidateDataStructure;
    const aiScene* scene = data != nullptr ? import->importer.ReadFileFromMemory(data, size, kSteps, hint)
                                           : import->importer.ReadFile(path, kSteps);
    if (scene == nullptr) {
      copy_message(import->importer.GetErrorString(), error, error_size);
      return nullptr;
    }
    collect(*scene, *import, *mesh);
    return import.release();
  } catch (const std::bad_alloc&) {
    copy_message("out of memory", error, error_size);
  } catch (const std::exception& e) {
    copy_message(e.what(), error, error_size);
  } catch (...) {
    copy_message("unknown error in Assimp", error, error_size);
  }
  return nullptr;
}

void free_import(void* handle) { delete static_cast<Import*>(handle); }

constexpr AssimpModuleApi kApi{kAssimpModuleVersion, import_mesh, free_import};

}  // namespace

}  // namespace quiver

extern "C" __attribute__((visibility("default"))) const quiver::AssimpModuleApi* quiver_assimp_module_api() {
  return &quiver::kApi;
}
