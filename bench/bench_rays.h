// Ray sets traced through a scene by the BVH and Embree benchmarks, made
// once per scene with quiver's camera and hit points:
//   primary:    pixel centres in 16 x 16 tiles, each 4 x 4 pixel group
//               16 consecutive rays row by row (an 8-wide packet covers
//               4 x 2 pixels), as the renderer issues them (coherent);
//   reflection: mirror rays from every primary hit (integrator/optics.h
//               offsets), in the same order (diverging after curved hits);
//   diffuse:    a uniformly random direction in the hemisphere of each
//               primary hit's normal (incoherent);
//   shadow:     from each primary hit toward a point above and behind the
//               camera, t in (0, 1) (any-hit).
#pragma once

#include <cstdint>

#include "geometry/soa.h"
#include "scene/scene.h"

namespace quiver::bench {

struct SceneRays {
  RaySoA primary, reflection, diffuse, shadow;
};

SceneRays make_scene_rays(const Scene& scene, int width, int height, std::uint32_t seed);

}  // namespace quiver::bench
