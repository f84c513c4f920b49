// libFuzzer target for the TOML scene reader (io/toml_reader.h). Each input
// is parsed with quiver::parse_toml_scene against io/examples
// (QUIVER_FUZZ_FILES_DIR), so "octahedron.obj" and "gradient.png" (in the
// dictionary) name files that exist and mesh includes run too.
// quiver::ParseError is the only accepted failure; any other exception, a
// sanitizer report or a broken invariant (tests/fuzz/scene_invariants.h)
// is a finding.
//
// Invariants: on success, those of check_scene (finite numbers, indices in
// range, the documented bounds); on a ParseError about fuzz.toml, a
// position "fuzz.toml:LINE:COLUMN: expected " naming a line of the input
// ('\n' ends lines) and a byte column at most one past its end. Errors in
// an included mesh name that file and are accepted as they are.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "io/parse_error.h"
#include "io/toml_reader.h"
#include "scene_invariants.h"

namespace {

constexpr std::string_view kFileName = "fuzz.toml";

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    const quiver::SceneDesc scene = quiver::parse_toml_scene(text, kFileName, QUIVER_FUZZ_FILES_DIR);
    quiver::fuzz::check_scene(scene);
  } catch (const quiver::ParseError& error) {
    if (error.file() == kFileName) quiver::fuzz::check_error_position(error, text, false);
  }
  return 0;
}
