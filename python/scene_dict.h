// Whole scenes from Python (quiver.from_dict): a dict holding the TOML
// scene format's keys, tables and arrays of tables (io/README.md), written
// out as that format's text by toml++ and read by the TOML reader itself,
// so every key, rule, bound and message is the reader's; the text is what
// Scene.to_toml writes, a file the CLI reads to the same scene.
#pragma once

#include <pybind11/pybind11.h>

#include <filesystem>
#include <string>
#include <string_view>

#include "io/mesh_append.h"
#include "io/parse_error.h"
#include "io/scene_loader.h"
#include "python/python_scene.h"

namespace quiver {

// A dict scene as TOML text, and the meshes it gives as arrays, each held
// as a binary PLY under the file name its entry's `file` key names in the
// text (kArrayMeshPrefix and a number).
struct DictSceneText {
  std::string toml;
  MeshBytes held_meshes;
};
inline constexpr std::string_view kArrayMeshPrefix = "array_mesh_";

// The scene's TOML text. Values: dict (str keys), list and tuple, bool,
// int (64-bit), float, str, os.PathLike, NumPy arrays and scalars (through
// tolist()); anything else, None among them, has no TOML form (TypeError
// naming the key, "spheres[2].radius"). At most kMaxTomlNodes values (the
// root table, tables, arrays and values, as the TOML reader counts its
// nodes) and kMaxDictDepth levels (ValueError), counted before the text is
// made. A meshes or instances entry may give its mesh as NumPy arrays
// instead of a file: vertices (V, 3) and triangles (F, 3), with normals
// (V, 3) and uvs (V, 2) if wanted (python/scene_arrays.h's ply_of_arrays
// checks them); entries giving the same array objects share one mesh.
DictSceneText toml_text_of_dict(const pybind11::handle& scene);
inline constexpr int kMaxDictDepth = 32;

// The file name a dict scene's errors and Scene.name show.
inline constexpr std::string_view kDictSceneName = "<dict>";

// Reads and builds the text of toml_text_of_dict, its relative file names
// resolved in folder (which, unless options.allow_outside_paths, holds
// every file it names); its errors are ParseError, said as dict_error says
// them. The scene keeps the text and the folder for write_dict_scene.
PythonScene read_dict_scene(DictSceneText text, const std::filesystem::path& folder, const SceneLoadOptions& options);

// Writes a dict scene's text to path (.toml), and each array mesh beside it
// as <stem>_array_mesh_N.ply (the text naming it so), through temporary
// files renamed over them together. Throws ValueError for a scene not from a dict, another
// extension, or (when the scene names files) a folder other than its
// base folder, where those names would not resolve; OSError when writing fails.
void write_dict_scene(const PythonScene& scene, const std::filesystem::path& path);

// An error of the TOML reader in text made from a dict, said in the dict's
// terms: "<dict>: spheres[1].radius: expected ..., found ..." (the key of
// the line it names, under the table that line is in), as the user never
// saw the text.
ParseError dict_error(const ParseError& error, std::string_view text);

}  // namespace quiver
