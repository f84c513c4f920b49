#include "io/mesh_import.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <map>
#include <memory>
#include <numeric>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "geometry/box.h"
#include "geometry/parallel_indices.h"
#include "geometry/position_welding.h"
#include "io/assimp_loader.h"
#include "io/file_extension.h"
#include "io/mesh_file_check.h"
#include "io/parse_error.h"
#include "io/ply_reader.h"
#include "io/reader_warnings.h"
#include "io/text_file.h"
#include "io/uri_path.h"
#include "scene/auto_view.h"

namespace quiver {

namespace {

namespace fs = std::filesystem;

enum class MeshFormat { ply, gltf, glb, stl };

std::optional<MeshFormat> format_of(std::string_view extension) {
  if (extension == ".ply") return MeshFormat::ply;
  if (extension == ".gltf") return MeshFormat::gltf;
  if (extension == ".glb") return MeshFormat::glb;
  if (extension == ".stl") return MeshFormat::stl;
  return std::nullopt;
}

// Frees an import when it goes out of scope.
struct ImportDeleter {
  const AssimpModuleApi* api;
  void operator()(void* handle) const { api->free_import(handle); }
};
using ImportHandle = std::unique_ptr<void, ImportDeleter>;

// Vertex `index` of an array of float triples.
Vec3<float> vector_at(const float* data, std::size_t index) {
  const float* v = data + 3 * index;
  return {v[0], v[1], v[2]};
}

// Smooth normals for the triangles (indices numbered across the parts, part
// i's from vertex_base[i]) into triangles[owner[k]]: every vertex welded by
// position, the positions numbered by the triangles' first use.
void add_smooth_normals(const ImportedMesh& mesh, const std::vector<std::size_t>& vertex_base,
                        std::vector<TriangleIndices>& unsmoothed, const std::vector<std::size_t>& owner,
                        double crease_angle_degrees, std::vector<SceneTriangle>& triangles) {
  WeldedPositions welding = weld_positions(vertex_base.back(), [&](std::size_t v) {
    const auto i = static_cast<std::size_t>(std::upper_bound(vertex_base.begin(), vertex_base.end(), v) -
                                            vertex_base.begin()) - 1;
    return vector_at(mesh.parts[i].positions, v - vertex_base[i]);
  });
  for_each_index(unsmoothed.size(), [&](std::size_t t) {
    for (std::uint32_t& v : unsmoothed[t]) v = welding.index_of[v];
  });
  number_by_first_use(welding.positions, unsmoothed);
  smooth_vertex_normals(welding.positions, unsmoothed, crease_angle_degrees,
                        [&](std::size_t k, const CornerNormals& normals) {
                          triangles[owner[k]].triangle.normals = normals;
                        });
}

// An Assimp texture map mode as quiver's wrap (decal, outside the image
// transparent, as clamp).
WrapMode wrap_of(int mode) {
  switch (mode) {
    case 1: return WrapMode::clamp;
    case 2: return WrapMode::mirror;
    case 3: return WrapMode::clamp;
    default: return WrapMode::repeat;
  }
}

// glTF's metallic-roughness in Phong's and Whitted's terms: a surface's
// smoothness s = (1 - roughness)^2 is the share of its specular reflectance
// at normal incidence F0 = 0.04 (1 - metallic) + metallic (glTF's dielectric
// 4%, a metal's all) that is a mirror image: kr = ks = s F0, what the mirror
// takes no longer diffused (kd times 1 - kr), highlights of Phong exponent
// 2 / a^2 - 2 for a = roughness^2 (Walter et al. 2007's match to Beckmann's
// width; 1 to 10^4). A rough surface (glTF's default: roughness 1) keeps
// the diffuse base colour, so a file without the factors renders as before.
void apply_metallic_roughness(float metallic, float roughness, MaterialDesc& material) {
  const float m = std::clamp(std::isfinite(metallic) ? metallic : 1.f, 0.f, 1.f);
  const float r = std::clamp(std::isfinite(roughness) ? roughness : 1.f, 0.f, 1.f);
  const float smoothness = (1.f - r) * (1.f - r);
  const float mirror = smoothness * (0.04f * (1.f - m) + m);
  material.kr = mirror;
  material.ks = mirror;
  material.kd *= 1.f - mirror;
  const float width = std::max(r * r, 0.01f);
  material.shininess = std::clamp(2.f / (width * width) - 2.f, 1.f, 1e4f);
}

// glTF materials into the scene (PLY and STL: one default material).
void add_materials(const ImportedMesh& mesh, MeshFormat format, std::string_view file, const fs::path& directory,
                   const PathRule& paths, ReaderWarnings& warnings, SceneDesc& scene) {
  if (format != MeshFormat::gltf && format != MeshFormat::glb) {
    scene.materials.assign(1, MaterialDesc{});
    return;
  }
  const FilePosition whole_file{std::string(file), 0, 0};
  // Each image once, however many materials use it: by its bytes' address or its path.
  std::map<std::string, std::size_t> texture_of;
  const auto add_texture = [&](const std::string& key, TextureDesc image) {
    const auto [entry, added] = texture_of.try_emplace(key, scene.textures.size());
    if (added) scene.textures.push_back(std::move(image));
    return entry->second;
  };
  for (std::size_t i = 0; i < mesh.material_count; ++i) {
    const ImportedMaterial& m = mesh.materials[i];
    MaterialDesc material;
    if (m.has_color) material.color = {m.color[0], m.color[1], m.color[2]};
    material.two_sided = m.two_sided != 0;
    apply_metallic_roughness(m.metallic, m.roughness, material);
    if (m.metallic_roughness_texture != 0) {
      warnings.warn("metallic-roughness texture", whole_file, "metallic and roughness as factors",
                    "a metallicRoughnessTexture", "its factors alone are used");
    }
    // KHR_materials_transmission and _ior: the transmitted share refracts
    // (Whitted's kt) instead of scattering diffusely; such a surface is seen
    // from inside too, so two-sided (as NFF's transmissive surfaces).
    if (std::isfinite(m.transmission) && m.transmission > 0.f) {
      const float transmission = std::min(m.transmission, 1.f);
      material.kt = transmission;
      material.kd *= 1.f - transmission;
      material.two_sided = true;
    }
    if (std::isfinite(m.ior) && m.ior >= 1.f) material.ior = m.ior;
    const std::string_view texture(m.texture, ::strnlen(m.texture, sizeof m.texture));
    // One wrap for both axes (TextureDesc's); the u axis's where they differ.
    const WrapMode wrap = wrap_of(m.wrap_u);
    if (!texture.empty() && wrap_of(m.wrap_v) != wrap) {
      warnings.warn("texture wrap", whole_file, "a texture sampler that wraps both axes alike",
                    "different wrapS and wrapT", "wrapS is used for both");
    }
    const std::string wrap_key = " wrap " + std::to_string(int(wrap));
    if (m.embedded != nullptr) {
      // Decoded with the scene's other images (io/texture_image.h).
      TextureDesc image;
      image.kind = TextureDesc::Kind::image;
      image.encoded.assign(m.embedded, m.embedded + m.embedded_size);
      image.named_at = whole_file;
      image.wrap = wrap;
      material.texture = add_texture(
          "embedded " + std::to_string(reinterpret_cast<std::uintptr_t>(m.embedded)) + wrap_key, std::move(image));
    } else if (m.embedded_raw != 0 || (!texture.empty() && texture[0] == '*')) {
      warnings.warn("embedded texture", whole_file, "a base colour texture as an image file",
                    "an image embedded as raw texels", "the base colour alone");
    } else if (!texture.empty()) {
      const fs::path path = file_named_by_uri(directory, texture);
      if (!uri_admitted(paths, directory, texture)) {
        throw ParseError::whole_file(file, joined({"expected material ", std::to_string(i), "'s image to be ",
                                                   paths.expected(), ", found ", quoted_token(texture)}));
      }
      std::error_code error;
      if (fs::is_regular_file(path, error)) {
        TextureDesc image;
        image.kind = TextureDesc::Kind::image;
        image.path = path.string();
        image.named_at = whole_file;
        image.wrap = wrap;
        material.texture = add_texture("file " + image.path + wrap_key, std::move(image));
      } else {
        warnings.warn(joined({"texture ", path.string()}), whole_file,
                      joined({"an image file that exists (looked for '", path.string(), "')"}),
                      quoted_token(texture), "the material is not textured");
      }
    }
    scene.materials.push_back(material);
  }
}

// A vertex position (of part `part`, after its node's transform) finite and
// within the OBJ reader's coordinate bound, as the camera and bounding
// boxes need.
void check_position(const Vec3<float>& p, std::string_view file, std::size_t part, std::uint32_t vertex) {
  const auto within = [](float c) { return std::fabs(c) <= kLargestMeshCoordinate; };  // false for NaN
  if (within(p.x) && within(p.y) && within(p.z)) return;  // the common case: no message made
  const std::string where = joined({" (mesh ", std::to_string(part), ", vertex ", std::to_string(vertex), ")"});
  if (!all_finite(p)) {
    throw ParseError::whole_file(file, joined({"expected finite vertex positions, found one that is not", where}));
  }
  char shown[96];
  std::snprintf(shown, sizeof shown, "(%g, %g, %g)", double(p.x), double(p.y), double(p.z));
  throw ParseError::whole_file(file, joined({"expected vertex positions from -3.4e38 to 3.4e38, found ", shown, where}));
}

SceneDesc scene_from(const ImportedMesh& mesh, MeshFormat format, std::string_view file, const fs::path& directory,
                     const PathRule& paths, double crease_angle_degrees, ReaderWarnings& warnings) {
  SceneDesc scene;
  add_materials(mesh, format, file, directory, paths, warnings, scene);
  if (mesh.dropped_points_and_lines > 0) {
    warnings.warn("points and lines", {std::string(file), 0, 0}, "triangles",
                  joined({std::to_string(mesh.dropped_points_and_lines), " points and lines"}), "they are not drawn");
  }
  std::size_t triangles = 0;
  for (std::size_t i = 0; i < mesh.part_count; ++i) triangles += mesh.parts[i].triangle_count;
  scene.face_tallies = {{std::string(file), triangles + mesh.dropped_points_and_lines, triangles}};
  if (triangles == 0) {
    const std::size_t others = mesh.dropped_points_and_lines;
    throw ParseError::whole_file(file, others == 0 ? std::string("expected at least one triangle, found none")
                                                   : joined({"expected at least one triangle, found only ",
                                                             std::to_string(others), " points and lines"}));
  }
  scene.triangles.reserve(triangles);

  // STL's normals are its facets': smooth ones are computed as for PLY.
  const bool file_normals_kept = format != MeshFormat::stl;
  // Faceted (crease angle 0): nothing to weld.
  const bool smooth_missing = (format == MeshFormat::ply || format == MeshFormat::stl) && crease_angle_degrees > 0.0;
  // Part i's vertices are numbered from vertex_base[i] for the welding.
  std::vector<std::size_t> vertex_base(mesh.part_count + 1, 0);
  for (std::size_t i = 0; i < mesh.part_count; ++i) vertex_base[i + 1] = vertex_base[i] + mesh.parts[i].vertex_count;
  std::vector<TriangleIndices> unsmoothed;     // of the triangles to smooth, by those numbers
  std::vector<std::size_t> unsmoothed_owner;  // their index in scene.triangles
  for (std::size_t i = 0; i < mesh.part_count; ++i) {
    const ImportedPart& part = mesh.parts[i];
    const bool has_normals = file_normals_kept && part.normals != nullptr;
    const std::size_t material = part.material < scene.materials.size() ? part.material : 0;
    for (std::size_t t = 0; t < part.triangle_count; ++t) {
      SceneTriangle triangle{};
      triangle.material = material;
      std::array<Vec3<float>, 3> normals{};
      std::array<std::array<float, 2>, 3> uvs{};
      for (std::size_t k = 0; k < 3; ++k) {
        const std::uint32_t v = part.indices[3 * t + k];
        triangle.triangle.p[k] = vector_at(part.positions, v);
        check_position(triangle.triangle.p[k], file, i, v);
        if (has_normals) normals[k] = vector_at(part.normals, v);
        if (part.uvs != nullptr) uvs[k] = {part.uvs[part.uv_stride * v], part.uvs[part.uv_stride * v + 1]};
      }
      if (has_normals && all_finite(normals[0]) && all_finite(normals[1]) && all_finite(normals[2])) {
        triangle.triangle.normals = normals;
      } else if (smooth_missing) {
        const std::uint32_t* v = part.indices + 3 * t;
        const auto base = static_cast<std::uint32_t>(vertex_base[i]);
        unsmoothed.push_back({base + v[0], base + v[1], base + v[2]});
        unsmoothed_owner.push_back(scene.triangles.size());
      }
      if (part.uvs != nullptr) triangle.triangle.uvs = uvs;
      scene.triangles.push_back(triangle);
    }
  }
  if (!unsmoothed.empty()) {
    add_smooth_normals(mesh, vertex_base, unsmoothed, unsmoothed_owner, crease_angle_degrees, scene.triangles);
  }
  scene.warnings = warnings.lines();
  return scene;
}

// One part of quiver's own reading (a PLY or binary STL mesh, which names
// no files) as an import with the default material, so that its triangles
// and smooth normals are built as every imported mesh's.
SceneDesc scene_from_part(const ImportedPart& part, MeshFormat format, std::string_view file,
                          double crease_angle_degrees, ReaderWarnings& warnings,
                          std::size_t dropped_points_and_lines = 0) {
  const ImportedMaterial material{};
  ImportedMesh mesh{};
  mesh.part_count = 1;
  mesh.parts = &part;
  mesh.material_count = 1;
  mesh.materials = &material;
  mesh.dropped_points_and_lines = dropped_points_and_lines;
  return scene_from(mesh, format, file, {}, PathRule{}, crease_angle_degrees, warnings);
}

// A PLY mesh (io/ply_reader.h).
SceneDesc scene_from_ply(const PlyMesh& ply, std::string_view file, double crease_angle_degrees,
                         ReaderWarnings& warnings) {
  ImportedPart part{};
  part.vertex_count = ply.positions.size() / 3;
  part.positions = ply.positions.data();
  part.normals = ply.normals.empty() ? nullptr : ply.normals.data();
  part.uvs = ply.uvs.empty() ? nullptr : ply.uvs.data();
  part.uv_stride = 2;
  part.triangle_count = ply.triangles.size() / 3;
  part.indices = ply.triangles.data();
  SceneDesc scene = scene_from_part(part, MeshFormat::ply, file, crease_angle_degrees, warnings, ply.point_cloud_vertices);
  scene.face_tallies = {{std::string(file), ply.faces_declared, ply.faces_kept}};
  return scene;
}

// A binary STL's corners (io/mesh_file_check.h): three vertices a triangle,
// welded by position for the smooth normals.
SceneDesc scene_from_binary_stl(const std::vector<float>& corners, std::string_view file, double crease_angle_degrees,
                                ReaderWarnings& warnings) {
  std::vector<std::uint32_t> indices(corners.size() / 3);
  std::iota(indices.begin(), indices.end(), 0u);
  ImportedPart part{};
  part.vertex_count = indices.size();
  part.positions = corners.data();
  part.triangle_count = indices.size() / 3;
  part.indices = indices.data();
  return scene_from_part(part, MeshFormat::stl, file, crease_angle_degrees, warnings);
}

// STL has no up axis of its own; CAD's convention, which STL files follow, is +z.
const SceneDesc::StatedUp kStlUp{{0.f, 0.f, 1.f}, "STL's convention"};

// A glTF's punctual lights, scaled as io/gltf_lights.h says for the scene's
// bounds, and what of them quiver does not model named; a scene lit by its
// own lights gets the default rig's background (glTF has none).
void use_gltf_lights(const GltfLights& lights, const std::string& file, ReaderWarnings& warnings, SceneDesc& scene) {
  if (lights.lights.empty()) return;
  Box bounds = empty_box();
  for (const SceneTriangle& t : scene.triangles) {
    for (const Vec3<float>& p : t.triangle.p) grow(bounds, p);
  }
  const Vec3<float> centre = is_empty(bounds) ? Vec3<float>{0.f, 0.f, 0.f} : centroid(bounds);
  scene.lights = scaled_gltf_lights(lights, centre, scene.ambient);
  if (!scene.background) scene.background = Vec3<float>{1.f, 1.f, 1.f} * kDefaultRigBackground;
  for (const std::string& ranged : lights.ranges) {
    warnings.warn("gltf light range", {file, 0, 0}, "a light without a range", ranged + ", with a range",
                  "its light does not fall off (quiver's lights never do)");
  }
  scene.warnings = warnings.lines();
}

// An ASCII STL or a glTF that io/mesh_file_check.h accepted, imported by the
// Assimp module (loaded on first use): STL from the bytes checked, glTF
// from its file, whose buffers and images are named relative to it.
SceneDesc scene_through_assimp(std::string_view bytes, const std::string& file, MeshFormat format,
                               const fs::path& directory, const PathRule& rule, double crease_angle_degrees,
                               std::size_t triangle_budget, ReaderWarnings& warnings) {
  const AssimpModuleApi* api = nullptr;
  try {
    api = &assimp_module();
  } catch (const std::runtime_error& error) {
    throw ParseError::whole_file(file, error.what());
  }
  const bool from_memory = format == MeshFormat::stl;
  const std::string extension = lowercase_extension(file);
  ImportedMesh mesh{};
  char error[1024] = {};
  ImportHandle handle(api->import_mesh(file.c_str(), from_memory ? bytes.data() : nullptr, bytes.size(),
                                       extension.c_str() + 1, triangle_budget, &mesh, error, sizeof error),
                      ImportDeleter{api});
  if (!handle) throw ParseError::whole_file(file, error);
  return scene_from(mesh, format, file, directory, rule, crease_angle_degrees, warnings);
}

// The format a mesh file name says, after the arguments every reading checks.
MeshFormat checked_format(const fs::path& path, double crease_angle_degrees) {
  if (!valid_crease_angle(crease_angle_degrees)) {
    throw std::invalid_argument("mesh reader: the crease angle is not in [0, 180] degrees");
  }
  const std::optional<MeshFormat> format = format_of(lowercase_extension(path));
  if (!format) throw std::invalid_argument("read_imported_mesh: not a PLY, glTF or STL file name");
  return *format;
}

// A mesh file's bytes read as its format; a glTF's other files from path's folder.
SceneDesc mesh_from_bytes(std::string_view bytes, const fs::path& path, MeshFormat format,
                          double crease_angle_degrees, bool strict, std::size_t triangle_budget,
                          const PathRule& paths) {
  const std::string file = path.string();
  const fs::path directory = path.parent_path();
  const PathRule rule = paths.for_folder(directory);
  ReaderWarnings warnings(strict);
  GltfContents gltf;
  std::uint64_t declared_triangles = 0;  // as the file counts them; 0 when it does not
  switch (format) {
    case MeshFormat::ply:
    {
      const PlyMesh ply = read_ply(bytes, file, warnings, triangle_budget);
      SceneDesc scene = scene_from_ply(ply, file, crease_angle_degrees, warnings);
      scene.model_up = ply.stated_up;
      return scene;
    }
    case MeshFormat::stl:
    {
      const MeshFileCounts counts = check_stl(bytes, file);
      if (counts.stl_binary) {
        SceneDesc scene = scene_from_binary_stl(binary_stl_corners(bytes, counts.triangles), file,
                                                crease_angle_degrees, warnings);
        scene.model_up = kStlUp;
        return scene;
      }
      declared_triangles = counts.triangles;  // ASCII STL: through Assimp
      break;
    }
    case MeshFormat::gltf:
      gltf = check_gltf(bytes, file, directory, rule, false, kMaxImportedMeshBytes, triangle_budget);
      declared_triangles = gltf.placed_triangles;
      break;
    case MeshFormat::glb:
      gltf = check_gltf(bytes, file, directory, rule, true, kMaxImportedMeshBytes, triangle_budget);
      declared_triangles = gltf.placed_triangles;
      break;
  }

  SceneDesc scene = scene_through_assimp(bytes, file, format, directory, rule, crease_angle_degrees,
                                         triangle_budget, warnings);
  if (format == MeshFormat::stl) scene.model_up = kStlUp;
  scene.camera = gltf.camera;
  if (!gltf.unused_camera.empty()) {
    warnings.warn("gltf camera", {file, 0, 0}, "a perspective camera", gltf.unused_camera,
                  "the default view is used");
    scene.warnings = warnings.lines();
  }
  use_gltf_lights(gltf.lights, file, warnings, scene);
  // Assimp must return every triangle the file declares; what it does not is named.
  FaceTally& tally = scene.face_tallies.front();
  if (declared_triangles > tally.kept) {
    warnings.warn("triangles declared", {file, 0, 0},
                  joined({"the ", std::to_string(declared_triangles), " triangles the file declares"}),
                  joined({std::to_string(tally.kept), " read by Assimp"}), "the others are not drawn");
    tally.declared += declared_triangles - tally.kept;
    scene.warnings = warnings.lines();
  }
  // Its buffer and image files are inputs too, which no output may overwrite.
  for (const fs::path& read : gltf.files) {
    const std::string name = read.string();
    if (std::find(scene.source_files.begin(), scene.source_files.end(), name) == scene.source_files.end()) {
      scene.source_files.push_back(name);
    }
  }
  return scene;
}

}  // namespace


bool is_imported_mesh_extension(std::string_view extension) { return format_of(extension).has_value(); }

SceneDesc read_imported_mesh(const fs::path& path, double crease_angle_degrees, bool strict,
                             std::size_t triangle_budget, const PathRule& paths) {
  const MeshFormat format = checked_format(path, crease_angle_degrees);  // before the file is opened
  return mesh_from_bytes(read_text_file(path, kMaxImportedMeshBytes, "a mesh"), path, format, crease_angle_degrees,
                         strict, triangle_budget, paths);
}

SceneDesc read_mesh_bytes(std::string_view bytes, const fs::path& path, double crease_angle_degrees, bool strict,
                          std::size_t triangle_budget) {
  const MeshFormat format = checked_format(path, crease_angle_degrees);
  if (format != MeshFormat::ply && format != MeshFormat::stl) {
    throw std::invalid_argument("read_mesh_bytes: only PLY and STL are read from bytes alone");
  }
  if (bytes.size() > kMaxImportedMeshBytes) {
    throw ParseError::whole_file(path.string(), "a mesh of at most " + std::to_string(kMaxImportedMeshBytes) + " bytes");
  }
  return mesh_from_bytes(bytes, path, format, crease_angle_degrees, strict, triangle_budget, {});
}

}  // namespace quiver
