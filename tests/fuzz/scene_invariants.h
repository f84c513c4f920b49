// Checks shared by the NFF, TOML and OBJ fuzz targets: the invariants every
// SceneDesc a reader returns must hold (scene/scene_desc.h, io/README.md), and
// the shape of a positioned ParseError. A broken invariant traps.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "io/nff_reader.h"
#include "io/parse_error.h"
#include "scene/scene_desc.h"

namespace quiver::fuzz {

inline void check(bool ok) {
  if (!ok) __builtin_trap();
}

inline bool finite(float x) { return std::isfinite(x); }
inline bool finite(const Vec3<float>& v) { return finite(v.x) && finite(v.y) && finite(v.z); }
inline bool non_negative(const Vec3<float>& v) { return v.x >= 0.f && v.y >= 0.f && v.z >= 0.f; }
inline bool is_zero(const Vec3<float>& v) { return v.x == 0.f && v.y == 0.f && v.z == 0.f; }

// Every number finite, every index in range, every documented bound held.
inline void check_scene(const SceneDesc& scene) {
  const std::size_t materials = scene.materials.size();
  if (scene.camera) {
    const CameraDesc& c = *scene.camera;
    check(finite(c.from) && finite(c.at) && finite(c.up));
    check(finite(c.angle_degrees) && c.angle_degrees > 0.f && c.angle_degrees < 180.f);
    check(finite(c.hither) && c.hither >= 0.f);
    check(c.width >= 1 && c.width <= kMaxImageSide && c.height >= 1 && c.height <= kMaxImageSide);
    check(std::int64_t{c.width} * c.height <= kMaxImagePixels);
    check(!(c.at.x == c.from.x && c.at.y == c.from.y && c.at.z == c.from.z));
  }
  if (scene.background) check(finite(*scene.background) && non_negative(*scene.background));
  check(finite(scene.ambient) && non_negative(scene.ambient));
  for (const LightDesc& l : scene.lights) {
    check(finite(l.position) && finite(l.direction) && finite(l.edge_u) && finite(l.edge_v));
    check(finite(l.color) && non_negative(l.color));
    check(finite(l.radius) && l.radius > 0.f);
    check(l.samples >= 1 && l.samples <= 64);
    if (l.kind == LightDesc::Kind::directional || l.kind == LightDesc::Kind::spot) check(!is_zero(l.direction));
    if (l.kind == LightDesc::Kind::spot) {
      check(l.cone_outer_cos >= 0.f && l.cone_outer_cos <= l.cone_inner_cos && l.cone_inner_cos <= 1.f);
    }
    if (l.kind == LightDesc::Kind::rectangle) check(!is_zero(l.edge_u) && !is_zero(l.edge_v));
  }
  for (const TextureDesc& t : scene.textures) {
    check(finite(t.color_a) && non_negative(t.color_a) && finite(t.color_b) && non_negative(t.color_b));
    check(finite(t.scale) && t.scale > 0.f);
    if (t.kind == TextureDesc::Kind::image) check(!t.path.empty());
  }
  for (const MaterialDesc& m : scene.materials) {
    check(finite(m.color) && non_negative(m.color));
    for (float x : {m.ka, m.kd, m.ks, m.shininess, m.kr, m.kt}) check(finite(x) && x >= 0.f);
    check(finite(m.ior) && m.ior > 0.f);
    if (m.texture) check(*m.texture < scene.textures.size());
  }
  if (scene.render.aa) check(to_string(parse_anti_aliasing(to_string(*scene.render.aa))) == to_string(*scene.render.aa));
  if (scene.render.max_depth) check(valid_max_depth(*scene.render.max_depth));
  if (scene.render.min_weight) check(valid_min_weight(*scene.render.min_weight));
  for (const SceneSphere& s : scene.spheres) {
    check(finite(s.sphere.center) && finite(s.sphere.radius) && s.material < materials);
  }
  for (const ScenePlane& p : scene.planes) {
    check(finite(p.plane.point) && finite(p.plane.normal) && !is_zero(p.plane.normal) && p.material < materials);
  }
  const auto check_triangle = [&](const SceneTriangle& t) {
    for (const Vec3<float>& p : t.triangle.p) check(finite(p));
    if (t.triangle.normals) {
      for (const Vec3<float>& n : *t.triangle.normals) check(finite(n));
    }
    if (t.triangle.uvs) {
      for (const auto& uv : *t.triangle.uvs) check(finite(uv[0]) && finite(uv[1]));
    }
    check(t.material < materials);
  };
  for (const SceneTriangle& t : scene.triangles) check_triangle(t);
  for (const SceneMesh& m : scene.meshes) {
    for (const SceneTriangle& t : m.triangles) check_triangle(t);
  }
  for (const SceneInstance& i : scene.instances) {
    check(i.mesh < scene.meshes.size());
    for (float x : i.object_to_world.m) check(finite(x));
    check(inverse(i.object_to_world).has_value());
  }
  for (const ScenePolygon& p : scene.polygons) {
    const std::size_t n = p.polygon.vertices.size();
    check(n >= 3 && n <= kMaxPolygonVertices);
    check(p.normals.empty() || p.normals.size() == n);
    for (const Vec3<float>& v : p.polygon.vertices) check(finite(v));
    for (const Vec3<float>& v : p.normals) check(finite(v));
    check(p.material < materials);
  }
  for (const SceneCone& c : scene.cones) {
    check(finite(c.cone.base) && finite(c.cone.apex) && finite(c.cone.base_radius) && finite(c.cone.apex_radius));
    check(c.material < materials);
  }
}

// Parses "NAME:LINE:COLUMN: expected " at the start of what; false if malformed.
inline bool position_in_message(std::string_view what, std::string_view name, std::size_t& line, std::size_t& column) {
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
  if (!what.starts_with(name) || what.substr(name.size(), 1) != ":") return false;
  what.remove_prefix(name.size() + 1);
  if (!read_number(line) || !what.starts_with(":")) return false;
  what.remove_prefix(1);
  if (!read_number(column)) return false;
  return what.starts_with(": expected ");
}

// A positioned error names a line of `text` (or the empty line after a
// final line end) and a byte column at most one past that line's end.
// `line_ends` splits lines: "\n" only (TOML) or also "\r\n" and a lone "\r"
// (OBJ and MTL).
inline void check_error_position(const ParseError& error, std::string_view text, bool cr_ends_lines) {
  std::size_t line = 0, column = 0;
  check(position_in_message(error.what(), error.file(), line, column));
  check(line == error.line() && column == error.column());
  check(line >= 1 && column >= 1);
  std::size_t start = 0;
  auto line_end = [&](std::size_t from) {
    std::size_t i = from;
    while (i < text.size() && text[i] != '\n' && !(cr_ends_lines && text[i] == '\r')) ++i;
    return i;
  };
  auto next_start = [&](std::size_t end) {
    if (end < text.size() && text[end] == '\r' && end + 1 < text.size() && text[end + 1] == '\n') return end + 2;
    return end + 1;
  };
  for (std::size_t i = 1; i < line; ++i) {
    const std::size_t end = line_end(start);
    check(end < text.size());
    start = next_start(end);
  }
  check(column <= line_end(start) - start + 1);
}

}  // namespace quiver::fuzz
