#include "app/scene_build.h"

#include <stdexcept>

namespace quiver {

namespace {

template <class Build>
Scene named(const std::string& name, Build build) {
  try {
    return build();
  } catch (const std::invalid_argument& error) {
    throw std::runtime_error((name.empty() ? std::string("the built-in scene") : name) + ": " + error.what());
  }
}

}  // namespace

Scene build_named_scene(const SceneDesc& desc, const SceneBuildOptions& options, const std::string& name) {
  return named(name, [&] { return build_scene(desc, options); });
}

Scene build_named_scene_releasing_triangles(SceneDesc& desc, const SceneBuildOptions& options,
                                            const std::string& name) {
  return named(name, [&] { return build_scene_releasing_triangles(desc, options); });
}

}  // namespace quiver
