#include "io/mesh_append.h"

#include <algorithm>
#include <cmath>
#include <glm/glm.hpp>
#include <glm/gtc/matrix_inverse.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <stdexcept>
#include <string>
#include <utility>

#include "io/file_extension.h"
#include "io/mesh_import.h"
#include "io/obj_reader.h"
#include "io/parse_error.h"

namespace quiver {

namespace fs = std::filesystem;

bool is_mesh_extension(std::string_view extension) {
  return extension == ".obj" || is_imported_mesh_extension(extension);
}

namespace {

// What append_mesh checks of its arguments before reading: the transform as
// double matrices, whether it mirrors.
struct Placement {
  glm::dmat4 m;
  glm::dmat3 normal_matrix;
  bool mirrors;
};

Placement checked_placement(const std::array<float, 16>& transform, std::optional<std::size_t> material_override,
                            const SceneDesc& scene) {
  if (material_override && *material_override >= scene.materials.size()) {
    throw std::invalid_argument("append_mesh: material_override is not an index into scene.materials");
  }
  const glm::dmat4 m(glm::make_mat4(transform.data()));
  const glm::dmat3 linear(m);
  const double determinant = glm::determinant(linear);
  if (!std::isfinite(determinant) || determinant == 0.0) {
    throw std::invalid_argument("append_mesh: the transform is singular or not finite");
  }
  return {m, glm::inverseTranspose(linear), determinant < 0.0};
}

// Moves the mesh read (named `name`) into scene under the placement.
void place_mesh(SceneDesc mesh, const std::string& name, const Placement& placement,
                std::optional<std::size_t> material_override, SceneDesc& scene) {
  auto not_finite = [&] {
    throw ParseError::whole_file(name, "a vertex is not finite after the mesh transform of the including scene");
  };
  for (SceneTriangle& t : mesh.triangles) {
    for (Vec3<float>& p : t.triangle.p) {
      const glm::dvec4 q = placement.m * glm::dvec4(p.x, p.y, p.z, 1.0);
      p = {static_cast<float>(q.x), static_cast<float>(q.y), static_cast<float>(q.z)};
      if (!all_finite(p)) not_finite();
    }
    if (t.triangle.normals) {
      for (Vec3<float>& n : *t.triangle.normals) {
        glm::dvec3 q = placement.normal_matrix * glm::dvec3(n.x, n.y, n.z);
        const double length = glm::length(q);
        if (length > 0.0) q /= length;  // unit in double, so the float never overflows
        n = {static_cast<float>(q.x), static_cast<float>(q.y), static_cast<float>(q.z)};
      }
    }
    if (placement.mirrors) {
      std::swap(t.triangle.p[1], t.triangle.p[2]);
      if (t.triangle.normals) std::swap((*t.triangle.normals)[1], (*t.triangle.normals)[2]);
      if (t.triangle.uvs) std::swap((*t.triangle.uvs)[1], (*t.triangle.uvs)[2]);
    }
  }
  // Nothing below throws except on allocation: the scene changes only here.
  const std::size_t material_base = scene.materials.size();
  const std::size_t texture_base = scene.textures.size();
  for (std::string& file : mesh.source_files) {
    const auto& known = scene.source_files;
    if (std::find(known.begin(), known.end(), file) == known.end()) scene.source_files.push_back(std::move(file));
  }
  if (!material_override) {
    for (TextureDesc& texture : mesh.textures) scene.textures.push_back(std::move(texture));
    for (MaterialDesc material : mesh.materials) {
      if (material.texture) *material.texture += texture_base;
      scene.materials.push_back(material);
    }
  }
  scene.warnings.insert(scene.warnings.end(), mesh.warnings.begin(), mesh.warnings.end());
  scene.face_tallies.insert(scene.face_tallies.end(), mesh.face_tallies.begin(), mesh.face_tallies.end());
  // Room grown geometrically: an exact reserve per mesh copied every earlier
  // mesh's triangles again (quadratic in a scene's [[meshes]] entries).
  const std::size_t needed = scene.triangles.size() + mesh.triangles.size();
  if (needed > scene.triangles.capacity()) {
    scene.triangles.reserve(std::max(needed, 2 * scene.triangles.capacity()));
  }
  for (SceneTriangle& t : mesh.triangles) {
    t.material = material_override ? *material_override : t.material + material_base;
    scene.triangles.push_back(std::move(t));
  }
}

}  // namespace

std::size_t triangles_left(std::size_t stored) { return kMaxObjTriangles - std::min(stored, kMaxObjTriangles); }

void append_mesh(const fs::path& path, const std::array<float, 16>& transform,
                 std::optional<std::size_t> material_override, SceneDesc& scene, double crease_angle_degrees,
                 bool strict, const PathRule& paths) {
  const std::string extension = lowercase_extension(path);
  if (!is_mesh_extension(extension)) throw std::invalid_argument("append_mesh: not a mesh file name");
  const Placement placement = checked_placement(transform, material_override, scene);
  const std::size_t budget = triangles_left(scene.triangles.size());
  SceneDesc mesh = extension == ".obj" ? read_obj_scene(path, crease_angle_degrees, strict, budget, paths)
                                       : read_imported_mesh(path, crease_angle_degrees, strict, budget, paths);
  mesh.source_files.insert(mesh.source_files.begin(), path.string());
  place_mesh(std::move(mesh), path.string(), placement, material_override, scene);
}

void append_mesh_bytes(std::string_view bytes, const fs::path& name, const std::array<float, 16>& transform,
                       std::optional<std::size_t> material_override, SceneDesc& scene, double crease_angle_degrees,
                       bool strict) {
  const Placement placement = checked_placement(transform, material_override, scene);
  SceneDesc mesh = read_mesh_bytes(bytes, name, crease_angle_degrees, strict, triangles_left(scene.triangles.size()));
  place_mesh(std::move(mesh), name.string(), placement, material_override, scene);
}

}  // namespace quiver
