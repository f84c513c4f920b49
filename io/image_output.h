// Image writers for the framebuffer: PNG through libpng, OpenEXR through the
// OpenEXR library, JPEG, HDR and TIFF through OpenImageIO in the quiver_oiio
// module (io/oiio_loader.h), loaded only when needed. PNG and JPEG get 8-bit
// sRGB-encoded RGB (exact sRGB OETF, clamped to [0, 1], rounded to nearest);
// OpenEXR, Radiance HDR and TIFF get 32-bit float linear RGB (RGBE, HDR's
// encoding, has no sign, NaN or infinity: values are clamped to [0, 1e38]
// and NaN written as 0). JPEG sides are limited to 65500. An EXR also
// carries the framebuffer's non-empty AOVs as float channels: "Z" (depth,
// +inf on a miss), "N.X" "N.Y" "N.Z" (normal), "kind" and "id" (integers
// stored as floats, exact up to 2^24; -1 on a miss). Files are written to a
// temporary name in the target's directory and renamed over the target only
// after a successful close, so a failed write leaves an existing file as it was.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "integrator/framebuffer.h"
#include "io/output_file.h"

namespace quiver {

// Checks, before rendering, that path can take the image: a supported
// extension (.png .jpg .jpeg .exr .hdr .tif .tiff, any case), .exr when
// there are AOVs, an existing parent directory, and not a directory itself.
// Throws std::runtime_error("<path>: <message>").
void check_output_path(const std::filesystem::path& path, bool has_aovs);

// Writes the framebuffer as described above to a temporary staged in
// outputs for path (committed with the other outputs). Throws
// std::runtime_error ("<path>: <message>") when the path fails
// check_output_path or writing fails, and std::invalid_argument when the
// framebuffer's arrays do not match its size.
void stage_image(StagedOutputs& outputs, const std::filesystem::path& path, const Framebuffer& framebuffer);

// The 8-bit sRGB codes (io/srgb_encoding.h) of the colours, 3 per pixel:
// what PNG and JPEG files hold.
std::vector<std::uint8_t> srgb_rgb_bytes(const Framebuffer& framebuffer);

// The PNG file a .png output would hold, in memory. Throws
// std::invalid_argument for colours that do not match the size, and
// std::runtime_error when encoding fails.
std::string encode_png(const Framebuffer& framebuffer);

// stage_image and commit for one image on its own.
void write_image(const std::filesystem::path& path, const Framebuffer& framebuffer);

}  // namespace quiver
