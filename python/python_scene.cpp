#include "python/python_scene.h"

#include <utility>

#include "app/render_options.h"
#include "app/scene_build.h"
#include "scene/auto_view.h"

namespace quiver {

PythonScene make_python_scene(std::string name, SceneDesc desc) {
  SceneDesc viewed = desc;
  if (!viewed.camera) add_default_view(viewed, kDefaultImageSide, kDefaultImageSide);
  Scene built = build_named_scene(viewed, {}, name);
  PythonScene scene{std::move(name), std::move(desc), std::move(built), {}, {}, {}, {}, {}};
  const std::size_t ids = scene.built.material_of_id.size();
  scene.kind_of_id.resize(ids);
  scene.index_of_id.resize(ids);
  for (std::size_t id = 0; id < ids; ++id) {
    const PrimitiveOrigin& origin = scene.built.origin(scene.built.locate(std::int32_t(id)));
    scene.kind_of_id[id] = static_cast<std::int32_t>(origin.kind);
    scene.index_of_id[id] = static_cast<std::int32_t>(origin.index);
  }
  return scene;
}

}  // namespace quiver
