// The C-style interface of the quiver_assimp module (io/assimp_module.cpp),
// the shared library that holds every use of Assimp (PLY, glTF 2.0 and STL
// import). quiver loads it with dlopen on first use (io/module_loader.h),
// so a run that reads no such file never maps Assimp. The module exports
// one function, kAssimpModuleEntry, returning a table of plain functions;
// no C++ type or exception crosses the boundary. Failure is reported by the
// return value, with a message ("Assimp: ..." for Assimp's own), cut to fit
// and NUL-terminated, in the caller's error buffer.
#pragma once

#include <cstddef>
#include <cstdint>

namespace quiver {

// Bumped whenever AssimpModuleApi or the structs below change.
inline constexpr int kAssimpModuleVersion = 6;

inline constexpr const char* kAssimpModuleEntry = "quiver_assimp_module_api";
inline constexpr const char* kAssimpModuleFileName = "quiver_assimp.so";

// A material as the file gives it (glTF's base colour; others' diffuse).
struct ImportedMaterial {
  float color[3];
  int has_color;        // 0: the file names no colour
  int two_sided;        // glTF doubleSided; 1 when the format has no such flag
  float transmission;   // glTF KHR_materials_transmission's factor; 0 when absent
  float ior;            // glTF KHR_materials_ior's; 0 when absent
  float metallic, roughness;  // glTF's metallic-roughness factors; 1 and 1 (glTF's defaults) when absent
  int metallic_roughness_texture;  // 1: glTF's metallicRoughnessTexture is named
  char texture[1024];   // the colour texture's path as written ("" none, "*N" embedded), cut to fit
  int wrap_u, wrap_v;   // its aiTextureMapMode per axis: 0 wrap, 1 clamp, 2 mirror, 3 decal (glTF's sampler)
  // An embedded colour texture's image file (PNG, JPEG, ...) bytes, or null;
  // embedded_raw is 1 for one embedded as raw texels instead.
  const unsigned char* embedded;
  std::size_t embedded_size;
  int embedded_raw;
};

// One mesh of the file as one node places it, in world space, triangles
// only. The arrays live as long as the import's handle.
struct ImportedPart {
  std::size_t vertex_count;
  const float* positions;  // 3 floats per vertex
  const float* normals;    // 3 floats per vertex, or null
  const float* uvs;        // first uv channel, uv_stride floats per vertex, or null
  std::size_t uv_stride;
  std::size_t triangle_count;
  const std::uint32_t* indices;  // 3 per triangle, below vertex_count
  std::size_t material;          // index into ImportedMesh::materials
};

struct ImportedMesh {
  std::size_t part_count;
  const ImportedPart* parts;
  std::size_t material_count;
  const ImportedMaterial* materials;
  std::size_t dropped_points_and_lines;  // primitives that are not triangles
};

struct AssimpModuleApi {
  int version;  // kAssimpModuleVersion

  // Imports a mesh with Assimp (polygons triangulated, each mesh placed by
  // every node that names it, the winding reversed under a mirroring
  // transform, points and lines counted apart, normals only as the file
  // gives them) and fills mesh: from the size bytes at data, of the format
  // named by the extension `hint` ("ply"), when data is not null; else from
  // the file at path (whose format may name others beside it). Returns a
  // handle that owns mesh's arrays, for free_import, or null with a message,
  // also when the placed meshes hold more than max_triangles (checked before
  // they are copied).
  void* (*import_mesh)(const char* path, const void* data, std::size_t size, const char* hint,
                       std::size_t max_triangles, ImportedMesh* mesh, char* error, std::size_t error_size);

  // Frees the import and its arrays.
  void (*free_import)(void* handle);
};

}  // namespace quiver

// The one exported function (C linkage, name kAssimpModuleEntry).
extern "C" const quiver::AssimpModuleApi* quiver_assimp_module_api();
