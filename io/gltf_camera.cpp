#include "io/gltf_camera.h"

#include <array>
#include <cmath>
#include <nlohmann/json.hpp>
#include <numbers>
#include <utility>
#include <vector>

#include "io/parse_error.h"

namespace quiver {

namespace {

using json = nlohmann::json;
using Matrix = std::array<double, 16>;  // column-major, as glTF's "matrix"

constexpr Matrix kIdentity{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};

Matrix times(const Matrix& a, const Matrix& b) {
  Matrix m{};
  for (int c = 0; c < 4; ++c) {
    for (int r = 0; r < 4; ++r) {
      double sum = 0.0;
      for (int k = 0; k < 4; ++k) sum += a[std::size_t(4 * k + r)] * b[std::size_t(4 * c + k)];
      m[std::size_t(4 * c + r)] = sum;
    }
  }
  return m;
}

class CameraReader {
 public:
  CameraReader(const json& document, std::string_view file) : document_(document), file_(file) {}

  GltfCamera run() {
    const auto nodes = document_.find("nodes");
    if (nodes == document_.end() || !nodes->is_array()) return {};
    // Depth-first from the roots, each node's world transform beside it.
    std::vector<std::pair<std::size_t, Matrix>> pending;
    const std::vector<std::size_t> roots = root_nodes(*nodes);
    for (auto root = roots.rbegin(); root != roots.rend(); ++root) pending.emplace_back(*root, kIdentity);
    GltfCamera result;
    while (!pending.empty()) {
      const auto [index, parent] = pending.back();
      pending.pop_back();
      const json& node = (*nodes)[index];
      const std::string path = "nodes[" + std::to_string(index) + "]";
      const Matrix world = times(parent, local(node, path));
      if (const auto camera = node.find("camera"); camera != node.end()) {
        if (!camera->is_number_unsigned()) fail(path + ".camera", "an index into cameras");
        if (auto found = perspective(camera->get<std::size_t>(), world, path, result)) {
          result.camera = std::move(found);
          return result;
        }
      }
      if (const auto children = node.find("children"); children != node.end() && children->is_array()) {
        for (auto child = children->rbegin(); child != children->rend(); ++child) {
          pending.emplace_back(child->get<std::size_t>(), world);
        }
      }
    }
    return result;
  }

 private:
  [[noreturn]] void fail(const std::string& path, std::string_view expected) const {
    throw ParseError::whole_file(file_, "expected " + path + " to be " + std::string(expected));
  }

  // The roots Assimp reads, as io/gltf_check.cpp counts them: the nodes of
  // "scene", else of every scene in turn; without scenes, every node no other names.
  std::vector<std::size_t> root_nodes(const json& nodes) const {
    std::vector<std::size_t> roots;
    const auto scenes = document_.find("scenes");
    if (scenes != document_.end() && scenes->is_array() && !scenes->empty()) {
      const auto chosen = document_.find("scene");
      const bool one = chosen != document_.end() && chosen->is_number_unsigned();
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

  // count finite numbers at node[key], or the default.
  template <std::size_t N>
  std::array<double, N> numbers(const json& node, const char* key, const std::string& path,
                                const std::array<double, N>& absent) const {
    const auto found = node.find(key);
    if (found == node.end()) return absent;
    const std::string where = path + "." + key;
    const std::string expected = "an array of " + std::to_string(N) + " finite numbers";
    if (!found->is_array() || found->size() != N) fail(where, expected);
    std::array<double, N> values{};
    for (std::size_t i = 0; i < N; ++i) {
      const json& v = (*found)[i];
      if (!v.is_number() || !std::isfinite(v.get<double>())) fail(where, expected);
      values[i] = v.get<double>();
    }
    return values;
  }

  // The node's "matrix", else translation x rotation (a unit quaternion x, y, z, w) x scale.
  Matrix local(const json& node, const std::string& path) const {
    if (node.contains("matrix")) return numbers<16>(node, "matrix", path, kIdentity);
    const std::array<double, 3> t = numbers<3>(node, "translation", path, {0, 0, 0});
    const std::array<double, 4> q = numbers<4>(node, "rotation", path, {0, 0, 0, 1});
    const std::array<double, 3> s = numbers<3>(node, "scale", path, {1, 1, 1});
    const double x = q[0], y = q[1], z = q[2], w = q[3];
    const double rotation[9] = {1 - 2 * (y * y + z * z), 2 * (x * y + z * w),     2 * (x * z - y * w),
                                2 * (x * y - z * w),     1 - 2 * (x * x + z * z), 2 * (y * z + x * w),
                                2 * (x * z + y * w),     2 * (y * z - x * w),     1 - 2 * (x * x + y * y)};
    Matrix m = kIdentity;
    for (int c = 0; c < 3; ++c) {
      for (int r = 0; r < 3; ++r) m[std::size_t(4 * c + r)] = rotation[3 * c + r] * s[std::size_t(c)];
      m[std::size_t(12 + c)] = t[std::size_t(c)];
    }
    return m;
  }

  // cameras[index] seen through world, when it is perspective; else a note in result.unused.
  std::optional<CameraDesc> perspective(std::size_t index, const Matrix& world, const std::string& node_path,
                                        GltfCamera& result) const {
    const auto cameras = document_.find("cameras");
    if (cameras == document_.end() || !cameras->is_array() || index >= cameras->size()) {
      fail(node_path + ".camera", "an index into cameras");
    }
    const json& camera = (*cameras)[index];
    const std::string path = "cameras[" + std::to_string(index) + "]";
    if (!camera.is_object()) fail(path, "a camera object");
    const auto type = camera.find("type");
    const auto lens = camera.find("perspective");
    if (type == camera.end() || *type != "perspective" || lens == camera.end() || !lens->is_object()) {
      if (result.unused.empty()) {
        result.unused = node_path + " names " + path + ", of type " +
                        (type != camera.end() && type->is_string() ? type->get<std::string>() : "none") +
                        "; quiver's camera is a perspective one";
      }
      return std::nullopt;
    }
    const auto yfov = lens->find("yfov");
    if (yfov == lens->end() || !yfov->is_number() || !(yfov->get<double>() > 0.0) ||
        !(yfov->get<double>() < std::numbers::pi)) {
      fail(path + ".perspective.yfov", "a number of radians in (0, pi)");
    }
    double aspect = 1.0;
    if (const auto given = lens->find("aspectRatio"); given != lens->end()) {
      if (!given->is_number() || !(given->get<double>() > 0.0) || !std::isfinite(given->get<double>())) {
        fail(path + ".perspective.aspectRatio", "a number > 0");
      }
      aspect = given->get<double>();
    }
    CameraDesc c{};
    c.width = aspect >= 1.0 ? kDefaultImageSide : std::max(1, int(std::lround(kDefaultImageSide * aspect)));
    c.height = aspect >= 1.0 ? std::max(1, int(std::lround(kDefaultImageSide / aspect))) : kDefaultImageSide;
    const double longer = double(std::max(c.width, c.height) - 1);
    const double half = std::atan(std::tan(0.5 * yfov->get<double>()) * std::max(longer, 1.0) / double(c.height));
    c.angle_degrees = float(2.0 * half * 180.0 / std::numbers::pi);
    if (!(c.angle_degrees < 180.f)) fail(path + ".perspective", "a view narrower than 180 degrees across");
    const auto point = [&](double x, double y, double z, double w) {
      Vec3<float> p;
      for (int r = 0; r < 3; ++r) {
        p[r] = float(world[std::size_t(r)] * x + world[std::size_t(4 + r)] * y + world[std::size_t(8 + r)] * z +
                     world[std::size_t(12 + r)] * w);
      }
      return p;
    };
    c.from = point(0, 0, 0, 1);
    const Vec3<float> forward = point(0, 0, -1, 0);
    c.at = c.from + forward;
    c.up = point(0, 1, 0, 0);
    c.hither = 0.f;
    const Vec3<float> across = cross(forward, c.up);
    if (!(dot(forward, forward) > 0.f) || !(dot(across, across) > 0.f) || !std::isfinite(dot(c.at, c.at))) {
      fail(node_path, "a transform that keeps a camera's view and up apart");
    }
    return c;
  }

  const json& document_;
  std::string_view file_;
};

}  // namespace

GltfCamera gltf_camera(const nlohmann::json& document, std::string_view file) {
  return CameraReader(document, file).run();
}

}  // namespace quiver
