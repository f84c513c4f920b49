// dlopen of a quiver module, tried at each candidate path in turn.
#include "io/module_loader.h"

#include <dlfcn.h>

#include <cstdlib>
#include <filesystem>
#include <vector>

namespace quiver {

namespace {

namespace fs = std::filesystem;

// Candidate paths of the module file, in the order they are tried.
std::vector<fs::path> module_candidates(const ModuleSpec& spec) {
  if (const char* chosen = std::getenv(spec.path_variable); chosen != nullptr && *chosen != '\0') {
    return {fs::path(chosen)};
  }
  std::vector<fs::path> candidates;
  std::error_code error;
  const fs::path executable = fs::read_symlink("/proc/self/exe", error);
  if (!error) {
    candidates.push_back(executable.parent_path() / spec.file_name);
    candidates.push_back(executable.parent_path() / QUIVER_MODULE_FROM_BINDIR / spec.file_name);
  }
  candidates.push_back(fs::path(QUIVER_MODULE_INSTALL_DIR) / spec.file_name);
  candidates.push_back(fs::path(QUIVER_MODULE_BUILD_DIR) / spec.file_name);
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

}  // namespace

LoadedModule load_module(const ModuleSpec& spec) {
  std::string tried;
  for (const fs::path& candidate : module_candidates(spec)) {
    // Lazy binding, as when the program linked the library: binding every
    // symbol of OpenImageIO's ~260 libraries up front costs ~35 ms more.
    void* library = ::dlopen(candidate.c_str(), RTLD_LAZY | RTLD_LOCAL);
    if (library == nullptr) {
      tried += failure_line(candidate, loader_error());
      continue;
    }
    using Entry = const void* (*)();
    auto entry = reinterpret_cast<Entry>(::dlsym(library, spec.entry));
    if (entry == nullptr) {
      tried += failure_line(candidate, loader_error());
      continue;
    }
    const void* table = entry();
    if (table == nullptr || *static_cast<const int*>(table) != spec.version) {
      tried += failure_line(candidate, "a module of another quiver version");
      continue;
    }
    return {table, {}};
  }
  return {nullptr, "cannot load quiver's " + std::string(spec.library) + " module (" + spec.file_name +
                       "; needed for " + spec.needed_for + "); tried:" + tried};
}

}  // namespace quiver
