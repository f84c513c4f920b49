#include "app/scene_build.h"

#include <stdexcept>

namespace quiver {

Scene build_named_scene(const SceneDesc& desc, const SceneBuildOptions& options, const std::string& name) {
  try {
    return build_scene(desc, options);
  } catch (const std::invalid_argument& error) {
    throw std::runtime_error((name.empty() ? std::string("the built-in scene") : name) + ": " + error.what());
  }
}

}  // namespace quiver
