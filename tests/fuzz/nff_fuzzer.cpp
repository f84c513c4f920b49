// libFuzzer target for the NFF reader (io/nff_reader.h). Each input is parsed
// with quiver::parse_nff; quiver::ParseError is the only accepted failure.
// Any other exception, a sanitizer report or a broken invariant below is a
// finding (__builtin_trap, or the uncaught exception's abort).
//
// Invariants on success (io/README.md, scene/scene_desc.h):
//   - every float in the SceneDesc is finite;
//   - every primitive's material index < materials.size();
//   - every polygon has 3 .. kMaxPolygonVertices vertices, and its normals are
//     empty (`p`) or one per vertex (`pp`);
//   - colours, Kd, Ks, Shine, T, ior, hither are >= 0; angle in (0, 180);
//     resolution sides in [1, kMaxImageSide], at most kMaxImagePixels.
// Invariants on ParseError (io/parse_error.h):
//   - what() starts with "fuzz.nff:LINE:COLUMN: expected ", file() is
//     "fuzz.nff", LINE >= 1 names a line of the input (or the empty line after
//     a final newline) and 1 <= COLUMN <= that line's length in bytes + 1.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "io/nff_reader.h"
#include "io/parse_error.h"
#include "tests/fuzz/scene_invariants.h"

namespace {

constexpr std::string_view kFileName = "fuzz.nff";

// The shared invariants, plus what NFF's mapping promises: point lights
// only, and two-sided exactly where T > 0.
void check_nff_scene(const quiver::SceneDesc& scene) {
  quiver::fuzz::check_scene(scene);
  for (const quiver::LightDesc& l : scene.lights) quiver::fuzz::check(l.kind == quiver::LightDesc::Kind::point);
  for (const quiver::MaterialDesc& m : scene.materials) quiver::fuzz::check(m.two_sided == (m.kt > 0.f));
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    check_nff_scene(quiver::parse_nff(text, kFileName));
  } catch (const quiver::ParseError& error) {
    // Whole-file errors (line 0) only come from inputs over kMaxNffBytes, far
    // beyond any fuzz input; NFF lines end at '\n' (a '\r' before it is a blank).
    quiver::fuzz::check(error.file() == kFileName);
    quiver::fuzz::check_error_position(error, text, false);
  }
  return 0;
}
