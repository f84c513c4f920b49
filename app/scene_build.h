// build_scene for a command: its errors (bad material or texture indices)
// name the scene the way every other scene error does.
#pragma once

#include <string>

#include "scene/scene.h"

namespace quiver {

// build_scene; its std::invalid_argument becomes std::runtime_error
// "<name>: <message>" (name empty: "the built-in scene").
Scene build_named_scene(const SceneDesc& desc, const SceneBuildOptions& options, const std::string& name);

// The same with build_scene_releasing_triangles: desc.triangles is empty afterwards.
Scene build_named_scene_releasing_triangles(SceneDesc& desc, const SceneBuildOptions& options,
                                            const std::string& name);

}  // namespace quiver
