// Reader for NFF, Eric Haines' Neutral File Format (the SPD scenes): one
// entity per line, `#` comments, errors as ParseError (io/parse_error.h).
// The bounds below are checked before anything is allocated; see io/README.md.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string_view>

#include "scene/scene_desc.h"

namespace quiver {

// Largest NFF input read, in bytes.
inline constexpr std::size_t kMaxNffBytes = std::size_t{1} << 30;
// Largest `resolution` side and pixel count: kMaxImageSide, kMaxImagePixels (scene/scene_desc.h).
// Largest `p` / `pp` vertex count: kMaxPolygonVertices (geometry/kinds/polygon.h).

// An NFF `f` line as written: colour, diffuse weight, specular (and mirror)
// weight, Phong exponent, transmitted fraction, index of refraction.
struct NffMaterial {
  Vec3<float> color;
  float kd, ks, shine, transmittance, ior;
};

// NFF's shading in quiver's terms (io/README.md): ka = kd = Kd (ambient
// reflectance follows the diffuse one), ks = kr = Ks (specular highlight
// and mirror weight), shininess = Shine, kt = T, ior only where T > 0 (and
// 1 when written as 0), two-sided exactly when T > 0.
MaterialDesc material_from_nff(const NffMaterial& nff);

// Reads a whole file; throws ParseError for bad input or an unreadable file.
SceneDesc read_nff(const std::filesystem::path& path);

// Parses NFF text; file_name only labels error messages.
SceneDesc parse_nff(std::string_view text, std::string_view file_name);

}  // namespace quiver
