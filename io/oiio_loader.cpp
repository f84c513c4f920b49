// dlopen of the quiver_oiio module, tried at each candidate path in turn.
#include "io/oiio_loader.h"

#include <dlfcn.h>

#include <cstdlib>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

namespace quiver {

namespace {

namespace fs = std::filesystem;

// Candidate paths of the module file, in the order they are tried.
std::vector<fs::path> module_candidates() {
  if (const char* chosen = std::getenv("QUIVER_OIIO_MODULE"); chosen != nullptr && *chosen != '\0') {
    return {fs::path(chosen)};
  }
  std::vector<fs::path> candidates;
  std::error_code error;
  const fs::path executable = fs::read_symlink("/proc/self/exe", error);
  if (!error) {
    candidates.push_back(executable.parent_path() / kOiioModuleFileName);
    candidates.push_back(executable.parent_path() / QUIVER_OIIO_MODULE_FROM_BINDIR / kOiioModuleFileName);
  }
  candidates.push_back(fs::path(QUIVER_OIIO_MODULE_INSTALL_DIR) / kOiioModuleFileName);
  candidates.push_back(fs::path(QUIVER_OIIO_MODULE_BUILD_DIR) / kOiioModuleFileName);
  return candidates;
}

// One line of the failure report: the candidate and why it failed. The
// dynamic loader's messages mostly name the file already.
std::string failure_line(const fs::path& candidate, const std::string& reason) {
  const bool names_file = reason.rfind(candidate.string() + ":", 0) == 0;
  return "\n  " + (names_file ? reason : candidate.string() + ": " + reason);
}

// The dynamic loader's message for the last failure.
std::string loader_error() {
  const char* message = ::dlerror();
  return message != nullptr ? message : "unknown error";
}

// Loads the first candidate that opens; on failure the error lists all.
const OiioModuleApi* load_module(std::string& failure) {
  std::string tried;
  for (const fs::path& candidate : module_candidates()) {
    // Lazy binding, as when the program linked OpenImageIO: binding every
    // symbol of its ~260 libraries up front costs ~35 ms more.
    void* library = ::dlopen(candidate.c_str(), RTLD_LAZY | RTLD_LOCAL);
    if (library == nullptr) {
      tried += failure_line(candidate, loader_error());
      continue;
    }
    // Never closed: OpenImageIO stays mapped until the process ends.
    using Entry = const OiioModuleApi* (*)();
    auto entry = reinterpret_cast<Entry>(::dlsym(library, kOiioModuleEntry));
    if (entry == nullptr) {
      tried += failure_line(candidate, loader_error());
      continue;
    }
    const OiioModuleApi* api = entry();
    if (api == nullptr || api->version != kOiioModuleVersion) {
      tried += failure_line(candidate, "a module of another quiver version");
      continue;
    }
    return api;
  }
  failure = "cannot load quiver's OpenImageIO module (" + std::string(kOiioModuleFileName) +
            "; needed for JPEG, HDR and TIFF images and for texture files); tried:" + tried;
  return nullptr;
}

}  // namespace

const OiioModuleApi& oiio_module() {
  static std::string failure;
  static const OiioModuleApi* const api = load_module(failure);
  if (api == nullptr) throw std::runtime_error(failure);
  return *api;
}

}  // namespace quiver
