#include "python/scene_dict.h"

#include <toml++/toml.h>

#include <array>
#include <cstdint>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>

#include "io/file_extension.h"
#include "io/output_file.h"
#include "io/path_rule.h"
#include "io/texture_image.h"
#include "io/ply_writer.h"
#include "io/toml_reader.h"
#include "python/arguments.h"
#include "python/scene_arrays.h"

namespace py = pybind11;

namespace quiver {
namespace {

// Converts a Python value to a toml++ node, counting the values made.
class DictConverter {
 public:
  toml::table table(const py::handle& value, const std::string& where, int depth) {
    if (!py::isinstance<py::dict>(value)) {
      throw py::type_error(where + ": expected a dict, found " + type_name(value));
    }
    toml::table out;
    const auto dict = py::reinterpret_borrow<py::dict>(value);
    const bool array_mesh = names_mesh_entry(where) && dict.contains("vertices");
    if (array_mesh) out.insert("file", held_mesh(dict, where));
    for (const auto& [key, item] : dict) {
      if (!py::isinstance<py::str>(key)) throw py::type_error(where + ": keys must be str, found " + type_name(key));
      const std::string name = key.cast<std::string>();
      if (array_mesh && is_array_mesh_key(name)) continue;
      const std::string path = where.empty() ? name : where + "." + name;
      insert(out, name, item, path, depth + 1);
    }
    return out;
  }

  MeshBytes&& held_meshes() && { return std::move(held_); }

 private:
  std::size_t values_ = 1;  // the document's root table, which the TOML reader counts too
  MeshBytes held_;
  // An array mesh's name by the identities of its arrays: entries sharing them share one file.
  std::map<std::array<PyObject*, 4>, std::string> held_names_;

  // A [[meshes]] or [[instances]] entry: "meshes[3]", not a table below one.
  static bool names_mesh_entry(const std::string& where) {
    return (where.starts_with("meshes[") || where.starts_with("instances[")) && where.ends_with("]") &&
           where.find('.') == std::string::npos;
  }
  static bool is_array_mesh_key(const std::string& key) {
    return key == "vertices" || key == "triangles" || key == "normals" || key == "uvs" || key == "file";
  }

  // The file name an entry's arrays are held under (kArrayMeshPrefix and a
  // number), encoded as binary PLY the first time these arrays are met.
  std::string held_mesh(const py::dict& entry, const std::string& where) {
    if (entry.contains("file")) {
      throw py::value_error(where + ": give either file or vertices and triangles, not both");
    }
    if (!entry.contains("triangles")) throw py::value_error(where + ": vertices need triangles indexing them");
    const auto item = [&](const char* key) { return entry.contains(key) ? entry[key].ptr() : nullptr; };
    const std::array<PyObject*, 4> identity{item("vertices"), item("triangles"), item("normals"), item("uvs")};
    if (const auto known = held_names_.find(identity); known != held_names_.end()) return known->second;
    const auto rows = [&](const char* key, std::size_t columns) -> std::optional<CheckedRows<FloatRows>> {
      if (!entry.contains(key)) return std::nullopt;
      return float_rows(entry[key], (where + "." + key).c_str(), columns, false);
    };
    const auto vertices = rows("vertices", 3), normals = rows("normals", 3), uvs = rows("uvs", 2);
    const CheckedRows<IndexRows> triangles = index_rows(entry["triangles"], (where + ".triangles").c_str());
    const PlyMesh mesh = ply_of_arrays(vertices->rows, triangles.rows, rows_of(normals), rows_of(uvs), where);
    std::string name = std::string(kArrayMeshPrefix) + std::to_string(held_.size()) + ".ply";
    held_.emplace(name, binary_ply(mesh));
    held_names_.emplace(identity, name);
    return name;
  }

  static std::string type_name(const py::handle& value) { return py::str(py::type::of(value).attr("__name__")); }

  void count(const std::string& where, int depth) {
    if (++values_ > kMaxTomlNodes) {
      throw py::value_error(where + ": a scene holds at most " + std::to_string(kMaxTomlNodes) +
                            " values (a TOML scene's bound); large geometry belongs in mesh files");
    }
    if (depth > kMaxDictDepth) {
      throw py::value_error(where + ": nested deeper than " + std::to_string(kMaxDictDepth) + " levels");
    }
  }

  template <class Container>
  void insert(Container& out, const std::string& key, const py::handle& item, const std::string& where, int depth) {
    count(where, depth);
    const py::object value = plain(item);
    const auto put = [&](auto&& node) {
      if constexpr (std::is_same_v<Container, toml::table>) {
        out.insert(key, std::forward<decltype(node)>(node));
      } else {
        out.push_back(std::forward<decltype(node)>(node));
      }
    };
    if (py::isinstance<py::bool_>(value)) {
      put(value.cast<bool>());
    } else if (py::isinstance<py::int_>(value)) {
      try {
        put(value.cast<std::int64_t>());
      } catch (const py::cast_error&) {
        throw py::value_error(where + ": " + std::string(py::repr(value)) + " does not fit in a 64-bit integer");
      }
    } else if (py::isinstance<py::float_>(value)) {
      put(value.cast<double>());
    } else if (py::isinstance<py::str>(value)) {
      put(value.cast<std::string>());
    } else if (py::isinstance<py::dict>(value)) {
      put(table(value, where, depth));
    } else if (py::isinstance<py::list>(value) || py::isinstance<py::tuple>(value)) {
      toml::array array;
      std::size_t index = 0;
      for (const py::handle element : value) {
        insert(array, key, element, where + "[" + std::to_string(index++) + "]", depth + 1);
      }
      put(std::move(array));
    } else {
      throw py::type_error(where + ": a " + type_name(item) + " has no TOML form (dict, list, tuple, bool, int, "
                           "float, str, os.PathLike or a NumPy array or scalar)");
    }
  }

  // NumPy values as Python's own (tolist), paths as str.
  static py::object plain(const py::handle& item) {
    // Kept for the process's life: a static py::object would be released after the interpreter is gone.
    static const py::object* const os = new py::object(py::module_::import("os"));
    if (py::isinstance(item, os->attr("PathLike"))) return os->attr("fspath")(item);
    if (!py::isinstance<py::str>(item) && py::hasattr(item, "tolist") && py::hasattr(item, "dtype")) {
      return item.attr("tolist")();
    }
    return py::reinterpret_borrow<py::object>(item);
  }
};

// The key a line of toml++'s text sets, and the table it is in: "camera.fov", "spheres[1].radius".
std::string key_at_line(std::string_view text, std::size_t line) {
  std::map<std::string, std::size_t, std::less<>> seen;  // [[name]] headers so far
  std::string table;
  std::string key;
  std::size_t number = 0;
  std::size_t start = 0;
  while (start <= text.size() && ++number <= line) {
    const std::size_t end = std::min(text.find('\n', start), text.size());
    const std::string_view row = text.substr(start, end - start);
    if (row.starts_with("[[") && row.ends_with("]]")) {
      const std::string name(row.substr(2, row.size() - 4));
      table = name + "[" + std::to_string(seen[name]++) + "]";
      key.clear();
    } else if (row.starts_with("[") && row.ends_with("]")) {
      table = std::string(row.substr(1, row.size() - 2));
      key.clear();
    } else if (const std::size_t equals = row.find(" = ");
               equals != std::string_view::npos && !row.starts_with(' ')) {
      key = std::string(row.substr(0, equals));  // a key's line; rows of a long array below it keep it
    }
    start = end + 1;
  }
  if (table.empty()) return key;
  return key.empty() ? table : table + "." + key;
}

// A string as toml++ writes it as a value (quoted and escaped).
std::string toml_string(const std::string& value) {
  std::ostringstream text;
  text << toml::value<std::string>(value);
  return text.str();
}

// Every TOML string value `from` in text becomes `to`: an array mesh's name
// as its file beside the TOML.
void replace_string_value(std::string& text, const std::string& from, const std::string& to) {
  const std::string quoted = toml_string(from), replacement = toml_string(to);
  for (std::size_t at = text.find(quoted); at != std::string::npos; at = text.find(quoted, at + replacement.size())) {
    text.replace(at, quoted.size(), replacement);
  }
}

}  // namespace

DictSceneText toml_text_of_dict(const py::handle& scene) {
  DictConverter converter;
  const toml::table table = converter.table(scene, "", 0);
  std::ostringstream text;
  text << table << "\n";
  return {text.str(), std::move(converter).held_meshes()};
}

PythonScene read_dict_scene(DictSceneText text, const std::filesystem::path& folder, const SceneLoadOptions& options) {
  SceneDesc desc;
  try {
    desc = parse_toml_scene(text.toml, kDictSceneName, folder, options.crease_angle_degrees, options.strict,
                            PathRule{options.allow_outside_paths, {}}.for_folder(folder), &text.held_meshes);
    read_texture_images(desc);
  } catch (const ParseError& error) {
    throw dict_error(error, text.toml);
  }
  PythonScene scene = make_python_scene(std::string(kDictSceneName), std::move(desc));
  scene.toml_text = std::move(text.toml);
  scene.held_meshes = std::move(text.held_meshes);
  scene.base_dir = folder;
  return scene;
}

void write_dict_scene(const PythonScene& scene, const std::filesystem::path& path) {
  if (scene.toml_text.empty()) {
    throw py::value_error("to_toml: only a scene made by quiver.from_dict has a TOML form (" + scene.name + ")");
  }
  if (lowercase_extension(path) != ".toml") throw py::value_error(path.string() + ": expected a .toml file name");
  const std::filesystem::path folder = path.parent_path().empty() ? "." : path.parent_path();
  if (!scene.desc.source_files.empty() && resolved_path(folder) != resolved_path(scene.base_dir)) {
    throw py::value_error(path.string() + ": the scene names files relative to '" + scene.base_dir.string() +
                          "' (its base_dir); write it there, or name its files by absolute paths");
  }
  try {
    check_output_directory(path);
    StagedOutputs outputs;
    std::string text = scene.toml_text;
    for (const auto& [name, bytes] : scene.held_meshes) {
      const std::string file = path.stem().string() + "_" + name;
      replace_string_value(text, name, file);
      outputs.stage_bytes(folder / file, bytes);
    }
    outputs.stage_bytes(path, text);
    outputs.commit();
  } catch (const std::runtime_error& error) {
    PyErr_SetString(PyExc_OSError, error.what());
    throw py::error_already_set();
  }
}

ParseError dict_error(const ParseError& error, std::string_view text) {
  if (error.line() == 0) return error;
  const std::string what = error.what();
  // what() is "file:line:column: message"; keep the message.
  const std::string prefix = error.file() + ":" + std::to_string(error.line()) + ":" + std::to_string(error.column()) + ": ";
  const std::string message = what.starts_with(prefix) ? what.substr(prefix.size()) : what;
  const std::string key = key_at_line(text, error.line());
  return ParseError::whole_file(error.file(), key.empty() ? message : key + ": " + message);
}

}  // namespace quiver
