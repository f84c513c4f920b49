// Texture images from files (OpenImageIO, through the quiver_oiio module of
// io/oiio_loader.h, loaded on the first read): read into the scene description
// before the scene is built, so that the layers above io/ read no file.
#pragma once

#include <cstdint>
#include <filesystem>
#include <span>
#include <string_view>

#include "scene/scene_desc.h"
#include "scene/texture.h"

namespace quiver {

// Reads an image file. One channel is grey (replicated), two are grey +
// alpha, three or more are RGB (+ alpha); alpha is dropped. Integer formats
// are sRGB-decoded (exact EOTF) unless the file's "oiio:ColorSpace" names a
// linear space; float formats are linear. The format is told by the
// file's first bytes (io/image_signature.h) and decoded by its plugin
// alone. Throws ParseError ("file: message") for a missing, unreadable or
// non-image file, sizes beyond kMaxTextureSide / kMaxTexturePixels, or
// non-finite texels.
TextureImage read_texture_image(const std::filesystem::path& path);

// As read_texture_image, for the bytes of an image file held in memory (a
// glTF's embedded image); name labels the errors.
TextureImage decode_texture_image(std::span<const std::uint8_t> bytes, std::string_view name);

// Reads the file of every image texture that names one, or decodes its
// encoded bytes, when it has no pixels yet, into its width, height and rgb
// (the encoded bytes are then released). Throws as read_texture_image, at the
// texture's named_at when it has one (ParseError::in_named_file).
void read_texture_images(SceneDesc& scene);

}  // namespace quiver
