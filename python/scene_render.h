// quiver.render without Python: `quiver render`'s steps on the scene's
// description (app/render_options.h): the options checked as the CLI
// checks its flags (UsageError, naming the flag), the ISA (the option, else
// $QUIVER_SIMD, else auto), the plan, the view, the build with the plan's
// options, and the render. The same options give the same image as the CLI.
#pragma once

#include "app/render_options.h"
#include "integrator/framebuffer.h"
#include "python/python_scene.h"

namespace quiver {

Framebuffer render_python_scene(const PythonScene& scene, const RenderOptions& options);

}  // namespace quiver
