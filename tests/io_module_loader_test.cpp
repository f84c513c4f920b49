// Tests of io/module_loader.h with the OpenImageIO module the build puts
// beside the test program: an empty path variable counts as unset, and a
// module whose version is not the one asked for, older or newer, is refused.
#include "io/module_loader.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <optional>
#include <string>

#include "io/oiio_module.h"

namespace quiver {
namespace {

ModuleSpec oiio_spec(int version) {
  return {"OpenImageIO", kOiioModuleFileName, "QUIVER_OIIO_MODULE", kOiioModuleEntry, version, "the test"};
}

// Sets an environment variable for the test's scope, restoring it after.
class ScopedVariable {
 public:
  ScopedVariable(const char* name, const char* value) : name_(name) {
    if (const char* old = std::getenv(name)) old_ = old;
    ::setenv(name, value, 1);
  }
  ~ScopedVariable() {
    if (old_) {
      ::setenv(name_, old_->c_str(), 1);
    } else {
      ::unsetenv(name_);
    }
  }

 private:
  const char* name_;
  std::optional<std::string> old_;
};

TEST(ModuleLoader, AnEmptyPathVariableIsUnset) {
  const ScopedVariable empty("QUIVER_OIIO_MODULE", "");
  const LoadedModule loaded = load_module(oiio_spec(kOiioModuleVersion));
  EXPECT_NE(loaded.table, nullptr) << loaded.failure;
}

TEST(ModuleLoader, AModuleOfAnotherVersionOlderOrNewerIsRefused) {
  ASSERT_NE(load_module(oiio_spec(kOiioModuleVersion)).table, nullptr);
  for (const int asked : {kOiioModuleVersion - 1, kOiioModuleVersion + 1}) {
    const LoadedModule loaded = load_module(oiio_spec(asked));
    EXPECT_EQ(loaded.table, nullptr) << "asked for version " << asked;
    EXPECT_NE(loaded.failure.find("a module of another quiver version"), std::string::npos) << loaded.failure;
  }
}

}  // namespace
}  // namespace quiver
