// Texture evaluation (the data: scene/texture.h). Wrap modes act on the
// integer texel indices of the four bilinear taps. Checker parities are
// computed in double from floor(coordinate * scale), so they are exact for
// every finite float. Non-finite u, v or world coordinates count as 0, so
// evaluate never returns NaN.
#pragma once

#include "scene/texture.h"
#include "simd/vec3.h"

namespace quiver {

// The texture's colour at surface coordinates (u, v) and world point p.
// checker2d: color_a where floor(u*scale) + floor(v*scale) is even, else
// color_b; checker3d: the same over floor(p.x*scale) + floor(p.y*scale) +
// floor(p.z*scale); image: bilinear over the four texels around (u, v).
Vec3<float> evaluate(const Texture& texture, float u, float v, const Vec3<float>& world_point);

}  // namespace quiver
