// The quiver_assimp module through io/module_loader.h.
#include "io/assimp_loader.h"

#include <stdexcept>

#include "io/module_loader.h"

namespace quiver {

const AssimpModuleApi& assimp_module() {
  static const LoadedModule module =
      load_module({"Assimp", kAssimpModuleFileName, "QUIVER_ASSIMP_MODULE", kAssimpModuleEntry, kAssimpModuleVersion,
                   "glTF and ASCII STL meshes"});
  if (module.table == nullptr) throw std::runtime_error(module.failure);
  return *static_cast<const AssimpModuleApi*>(module.table);
}

}  // namespace quiver
