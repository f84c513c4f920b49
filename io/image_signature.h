// The texture image formats quiver reads, told apart by the first bytes of
// a file (their signatures), so that a file that is no image is refused
// before any decoder reads it: OpenImageIO, given a file no plugin claims,
// tries every plugin in turn, some of which read the whole file.
#pragma once

#include <cstddef>
#include <optional>
#include <string_view>

namespace quiver {

// How many first bytes of a file image_format_of looks at (a TGA header
// is 18 bytes).
inline constexpr std::size_t kImageSignatureBytes = 18;

// The formats, as error messages list them.
inline constexpr std::string_view kTextureFormatNames =
    "PNG, JPEG, TIFF, OpenEXR, Radiance HDR, PNM (PBM, PGM, PPM, PFM), BMP, GIF, WebP, DDS or TGA";

// The OpenImageIO format name ("png", "jpeg", ...) of a file that starts
// with `head` (its first kImageSignatureBytes bytes, or all of a shorter
// file), or nullopt. TGA has no signature: it needs `extension` (".tga",
// any case) and a header that describes an image.
std::optional<std::string_view> image_format_of(std::string_view head, std::string_view extension);

}  // namespace quiver
