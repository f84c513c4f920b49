// Loads one of quiver's optional shared modules (quiver_oiio.so for
// OpenImageIO, quiver_assimp.so for Assimp) with dlopen, so that a run
// which needs neither never maps those libraries and their dependencies.
// A module exports one C function returning a table of plain functions
// whose first member is an int version. It is looked for, in order: at
// $<path_variable> alone when that is set; beside the running executable
// (the build tree's bin/); in <executable>/../<libdir>/quiver (an
// installed tree); in the configured install directory; in the build
// directory.
#pragma once

#include <string>

namespace quiver {

struct ModuleSpec {
  const char* library;        // "OpenImageIO", for the error
  const char* file_name;      // "quiver_oiio.so"
  const char* path_variable;  // "QUIVER_OIIO_MODULE"
  const char* entry;          // the exported function's name
  int version;                // the table's first member must equal it
  const char* needed_for;     // for the error: "needed for ..."
};

// The module's table, or null with `failure` naming every path tried and
// the loader's message for each. The library stays mapped until the
// process ends.
struct LoadedModule {
  const void* table = nullptr;
  std::string failure;
};
LoadedModule load_module(const ModuleSpec& spec);

}  // namespace quiver
