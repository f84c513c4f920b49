#include "io/gltf_node_walk.h"

#include <cmath>
#include <nlohmann/json.hpp>
#include <utility>
#include <vector>

namespace quiver {

namespace {

using json = nlohmann::json;

constexpr GltfMatrix kIdentity{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};

GltfMatrix times(const GltfMatrix& a, const GltfMatrix& b) {
  GltfMatrix m{};
  for (int c = 0; c < 4; ++c) {
    for (int r = 0; r < 4; ++r) {
      double sum = 0.0;
      for (int k = 0; k < 4; ++k) sum += a[std::size_t(4 * k + r)] * b[std::size_t(4 * c + k)];
      m[std::size_t(4 * c + r)] = sum;
    }
  }
  return m;
}

// N finite numbers at node[key], or the default.
template <std::size_t N>
std::array<double, N> numbers(const json& node, const char* key, const std::string& path,
                              const std::array<double, N>& absent, std::string_view file) {
  const auto found = node.find(key);
  if (found == node.end()) return absent;
  const std::string where = path + "." + key;
  const std::string expected = "an array of " + std::to_string(N) + " finite numbers";
  if (!found->is_array() || found->size() != N) throw gltf_value_error(file, where, expected);
  std::array<double, N> values{};
  for (std::size_t i = 0; i < N; ++i) {
    const json& v = (*found)[i];
    if (!v.is_number() || !std::isfinite(v.get<double>())) throw gltf_value_error(file, where, expected);
    values[i] = v.get<double>();
  }
  return values;
}

// The node's "matrix", else translation x rotation x scale.
GltfMatrix local(const json& node, const std::string& path, std::string_view file) {
  if (node.contains("matrix")) return numbers<16>(node, "matrix", path, kIdentity, file);
  const std::array<double, 3> t = numbers<3>(node, "translation", path, {0, 0, 0}, file);
  const std::array<double, 4> q = numbers<4>(node, "rotation", path, {0, 0, 0, 1}, file);
  const std::array<double, 3> s = numbers<3>(node, "scale", path, {1, 1, 1}, file);
  const double x = q[0], y = q[1], z = q[2], w = q[3];
  const double rotation[9] = {1 - 2 * (y * y + z * z), 2 * (x * y + z * w),     2 * (x * z - y * w),
                              2 * (x * y - z * w),     1 - 2 * (x * x + z * z), 2 * (y * z + x * w),
                              2 * (x * z + y * w),     2 * (y * z - x * w),     1 - 2 * (x * x + y * y)};
  GltfMatrix m = kIdentity;
  for (int c = 0; c < 3; ++c) {
    for (int r = 0; r < 3; ++r) m[std::size_t(4 * c + r)] = rotation[3 * c + r] * s[std::size_t(c)];
    m[std::size_t(12 + c)] = t[std::size_t(c)];
  }
  return m;
}

std::vector<std::size_t> root_nodes(const json& document, const json& nodes) {
  std::vector<std::size_t> roots;
  const auto scenes = document.find("scenes");
  if (scenes != document.end() && scenes->is_array() && !scenes->empty()) {
    const auto chosen = document.find("scene");
    const bool one = chosen != document.end() && chosen->is_number_unsigned();
    for (std::size_t s = 0; s < scenes->size(); ++s) {
      if (one && s != chosen->get<std::size_t>()) continue;
      const json& scene = (*scenes)[s];
      if (const auto list = scene.find("nodes"); list != scene.end() && list->is_array()) {
        for (const json& n : *list) roots.push_back(n.get<std::size_t>());
      }
    }
    return roots;
  }
  std::vector<bool> named(nodes.size(), false);
  for (const json& node : nodes) {
    if (const auto children = node.find("children"); children != node.end() && children->is_array()) {
      for (const json& c : *children) named[c.get<std::size_t>()] = true;
    }
  }
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    if (!named[i]) roots.push_back(i);
  }
  return roots;
}

}  // namespace

ParseError gltf_value_error(std::string_view file, const std::string& path, std::string_view expected) {
  return ParseError::whole_file(file, "expected " + path + " to be " + std::string(expected));
}

Vec3<float> gltf_transformed(const GltfMatrix& world, double x, double y, double z, double w) {
  Vec3<float> p;
  for (int r = 0; r < 3; ++r) {
    p[r] = float(world[std::size_t(r)] * x + world[std::size_t(4 + r)] * y + world[std::size_t(8 + r)] * z +
                 world[std::size_t(12 + r)] * w);
  }
  return p;
}

void walk_gltf_nodes(const json& document, std::string_view file,
                     const std::function<bool(const json& node, const std::string& path, const GltfMatrix& world)>& visit) {
  const auto nodes = document.find("nodes");
  if (nodes == document.end() || !nodes->is_array()) return;
  std::vector<std::pair<std::size_t, GltfMatrix>> pending;
  const std::vector<std::size_t> roots = root_nodes(document, *nodes);
  for (auto root = roots.rbegin(); root != roots.rend(); ++root) pending.emplace_back(*root, kIdentity);
  while (!pending.empty()) {
    const auto [index, parent] = pending.back();
    pending.pop_back();
    const json& node = (*nodes)[index];
    const std::string path = "nodes[" + std::to_string(index) + "]";
    const GltfMatrix world = times(parent, local(node, path, file));
    if (!visit(node, path, world)) return;
    if (const auto children = node.find("children"); children != node.end() && children->is_array()) {
      for (auto child = children->rbegin(); child != children->rend(); ++child) {
        pending.emplace_back(child->get<std::size_t>(), world);
      }
    }
  }
}

}  // namespace quiver
