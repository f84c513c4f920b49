// TOML scene reader: io/toml_prescan.h bounds the text, toml++ parses the
// document (its errors become ParseError at their position), then one
// function per section checks the keys of each table against the keys that
// section allows and reads every value with its type, range and default.
// Positions come from toml++'s source regions, whose columns count code
// points; they are turned into byte columns against the text.
#include "io/toml_reader.h"
#include "io/file_extension.h"

#include <toml++/toml.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <cstdint>
#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <initializer_list>
#include <limits>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <system_error>
#include <unordered_map>
#include <utility>
#include <vector>

#include "geometry/vertex_normals.h"
#include "scene/anti_aliasing.h"
#include "io/nff_reader.h"
#include "io/mesh_append.h"
#include "io/obj_reader.h"
#include "io/parse_error.h"
#include "io/text_file.h"
#include "io/toml_prescan.h"

namespace quiver {

namespace {

namespace fs = std::filesystem;

using KeyList = std::initializer_list<std::string_view>;

// "KIND (KEY in SECTION)": what an error message says was expected.
std::string expected_for(std::string_view kind, std::string_view key, std::string_view section) {
  return joined({kind, " (", key, " in ", section, ")"});
}

std::string list_of(KeyList keys) {
  std::string text;
  for (std::string_view key : keys) {
    if (!text.empty()) text += ", ";
    text += key;
  }
  return text;
}

bool is_continuation_byte(char c) { return (static_cast<unsigned char>(c) & 0xC0) == 0x80; }

// Where a bare TOML word ends.
bool is_toml_delimiter(char c) {
  return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == ',' || c == '[' || c == ']' || c == '{' ||
         c == '}' || c == '=' || c == '#' || static_cast<unsigned char>(c) >= 0x80;
}

// Why the input is bounded, for the bounds' error messages.
constexpr std::string_view kTomlBoundsHint =
    "a TOML scene is for what is written by hand; large geometry belongs in an OBJ file included with "
    "[[meshes]], many spheres in an NFF scene";

// The scene text, for turning toml++ positions into byte positions and
// quoting what stands there. Lines end at '\n' (TOML allows no lone '\r').
class SourceText {
 public:
  explicit SourceText(std::string_view text) : text_(text) {}

  // Offset of the first byte of line `number` (1-based); npos past the end.
  std::size_t line_start(std::size_t number) const {
    std::size_t start = 0;
    for (std::size_t i = 1; i < number; ++i) {
      const std::size_t newline = text_.find('\n', start);
      if (newline == std::string_view::npos) return std::string_view::npos;
      start = newline + 1;
    }
    return start;
  }

  // The line without its line end ("\n" or "\r\n"); empty past the end.
  std::string_view line(std::size_t number) const {
    const std::size_t start = line_start(number);
    if (start == std::string_view::npos) return {};
    const std::size_t end = std::min(text_.find('\n', start), text_.size());
    std::string_view line = text_.substr(start, end - start);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    return line;
  }

  bool is_end(std::size_t number, std::size_t byte_column) const {
    const std::size_t start = line_start(number);
    return start == std::string_view::npos || start + byte_column - 1 >= text_.size();
  }

  // The 1-based byte column of the code-point column `column` on `line`,
  // at most the line's length + 1.
  static std::size_t byte_column(std::string_view line, std::size_t column) {
    std::size_t byte = 0;
    for (std::size_t point = 1; point < column && byte < line.size(); ++point) {
      ++byte;
      while (byte < line.size() && is_continuation_byte(line[byte])) ++byte;
    }
    return byte + 1;
  }

 private:
  std::string_view text_;
};

class TomlSceneReader {
 public:
  TomlSceneReader(std::string_view text, std::string_view file, const fs::path& base_dir,
                  std::optional<double> crease_angle_override, bool strict, const PathRule& paths,
                  const MeshBytes* held_meshes)
      : text_(text),
        source_(text),
        file_(file),
        base_dir_(base_dir),
        crease_angle_override_(crease_angle_override),
        strict_(strict),
        paths_(paths.for_folder(base_dir)),
        held_meshes_(held_meshes) {}

  SceneDesc read() {
    const TomlPrescan prescan = prescan_toml(text_, kMaxTomlNodes);
    if (prescan.misread) {
      fail_at_byte(*prescan.misread,
                   "an ASCII character (outside strings and comments, after a backslash in a string, and "
                   "after a line-ending backslash, toml++ 3.3 misreads others)");
    }
    if (prescan.past_node_bound) {
      fail_at_byte(*prescan.past_node_bound,
                   joined({"at most ", std::to_string(kMaxTomlNodes), " keys, values and tables (", kTomlBoundsHint,
                           ")"}));
    }
    toml::table root;
    try {
      root = toml::parse(text_, file_);
    } catch (const toml::parse_error& error) {
      fail_at_position(error.source().begin, joined({"valid TOML (", error.description(), ")"}), std::nullopt);
    }
    check_keys(root,
               {"background", "ambient", "camera", "render", "lights", "textures", "materials", "spheres", "planes",
                "triangles", "polygons", "cylinders", "cones", "meshes", "instances"},
               "the top level");
    if (const toml::node* node = root.get("background"))
      scene_.background = color(*node, "background", "the top level");
    if (const toml::node* node = root.get("ambient")) scene_.ambient = color(*node, "ambient", "the top level");
    if (const toml::node* node = root.get("camera")) read_camera(table(*node, "camera", "the top level"));
    if (const toml::node* node = root.get("render")) read_render(table(*node, "render", "the top level"));
    for_each_entry(root, "textures", kMaxTomlTextures, [this](const toml::table& t) { read_texture(t); });
    for_each_entry(root, "materials", kMaxTomlMaterials, [this](const toml::table& t) { read_material(t); });
    for_each_entry(root, "lights", kMaxTomlLights, [this](const toml::table& t) { read_light(t); });
    const std::size_t unbounded = std::numeric_limits<std::size_t>::max();
    for_each_entry(root, "spheres", unbounded, [this](const toml::table& t) { read_sphere(t); });
    for_each_entry(root, "planes", unbounded, [this](const toml::table& t) { read_plane(t); });
    for_each_entry(root, "triangles", unbounded, [this](const toml::table& t) { read_triangle(t); });
    for_each_entry(root, "polygons", unbounded, [this](const toml::table& t) { read_polygon(t); });
    for_each_entry(root, "cylinders", unbounded, [this](const toml::table& t) { read_cylinder(t); });
    for_each_entry(root, "cones", unbounded, [this](const toml::table& t) { read_cone(t); });
    for_each_entry(root, "meshes", kMaxTomlMeshes, [this](const toml::table& t) { read_mesh(t); });
    // Bounded by the node limit: each entry is a table with a file.
    for_each_entry(root, "instances", unbounded, [this](const toml::table& t) { read_instance(t); });
    // A scene without objects renders nothing: almost always a mistake.
    if (scene_.spheres.empty() && scene_.planes.empty() && scene_.triangles.empty() && scene_.polygons.empty() &&
        scene_.cones.empty() && scene_.instances.empty()) {
      const TextPosition end = end_of_text(text_);
      throw ParseError(file_, end.line, end.column,
                       "at least one object ([[spheres]], [[planes]], [[triangles]], [[polygons]], [[cylinders]], "
                       "[[cones]], [[meshes]] or [[instances]])",
                       kNoObjectsFound);
    }
    return std::move(scene_);
  }

 private:
  // ---- errors ----

  // Throws at a toml++ position; `end` bounds the quoted text when it is on
  // the same line (otherwise the token at the position is quoted).
  [[noreturn]] void fail_at_position(const toml::source_position& begin, std::string_view expected,
                                     std::optional<toml::source_position> end) const {
    const auto [line_number, column] = byte_position(begin);
    const std::string_view line = source_.line(line_number);
    std::size_t stop = column - 1;
    if (end && end->line == begin.line) {
      stop = SourceText::byte_column(line, end->column) - 1;
    } else {
      while (stop < line.size() && line[stop] != ' ' && line[stop] != '\t') ++stop;
    }
    const std::string_view found = line.substr(column - 1, std::max(stop, column - 1) - (column - 1));
    std::string shown;
    if (!found.empty()) {
      shown = quoted_token(found);
    } else {
      shown = source_.is_end(line_number, column) ? "end of file" : "end of line";
    }
    throw ParseError(file_, line_number, column, expected, shown);
  }

  // The 1-based line and byte column of a toml++ position.
  TextPosition byte_position(const toml::source_position& at) const {
    const std::size_t line_number = std::max<std::size_t>(at.line, 1);
    return {line_number, SourceText::byte_column(source_.line(line_number), std::max<std::size_t>(at.column, 1))};
  }

  // Where the scene text holds node, for errors found once it is read.
  FilePosition named_at(const toml::node& node) const {
    const TextPosition at = byte_position(node.source().begin);
    return {std::string(file_), at.line, at.column};
  }

  // An error found by prescan_toml at a byte offset; the token there is
  // the character (a misread one) or the bare word (a value past the bound).
  [[noreturn]] void fail_at_byte(std::size_t offset, std::string_view expected) const {
    const std::size_t line_start = text_.rfind('\n', offset == 0 ? 0 : offset - 1);
    const std::size_t start = line_start == std::string_view::npos || offset == 0 ? 0 : line_start + 1;
    const auto line =
        static_cast<std::size_t>(std::count(text_.begin(), text_.begin() + static_cast<std::ptrdiff_t>(start), '\n')) +
        1;
    std::size_t end = offset + 1;
    while (end < text_.size() && end - offset < 4 && is_continuation_byte(text_[end])) ++end;
    while (end < text_.size() && !is_toml_delimiter(text_[offset]) && !is_toml_delimiter(text_[end])) ++end;
    throw ParseError(file_, line, offset - start + 1, expected, quoted_token(text_.substr(offset, end - offset)));
  }

  [[noreturn]] void fail(const toml::node& node, std::string_view expected) const {
    fail_at_position(node.source().begin, expected, node.source().end);
  }

  [[noreturn]] void fail_key(const toml::key& key, std::string_view expected) const {
    fail_at_position(key.source().begin, expected, key.source().end);
  }

  // Unknown keys are errors; the first one in the file is reported.
  void check_keys(const toml::table& table, KeyList allowed, std::string_view section) const {
    const toml::key* first = nullptr;
    for (auto&& [key, value] : table) {
      if (std::find(allowed.begin(), allowed.end(), key.str()) != allowed.end()) continue;
      const toml::source_position& at = key.source().begin;
      if (first == nullptr || at.line < first->source().begin.line ||
          (at.line == first->source().begin.line && at.column < first->source().begin.column)) {
        first = &key;
      }
    }
    if (first != nullptr) fail_key(*first, joined({"a key of ", section, " (", list_of(allowed), ")"}));
  }

  const toml::node& required(const toml::table& table, std::string_view key, std::string_view section) const {
    if (const toml::node* node = table.get(key)) return *node;
    fail(table, joined({"a '", key, "' key in ", section}));
  }

  // ---- values ----

  const toml::table& table(const toml::node& node, std::string_view key, std::string_view section) const {
    if (const toml::table* t = node.as_table()) return *t;
    fail(node, expected_for("a table", key, section));
  }

  std::string_view string(const toml::node& node, std::string_view key, std::string_view section) const {
    if (const auto* s = node.as_string()) return s->get();
    fail(node, expected_for("a string", key, section));
  }

  bool boolean(const toml::node& node, std::string_view key, std::string_view section) const {
    if (const auto* b = node.as_boolean()) return b->get();
    fail(node, expected_for("true or false", key, section));
  }

  std::int64_t integer(const toml::node& node, std::string_view key, std::string_view section, std::int64_t min,
                       std::int64_t max) const {
    const auto* i = node.as_integer();
    if (i == nullptr || i->get() < min || i->get() > max) {
      fail(node,
           expected_for(joined({"an integer from ", std::to_string(min), " to ", std::to_string(max)}), key, section));
    }
    return i->get();
  }

  // A finite number within float range (integer or float in the file).
  float number(const toml::node& node, std::string_view key, std::string_view section) const {
    double value = 0.0;
    if (const auto* i = node.as_integer()) {
      value = static_cast<double>(i->get());
    } else if (const auto* f = node.as_floating_point()) {
      value = f->get();
    } else {
      fail(node, expected_for("a number", key, section));
    }
    if (!std::isfinite(value)) fail(node, expected_for("a finite number", key, section));
    if (std::fabs(value) > double(std::numeric_limits<float>::max())) {
      fail(node, expected_for("a number within float range", key, section));
    }
    return static_cast<float>(value);
  }

  float non_negative(const toml::node& node, std::string_view key, std::string_view section) const {
    const float value = number(node, key, section);
    if (value < 0.f) fail(node, expected_for("a number >= 0", key, section));
    return value;
  }

  float positive(const toml::node& node, std::string_view key, std::string_view section) const {
    const float value = number(node, key, section);
    if (!(value > 0.f)) fail(node, expected_for("a number > 0", key, section));
    return value;
  }

  const toml::array& array(const toml::node& node, std::string_view kind, std::string_view key,
                           std::string_view section, std::size_t min, std::size_t max) const {
    const toml::array* a = node.as_array();
    if (a == nullptr || a->size() < min || a->size() > max) fail(node, expected_for(kind, key, section));
    return *a;
  }

  Vec3<float> vec3(const toml::node& node, std::string_view key, std::string_view section) const {
    const toml::array& a = array(node, "an array of 3 numbers", key, section, 3, 3);
    return {number(a[0], key, section), number(a[1], key, section), number(a[2], key, section)};
  }

  Vec3<float> nonzero_vec3(const toml::node& node, std::string_view key, std::string_view section) const {
    const Vec3<float> v = vec3(node, key, section);
    if (v.x == 0.f && v.y == 0.f && v.z == 0.f) fail(node, expected_for("a non-zero vector", key, section));
    return v;
  }

  Vec3<float> color(const toml::node& node, std::string_view key, std::string_view section) const {
    const toml::array& a = array(node, "an array of 3 numbers (r, g, b)", key, section, 3, 3);
    return {non_negative(a[0], key, section), non_negative(a[1], key, section), non_negative(a[2], key, section)};
  }

  std::vector<Vec3<float>> vec3_list(const toml::node& node, std::string_view kind, std::string_view key,
                                     std::string_view section, std::size_t min, std::size_t max) const {
    const toml::array& a = array(node, kind, key, section, min, max);
    std::vector<Vec3<float>> list;
    list.reserve(a.size());
    for (const toml::node& element : a) list.push_back(vec3(element, key, section));
    return list;
  }

  // A word out of `choices` (string), or the error lists them.
  std::string_view choice(const toml::node& node, std::string_view key, std::string_view section,
                          KeyList choices) const {
    const std::string_view word = string(node, key, section);
    if (std::find(choices.begin(), choices.end(), word) == choices.end()) {
      fail(node, expected_for(joined({"one of ", list_of(choices)}), key, section));
    }
    return word;
  }

  // A path in the file, relative to the scene's folder; it must name a file.
  std::string existing_file(const toml::node& node, std::string_view key, std::string_view section,
                            std::string_view kind) const {
    const std::string_view written = string(node, key, section);
    if (written.empty()) fail(node, expected_for(joined({"the path of ", kind}), key, section));
    const fs::path path = (base_dir_ / fs::path(written)).lexically_normal();
    if (!paths_.admits(path)) fail(node, expected_for(paths_.expected(), key, section));
    std::error_code error;
    if (!fs::is_regular_file(path, error)) {
      fail(node, expected_for(joined({"the path of ", kind, " that exists (looked for '", path.string(), "')"}), key,
                              section));
    }
    return path.string();
  }

  // Each table of the array `key` (an array of tables or of inline tables).
  template <class Read>
  void for_each_entry(const toml::table& root, std::string_view key, std::size_t max, Read read) const {
    const toml::node* node = root.get(key);
    if (node == nullptr) return;
    const std::string section = joined({"[[", key, "]]"});
    const toml::array* entries = node->as_array();
    if (entries == nullptr) fail(*node, joined({"an array of tables (", section, ")"}));
    if (entries->size() > max) {
      fail((*entries)[max], joined({"at most ", std::to_string(max), " ", section, " entries"}));
    }
    for (const toml::node& entry : *entries) {
      const toml::table* t = entry.as_table();
      if (t == nullptr) fail(entry, joined({"a table (an entry of ", section, ")"}));
      read(*t);
    }
  }

  // ---- sections ----

  void read_camera(const toml::table& t) {
    constexpr std::string_view s = "[camera]";
    check_keys(t, {"from", "at", "up", "fov", "width", "height"}, s);
    CameraDesc camera{};
    camera.from = vec3(required(t, "from", s), "from", s);
    const toml::node& at = required(t, "at", s);
    camera.at = vec3(at, "at", s);
    if (camera.at.x == camera.from.x && camera.at.y == camera.from.y && camera.at.z == camera.from.z) {
      fail(at, expected_for("a point different from 'from'", "at", s));
    }
    camera.up = {0.f, 1.f, 0.f};
    const toml::node* up = t.get("up");
    if (up != nullptr) camera.up = vec3(*up, "up", s);
    if (parallel_to_view(camera)) {
      if (up != nullptr) fail(*up, expected_for("a vector not parallel to at - from (nor zero)", "up", s));
      fail(t, "an 'up' key in [camera] (the default [0, 1, 0] is parallel to at - from)");
    }
    camera.angle_degrees = 45.f;
    if (const toml::node* fov = t.get("fov")) {
      camera.angle_degrees = number(*fov, "fov", s);
      if (!(camera.angle_degrees > 0.f && camera.angle_degrees < 180.f)) {
        fail(*fov, expected_for("a field of view strictly between 0 and 180 degrees", "fov", s));
      }
    }
    camera.hither = 0.f;
    camera.width = 640;
    camera.height = 480;
    if (const toml::node* w = t.get("width"))
      camera.width = static_cast<int>(integer(*w, "width", s, 1, kMaxImageSide));
    const toml::node* h = t.get("height");
    if (h != nullptr) camera.height = static_cast<int>(integer(*h, "height", s, 1, kMaxImageSide));
    if (std::int64_t{camera.width} * camera.height > kMaxImagePixels) {
      fail(h != nullptr ? *h : required(t, "width", s),
           joined({"at most ", std::to_string(kMaxImagePixels), " pixels (width * height in [camera])"}));
    }
    scene_.camera = camera;
  }

  // True when up has no part perpendicular to the view direction (in double).
  static bool parallel_to_view(const CameraDesc& c) {
    const double dx = double(c.at.x) - c.from.x, dy = double(c.at.y) - c.from.y, dz = double(c.at.z) - c.from.z;
    const double ux = c.up.x, uy = c.up.y, uz = c.up.z;
    return dy * uz - dz * uy == 0.0 && dz * ux - dx * uz == 0.0 && dx * uy - dy * ux == 0.0;
  }

  void read_render(const toml::table& t) {
    constexpr std::string_view s = "[render]";
    check_keys(t, {"aa", "max_depth", "min_weight"}, s);
    if (const toml::node* aa = t.get("aa")) {
      const std::string_view text = string(*aa, "aa", s);
      if (text.empty() || text.size() > 64) fail(*aa, expected_for("a non-empty string of at most 64 bytes", "aa", s));
      try {
        scene_.render.aa = parse_anti_aliasing(text);
      } catch (const std::invalid_argument& error) {
        // "anti-aliasing[ part]: expected ..." without its first word.
        std::string_view why = error.what();
        if (why.starts_with("anti-aliasing")) why.remove_prefix(std::string_view("anti-aliasing").size());
        while (why.starts_with(":") || why.starts_with(" ")) why.remove_prefix(1);
        fail(*aa, expected_for(joined({"an anti-aliasing mode (", why, ")"}), "aa", s));
      }
    }
    if (const toml::node* depth = t.get("max_depth")) {
      scene_.render.max_depth = static_cast<int>(integer(*depth, "max_depth", s, 0, kMaxMaxDepth));
    }
    if (const toml::node* weight = t.get("min_weight")) {
      const float w = number(*weight, "min_weight", s);
      if (!valid_min_weight(w)) fail(*weight, expected_for("a number from 0 to 1", "min_weight", s));
      scene_.render.min_weight = w;
    }
  }

  // A new name for the section's name map (or the error names the clash).
  std::string unique_name(const toml::table& t, std::string_view section,
                          const std::unordered_map<std::string, std::size_t>& names) const {
    const toml::node& node = required(t, "name", section);
    const std::string_view name = string(node, "name", section);
    if (name.empty()) fail(node, expected_for("a non-empty string", "name", section));
    if (names.contains(std::string(name)))
      fail(node, expected_for("a name not used by an earlier entry", "name", section));
    return std::string(name);
  }

  void read_texture(const toml::table& t) {
    constexpr std::string_view s = "[[textures]]";
    const std::string_view type = choice(required(t, "type", s), "type", s, {"checker2d", "checker3d", "image"});
    TextureDesc texture;
    if (type == "image") {
      check_keys(t, {"name", "type", "file", "wrap"}, "an image texture");
      texture.kind = TextureDesc::Kind::image;
      const toml::node& file = required(t, "file", s);
      texture.path = existing_file(file, "file", s, "an image file");
      texture.named_at = named_at(file);
      if (const toml::node* wrap = t.get("wrap")) {
        const std::string_view mode = choice(*wrap, "wrap", s, {"repeat", "clamp", "mirror"});
        texture.wrap = mode == "repeat" ? WrapMode::repeat : mode == "clamp" ? WrapMode::clamp : WrapMode::mirror;
      }
    } else {
      check_keys(t, {"name", "type", "colors", "scale"}, "a checker texture");
      texture.kind = type == "checker2d" ? TextureDesc::Kind::checker2d : TextureDesc::Kind::checker3d;
      if (const toml::node* colors = t.get("colors")) {
        const toml::array& pair = array(*colors, "an array of 2 colours", "colors", s, 2, 2);
        texture.color_a = color(pair[0], "colors", s);
        texture.color_b = color(pair[1], "colors", s);
      }
      if (const toml::node* scale = t.get("scale")) texture.scale = positive(*scale, "scale", s);
    }
    const std::string name = unique_name(t, s, texture_names_);
    texture_names_.emplace(name, scene_.textures.size());
    scene_.textures.push_back(std::move(texture));
  }

  void read_material(const toml::table& t) {
    constexpr std::string_view s = "[[materials]]";
    check_keys(t, {"name", "color", "texture", "ka", "kd", "ks", "shininess", "kr", "kt", "ior", "two_sided", "fresnel"},
               s);
    const std::string name = unique_name(t, s, material_names_);
    MaterialDesc m;
    const toml::node* color_node = t.get("color");
    if (color_node != nullptr) m.color = color(*color_node, "color", s);
    if (const toml::node* texture = t.get("texture")) {
      if (color_node != nullptr) fail(*texture, "either 'color' or 'texture' in a [[materials]] entry, not both");
      const auto found = texture_names_.find(std::string(string(*texture, "texture", s)));
      if (found == texture_names_.end()) fail(*texture, expected_for("the name of a [[textures]] entry", "texture", s));
      m.texture = found->second;
    }
    const std::pair<std::string_view, float*> weights[] = {
        {"ka", &m.ka}, {"kd", &m.kd}, {"ks", &m.ks}, {"shininess", &m.shininess}, {"kr", &m.kr}, {"kt", &m.kt}};
    for (const auto& [key, field] : weights) {
      if (const toml::node* node = t.get(key)) *field = non_negative(*node, key, s);
    }
    if (const toml::node* ior = t.get("ior")) m.ior = positive(*ior, "ior", s);
    if (const toml::node* two_sided = t.get("two_sided")) m.two_sided = boolean(*two_sided, "two_sided", s);
    if (const toml::node* fresnel = t.get("fresnel")) m.fresnel = boolean(*fresnel, "fresnel", s);
    material_names_.emplace(name, scene_.materials.size());
    scene_.materials.push_back(m);
  }

  // A spot's cone half-angles in degrees: inner_angle (default 0, full
  // light within) below outer_angle (default 45, no light beyond), at most 90.
  void set_spot_cone(const toml::table& t, LightDesc& light) const {
    constexpr std::string_view s = "[[lights]]";
    double inner = 0.0, outer = 45.0;
    const toml::node* inner_node = t.get("inner_angle");
    const toml::node* outer_node = t.get("outer_angle");
    if (outer_node) {
      outer = number(*outer_node, "outer_angle", s);
      if (!(outer > 0.0 && outer <= 90.0)) fail(*outer_node, expected_for("an angle in (0, 90] degrees", "outer_angle", s));
    }
    if (inner_node) {
      inner = number(*inner_node, "inner_angle", s);
      if (!(inner >= 0.0 && inner < outer)) {
        fail(*inner_node, expected_for("an angle of at least 0 degrees, below outer_angle", "inner_angle", s));
      }
    }
    light.cone_inner_cos = float(std::cos(inner * std::numbers::pi / 180.0));
    light.cone_outer_cos = float(std::cos(outer * std::numbers::pi / 180.0));
  }

  void read_light(const toml::table& t) {
    constexpr std::string_view s = "[[lights]]";
    std::string_view type = "point";
    if (const toml::node* node = t.get("type")) {
      type = choice(*node, "type", s, {"point", "directional", "rectangle", "sphere", "spot"});
    }
    LightDesc light;
    if (type == "point") {
      check_keys(t, {"type", "position", "color", "intensity"}, "a point light");
      light.kind = LightDesc::Kind::point;
      light.position = vec3(required(t, "position", s), "position", s);
    } else if (type == "directional") {
      check_keys(t, {"type", "direction", "color", "intensity"}, "a directional light");
      light.kind = LightDesc::Kind::directional;
      light.direction = nonzero_vec3(required(t, "direction", s), "direction", s);
    } else if (type == "spot") {
      check_keys(t, {"type", "position", "direction", "inner_angle", "outer_angle", "color", "intensity"},
                 "a spot light");
      light.kind = LightDesc::Kind::spot;
      light.position = vec3(required(t, "position", s), "position", s);
      light.direction = nonzero_vec3(required(t, "direction", s), "direction", s);
      set_spot_cone(t, light);
    } else if (type == "rectangle") {
      check_keys(t, {"type", "corner", "edge_u", "edge_v", "color", "intensity", "samples"}, "a rectangle light");
      light.kind = LightDesc::Kind::rectangle;
      light.position = vec3(required(t, "corner", s), "corner", s);
      light.edge_u = nonzero_vec3(required(t, "edge_u", s), "edge_u", s);
      const toml::node& edge_v = required(t, "edge_v", s);
      light.edge_v = nonzero_vec3(edge_v, "edge_v", s);
      const Vec3<float>& u = light.edge_u;
      const Vec3<float>& v = light.edge_v;
      const double cx = double(u.y) * v.z - double(u.z) * v.y, cy = double(u.z) * v.x - double(u.x) * v.z,
                   cz = double(u.x) * v.y - double(u.y) * v.x;
      if (cx == 0.0 && cy == 0.0 && cz == 0.0)
        fail(edge_v, expected_for("an edge not parallel to edge_u", "edge_v", s));
    } else {
      check_keys(t, {"type", "center", "radius", "color", "intensity", "samples"}, "a sphere light");
      light.kind = LightDesc::Kind::sphere;
      light.position = vec3(required(t, "center", s), "center", s);
      light.radius = positive(required(t, "radius", s), "radius", s);
    }
    if (const toml::node* node = t.get("color")) light.color = color(*node, "color", s);
    if (const toml::node* node = t.get("intensity")) {
      const float intensity = non_negative(*node, "intensity", s);
      light.color = light.color * intensity;
      if (!std::isfinite(light.color.x) || !std::isfinite(light.color.y) || !std::isfinite(light.color.z)) {
        fail(*node, expected_for("an intensity that keeps color * intensity within float range", "intensity", s));
      }
    }
    if (const toml::node* node = t.get("samples")) {
      light.samples = static_cast<int>(integer(*node, "samples", s, 1, kMaxLightSamples));
    }
    scene_.lights.push_back(light);
  }

  // The entry's `material` (a [[materials]] name), or the default material.
  std::size_t material_of(const toml::table& t, std::string_view section) {
    const toml::node* node = t.get("material");
    if (node == nullptr) return default_material();
    const auto found = material_names_.find(std::string(string(*node, "material", section)));
    if (found == material_names_.end())
      fail(*node, expected_for("the name of a [[materials]] entry", "material", section));
    return found->second;
  }

  std::size_t default_material() {
    if (!default_material_) {
      default_material_ = scene_.materials.size();
      scene_.materials.push_back(MaterialDesc{});
    }
    return *default_material_;
  }

  void read_sphere(const toml::table& t) {
    constexpr std::string_view s = "[[spheres]]";
    check_keys(t, {"center", "radius", "material"}, s);
    SceneSphere sphere{};
    sphere.sphere.center = vec3(required(t, "center", s), "center", s);
    sphere.sphere.radius = positive(required(t, "radius", s), "radius", s);
    sphere.material = material_of(t, s);
    scene_.spheres.push_back(sphere);
  }

  void read_plane(const toml::table& t) {
    constexpr std::string_view s = "[[planes]]";
    check_keys(t, {"point", "normal", "material"}, s);
    ScenePlane plane{};
    plane.plane.point = vec3(required(t, "point", s), "point", s);
    plane.plane.normal = nonzero_vec3(required(t, "normal", s), "normal", s);
    plane.material = material_of(t, s);
    scene_.planes.push_back(plane);
  }

  void read_triangle(const toml::table& t) {
    constexpr std::string_view s = "[[triangles]]";
    check_keys(t, {"vertices", "normals", "uvs", "material"}, s);
    SceneTriangle triangle{};
    const std::vector<Vec3<float>> vertices =
        vec3_list(required(t, "vertices", s), "an array of 3 points", "vertices", s, 3, 3);
    std::copy(vertices.begin(), vertices.end(), triangle.triangle.p.begin());
    if (const toml::node* node = t.get("normals")) {
      const std::vector<Vec3<float>> normals = vec3_list(*node, "an array of 3 vectors", "normals", s, 3, 3);
      triangle.triangle.normals.emplace();
      std::copy(normals.begin(), normals.end(), triangle.triangle.normals->begin());
    }
    if (const toml::node* node = t.get("uvs")) {
      const toml::array& uvs = array(*node, "an array of 3 [u, v] pairs", "uvs", s, 3, 3);
      triangle.triangle.uvs.emplace();
      for (std::size_t i = 0; i < 3; ++i) {
        const toml::array& uv = array(uvs[i], "an array of 2 numbers [u, v]", "uvs", s, 2, 2);
        (*triangle.triangle.uvs)[i] = {number(uv[0], "uvs", s), number(uv[1], "uvs", s)};
      }
    }
    triangle.material = material_of(t, s);
    scene_.triangles.push_back(triangle);
  }

  void read_polygon(const toml::table& t) {
    constexpr std::string_view s = "[[polygons]]";
    check_keys(t, {"vertices", "normals", "material"}, s);
    ScenePolygon polygon{};
    const std::string kind = joined({"an array of 3 to ", std::to_string(kMaxPolygonVertices), " points"});
    polygon.polygon.vertices = vec3_list(required(t, "vertices", s), kind, "vertices", s, 3, kMaxPolygonVertices);
    if (const toml::node* node = t.get("normals")) {
      const std::size_t n = polygon.polygon.vertices.size();
      polygon.normals = vec3_list(*node, joined({"an array of ", std::to_string(n), " vectors (one per vertex)"}),
                                  "normals", s, n, n);
    }
    polygon.material = material_of(t, s);
    scene_.polygons.push_back(std::move(polygon));
  }

  // The apex node must differ from the base point.
  Vec3<float> apex(const toml::table& t, const Vec3<float>& base, std::string_view s) const {
    const toml::node& node = required(t, "apex", s);
    const Vec3<float> apex = vec3(node, "apex", s);
    if (apex.x == base.x && apex.y == base.y && apex.z == base.z) {
      fail(node, expected_for("a point different from 'base'", "apex", s));
    }
    return apex;
  }

  void read_cylinder(const toml::table& t) {
    constexpr std::string_view s = "[[cylinders]]";
    check_keys(t, {"base", "apex", "radius", "material"}, s);
    SceneCone cone{};
    cone.cone.base = vec3(required(t, "base", s), "base", s);
    cone.cone.apex = apex(t, cone.cone.base, s);
    cone.cone.base_radius = cone.cone.apex_radius = positive(required(t, "radius", s), "radius", s);
    cone.material = material_of(t, s);
    scene_.cones.push_back(cone);
  }

  void read_cone(const toml::table& t) {
    constexpr std::string_view s = "[[cones]]";
    check_keys(t, {"base", "apex", "base_radius", "apex_radius", "material"}, s);
    SceneCone cone{};
    cone.cone.base = vec3(required(t, "base", s), "base", s);
    cone.cone.apex = apex(t, cone.cone.base, s);
    cone.cone.base_radius = non_negative(required(t, "base_radius", s), "base_radius", s);
    const toml::node& apex_radius = required(t, "apex_radius", s);
    cone.cone.apex_radius = non_negative(apex_radius, "apex_radius", s);
    if (cone.cone.base_radius == 0.f && cone.cone.apex_radius == 0.f) {
      fail(apex_radius, expected_for("a radius > 0 (the base radius is 0 too)", "apex_radius", s));
    }
    cone.material = material_of(t, s);
    scene_.cones.push_back(cone);
  }

  // rotate = [x, y, z] degrees (about the world x, then y, then z axes) or
  // rotate = { axis = [x, y, z], angle = degrees }.
  glm::dmat4 rotation(const toml::node& node, std::string_view s) const {
    const glm::dmat4 identity(1.0);
    if (const toml::table* t = node.as_table()) {
      check_keys(*t, {"axis", "angle"}, "a mesh rotation");
      const Vec3<float> axis = nonzero_vec3(required(*t, "axis", "a mesh rotation"), "axis", "rotate");
      const float angle = number(required(*t, "angle", "a mesh rotation"), "angle", "rotate");
      return glm::rotate(identity, glm::radians(double(angle)), glm::dvec3(axis.x, axis.y, axis.z));
    }
    if (!node.is_array())
      fail(node, expected_for("[x, y, z] degrees or { axis = [x, y, z], angle = degrees }", "rotate", s));
    const Vec3<float> degrees = vec3(node, "rotate", s);
    const glm::dmat4 rx = glm::rotate(identity, glm::radians(double(degrees.x)), glm::dvec3(1, 0, 0));
    const glm::dmat4 ry = glm::rotate(identity, glm::radians(double(degrees.y)), glm::dvec3(0, 1, 0));
    const glm::dmat4 rz = glm::rotate(identity, glm::radians(double(degrees.z)), glm::dvec3(0, 0, 1));
    return rz * ry * rx;
  }

  // What a [[meshes]] or [[instances]] entry says of its mesh: the file,
  // the material override and the crease angle.
  struct MeshSource {
    std::string path;
    const std::string* bytes = nullptr;  // a held mesh's (MeshBytes), else read from path
    std::optional<std::size_t> material;
    double crease_angle = kDefaultCreaseAngleDegrees;
  };

  // The file name a mesh's `file` key gives and, when held_meshes holds it, its bytes (else null).
  std::pair<std::string_view, const std::string*> held_mesh(const toml::node& file_node) const {
    const std::optional<std::string_view> written = file_node.value<std::string_view>();
    if (held_meshes_ == nullptr || !written) return {};
    const auto held = held_meshes_->find(*written);
    return {*written, held == held_meshes_->end() ? nullptr : &held->second};
  }

  MeshSource mesh_source(const toml::table& t, std::string_view s) {
    MeshSource m;
    const toml::node& file_node = required(t, "file", s);
    if (const auto [written, bytes] = held_mesh(file_node); bytes != nullptr) {
      m.path = (base_dir_ / fs::path(written)).lexically_normal().string();
      m.bytes = bytes;
      const std::string extension = lowercase_extension(m.path);
      if (extension != ".ply" && extension != ".stl") fail(file_node, expected_for("a .ply or .stl", "file", s));
    } else {
      m.path = existing_file(file_node, "file", s, "a mesh file");
    }
    if (!is_mesh_extension(lowercase_extension(m.path))) {
      fail(file_node, expected_for("a mesh file (.obj, .ply, .gltf, .glb or .stl)", "file", s));
    }
    if (t.contains("material")) m.material = material_of(t, s);
    if (const toml::node* node = t.get("crease_angle")) {
      m.crease_angle = number(*node, "crease_angle", s);
      if (!valid_crease_angle(m.crease_angle)) {
        fail(*node, expected_for("an angle from 0 to 180 degrees", "crease_angle", s));
      }
    }
    if (crease_angle_override_) m.crease_angle = *crease_angle_override_;
    return m;
  }

  // An entry's placement, world = translate + rotate * (scale * p), as a
  // column-major 4x4 matrix in float.
  std::array<float, 16> placement(const toml::table& t, std::string_view s) const {
    glm::dvec3 scale(1.0);
    if (const toml::node* node = t.get("scale")) {
      if (node->is_array()) {
        const Vec3<float> v = vec3(*node, "scale", s);
        scale = {v.x, v.y, v.z};
      } else {
        scale = glm::dvec3(number(*node, "scale", s));
      }
      if (scale.x == 0.0 || scale.y == 0.0 || scale.z == 0.0) fail(*node, expected_for("a non-zero scale", "scale", s));
    }
    glm::dmat4 rotate(1.0);
    if (const toml::node* node = t.get("rotate")) rotate = rotation(*node, s);
    glm::dvec3 translate(0.0);
    if (const toml::node* node = t.get("translate")) {
      const Vec3<float> v = vec3(*node, "translate", s);
      translate = {v.x, v.y, v.z};
    }
    const glm::dmat4 m = glm::translate(glm::dmat4(1.0), translate) * rotate * glm::scale(glm::dmat4(1.0), scale);
    std::array<float, 16> columns{};
    for (int c = 0; c < 4; ++c) {
      for (int r = 0; r < 4; ++r) columns[static_cast<std::size_t>(4 * c + r)] = static_cast<float>(m[c][r]);
    }
    return columns;
  }

  // Appends the mesh of `source` to the scene under `columns` (the file
  // named at t's "file").
  void append_mesh_of(const toml::table& t, const MeshSource& source, const std::array<float, 16>& columns,
                      std::string_view s) {
    try {
      if (source.bytes) {
        append_mesh_bytes(*source.bytes, source.path, columns, source.material, scene_, source.crease_angle, strict_);
      } else {
        append_mesh(source.path, columns, source.material, scene_, source.crease_angle, strict_, paths_);
      }
    } catch (const std::invalid_argument&) {
      fail(t, joined({"a ", s, " transform that is not singular once rounded to float"}));
    } catch (const ParseError& error) {
      throw ParseError::in_named_file(named_at(*t.get("file")), "mesh", error);
    }
  }

  void read_mesh(const toml::table& t) {
    constexpr std::string_view s = "[[meshes]]";
    check_keys(t, {"file", "material", "translate", "rotate", "scale", "crease_angle"}, s);
    const MeshSource source = mesh_source(t, s);
    append_mesh_of(t, source, placement(t, s), s);
  }

  // An [[instances]] entry: its mesh is read once per file, material and
  // crease angle (SceneDesc::meshes), and placed by the entry's transform.
  void read_instance(const toml::table& t) {
    constexpr std::string_view s = "[[instances]]";
    check_keys(t, {"file", "material", "translate", "rotate", "scale", "crease_angle"}, s);
    const MeshSource source = mesh_source(t, s);
    const std::array<float, 16> columns = placement(t, s);
    AffineTransform object_to_world;
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 4; ++c) {
        object_to_world.m[static_cast<std::size_t>(4 * r + c)] = columns[static_cast<std::size_t>(4 * c + r)];
      }
    }
    if (!inverse(object_to_world)) fail(t, joined({"a ", s, " transform that is not singular once rounded to float"}));
    std::error_code ignored;
    const fs::path canonical = fs::weakly_canonical(source.path, ignored);
    const std::string key = joined({canonical.string(), "\n", source.material ? std::to_string(*source.material) : "-",
                                    "\n", std::to_string(source.crease_angle)});
    auto [it, added] = instanced_meshes_.try_emplace(key, scene_.meshes.size());
    if (added) {
      const std::array<float, 16> identity{1.f, 0.f, 0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 0.f, 0.f, 1.f};
      const std::size_t before = scene_.triangles.size();
      append_mesh_of(t, source, identity, s);
      std::string name = source.path;
      if (const toml::node* material = t.get("material")) name += " with material " + material->value_or(std::string());
      if (source.crease_angle != kDefaultCreaseAngleDegrees) {
        std::ostringstream angle;
        angle << source.crease_angle;
        name += ", crease angle " + angle.str();
      }
      SceneMesh mesh{std::move(name), {}};
      mesh.triangles.assign(std::make_move_iterator(scene_.triangles.begin() + std::ptrdiff_t(before)),
                            std::make_move_iterator(scene_.triangles.end()));
      scene_.triangles.resize(before);
      scene_.meshes.push_back(std::move(mesh));
    }
    scene_.instances.push_back({it->second, object_to_world});
  }

  std::string_view text_;
  SourceText source_;
  std::string_view file_;
  fs::path base_dir_;
  std::optional<double> crease_angle_override_;
  bool strict_;  // the included meshes' readers (obj_reader.h)
  PathRule paths_;
  const MeshBytes* held_meshes_;
  SceneDesc scene_;
  std::unordered_map<std::string, std::size_t> texture_names_;
  std::unordered_map<std::string, std::size_t> material_names_;
  // [[instances]] meshes read so far: file, material and crease angle to SceneDesc::meshes index.
  std::unordered_map<std::string, std::size_t> instanced_meshes_;
  std::optional<std::size_t> default_material_;
};

}  // namespace

SceneDesc parse_toml_scene(std::string_view text, std::string_view file_name, const fs::path& base_dir,
                           std::optional<double> crease_angle_override, bool strict, const PathRule& paths,
                           const MeshBytes* held_meshes) {
  if (crease_angle_override && !valid_crease_angle(*crease_angle_override)) {
    throw std::invalid_argument("TOML reader: the crease angle is not in [0, 180] degrees");
  }
  if (text.size() > kMaxTomlBytes) {
    throw ParseError::whole_file(file_name, joined({"larger than the TOML limit of ", std::to_string(kMaxTomlBytes),
                                                    " bytes (", kTomlBoundsHint, ")"}));
  }
  return TomlSceneReader(text, file_name, base_dir, crease_angle_override, strict, paths, held_meshes).read();
}

SceneDesc read_toml_scene(const fs::path& path, std::optional<double> crease_angle_override, bool strict,
                          const PathRule& paths) {
  const FileBytes text = read_text_file(path, kMaxTomlBytes, "a TOML scene", kTomlBoundsHint);
  return parse_toml_scene(text, path.string(), path.parent_path(), crease_angle_override, strict, paths);
}

}  // namespace quiver
