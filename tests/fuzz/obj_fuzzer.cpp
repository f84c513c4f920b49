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
// finding too. OBJ text without '\r' (read in parallel chunks) and the same
// text with "\r\n" line ends (scanned line by line) give the same outcome:
// the same triangles, materials and warnings, or the same error.
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <optional>
#include <string>
#include <string_view>
#include <variant>

#include "io/obj_reader.h"
#include "io/parse_error.h"
#include "scene_invariants.h"

namespace {

constexpr std::string_view kFileName = "fuzz.obj";
constexpr std::string_view kMtlFileName = "fuzz.mtl";

// The scene, or the error's message.
using Outcome = std::variant<quiver::SceneDesc, std::string>;

Outcome read(std::string_view obj, const quiver::MtlLookup& find_library) {
  try {
    return quiver::parse_obj_scene(obj, kFileName, find_library);
  } catch (const quiver::ParseError& error) {
    return std::string(error.what());
  }
}

bool same_bits(const quiver::Vec3<float>& a, const quiver::Vec3<float>& b) { return std::memcmp(&a, &b, sizeof a) == 0; }

bool same_outcome(const Outcome& a, const Outcome& b) {
  if (a.index() != b.index()) return false;
  if (a.index() == 1) return std::get<1>(a) == std::get<1>(b);
  const quiver::SceneDesc& x = std::get<0>(a);
  const quiver::SceneDesc& y = std::get<0>(b);
  if (x.triangles.size() != y.triangles.size() || x.materials.size() != y.materials.size() ||
      x.textures.size() != y.textures.size() || x.warnings != y.warnings) {
    return false;
  }
  for (std::size_t i = 0; i < x.triangles.size(); ++i) {
    const quiver::TriangleDesc& s = x.triangles[i].triangle;
    const quiver::TriangleDesc& t = y.triangles[i].triangle;
    if (x.triangles[i].material != y.triangles[i].material || s.normals.has_value() != t.normals.has_value() ||
        s.uvs != t.uvs) {
      return false;
    }
    for (int k = 0; k < 3; ++k) {
      if (!same_bits(s.p[k], t.p[k]) || (s.normals && !same_bits((*s.normals)[k], (*t.normals)[k]))) return false;
    }
  }
  return true;
}

std::string with_crlf(std::string_view text) {
  std::string crlf;
  for (const char c : text) {
    if (c == '\n') crlf += '\r';
    crlf += c;
  }
  return crlf;
}

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
  if (obj.find('\r') == std::string_view::npos) {
    check(same_outcome(read(obj, find_library), read(with_crlf(obj), find_library)));
  }
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
