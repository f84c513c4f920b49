// The quiver_oiio module through io/module_loader.h.
#include "io/oiio_loader.h"

#include <stdexcept>

#include "io/module_loader.h"

namespace quiver {

const OiioModuleApi& oiio_module() {
  static const LoadedModule module =
      load_module({"OpenImageIO", kOiioModuleFileName, "QUIVER_OIIO_MODULE", kOiioModuleEntry, kOiioModuleVersion,
                   "JPEG, HDR and TIFF images and for texture files"});
  if (module.table == nullptr) throw std::runtime_error(module.failure);
  return *static_cast<const OiioModuleApi*>(module.table);
}

}  // namespace quiver
