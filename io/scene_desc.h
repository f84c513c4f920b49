// A scene as a reader found it: plain arrays of structs, already checked for
// syntax, finite numbers and sane bounds, with no rendering policy (how NFF
// material numbers become shading is the renderer's choice). Geometric
// degeneracy (zero radius, collinear vertices, ...) is left to the geometry
// builders, which drop and count it.
#pragma once

#include <cstddef>
#include <optional>
#include <vector>

#include "geometry/cone_soa.h"
#include "geometry/polygon_soa.h"
#include "geometry/sphere_soa.h"
#include "simd/vec3.h"

namespace quiver {

// Pinhole camera: eye, look-at point, up hint (any length, not parallel to
// at - from), full field of view between the outermost pixel centres.
struct CameraDesc {
  Vec3<float> from, at, up;
  float angle_degrees;
  float hither;  // near-plane distance as written; a ray tracer may ignore it
  int width, height;
};

// Point light; color is (1, 1, 1) when the file gave none (has_color false).
struct PointLightDesc {
  Vec3<float> position;
  Vec3<float> color;
  bool has_color;
};

// NFF `f` line, as written: colour, diffuse weight, specular (and mirror)
// weight, Phong exponent, transmitted fraction, index of refraction.
struct NffMaterial {
  Vec3<float> color;
  float kd, ks, shine, transmittance, ior;
};

// Primitives refer to materials by index into SceneDesc::materials.
struct SceneSphere {
  SphereDesc sphere;
  std::size_t material;
};

// A polygon; normals holds one shading normal per vertex for an NFF `pp`
// patch and is empty for a plain `p` polygon.
struct ScenePolygon {
  PolygonDesc polygon;
  std::vector<Vec3<float>> normals;
  std::size_t material;
};

struct SceneCone {
  ConeDesc cone;
  std::size_t material;
};

struct SceneDesc {
  std::optional<CameraDesc> camera;
  Vec3<float> background{0.f, 0.f, 0.f};
  std::vector<PointLightDesc> lights;
  std::vector<NffMaterial> materials;
  std::vector<SceneSphere> spheres;
  std::vector<ScenePolygon> polygons;
  std::vector<SceneCone> cones;
};

}  // namespace quiver
