// What quiver.render returns, whatever its options (quiver.Image): the
// rendered framebuffer, whose colour and AOVs Python reads as NumPy views
// of it (color, depth, normal, kind, id; None for an AOV not asked for),
// and save(path), which writes the file `quiver render -o PATH` writes for
// the same options, through the same writers.
#pragma once

#include <pybind11/pybind11.h>

#include "integrator/framebuffer.h"

namespace quiver {

struct RenderedImage {
  Framebuffer frame;
};

// Adds the class quiver.Image to the module.
void bind_rendered_image(pybind11::module_& module);

}  // namespace quiver
