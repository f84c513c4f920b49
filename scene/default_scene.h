// The built-in scene `quiver render` shows without a scene file: every seed
// effect at once. A checkerboard floor, a mirror sphere, a glass sphere
// (refraction, total internal reflection, a transparent shadow), a textured
// quad (an image texture made in memory, bilinearly filtered), an open
// cylinder with a solid checker, two point lights and one rectangle area
// light (soft shadows), adaptive anti-aliasing.
#pragma once

#include "scene/scene_desc.h"

namespace quiver {

SceneDesc default_scene();

}  // namespace quiver
