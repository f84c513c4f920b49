// Loads the quiver_assimp module (io/assimp_module.h) on first use: Assimp
// is mapped only by a run that reads a glTF or STL mesh. Where it is
// looked for: io/module_loader.h, with $QUIVER_ASSIMP_MODULE.
#pragma once

#include "io/assimp_module.h"

namespace quiver {

// The module's function table, loaded once per process (thread-safe).
// Throws std::runtime_error naming every path tried when the module cannot
// be loaded; later calls throw the same error.
const AssimpModuleApi& assimp_module();

}  // namespace quiver
