// The quiver_assimp module: Assimp's importers behind the plain function
// table of io/assimp_module.h. Built as a shared module that quiver dlopens
// on first use; nothing here throws.
#include "io/assimp_module.h"

#include <assimp/material.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <assimp/DefaultIOSystem.h>
#include <assimp/Importer.hpp>
#include <cstring>
#include <deque>
#include <exception>
#include <memory>
#include <new>
#include <string>
#include <utility>
#include <vector>

#include "io/module_message.h"
#include "io/uri_path.h"

namespace quiver {

namespace {

static_assert(sizeof(aiVector3D) == 3 * sizeof(float), "quiver reads Assimp's vectors as float triples");

// The file system as Assimp's default, except that a name that does not
// exist as written is looked for percent-decoded (io/uri_path.h): glTF
// writes "my%20mesh.bin" for "my mesh.bin".
class UriDecodingIOSystem : public Assimp::DefaultIOSystem {
 public:
  bool Exists(const char* file) const override {
    return DefaultIOSystem::Exists(file) || DefaultIOSystem::Exists(percent_decoded(file).c_str());
  }
  Assimp::IOStream* Open(const char* file, const char* mode) override {
    if (DefaultIOSystem::Exists(file)) return DefaultIOSystem::Open(file, mode);
    return DefaultIOSystem::Open(percent_decoded(file).c_str(), mode);
  }
};

// What one import owns: Assimp's scene and the arrays made from it.
struct Import {
  Assimp::Importer importer;
  // Each part's arrays (a deque: adding one moves none).
  std::deque<std::vector<std::uint32_t>> indices;
  std::deque<std::vector<float>> floats;
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
  float value = 0.f;
  if (m.Get(AI_MATKEY_TRANSMISSION_FACTOR, value) == aiReturn_SUCCESS) out.transmission = value;
  if (m.Get(AI_MATKEY_REFRACTI, value) == aiReturn_SUCCESS) out.ior = value;
  out.metallic = m.Get(AI_MATKEY_METALLIC_FACTOR, value) == aiReturn_SUCCESS ? value : 1.f;
  out.roughness = m.Get(AI_MATKEY_ROUGHNESS_FACTOR, value) == aiReturn_SUCCESS ? value : 1.f;
  out.metallic_roughness_texture = m.GetTextureCount(aiTextureType_UNKNOWN) > 0 ? 1 : 0;
  aiString texture;
  aiTextureMapMode modes[3] = {aiTextureMapMode_Wrap, aiTextureMapMode_Wrap, aiTextureMapMode_Wrap};
  const auto colour_texture = [&](aiTextureType type) {
    return m.GetTexture(type, 0, &texture, nullptr, nullptr, nullptr, nullptr, modes) == aiReturn_SUCCESS;
  };
  if (colour_texture(aiTextureType_BASE_COLOR) || colour_texture(aiTextureType_DIFFUSE)) {
    out.wrap_u = static_cast<int>(modes[0]);
    out.wrap_v = static_cast<int>(modes[1]);
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

// Whether a mesh holds triangles only (after aiProcess_SortByPType a mesh
// holds one kind; the flags beside the kinds, such as
// aiPrimitiveType_NGONEncodingFlag, do not matter).
bool holds_triangles(const aiMesh& m) {
  constexpr unsigned kOthers = aiPrimitiveType_POINT | aiPrimitiveType_LINE | aiPrimitiveType_POLYGON;
  return (m.mPrimitiveTypes & aiPrimitiveType_TRIANGLE) != 0 && (m.mPrimitiveTypes & kOthers) == 0;
}

// Every node with its world transform (the product of its ancestors'),
// walked without recursion: a file's nesting depth is not bounded.
template <class Visit>
void for_each_node(const aiScene& scene, Visit visit) {
  std::vector<std::pair<const aiNode*, aiMatrix4x4>> pending{{scene.mRootNode, aiMatrix4x4()}};
  while (!pending.empty()) {
    const auto [node, parent] = pending.back();
    pending.pop_back();
    if (node == nullptr) continue;
    const aiMatrix4x4 world = parent * node->mTransformation;
    visit(*node, world);
    for (unsigned i = 0; i < node->mNumChildren; ++i) pending.emplace_back(node->mChildren[i], world);
  }
}

// One mesh placed by a node: positions by the world transform, normals by
// its inverse transpose (renormalised), the winding reversed where the
// transform mirrors (glTF: a negative determinant turns the front faces
// clockwise), so that each triangle's front stays the file's.
void add_part(const aiScene& scene, const aiMesh& m, const aiMatrix4x4& world, Import& import) {
  std::vector<float>& positions = import.floats.emplace_back();
  positions.reserve(std::size_t{3} * m.mNumVertices);
  for (unsigned v = 0; v < m.mNumVertices; ++v) {
    const aiVector3D p = world * m.mVertices[v];
    positions.insert(positions.end(), {p.x, p.y, p.z});
  }
  const aiMatrix3x3 linear(world);
  const bool mirrors = linear.Determinant() < 0.f;
  const float* normals = nullptr;
  if (m.mNormals != nullptr) {
    aiMatrix3x3 normal_matrix = linear;
    normal_matrix.Inverse().Transpose();
    std::vector<float>& out = import.floats.emplace_back();
    out.reserve(std::size_t{3} * m.mNumVertices);
    for (unsigned v = 0; v < m.mNumVertices; ++v) {
      aiVector3D n = normal_matrix * m.mNormals[v];
      const float length = n.Length();
      if (length > 0.f) n /= length;
      out.insert(out.end(), {n.x, n.y, n.z});
    }
    normals = out.data();
  }
  std::vector<std::uint32_t>& indices = import.indices.emplace_back();
  indices.reserve(std::size_t{3} * m.mNumFaces);
  for (unsigned f = 0; f < m.mNumFaces; ++f) {
    const unsigned* corner = m.mFaces[f].mIndices;  // triangulated: 3 each
    indices.insert(indices.end(), {corner[0], corner[mirrors ? 2 : 1], corner[mirrors ? 1 : 2]});
  }
  ImportedPart part{};
  part.vertex_count = m.mNumVertices;
  part.positions = positions.data();
  part.normals = normals;
  if (m.mTextureCoords[0] != nullptr) {
    part.uvs = &m.mTextureCoords[0][0].x;
    part.uv_stride = 3;
  }
  part.triangle_count = m.mNumFaces;
  part.indices = indices.data();
  part.material = m.mMaterialIndex < scene.mNumMaterials ? m.mMaterialIndex : 0;
  import.parts.push_back(part);
}

// The scene's triangle meshes, one part per node that places one; other
// primitives are counted and left out. False, with nothing copied, when
// the placed meshes hold more than max_triangles (a small file can place
// one mesh many times).
bool collect(const aiScene& scene, std::size_t max_triangles, Import& import, ImportedMesh& mesh) {
  mesh = {};
  std::size_t triangles = 0;
  for_each_node(scene, [&](const aiNode& node, const aiMatrix4x4&) {
    for (unsigned i = 0; i < node.mNumMeshes; ++i) {
      const aiMesh& m = *scene.mMeshes[node.mMeshes[i]];
      if (holds_triangles(m)) triangles += m.mNumFaces;
    }
  });
  if (triangles > max_triangles) return false;
  for (unsigned i = 0; i < scene.mNumMaterials; ++i) import.materials.push_back(material_of(scene, *scene.mMaterials[i]));
  for_each_node(scene, [&](const aiNode& node, const aiMatrix4x4& world) {
    for (unsigned i = 0; i < node.mNumMeshes; ++i) {
      const aiMesh& m = *scene.mMeshes[node.mMeshes[i]];
      if (holds_triangles(m)) {
        add_part(scene, m, world, import);
      } else {
        mesh.dropped_points_and_lines += m.mNumFaces;
      }
    }
  });
  if (import.materials.empty()) import.materials.push_back(ImportedMaterial{});
  mesh.part_count = import.parts.size();
  mesh.parts = import.parts.data();
  mesh.material_count = import.materials.size();
  mesh.materials = import.materials.data();
  return true;
}

void* import_mesh(const char* path, const void* data, std::size_t size, const char* hint, std::size_t max_triangles,
                  ImportedMesh* mesh, char* error, std::size_t error_size) {
  try {
    auto import = std::make_unique<Import>();
    import->importer.SetIOHandler(new UriDecodingIOSystem);  // the importer owns it
    constexpr unsigned kSteps = aiProcess_Triangulate | aiProcess_SortByPType | aiProcess_ValidateDataStructure;
    const aiScene* scene = data != nullptr ? import->importer.ReadFileFromMemory(data, size, kSteps, hint)
                                           : import->importer.ReadFile(path, kSteps);
    if (scene == nullptr) {
      copy_message(std::string("Assimp: ") + import->importer.GetErrorString(), error, error_size);
      return nullptr;
    }
    if (!collect(*scene, max_triangles, *import, *mesh)) {
      copy_message("expected at most " + std::to_string(max_triangles) +
                       " triangles once the file's nodes place its meshes, found more",
                   error, error_size);
      return nullptr;
    }
    return import.release();
  } catch (const std::bad_alloc&) {
    copy_message("Assimp: out of memory", error, error_size);
  } catch (const std::exception& e) {
    copy_message(std::string("Assimp: ") + e.what(), error, error_size);
  } catch (...) {
    copy_message("Assimp: an unknown error", error, error_size);
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
