// Reader for quiver's TOML scene format (toml++): camera, render settings,
// lights, textures, materials, primitives and OBJ mesh includes, every key
// checked (unknown keys are errors, so typos are caught). Errors are
// ParseError with the file:line:column of the offending key or value. The
// format, with every key's type, default and unit, is in io/README.md.
#pragma once

#include <cstddef>
#include <filesystem>
#include <optional>
#include <string_view>

#include "io/mesh_append.h"
#include "io/path_rule.h"
#include "scene/scene_desc.h"

namespace quiver {

// Largest TOML scene read, in bytes, and most keys, values, arrays and
// tables in it (counted by io/toml_prescan.h before toml++ builds its
// document, which takes 70-120 bytes a node). A TOML scene is for what is
// written by hand: about 47,000 spheres fit; large geometry belongs in OBJ
// files included with [[meshes]].
inline constexpr std::size_t kMaxTomlBytes = std::size_t{16} << 20;
inline constexpr std::size_t kMaxTomlNodes = std::size_t{1} << 19;
// Most entries of [[lights]], [[textures]], [[materials]] and [[meshes]].
inline constexpr std::size_t kMaxTomlLights = 1024;
inline constexpr std::size_t kMaxTomlTextures = 1024;
inline constexpr std::size_t kMaxTomlMaterials = 65'536;
inline constexpr std::size_t kMaxTomlMeshes = 1024;
// Largest area-light `samples` (per side); [render]'s bounds are the
// scene description's (scene/scene_desc.h).
inline constexpr int kMaxLightSamples = 64;

// Reads a scene file; relative paths in it (meshes, image textures) are
// relative to the file's folder. crease_angle_override, when given (in
// [0, 180]), is every mesh's crease angle, over its `crease_angle` key.
// `strict` reads the included meshes strictly (obj_reader.h); their
// warnings are the scene's. Every file the scene and its meshes name keeps
// `paths` (io/path_rule.h; by default the scene's folder and below).
// Throws ParseError.
SceneDesc read_toml_scene(const std::filesystem::path& path,
                          std::optional<double> crease_angle_override = std::nullopt, bool strict = false,
                          const PathRule& paths = {});

// Parses TOML scene text; file_name labels error messages and relative
// paths are resolved against base_dir. A mesh `file` named as written by a
// key of held_meshes is read from its bytes (a .ply or .stl; no file is
// looked for, so the path rule does not apply and source_files does not
// list it): a Python scene's array meshes (python/scene_dict.h).
SceneDesc parse_toml_scene(std::string_view text, std::string_view file_name, const std::filesystem::path& base_dir,
                           std::optional<double> crease_angle_override = std::nullopt, bool strict = false,
                           const PathRule& paths = {}, const MeshBytes* held_meshes = nullptr);

}  // namespace quiver
