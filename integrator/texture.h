// Texture evaluation (the data: scene/texture.h). Wrap modes act on the
// integer texel indices of the four bilinear taps. Checker parities are
// computed in double from floor(coordinate * scale), so they are exact for
// every finite float. Non-finite u, v or world coordinates count as 0, so
// evaluate never returns NaN.
// Filtered checkers: the box filter over a footprint, analytically. A
// checker is (a + b) / 2 + (a - b) / 2 * s(x) s(y) [s(z)] with s the square
// wave (-1)^floor; its box average is the product of each axis's average,
// the difference of the integrated square wave (a triangle wave) at the
// box's ends over its width (the separable box: Heckbert 1989, Apodaca and
// Gritz 2000). Footprints below kPointFootprint of a cell are point-sampled
// (the same bits as evaluate); unbounded ones average to the mean colour.
#pragma once

#include "scene/texture.h"
#include "simd/vec3.h"

namespace quiver {

// The texture's colour at surface coordinates (u, v) and world point p.
// checker2d: color_a where floor(u*scale) + floor(v*scale) is even, else
// color_b; checker3d: the same over floor(p.x*scale) + floor(p.y*scale) +
// floor(p.z*scale); image: bilinear over the four texels around (u, v).
Vec3<float> evaluate(const Texture& texture, float u, float v, const Vec3<float>& world_point);

// The change of (u, v) and of the world point over one sample spacing along
// the film's x and y (integrator/ray_differentials.h).
struct TextureFootprint {
  float du_dx = 0.f, dv_dx = 0.f, du_dy = 0.f, dv_dy = 0.f;
  Vec3<float> dp_dx{0.f, 0.f, 0.f}, dp_dy{0.f, 0.f, 0.f};
};

// A footprint this small against one checker cell samples the point.
inline constexpr double kPointFootprint = 1e-4;

// The texture filtered over the footprint. Checkers: the box spans
// |d/dx| + |d/dy| per axis (the footprint parallelogram's bounding box).
// Images: trilinear MIP mapping, the level from the footprint's longer
// side in texels (texture.cpp says how); up to sqrt 3 texels, the
// bilinear lookup of evaluate.
Vec3<float> evaluate_filtered(const Texture& texture, float u, float v, const Vec3<float>& world_point,
                              const TextureFootprint& footprint);

}  // namespace quiver
