// A test scene: a fine checker floor running to the horizon, lit by the
// ambient term alone; with `mirror`, a mirror wall across the view (tilted
// a little down) shows the floor behind the camera at grazing angles, so
// its footprint comes from differentials carried through a reflection.
#pragma once

#include "scene/scene_desc.h"

namespace quiver::testing {

inline SceneDesc checker_floor(bool mirror, int width = 96, int height = 54) {
  SceneDesc s;
  s.camera = CameraDesc{{0.f, 1.f, 4.f}, {0.f, 0.6f, -10.f}, {0.f, 1.f, 0.f}, 40.f, 0.f, width, height};
  s.background = {1.f, 1.f, 1.f};
  s.ambient = {1.f, 1.f, 1.f};
  TextureDesc checks;
  checks.kind = TextureDesc::Kind::checker2d;
  checks.scale = 2.f;
  s.textures.push_back(checks);
  MaterialDesc floor;
  floor.ka = 1.f;
  floor.kd = floor.ks = 0.f;
  floor.texture = 0;
  s.materials.push_back(floor);
  s.planes.push_back({{{0.f, 0.f, 0.f}, {0.f, 1.f, 0.f}}, 0});
  if (mirror) {
    MaterialDesc wall;
    wall.ka = wall.kd = wall.ks = 0.f;
    wall.kr = 1.f;
    s.materials.push_back(wall);
    s.planes.push_back({{{0.f, 0.f, -3.f}, {0.f, -0.05f, 1.f}}, 1});
  }
  return s;
}

}  // namespace quiver::testing
