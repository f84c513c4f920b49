#include "io/gltf_camera.h"

#include <cmath>
#include <nlohmann/json.hpp>
#include <numbers>

#include "io/gltf_node_walk.h"

namespace quiver {

namespace {

using json = nlohmann::json;

class CameraReader {
 public:
  CameraReader(const json& document, std::string_view file) : document_(document), file_(file) {}

  GltfCamera run() {
    GltfCamera result;
    walk_gltf_nodes(document_, file_, [&](const json& node, const std::string& path, const GltfMatrix& world) {
      const auto camera = node.find("camera");
      if (camera == node.end()) return true;
      if (!camera->is_number_unsigned()) fail(path + ".camera", "an index into cameras");
      result.camera = perspective(camera->get<std::size_t>(), world, path, result);
      return !result.camera;
    });
    return result;
  }

 private:
  [[noreturn]] void fail(const std::string& path, std::string_view expected) const {
    throw gltf_value_error(file_, path, expected);
  }

  // cameras[index] seen through world, when it is perspective; else a note in result.unused.
  std::optional<CameraDesc> perspective(std::size_t index, const GltfMatrix& world, const std::string& node_path,
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
    const auto point = [&](double x, double y, double z, double w) { return gltf_transformed(world, x, y, z, w); };
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
