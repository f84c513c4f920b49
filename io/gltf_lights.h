// A glTF 2.0 file's punctual lights (KHR_lights_punctual), read from its
// JSON after io/gltf_check.h has checked the document: each node, depth
// first from the roots (io/gltf_node_walk.h), that names a light places one.
// A point or spot light sits at the node's origin, a directional or spot
// light shines down the node's -z, a spot within its cone angles. glTF's
// units are physical (candela for point and spot lights, lux for
// directional ones) and its point lights fall off with the square of the
// distance; quiver's lights are Whitted's, which do not fall off, so
// scaled_gltf_lights keeps the lights' colours and how bright each is at
// the centre of the model, against the others:
//   illuminance E = intensity (directional), intensity / d^2 (point, spot;
//   d from the light to the centre of the scene's bounds),
//   quiver colour = color * E * total / (sum over the lights of E times
//   their color's largest channel), total = default_light_total (the
//   default rig's sum, scene/auto_view.h);
// lights of zero intensity stay dark. A light's range is not modelled: it
// is named for a warning (an error with --strict).
#pragma once

#include <nlohmann/json_fwd.hpp>
#include <string>
#include <string_view>
#include <vector>

#include "scene/scene_desc.h"

namespace quiver {

struct GltfLight {
  LightDesc light;          // placed; colour = glTF's color, unscaled
  double intensity = 1.0;   // candela (point, spot) or lux (directional)
};

struct GltfLights {
  std::vector<GltfLight> lights;
  // What is not modelled, for warnings: per light with a range,
  // "nodes[N] names extensions.KHR_lights_punctual.lights[M]".
  std::vector<std::string> ranges;
};

// Throws ParseError naming file and the JSON path of a light that is not an
// object of a known type with a color of three finite numbers in [0, 1]
// and a finite intensity >= 0, or of a node's light index that names none.
GltfLights gltf_lights(const nlohmann::json& document, std::string_view file);

// quiver's lights for them, by the rule above, in a scene whose bounds
// centre is `centre` and whose ambient is `ambient`.
std::vector<LightDesc> scaled_gltf_lights(const GltfLights& lights, const Vec3<float>& centre,
                                          const Vec3<float>& ambient);

}  // namespace quiver
