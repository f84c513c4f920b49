// Loads a scene file with the reader its extension names (.nff, .toml,
// .obj; case-insensitive), and reads the image files its textures name.
#pragma once

#include <filesystem>

#include "scene/scene_desc.h"

namespace quiver {

// Throws ParseError: from the reader or the texture images, or "file:
// message" for an extension that names no reader.
SceneDesc load_scene(const std::filesystem::path& path);

}  // namespace quiver
