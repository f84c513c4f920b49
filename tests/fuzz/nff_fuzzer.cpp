// libFuzzer target for the NFF reader (io/nff_reader.h). Each input is parsed
// with quiver::parse_nff; quiver::ParseError is the only accepted failure.
// Any other exception, a sanitizer report or a broken invariant below is a
// finding (__builtin_trap, or the uncaught exception's abort).
//
// Invariants on success (io/README.md, io/scene_desc.h):
//   - every float in the SceneDesc is finite;
//   - every primitive's material index < materials.size();
//   - every polygon has 3 .. kMaxPolygonVertices vertices, and its normals are
//     empty (`p`) or one per vertex (`pp`);
//   - colours, Kd, Ks, Shine, T, ior, hither are >= 0; angle in (0, 180);
//     resolution sides in [1, kMaxNffImageSide], at most kMaxNffImagePixels.
// Invariants on ParseError (io/parse_error.h):
//   - what() starts with "fuzz.nff:LINE:COLUMN: expected ", file() is
//     "fuzz.nff", LINE >= 1 names a line of the input (or the empty line after
//     a final newline) and 1 <= COLUMN <= that line's length in bytes + 1.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "io/nff_reader.h"
#include "io/parse_error.h"

namespace {

constexpr std::string_view kFileName = "fuzz.nff";

void check(bool ok) {
  if (!ok) __builtin_trap();
}

bool finite(float x) { return std::isfinite(x); }
bool finite(const quiver::Vec3<float>& v) { return finite(v.x) && finite(v.y) && finite(v.z); }
bool non_negative(const quiver::Vec3<float>& v) { return v.x >= 0.f && v.y >= 0.f && v.z >= 0.f; }

void check_scene(const quiver::SceneDesc& scene) {
  const std::size_t materials = scene.materials.size();
  if (scene.camera) {
    const quiver::CameraDesc& c = *scene.camera;
    check(finite(c.from) && finite(c.at) && finite(c.up));
    check(finite(c.angle_degrees) && c.angle_degrees > 0.f && c.angle_degrees < 180.f);
    check(finite(c.hither) && c.hither >= 0.f);
    check(c.width >= 1 && c.width <= quiver::kMaxNffImageSide);
    check(c.height >= 1 && c.height <= quiver::kMaxNffImageSide);
    check(std::int64_t{c.width} * c.height <= quiver::kMaxNffImagePixels);
    check(!(c.at.x == c.from.x && c.at.y == c.from.y && c.at.z == c.from.z));
  }
  check(finite(scene.background) && non_negative(scene.background));
  for (const quiver::LightDesc& l : scene.lights) {
    check(l.kind == quiver::LightDesc::Kind::point);
    check(finite(l.position) && finite(l.color) && non_negative(l.color));
  }
  check(finite(scene.ambient) && non_negative(scene.ambient));
  for (const quiver::MaterialDesc& m : scene.materials) {
    check(finite(m.color) && non_negative(m.color));
    for (float x : {m.ka, m.kd, m.ks, m.shininess, m.kr, m.kt}) check(finite(x) && x >= 0.f);
    check(finite(m.ior) && m.ior > 0.f);
    check(m.two_sided == (m.kt > 0.f));
  }
  for (const quiver::SceneSphere& s : scene.spheres) {
    check(finite(s.sphere.center) && finite(s.sphere.radius));
    check(s.material < materials);
  }
  for (const quiver::SceneCone& c : scene.cones) {
    check(finite(c.cone.base) && finite(c.cone.base_radius));
    check(finite(c.cone.apex) && finite(c.cone.apex_radius));
    check(c.material < materials);
  }
  for (const quiver::ScenePolygon& p : scene.polygons) {
    const std::size_t n = p.polygon.vertices.size();
    check(n >= 3 && n <= quiver::kMaxPolygonVertices);
    check(p.normals.empty() || p.normals.size() == n);
    for (const auto& v : p.polygon.vertices) check(finite(v));
    for (const auto& v : p.normals) check(finite(v));
    check(p.material < materials);
  }
}

// Parses "LINE:COLUMN: expected " after the file name; false if malformed.
bool position_in_message(std::string_view what, std::size_t& line, std::size_t& column) {
  auto read_number = [&what](std::size_t& value) {
    std::size_t digits = 0;
    value = 0;
    while (digits < what.size() && what[digits] >= '0' && what[digits] <= '9' && digits < 19) {
      value = value * 10 + static_cast<std::size_t>(what[digits] - '0');
      ++digits;
    }
    what.remove_prefix(digits);
    return digits > 0;
  };
  if (!what.starts_with(kFileName) || what.substr(kFileName.size(), 1) != ":") return false;
  what.remove_prefix(kFileName.size() + 1);
  if (!read_number(line) || !what.starts_with(":")) return false;
  what.remove_prefix(1);
  if (!read_number(column)) return false;
  return what.starts_with(": expected ");
}

void check_error(const quiver::ParseError& error, std::string_view text) {
  check(error.file() == kFileName);
  // Whole-file errors (line 0) only come from inputs over kMaxNffBytes, far
  // beyond any fuzz input.
  std::size_t line = 0, column = 0;
  check(position_in_message(error.what(), line, column));
  check(line == error.line() && column == error.column());
  check(line >= 1 && column >= 1);
  // Find line `line` (1-based, split at '\n'); one past the last line is the
  // empty line after a final newline.
  std::size_t start = 0;
  for (std::size_t i = 1; i < line; ++i) {
    const std::size_t newline = text.find('\n', start);
    check(newline != std::string_view::npos);
    start = newline + 1;
  }
  const std::size_t newline = text.find('\n', start);
  const std::size_t length = (newline == std::string_view::npos ? text.size() : newline) - start;
  check(column <= length + 1);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    const quiver::SceneDesc scene = quiver::parse_nff(text, kFileName);
    check_scene(scene);
  } catch (const quiver::ParseError& error) {
    check_error(error, text);
  }
  return 0;
}
