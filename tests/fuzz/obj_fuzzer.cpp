// libFuzzer target for the OBJ/MTL reader (io/obj_reader.h). An input is
// OBJ text, optionally followed by a NUL byte and MTL text; every `mtllib`
// name finds that MTL text (as fuzz.mtl), and relative texture paths are
// looked up in tests/data/obj (QUIVER_FUZZ_FILES_DIR, holding
// tex/checker.png, which the seed materials.mtl names).
// quiver::ParseError is the only accepted failure; any other exception, a
// sanitizer report or a broken invariant (tests/fuzz/scene_invariants.h)
// is a finding.
//
// Invariants: on success, those of check_scene plus: no camera and no
// lights, kt in [0, 1], every texture an image; on a ParseError, a
// position "FILE:LINE:COLUMN: expected " in the OBJ text (fuzz.obj) or the
// MTL text (fuzz.mtl), lines ending at "\n", "\r\n" or a lone "\r". A
// whole-file error (line 0) cannot come from text in memory and is a
// finding too.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "io/obj_reader.h"
#include "io/parse_error.h"
#include "scene_invariants.h"

namespace {

constexpr std::string_view kFileName = "fuzz.obj";
constexpr std::string_view kMtlFileName = "fuzz.mtl";

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view input(reinterpret_cast<const char*>(data), size);
  const std::size_t split = input.find('\0');
  const std::string_view obj = input.substr(0, split);
  const std::string_view mtl = split == std::string_view::npos ? std::string_view() : input.substr(split + 1);
  const quiver::MtlLookup find_library = [mtl](std::string_view) -> std::optional<quiver::MtlLibrary> {
    return quiver::MtlLibrary{std::string(mtl), std::string(kMtlFileName), QUIVER_FUZZ_FILES_DIR, {}};
  };
  using quiver::fuzz::check;
  try {
    const quiver::SceneDesc scene = quiver::parse_obj_scene(obj, kFileName, find_library);
    quiver::fuzz::check_scene(scene);
    check(!scene.camera && scene.lights.empty());
    for (const quiver::MaterialDesc& m : scene.materials) check(m.kt <= 1.f);
    for (const quiver::TextureDesc& t : scene.textures) check(t.kind == quiver::TextureDesc::Kind::image);
  } catch (const quiver::ParseError& error) {
    check(error.line() >= 1 && (error.file() == kFileName || error.file() == kMtlFileName));
    quiver::fuzz::check_error_position(error, error.file() == kFileName ? obj : mtl, true);
  }
  return 0;
}
