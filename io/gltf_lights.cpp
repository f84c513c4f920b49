#include "io/gltf_lights.h"

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <numbers>

#include "io/gltf_node_walk.h"
#include "scene/auto_view.h"

namespace quiver {

namespace {

using json = nlohmann::json;

// object.extensions.KHR_lights_punctual[key] (the document's "lights", a
// node's "light"), or null when absent.
const json* punctual_entry(const json& object, const char* key) {
  const auto extensions = object.find("extensions");
  if (extensions == object.end() || !extensions->is_object()) return nullptr;
  const auto punctual = extensions->find("KHR_lights_punctual");
  if (punctual == extensions->end() || !punctual->is_object()) return nullptr;
  const auto entry = punctual->find(key);
  return entry == punctual->end() ? nullptr : &*entry;
}

class LightReader {
 public:
  LightReader(const json& document, std::string_view file) : list_(punctual_entry(document, "lights")), file_(file) {}

  // lights[index] placed by its node.
  void place(const json& index, const std::string& node_path, const GltfMatrix& world, GltfLights& out) const {
    const std::string where = node_path + ".extensions.KHR_lights_punctual.light";
    if (list_ == nullptr || !list_->is_array() || !index.is_number_unsigned() ||
        index.get<std::size_t>() >= list_->size()) {
      throw gltf_value_error(file_, where, "an index into the file's KHR_lights_punctual lights");
    }
    const std::string path = "extensions.KHR_lights_punctual.lights[" + std::to_string(index.get<std::size_t>()) + "]";
    const json& light = (*list_)[index.get<std::size_t>()];
    if (!light.is_object()) throw gltf_value_error(file_, path, "a light object");
    const auto type = light.find("type");
    const bool known = type != light.end() && type->is_string() &&
                       (*type == "point" || *type == "spot" || *type == "directional");
    if (!known) throw gltf_value_error(file_, path + ".type", "\"point\", \"spot\" or \"directional\"");
    GltfLight placed;
    placed.light.color = color(light, path);
    placed.intensity = intensity(light, path);
    placed.light.kind = *type == "directional" ? LightDesc::Kind::directional
                        : *type == "spot"        ? LightDesc::Kind::spot
                                                 : LightDesc::Kind::point;
    if (placed.light.kind != LightDesc::Kind::directional) {
      placed.light.position = gltf_transformed(world, 0, 0, 0, 1);
      if (!std::isfinite(dot(placed.light.position, placed.light.position))) {
        throw gltf_value_error(file_, node_path, "a transform that places a light at finite coordinates");
      }
    }
    if (placed.light.kind != LightDesc::Kind::point) {
      placed.light.direction = gltf_transformed(world, 0, 0, -1, 0);
      const Vec3<float>& d = placed.light.direction;
      if (!(dot(d, d) > 0.f) || !std::isfinite(dot(d, d))) {
        throw gltf_value_error(file_, node_path, "a transform that keeps a light's direction");
      }
    }
    if (placed.light.kind == LightDesc::Kind::spot) set_cone(light, path, placed.light);
    if (light.contains("range")) out.ranges.push_back(node_path + " names " + path);
    out.lights.push_back(placed);
  }

 private:
  // A spot's "spot" object, which glTF requires: cone angles 0 <= inner < outer <= pi/2.
  void set_cone(const json& light, const std::string& path, LightDesc& spot_light) const {
    const auto spot = light.find("spot");
    const char* expected = "an object whose innerConeAngle (default 0) and outerConeAngle (default pi/4) satisfy "
                           "0 <= inner < outer <= pi/2";
    if (spot == light.end() || !spot->is_object()) throw gltf_value_error(file_, path + ".spot", expected);
    const auto angle = [&](const char* key, double absent) {
      const auto found = spot->find(key);
      if (found == spot->end()) return absent;
      if (!found->is_number()) throw gltf_value_error(file_, path + ".spot", expected);
      return found->get<double>();
    };
    const double inner = angle("innerConeAngle", 0.0), outer = angle("outerConeAngle", std::numbers::pi / 4);
    if (!(inner >= 0.0 && inner < outer && outer <= std::numbers::pi / 2)) {
      throw gltf_value_error(file_, path + ".spot", expected);
    }
    spot_light.cone_inner_cos = float(std::cos(inner));
    spot_light.cone_outer_cos = float(std::cos(outer));
  }

  Vec3<float> color(const json& light, const std::string& path) const {
    const auto found = light.find("color");
    if (found == light.end()) return {1.f, 1.f, 1.f};
    const char* expected = "an array of three numbers in [0, 1]";
    if (!found->is_array() || found->size() != 3) throw gltf_value_error(file_, path + ".color", expected);
    Vec3<float> c;
    for (int k = 0; k < 3; ++k) {
      const json& v = (*found)[std::size_t(k)];
      if (!v.is_number() || !(v.get<double>() >= 0.0 && v.get<double>() <= 1.0)) {
        throw gltf_value_error(file_, path + ".color", expected);
      }
      c[k] = v.get<float>();
    }
    return c;
  }

  double intensity(const json& light, const std::string& path) const {
    const auto found = light.find("intensity");
    if (found == light.end()) return 1.0;
    if (!found->is_number() || !(found->get<double>() >= 0.0) || !std::isfinite(found->get<double>())) {
      throw gltf_value_error(file_, path + ".intensity", "a finite number >= 0");
    }
    return found->get<double>();
  }

  const json* list_;
  std::string_view file_;
};

}  // namespace

GltfLights gltf_lights(const json& document, std::string_view file) {
  GltfLights out;
  const LightReader reader(document, file);
  walk_gltf_nodes(document, file, [&](const json& node, const std::string& path, const GltfMatrix& world) {
    if (const json* index = punctual_entry(node, "light")) reader.place(*index, path, world, out);
    return true;
  });
  return out;
}

std::vector<LightDesc> scaled_gltf_lights(const GltfLights& lights, const Vec3<float>& centre,
                                          const Vec3<float>& ambient) {
  std::vector<double> illuminance;
  double sum = 0.0;
  for (const GltfLight& g : lights.lights) {
    double e = g.intensity;
    if (g.light.kind != LightDesc::Kind::directional) {
      double d2 = 0.0;
      for (int a = 0; a < 3; ++a) {
        const double d = double(g.light.position[a]) - double(centre[a]);
        d2 += d * d;
      }
      e /= d2 > 0.0 ? d2 : 1.0;  // a light at the centre itself is taken as one unit away
    }
    illuminance.push_back(e);
    sum += e * double(std::max({g.light.color.x, g.light.color.y, g.light.color.z}));
  }
  const double scale = sum > 0.0 && std::isfinite(sum) ? double(default_light_total(ambient)) / sum : 0.0;
  std::vector<LightDesc> out;
  for (std::size_t i = 0; i < lights.lights.size(); ++i) {
    LightDesc light = lights.lights[i].light;
    light.color = light.color * float(illuminance[i] * scale);
    out.push_back(light);
  }
  return out;
}

}  // namespace quiver
