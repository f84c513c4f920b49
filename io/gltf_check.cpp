#include "io/gltf_check.h"

#include <algorithm>
#include <array>
#include <limits>
#include <nlohmann/json.hpp>
#include <optional>
#include <system_error>
#include <utility>

#include "io/parse_error.h"
#include "io/uri_path.h"

namespace quiver {

namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

constexpr std::uint64_t kSaturated = std::numeric_limits<std::uint64_t>::max();
// Bytes of zero-filled accessors allowed beyond the buffers' bytes.
constexpr std::uint64_t kZeroAccessorAllowance = std::uint64_t{1} << 20;

std::uint64_t saturating_add(std::uint64_t a, std::uint64_t b) {
  std::uint64_t sum = 0;
  return __builtin_add_overflow(a, b, &sum) ? kSaturated : sum;
}

std::uint64_t saturating_mul(std::uint64_t a, std::uint64_t b) {
  std::uint64_t product = 0;
  return __builtin_mul_overflow(a, b, &product) ? kSaturated : product;
}

// A JSON value as messages show it, cut after 40 characters.
std::string shown(const json& value) {
  if (value.is_null()) return "none";
  std::string text = value.dump();
  return text.size() > 40 ? text.substr(0, 40) + "..." : text;
}

std::string shown_size(std::uint64_t bytes) {
  return bytes == kSaturated ? std::string("beyond 2^64") : std::to_string(bytes);
}

// Extensions whose data Assimp would read without quiver's bounds: Draco
// and meshopt decode compressed bufferViews of their own sizes, mesh
// quantization lets positions and normals be integers that Assimp 5.2
// copies into floats byte for byte, KHR_binary_glTF is glTF 1.0's binary container.
constexpr std::array<std::string_view, 5> kUnreadExtensions = {"KHR_draco_mesh_compression", "EXT_meshopt_compression",
                                                               "KHR_meshopt_compression", "KHR_mesh_quantization",
                                                               "KHR_binary_glTF"};

struct ComponentType {
  std::uint64_t code, bytes;
};
constexpr std::array<ComponentType, 6> kComponentTypes = {
    {{5120, 1}, {5121, 1}, {5122, 2}, {5123, 2}, {5125, 4}, {5126, 4}}};
constexpr std::uint64_t kFloat = 5126;

struct ElementType {
  std::string_view name;
  std::uint64_t rows, columns;
};
constexpr std::array<ElementType, 7> kElementTypes = {
    {{"SCALAR", 1, 1}, {"VEC2", 2, 1}, {"VEC3", 3, 1}, {"VEC4", 4, 1}, {"MAT2", 2, 2}, {"MAT3", 3, 3}, {"MAT4", 4, 4}}};

// A glTF array (2.0) or object keyed by id (1.0) of objects.
struct Collection {
  std::string name;
  std::vector<const json*> items;
  std::vector<std::string> ids;  // glTF 1.0's keys, in the order of items; empty for an array

  std::string path(std::size_t i) const {
    return ids.empty() ? name + "[" + std::to_string(i) + "]" : name + "." + ids[i];
  }
};

struct Accessor {
  std::uint64_t count = 0, components = 0, component_type = 0;
  std::string_view type;
};

class ContentsCheck {
 public:
  ContentsCheck(const json& document, std::string_view file, const fs::path& directory, const PathRule& paths,
                std::size_t budget)
      : document_(document), file_(file), directory_(directory), paths_(paths), budget_(budget) {}

  GltfContents run() {
    refuse_extension_names(document_, "extensionsRequired");
    refuse_extension_names(document_, "extensionsUsed");
    buffers_ = collection("buffers");
    views_ = collection("bufferViews");
    accessors_ = collection("accessors");
    meshes_ = collection("meshes");
    nodes_ = collection("nodes");
    images_ = collection("images");
    check_buffer_views();
    for (std::size_t i = 0; i < accessors_.items.size(); ++i) check_accessor(i);
    check_zero_accessors();
    for (std::size_t i = 0; i < meshes_.items.size(); ++i) check_mesh(i);
    check_images_and_textures();
    check_skins_and_animations();
    if (decoded_bytes_ > kMaxGltfDecodedBytes) {
      fail(joined({"expected the accessors' data, as decoded once per use, to take at most ",
                   std::to_string(kMaxGltfDecodedBytes), " bytes, found ", shown_size(decoded_bytes_)}));
    }
    check_node_graph();
    return std::move(contents_);
  }

 private:
  [[noreturn]] void fail(std::string_view message) const { throw ParseError::whole_file(file_, message); }

  Collection collection(const char* name) const {
    Collection result{name, {}, {}};
    const auto found = document_.find(name);
    if (found == document_.end()) return result;
    if (!found->is_array() && !found->is_object()) {
      fail(joined({"expected \"", name, "\" to be an array (or, in glTF 1.0, an object), found ", shown(*found)}));
    }
    for (auto entry = found->begin(); entry != found->end(); ++entry) {
      if (found->is_object()) result.ids.push_back(entry.key());
      result.items.push_back(&*entry);
      if (!entry->is_object()) {
        fail(joined({"expected ", result.path(result.items.size() - 1), " to be an object, found ", shown(*entry)}));
      }
    }
    return result;
  }

  // object[key] as a whole number; `fallback` when absent (required without one).
  std::uint64_t whole(const json& object, const char* key, const std::string& path,
                      std::optional<std::uint64_t> fallback = std::nullopt) const {
    const auto found = object.find(key);
    if (found == object.end()) {
      if (fallback) return *fallback;
      fail(joined({"expected ", path, ".", key, ", a whole number, found none"}));
    }
    if (!found->is_number_unsigned()) {
      fail(joined({"expected ", path, ".", key, " to be a whole number below 2^64, found ", shown(*found)}));
    }
    return found->get<std::uint64_t>();
  }

  // The item of `target` that `value` (at `path`) refers to: an index (glTF 2.0) or an id (1.0).
  std::size_t reference(const json& value, const Collection& target, const std::string& path) const {
    if (target.ids.empty()) {
      if (value.is_number_unsigned() && value.get<std::uint64_t>() < target.items.size()) {
        return static_cast<std::size_t>(value.get<std::uint64_t>());
      }
      fail(joined({"expected ", path, " to be an index below ", std::to_string(target.items.size()), " (the ",
                   target.name, "), found ", shown(value)}));
    }
    if (value.is_string()) {
      const auto at = std::find(target.ids.begin(), target.ids.end(), value.get<std::string>());
      if (at != target.ids.end()) return static_cast<std::size_t>(at - target.ids.begin());
    }
    fail(joined({"expected ", path, " to be the id of one of the ", target.name, ", found ", shown(value)}));
  }

  std::optional<std::size_t> optional_reference(const json& object, const char* key, const Collection& target,
                                                const std::string& path) const {
    const auto found = object.find(key);
    if (found == object.end()) return std::nullopt;
    return reference(*found, target, path + "." + key);
  }

  // Every reference of object[key], an array of them (absent: none).
  std::vector<std::size_t> references(const json& object, const char* key, const Collection& target,
                                      const std::string& path) const {
    std::vector<std::size_t> result;
    const auto found = object.find(key);
    if (found == object.end()) return result;
    if (!found->is_array()) fail(joined({"expected ", path, ".", key, " to be an array, found ", shown(*found)}));
    for (std::size_t i = 0; i < found->size(); ++i) {
      result.push_back(reference((*found)[i], target, path + "." + key + "[" + std::to_string(i) + "]"));
    }
    return result;
  }

  // An array of extension names, or an object keyed by them.
  void refuse_extension_names(const json& owner, const char* key) const {
    const auto found = owner.find(key);
    if (found == owner.end()) return;
    const auto refuse = [&](const std::string& name) {
      if (std::find(kUnreadExtensions.begin(), kUnreadExtensions.end(), name) != kUnreadExtensions.end()) {
        fail(joined({"uses ", name, ", which quiver does not read"}));
      }
    };
    if (found->is_object()) {
      for (auto entry = found->begin(); entry != found->end(); ++entry) refuse(entry.key());
    } else if (found->is_array()) {
      for (const json& name : *found) {
        if (name.is_string()) refuse(name.get<std::string>());
      }
    }
  }

  void check_buffer_views() {
    for (std::size_t i = 0; i < buffers_.items.size(); ++i) {
      buffer_bytes_.push_back(whole(*buffers_.items[i], "byteLength", buffers_.path(i)));
    }
    for (std::size_t i = 0; i < views_.items.size(); ++i) {
      const json& view = *views_.items[i];
      const std::string path = views_.path(i);
      refuse_extension_names(view, "extensions");
      const std::size_t buffer =
          reference(view.contains("buffer") ? view["buffer"] : json(), buffers_, path + ".buffer");
      const std::uint64_t available = buffer_bytes_[buffer];
      const std::uint64_t offset = whole(view, "byteOffset", path, 0);
      const std::uint64_t length = whole(view, "byteLength", path);
      if (offset > available) {
        fail(joined({"expected ", path, ".byteOffset to be at most the ", std::to_string(available), " bytes of ",
                     buffers_.path(buffer), ", found ", std::to_string(offset)}));
      }
      if (length > available - offset) {
        fail(joined({"expected ", path, ".byteLength to be at most the ", std::to_string(available - offset),
                     " bytes of ", buffers_.path(buffer), " after its byteOffset ", std::to_string(offset), ", found ",
                     std::to_string(length)}));
      }
      const std::uint64_t stride = whole(view, "byteStride", path, 0);
      if (view.contains("byteStride") && (stride < 4 || stride > 252 || stride % 4 != 0)) {
        fail(joined(
            {"expected ", path, ".byteStride to be a multiple of 4 from 4 to 252, found ", std::to_string(stride)}));
      }
      view_bytes_.push_back(length);
      view_stride_.push_back(stride);
    }
  }

  // Bytes of one element: a matrix's columns each start at a multiple of 4.
  static std::uint64_t element_bytes(const ElementType& type, std::uint64_t component_bytes) {
    if (type.columns == 1) return type.rows * component_bytes;
    return type.columns * ((type.rows * component_bytes + 3) / 4 * 4);
  }

  void check_accessor(std::size_t i) {
    const json& a = *accessors_.items[i];
    const std::string path = accessors_.path(i);
    const std::uint64_t code = whole(a, "componentType", path);
    const auto component = std::find_if(kComponentTypes.begin(), kComponentTypes.end(),
                                        [&](const ComponentType& c) { return c.code == code; });
    if (component == kComponentTypes.end()) {
      fail(joined({"expected ", path, ".componentType to be 5120, 5121, 5122, 5123, 5125 or 5126, found ",
                   std::to_string(code)}));
    }
    const auto type_value = a.find("type");
    const auto type = std::find_if(kElementTypes.begin(), kElementTypes.end(), [&](const ElementType& t) {
      return type_value != a.end() && type_value->is_string() && type_value->get<std::string>() == t.name;
    });
    if (type == kElementTypes.end()) {
      fail(joined({"expected ", path, ".type to be SCALAR, VEC2, VEC3, VEC4, MAT2, MAT3 or MAT4, found ",
                   type_value == a.end() ? std::string("none") : shown(*type_value)}));
    }
    const std::uint64_t count = whole(a, "count", path);
    if (count < 1 || count > kMaxGltfAccessorCount) {
      fail(joined({"expected ", path, ".count to be from 1 to ", std::to_string(kMaxGltfAccessorCount), ", found ",
                   std::to_string(count)}));
    }
    const std::uint64_t element = element_bytes(*type, component->bytes);
    if (const std::optional<std::size_t> view = optional_reference(a, "bufferView", views_, path)) {
      // glTF 2.0 strides in the bufferView, 1.0 in the accessor; 0: packed.
      std::uint64_t stride = std::max(view_stride_[*view], whole(a, "byteStride", path, 0));
      if (stride == 0) stride = element;
      check_span(path, whole(a, "byteOffset", path, 0), count, stride, element, *view);
    } else {
      zero_bytes_ = saturating_add(zero_bytes_, saturating_mul(count, element));
    }
    if (const auto sparse = a.find("sparse"); sparse != a.end())
      check_sparse(*sparse, path + ".sparse", count, element);
    accessor_info_.push_back({count, type->rows * type->columns, code, type->name});
  }

  // Accessors without a bufferView are zeros (a sparse part may patch
  // them): as many bytes of them as the buffers hold, plus
  // kZeroAccessorAllowance, so that a small file cannot make large ones.
  void check_zero_accessors() const {
    std::uint64_t backed = kZeroAccessorAllowance;
    for (std::uint64_t bytes : buffer_bytes_) backed = saturating_add(backed, bytes);
    if (zero_bytes_ > backed) {
      fail(joined({"expected the accessors without a bufferView to take at most ", std::to_string(backed),
                   " bytes (the buffers' bytes and 1 MiB), found ", shown_size(zero_bytes_)}));
    }
  }

  // count elements of `element` bytes, `stride` apart, from `offset` of bufferView `view` lie within it.
  void check_span(const std::string& path, std::uint64_t offset, std::uint64_t count, std::uint64_t stride,
                  std::uint64_t element, std::size_t view) const {
    const std::uint64_t available = view_bytes_[view];
    if (offset > available) {
      fail(joined({"expected ", path, ".byteOffset to be at most the ", std::to_string(available), " bytes of ",
                   views_.path(view), ", found ", std::to_string(offset)}));
    }
    const std::uint64_t end = saturating_add(saturating_add(offset, saturating_mul(count - 1, stride)), element);
    if (end > available) {
      fail(joined({"expected ", path, "'s ", std::to_string(count), " elements (", std::to_string(element), " bytes, ",
                   std::to_string(stride), " apart, from byteOffset ", std::to_string(offset), ") within the ",
                   std::to_string(available), " bytes of ", views_.path(view), ", found them ending at byte ",
                   shown_size(end)}));
    }
  }

  void check_sparse(const json& sparse, const std::string& path, std::uint64_t accessor_count,
                    std::uint64_t element) const {
    if (!sparse.is_object()) fail(joined({"expected ", path, " to be an object, found ", shown(sparse)}));
    const std::uint64_t count = whole(sparse, "count", path);
    if (count < 1 || count > accessor_count) {
      fail(joined({"expected ", path, ".count to be from 1 to the accessor's count ", std::to_string(accessor_count),
                   ", found ", std::to_string(count)}));
    }
    for (const char* part : {"indices", "values"}) {
      const std::string part_path = path + "." + part;
      const auto found = sparse.find(part);
      if (found == sparse.end() || !found->is_object()) {
        fail(joined({"expected ", part_path, " to be an object, found ",
                     found == sparse.end() ? std::string("none") : shown(*found)}));
      }
      std::uint64_t bytes = element;
      if (part == std::string_view("indices")) {
        const std::uint64_t code = whole(*found, "componentType", part_path);
        if (code != 5121 && code != 5123 && code != 5125) {
          fail(joined(
              {"expected ", part_path, ".componentType to be 5121, 5123 or 5125, found ", std::to_string(code)}));
        }
        bytes = code == 5121 ? 1 : code == 5123 ? 2 : 4;
      }
      const json& view_value = found->contains("bufferView") ? (*found)["bufferView"] : json();
      const std::size_t view = reference(view_value, views_, part_path + ".bufferView");
      check_span(part_path, whole(*found, "byteOffset", part_path, 0), count, bytes, bytes, view);
    }
  }

  // Counts accessor `index`'s data as Assimp decodes it (4 bytes a component).
  const Accessor& use_accessor(std::size_t index) {
    const Accessor& a = accessor_info_[index];
    decoded_bytes_ = saturating_add(decoded_bytes_, saturating_mul(a.count, 4 * a.components));
    return a;
  }

  // Each attribute of an attributes object (a primitive's or a morph target's).
  void use_attributes(const json& attributes, const std::string& path, std::uint64_t* positions) {
    if (!attributes.is_object()) fail(joined({"expected ", path, " to be an object, found ", shown(attributes)}));
    for (auto entry = attributes.begin(); entry != attributes.end(); ++entry) {
      const std::string attribute_path = path + "." + entry.key();
      const Accessor& a = use_accessor(reference(entry.value(), accessors_, attribute_path));
      if ((entry.key() == "POSITION" || entry.key() == "NORMAL") && (a.type != "VEC3" || a.component_type != kFloat)) {
        fail(joined({"expected ", attribute_path, " to name a VEC3 accessor of floats (componentType 5126), found ",
                     std::string(a.type), " of componentType ", std::to_string(a.component_type)}));
      }
      if (entry.key() == "POSITION" && positions != nullptr) *positions = a.count;
    }
  }

  void check_mesh(std::size_t m) {
    const json& mesh = *meshes_.items[m];
    const std::string path = meshes_.path(m);
    const auto primitives = mesh.find("primitives");
    if (primitives == mesh.end() || !primitives->is_array()) {
      fail(joined({"expected ", path, ".primitives to be an array, found ",
                   primitives == mesh.end() ? std::string("none") : shown(*primitives)}));
    }
    std::uint64_t triangles = 0, vertices = 0;
    for (std::size_t p = 0; p < primitives->size(); ++p) {
      const json& primitive = (*primitives)[p];
      const std::string primitive_path = path + ".primitives[" + std::to_string(p) + "]";
      if (!primitive.is_object())
        fail(joined({"expected ", primitive_path, " to be an object, found ", shown(primitive)}));
      refuse_extension_names(primitive, "extensions");
      std::uint64_t positions = 0;
      use_attributes(primitive.contains("attributes") ? primitive["attributes"] : json::object(),
                     primitive_path + ".attributes", &positions);
      if (const auto targets = primitive.find("targets"); targets != primitive.end()) {
        if (!targets->is_array()) fail(joined({"expected ", primitive_path, ".targets to be an array"}));
        for (std::size_t t = 0; t < targets->size(); ++t) {
          use_attributes((*targets)[t], primitive_path + ".targets[" + std::to_string(t) + "]", nullptr);
        }
      }
      std::uint64_t corners = positions;
      if (const std::optional<std::size_t> indices =
              optional_reference(primitive, "indices", accessors_, primitive_path)) {
        const Accessor& a = use_accessor(*indices);
        if (a.type != "SCALAR" || (a.component_type != 5121 && a.component_type != 5123 && a.component_type != 5125)) {
          fail(joined({"expected ", primitive_path, ".indices to name a SCALAR accessor of unsigned integers (5121, ",
                       "5123 or 5125), found ", std::string(a.type), " of componentType ",
                       std::to_string(a.component_type)}));
        }
        corners = a.count;
      }
      const std::uint64_t mode = whole(primitive, "mode", primitive_path, 4);
      if (mode > 6) fail(joined({"expected ", primitive_path, ".mode to be 0 to 6, found ", std::to_string(mode)}));
      // 4: a list of triangles; 5 and 6: a strip and a fan.
      const std::uint64_t made = mode == 4 ? corners / 3 : mode >= 5 ? (corners >= 3 ? corners - 2 : 0) : 0;
      triangles = saturating_add(triangles, made);
      if (mode >= 4) vertices = saturating_add(vertices, positions);
    }
    mesh_triangles_.push_back(triangles);
    mesh_vertices_.push_back(vertices);
  }

  void check_images_and_textures() {
    for (std::size_t i = 0; i < images_.items.size(); ++i) {
      const json& image = *images_.items[i];
      // Assimp copies an image's bufferView for each image that names it.
      if (const auto view = optional_reference(image, "bufferView", views_, images_.path(i))) {
        decoded_bytes_ = saturating_add(decoded_bytes_, view_bytes_[*view]);
      }
      const auto uri = image.find("uri");
      if (uri == image.end()) continue;
      if (!uri->is_string()) fail(joined({"expected ", images_.path(i), ".uri to be a string, found ", shown(*uri)}));
      const std::string text = uri->get<std::string>();
      if (text.rfind("data:", 0) == 0) continue;
      if (!uri_admitted(paths_, directory_, text)) {
        fail(joined({"expected ", images_.path(i), "'s file to be ", paths_.expected(), ", found ", quoted_token(text)}));
      }
      const fs::path path = file_named_by_uri(directory_, text);
      std::error_code error;
      if (fs::is_regular_file(path, error)) contents_.files.push_back(path);
    }
    const Collection textures = collection("textures");
    for (std::size_t i = 0; i < textures.items.size(); ++i) {
      optional_reference(*textures.items[i], "source", images_, textures.path(i));
    }
  }

  // Skins' inverse bind matrices and animation samplers' keys are decoded too.
  void check_skins_and_animations() {
    const Collection skins = collection("skins");
    for (std::size_t i = 0; i < skins.items.size(); ++i) {
      if (const auto a = optional_reference(*skins.items[i], "inverseBindMatrices", accessors_, skins.path(i))) {
        use_accessor(*a);
      }
    }
    const Collection animations = collection("animations");
    for (std::size_t i = 0; i < animations.items.size(); ++i) {
      const json& animation = *animations.items[i];
      const std::string path = animations.path(i);
      // glTF 1.0 names its accessors in "parameters"; 2.0 in samplers' input and output.
      if (const auto parameters = animation.find("parameters");
          parameters != animation.end() && parameters->is_object()) {
        for (auto entry = parameters->begin(); entry != parameters->end(); ++entry) {
          use_accessor(reference(entry.value(), accessors_, path + ".parameters." + entry.key()));
        }
      }
      const auto samplers = animation.find("samplers");
      if (samplers == animation.end() || !samplers->is_array()) continue;
      for (std::size_t s = 0; s < samplers->size(); ++s) {
        const json& sampler = (*samplers)[s];
        const std::string sampler_path = path + ".samplers[" + std::to_string(s) + "]";
        if (!sampler.is_object()) fail(joined({"expected ", sampler_path, " to be an object, found ", shown(sampler)}));
        for (const char* key : {"input", "output"}) {
          if (const auto a = optional_reference(sampler, key, accessors_, sampler_path)) use_accessor(*a);
        }
      }
    }
  }

  // Each node's children and meshes (glTF 2.0 "mesh", 1.0 "meshes").
  void read_nodes(std::vector<std::vector<std::size_t>>& children, std::vector<std::vector<std::size_t>>& meshes) {
    for (std::size_t i = 0; i < nodes_.items.size(); ++i) {
      const json& node = *nodes_.items[i];
      const std::string path = nodes_.path(i);
      children[i] = references(node, "children", nodes_, path);
      meshes[i] = references(node, "meshes", meshes_, path);
      if (const auto mesh = optional_reference(node, "mesh", meshes_, path)) meshes[i].push_back(*mesh);
    }
  }

  // How often each node is a root: the nodes of the scene Assimp reads
  // ("scene", else every scene's), or every node without a parent when there are no scenes.
  std::vector<std::uint64_t> root_counts(const std::vector<std::vector<std::size_t>>& children) const {
    std::vector<std::uint64_t> roots(nodes_.items.size(), 0);
    const Collection scenes = collection("scenes");
    if (scenes.items.empty()) {
      std::vector<bool> has_parent(nodes_.items.size(), false);
      for (const std::vector<std::size_t>& list : children) {
        for (std::size_t child : list) has_parent[child] = true;
      }
      for (std::size_t i = 0; i < roots.size(); ++i) roots[i] = has_parent[i] ? 0 : 1;
      return roots;
    }
    // Every scene's roots, unless "scene" picks one.
    const auto scene = document_.find("scene");
    const std::size_t chosen = scene == document_.end() ? scenes.items.size() : reference(*scene, scenes, "scene");
    for (std::size_t s = 0; s < scenes.items.size(); ++s) {
      const std::vector<std::size_t> nodes = references(*scenes.items[s], "nodes", nodes_, scenes.path(s));
      if (chosen != scenes.items.size() && chosen != s) continue;
      for (std::size_t node : nodes) roots[node] = saturating_add(roots[node], 1);
    }
    return roots;
  }

  // The nodes with every node after its descendants (a depth-first walk on
  // the heap); throws on a cycle or a chain deeper than kMaxGltfNodeDepth.
  std::vector<std::size_t> descendants_first(const std::vector<std::vector<std::size_t>>& children) const {
    const std::size_t n = children.size();
    enum class Mark : unsigned char { unseen, open, done };
    std::vector<Mark> mark(n, Mark::unseen);
    std::vector<std::size_t> height(n, 1), order;
    order.reserve(n);
    std::vector<std::pair<std::size_t, std::size_t>> stack;  // node, next child
    for (std::size_t start = 0; start < n; ++start) {
      if (mark[start] != Mark::unseen) continue;
      stack.push_back({start, 0});
      mark[start] = Mark::open;
      while (!stack.empty()) {
        auto& [node, next] = stack.back();
        if (next < children[node].size()) {
          const std::size_t child = children[node][next++];
          if (mark[child] == Mark::open) {
            fail(joined({"expected nodes that form trees, found ", nodes_.path(child), " among its own descendants (",
                         nodes_.path(node), ".children names it)"}));
          }
          if (mark[child] == Mark::unseen) {
            mark[child] = Mark::open;
            stack.push_back({child, 0});
          }
          continue;
        }
        for (std::size_t child : children[node]) height[node] = std::max(height[node], height[child] + 1);
        if (height[node] > kMaxGltfNodeDepth) {
          fail(joined({"expected nodes nested at most ", std::to_string(kMaxGltfNodeDepth), " deep, found ",
                       std::to_string(height[node]), " levels from ", nodes_.path(node), " down"}));
        }
        mark[node] = Mark::done;
        order.push_back(node);
        stack.pop_back();
      }
    }
    return order;
  }

  void check_node_graph() {
    const std::size_t n = nodes_.items.size();
    std::vector<std::vector<std::size_t>> children(n), meshes(n);
    read_nodes(children, meshes);
    // Paths from the roots to each node: Assimp copies a node under every one.
    std::vector<std::uint64_t> paths = root_counts(children);
    const std::vector<std::size_t> order = descendants_first(children);
    for (auto node = order.rbegin(); node != order.rend(); ++node) {
      for (std::size_t child : children[*node]) paths[child] = saturating_add(paths[child], paths[*node]);
    }
    std::vector<std::uint64_t> placements(meshes_.items.size(), 0);
    for (std::size_t i = 0; i < n; ++i) {
      contents_.node_placements = saturating_add(contents_.node_placements, paths[i]);
      for (std::size_t mesh : meshes[i]) placements[mesh] = saturating_add(placements[mesh], paths[i]);
    }
    if (contents_.node_placements > kMaxGltfNodePlacements) {
      fail(joined({"expected at most ", std::to_string(kMaxGltfNodePlacements),
                   " nodes once each is placed under every parent, found ", shown_size(contents_.node_placements)}));
    }
    std::uint64_t vertices = 0;
    for (std::size_t m = 0; m < placements.size(); ++m) {
      contents_.placed_triangles =
          saturating_add(contents_.placed_triangles, saturating_mul(mesh_triangles_[m], placements[m]));
      vertices = saturating_add(vertices, saturating_mul(mesh_vertices_[m], placements[m]));
    }
    if (contents_.placed_triangles > budget_) {
      fail(joined({"expected at most ", std::to_string(budget_), " triangles once the file's nodes place its meshes, ",
                   "found ", shown_size(contents_.placed_triangles)}));
    }
    if (vertices > kMaxGltfPlacedVertices) {
      fail(joined({"expected at most ", std::to_string(kMaxGltfPlacedVertices),
                   " vertices once the file's nodes place its meshes, found ", shown_size(vertices)}));
    }
  }

  const json& document_;
  std::string_view file_;
  const fs::path& directory_;
  const PathRule& paths_;
  std::uint64_t budget_;
  Collection buffers_, views_, accessors_, meshes_, nodes_, images_;
  std::vector<std::uint64_t> buffer_bytes_, view_bytes_, view_stride_;
  std::vector<Accessor> accessor_info_;
  std::vector<std::uint64_t> mesh_triangles_, mesh_vertices_;
  std::uint64_t decoded_bytes_ = 0, zero_bytes_ = 0;
  GltfContents contents_;
};

}  // namespace

GltfContents check_gltf_contents(const nlohmann::json& document, std::string_view file, const fs::path& directory,
                                 const PathRule& paths, std::size_t triangle_budget) {
  return ContentsCheck(document, file, directory, paths, triangle_budget).run();
}

}  // namespace quiver
