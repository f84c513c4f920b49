#include "python/scene_render.h"

#include <cstdlib>
#include <utility>

#include "app/scene_build.h"

namespace quiver {

Framebuffer render_python_scene(const PythonScene& scene, const RenderOptions& options) {
  check_render_options(options);
  const Isa isa = choose_isa(options.simd, std::getenv("QUIVER_SIMD"));
  SceneDesc desc = scene.desc;
  const RenderPlan plan = plan_render(options, desc, isa);
  set_view(desc, options.camera, plan.settings.width, plan.settings.height);
  const Scene built = build_named_scene(desc, plan.build, scene.name);
  return std::move(render(built, plan.settings).image);
}

}  // namespace quiver
