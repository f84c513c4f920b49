#include "scene/default_scene.h"

#include <cmath>
#include <numbers>

namespace quiver {

namespace {

// A 128 x 64 picture made in memory: rings over a warm-to-cool gradient.
TextureDesc picture_texture() {
  TextureDesc t;
  t.kind = TextureDesc::Kind::image;
  t.width = 128;
  t.height = 64;
  t.wrap = WrapMode::clamp;
  t.rgb.resize(std::size_t(t.width) * std::size_t(t.height) * 3);
  for (int y = 0; y < t.height; ++y) {
    for (int x = 0; x < t.width; ++x) {
      const float u = (float(x) + 0.5f) / float(t.width), v = (float(y) + 0.5f) / float(t.height);
      const float dx = (u - 0.5f) * 2.f, dy = (v - 0.5f);
      const float ring = 0.5f + 0.5f * std::cos(float(std::numbers::pi) * 12.f * std::sqrt(dx * dx + dy * dy));
      float* p = &t.rgb[(std::size_t(y) * std::size_t(t.width) + std::size_t(x)) * 3];
      p[0] = 0.15f + 0.8f * u * ring;
      p[1] = 0.2f + 0.5f * ring * (1.f - v);
      p[2] = 0.25f + 0.7f * (1.f - u) * ring;
    }
  }
  return t;
}

}  // namespace

SceneDesc default_scene() {
  SceneDesc s;
  s.camera = CameraDesc{{0.f, 2.2f, 7.f}, {0.f, 0.9f, 0.f}, {0.f, 1.f, 0.f}, 45.f, 0.f, 640, 480};
  s.background = {0.05f, 0.07f, 0.12f};
  s.ambient = {0.08f, 0.08f, 0.08f};
  s.render.aa = parse_anti_aliasing("adaptive:0.05:2");

  LightDesc key;
  key.position = {5.f, 8.f, 6.f};
  key.color = {0.5f, 0.5f, 0.48f};
  LightDesc fill;
  fill.position = {-6.f, 5.f, 4.f};
  fill.color = {0.18f, 0.2f, 0.26f};
  LightDesc area;
  area.kind = LightDesc::Kind::rectangle;
  area.position = {-1.f, 6.f, -1.f};
  area.edge_u = {2.f, 0.f, 0.f};
  area.edge_v = {0.f, 0.f, 2.f};
  area.color = {0.45f, 0.45f, 0.45f};
  area.samples = 3;
  s.lights = {key, fill, area};

  TextureDesc floor_checks;
  floor_checks.kind = TextureDesc::Kind::checker2d;
  floor_checks.color_a = {0.9f, 0.9f, 0.88f};
  floor_checks.color_b = {0.15f, 0.15f, 0.17f};
  TextureDesc solid_checks;
  solid_checks.kind = TextureDesc::Kind::checker3d;
  solid_checks.color_a = {0.85f, 0.3f, 0.2f};
  solid_checks.color_b = {0.95f, 0.85f, 0.3f};
  solid_checks.scale = 4.f;
  s.textures = {floor_checks, solid_checks, picture_texture()};

  MaterialDesc floor;
  floor.texture = 0;
  floor.ka = 1.f;
  floor.kd = 0.8f;
  floor.ks = 0.1f;
  floor.shininess = 30.f;
  floor.kr = 0.15f;
  MaterialDesc mirror;
  mirror.color = {0.9f, 0.9f, 0.9f};
  mirror.ka = 0.1f;
  mirror.kd = 0.05f;
  mirror.ks = 0.6f;
  mirror.shininess = 200.f;
  mirror.kr = 0.85f;
  MaterialDesc glass;
  glass.color = {0.95f, 1.f, 0.97f};
  glass.ka = 0.f;
  glass.kd = 0.02f;
  glass.ks = 0.5f;
  glass.shininess = 300.f;
  glass.kr = 0.08f;
  glass.kt = 0.9f;
  glass.ior = 1.5f;
  MaterialDesc picture;
  picture.texture = 2;
  picture.ka = 1.f;
  picture.kd = 0.9f;
  MaterialDesc pillar;
  pillar.texture = 1;
  pillar.ka = 1.f;
  pillar.kd = 0.8f;
  pillar.ks = 0.3f;
  pillar.shininess = 40.f;
  s.materials = {floor, mirror, glass, picture, pillar};

  s.planes.push_back({{{0.f, 0.f, 0.f}, {0.f, 1.f, 0.f}}, 0});
  s.spheres.push_back({{{-1.3f, 1.f, 0.f}, 1.f}, 1});
  s.spheres.push_back({{{1.1f, 0.8f, 1.2f}, 0.8f}, 2});
  s.polygons.push_back({{{{0.2f, 0.4f, -2.f}, {2.6f, 0.4f, -2.f}, {2.6f, 2.f, -2.f}, {0.2f, 2.f, -2.f}}}, {}, 3});
  s.cones.push_back({{{-3.2f, 0.f, -1.5f}, 0.5f, {-3.2f, 1.8f, -1.5f}, 0.5f}, 4});
  return s;
}

}  // namespace quiver
