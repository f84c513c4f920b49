#include "scene/auto_view.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

#include "scene/camera_frame.h"

namespace quiver {

namespace {

// Axis-aligned bounds in double of the points fed to it (finite ones only).
struct Bounds {
  double lo[3] = {std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
                  std::numeric_limits<double>::infinity()};
  double hi[3] = {-std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(),
                  -std::numeric_limits<double>::infinity()};

  void add(const Vec3<float>& p, double margin = 0.0) {
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z) || !std::isfinite(margin)) return;
    for (int a = 0; a < 3; ++a) {
      lo[a] = std::min(lo[a], double(p[a]) - margin);
      hi[a] = std::max(hi[a], double(p[a]) + margin);
    }
  }
  bool empty() const { return lo[0] > hi[0]; }
};

Bounds scene_bounds(const SceneDesc& scene) {
  Bounds b;
  for (const SceneSphere& s : scene.spheres) b.add(s.sphere.center, std::fabs(double(s.sphere.radius)));
  for (const ScenePlane& p : scene.planes) b.add(p.plane.point);
  for (const SceneTriangle& t : scene.triangles) {
    for (const Vec3<float>& p : t.triangle.p) b.add(p);
  }
  for (const ScenePolygon& p : scene.polygons) {
    for (const Vec3<float>& v : p.polygon.vertices) b.add(v);
  }
  for (const SceneCone& c : scene.cones) {
    const double r = std::max(std::fabs(double(c.cone.base_radius)), std::fabs(double(c.cone.apex_radius)));
    b.add(c.cone.base, r);
    b.add(c.cone.apex, r);
  }
  return b;
}

double length(const double v[3]) { return std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]); }

Vec3<float> to_float(const double v[3]) {
  return {static_cast<float>(v[0]), static_cast<float>(v[1]), static_cast<float>(v[2])};
}

}  // namespace

void add_default_view(SceneDesc& scene, int width, int height) {
  if (width < 1 || height < 1 || width > kMaxImageSide || height > kMaxImageSide) {
    throw std::invalid_argument("add_default_view: width and height must lie in [1, 65536]");
  }
  // Bounding sphere of the primitives' box (the unit sphere when there is none).
  const Bounds bounds = scene_bounds(scene);
  double center[3] = {0.0, 0.0, 0.0};
  double radius = 1.0;
  if (!bounds.empty()) {
    double squared = 0.0;
    for (int a = 0; a < 3; ++a) {
      center[a] = 0.5 * bounds.lo[a] + 0.5 * bounds.hi[a];
      const double half = 0.5 * bounds.hi[a] - 0.5 * bounds.lo[a];
      squared += half * half;
    }
    radius = std::sqrt(squared);
    if (!(radius > 0.0)) radius = 1.0;  // a single point
  }

  // Three-quarter view: 35 degrees round from +z towards +x, 25 degrees up.
  const double azimuth = 35.0 * std::numbers::pi / 180.0, elevation = 25.0 * std::numbers::pi / 180.0;
  const double toward_eye[3] = {std::sin(azimuth) * std::cos(elevation), std::sin(elevation),
                                std::cos(azimuth) * std::cos(elevation)};
  // Tangent of the half field of view across the shorter side (CameraDesc:
  // the angle spans the outermost pixel centres of the longer side).
  const int longer = std::max(width, height), shorter = std::min(width, height);
  const double half_angle = double(kDefaultViewAngleDegrees) * std::numbers::pi / 360.0;
  const double tangent = std::tan(half_angle) * double(std::max(shorter - 1, 1)) / double(std::max(longer - 1, 1));
  // The sphere fits a cone of that half-angle at distance r / sin(angle); 10% margin.
  const double distance = 1.1 * radius * std::sqrt(1.0 + tangent * tangent) / tangent;

  double eye[3];
  for (int a = 0; a < 3; ++a) eye[a] = center[a] + distance * toward_eye[a];
  if (!scene.camera) {
    CameraDesc camera{};
    camera.from = to_float(eye);
    camera.at = to_float(center);
    camera.up = {0.f, 1.f, 0.f};
    camera.angle_degrees = kDefaultViewAngleDegrees;
    camera.hither = 0.f;
    camera.width = width;
    camera.height = height;
    scene.camera = camera;
  }
  if (scene.lights.empty()) {
    // Above and to the right of the scene's camera, half the view distance away.
    const CameraDesc& c = *scene.camera;
    double to_target[3];
    for (int a = 0; a < 3; ++a) to_target[a] = double(c.at[a]) - double(c.from[a]);
    const double view_distance = length(to_target);
    const CameraFrame frame = camera_frame(c);
    double position[3];
    for (int a = 0; a < 3; ++a) {
      position[a] = double(c.from[a]) + 0.5 * view_distance * (frame.right[a] + frame.up[a]);
    }
    const float largest_ambient = std::max({scene.ambient.x, scene.ambient.y, scene.ambient.z});
    if (largest_ambient == 0.f) scene.ambient = {0.1f, 0.1f, 0.1f};
    const float intensity = std::max(0.3f, 1.f - std::max(largest_ambient, 0.1f));
    LightDesc light;
    light.kind = LightDesc::Kind::point;
    light.position = to_float(position);
    light.color = {intensity, intensity, intensity};
    scene.lights.push_back(light);
  }
}

}  // namespace quiver
