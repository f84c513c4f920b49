// Loads the quiver_oiio module (io/oiio_module.h) on first use: OpenImageIO
// is mapped only by a run that reads a texture image or writes JPEG, HDR or
// TIFF. Where it is looked for: io/module_loader.h, with $QUIVER_OIIO_MODULE.
#pragma once

#include "io/oiio_module.h"

namespace quiver {

// The module's function table, loaded once per process (thread-safe).
// Throws std::runtime_error naming every path tried and the loader's
// message for each when the module cannot be loaded or is of another
// version; later calls throw the same error.
const OiioModuleApi& oiio_module();

}  // namespace quiver
