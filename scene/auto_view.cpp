#include "scene/auto_view.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <string>
#include <type_traits>

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
  for_each_kind([&]<class K>(K) {
    for (const auto& entry : scene.*SceneEntries<K>::of) {
      K::extent(entry.*SceneEntries<K>::desc, [&](const Vec3<float>& p, double margin) { b.add(p, margin); });
    }
  });
  // Instances: the corners of their mesh's box, placed.
  std::vector<Bounds> mesh_bounds(scene.meshes.size());
  for (std::size_t m = 0; m < scene.meshes.size(); ++m) {
    for (const SceneTriangle& t : scene.meshes[m].triangles) {
      for (const Vec3<float>& p : t.triangle.p) mesh_bounds[m].add(p);
    }
  }
  for (const SceneInstance& instance : scene.instances) {
    if (instance.mesh >= mesh_bounds.size() || mesh_bounds[instance.mesh].empty()) continue;
    const Bounds& m = mesh_bounds[instance.mesh];
    for (int corner = 0; corner < 8; ++corner) {
      const Vec3<float> p{static_cast<float>(corner & 1 ? m.hi[0] : m.lo[0]),
                          static_cast<float>(corner & 2 ? m.hi[1] : m.lo[1]),
                          static_cast<float>(corner & 4 ? m.hi[2] : m.lo[2])};
      b.add(apply_point(instance.object_to_world, p));
    }
  }
  return b;
}

double length(const double v[3]) { return std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]); }

Vec3<float> to_float(const double v[3]) {
  return {static_cast<float>(v[0]), static_cast<float>(v[1]), static_cast<float>(v[2])};
}

Vec3<double> to_double(const Vec3<float>& v) { return {double(v.x), double(v.y), double(v.z)}; }

Vec3<double> unit(const Vec3<double>& v) { return v * (1.0 / std::sqrt(dot(v, v))); }

// A triangle's corners in double and its normal scaled by twice its area.
struct TriangleArea {
  Vec3<double> a, b, c, n;
  explicit TriangleArea(const SceneTriangle& t)
      : a(to_double(t.triangle.p[0])), b(to_double(t.triangle.p[1])), c(to_double(t.triangle.p[2])),
        n(cross(b - a, c - a)) {}
  double twice_area() const { return std::sqrt(dot(n, n)); }
};

// The faces' area (in total, and on a flat base facing -axis at the box's
// lowest side along axis), for the triangles of a mesh.
double base_area(const SceneDesc& scene, int axis, const Bounds& bounds) {
  const double tolerance = 0.01 * (bounds.hi[axis] - bounds.lo[axis]);
  const double flat = std::cos(2.0 * std::numbers::pi / 180.0);
  double area = 0.0;
  for (const SceneTriangle& t : scene.triangles) {
    const TriangleArea f(t);
    bool low = true;
    for (const Vec3<double>& p : {f.a, f.b, f.c}) low = low && p[axis] - bounds.lo[axis] <= tolerance;
    const double twice_area = f.twice_area();
    if (low && twice_area > 0.0 && std::fabs(f.n[axis]) >= flat * twice_area) area += 0.5 * twice_area;
  }
  return area;
}

double mesh_area(const SceneDesc& scene) {
  double area = 0.0;
  for (const SceneTriangle& t : scene.triangles) area += 0.5 * TriangleArea(t).twice_area();
  return area;
}

// The mesh's top (vertices in the upper two fifths along up, each weighted by
// a third of its faces' areas) less its area-weighted centre, over the half
// extent of the vertices along each of the two axes across up.
std::pair<double, double> top_lean(const SceneDesc& scene, const Vec3<double>& up, const Vec3<double>& front,
                                   const Vec3<double>& side) {
  double low = std::numeric_limits<double>::infinity(), high = -low;
  double extent[2][2] = {{low, high}, {low, high}};
  for (const SceneTriangle& t : scene.triangles) {
    for (const Vec3<float>& p : t.triangle.p) {
      const Vec3<double> q = to_double(p);
      low = std::min(low, dot(q, up));
      high = std::max(high, dot(q, up));
      const double along[2] = {dot(q, front), dot(q, side)};
      for (int k = 0; k < 2; ++k) {
        extent[k][0] = std::min(extent[k][0], along[k]);
        extent[k][1] = std::max(extent[k][1], along[k]);
      }
    }
  }
  const double top_from = low + 0.6 * (high - low);
  Vec3<double> centre{0.0, 0.0, 0.0}, top{0.0, 0.0, 0.0};
  double weight = 0.0, top_weight = 0.0;
  for (const SceneTriangle& t : scene.triangles) {
    const TriangleArea f(t);
    const double w = f.twice_area() / 6.0;  // a third of the area to each corner
    for (const Vec3<double>& p : {f.a, f.b, f.c}) {
      centre = centre + p * w;
      weight += w;
      if (dot(p, up) >= top_from) {
        top = top + p * w;
        top_weight += w;
      }
    }
  }
  if (!(weight > 0.0) || !(top_weight > 0.0)) return {0.0, 0.0};
  const Vec3<double> lean = top * (1.0 / top_weight) - centre * (1.0 / weight);
  const auto share = [](double d, const double range[2]) {
    const double half = 0.5 * (range[1] - range[0]);
    return half > 0.0 ? d / half : 0.0;
  };
  return {share(dot(lean, front), extent[0]), share(dot(lean, side), extent[1])};
}

std::string axis_name(const Vec3<double>& v) {
  for (int a = 0; a < 3; ++a) {
    if (std::fabs(v[a]) == 1.0) return {v[a] > 0.0 ? '+' : '-', "xyz"[a]};
  }
  std::ostringstream text;
  text << "(" << v.x << ", " << v.y << ", " << v.z << ")";
  return text.str();
}

}  // namespace

DefaultView choose_default_view(const SceneDesc& scene, const std::optional<Vec3<double>>& up) {
  const Vec3<double> y{0.0, 1.0, 0.0}, z{0.0, 0.0, 1.0};
  bool only_triangles = true;
  for_each_kind([&]<class K>(K) {
    if constexpr (!std::is_same_v<K, TriangleKind>) only_triangles = only_triangles && (scene.*SceneEntries<K>::of).empty();
  });
  const bool mesh = scene.triangles.size() >= kViewMeshTriangles && only_triangles;
  DefaultView view{y, z, "+y, the default", "+z, the default"};
  if (up) {
    view.up = unit(*up);
    view.up_reason = axis_name(view.up) + ", from --up";
  } else if (mesh) {
    const Bounds bounds = scene_bounds(scene);
    const double least = 0.02 * mesh_area(scene);
    if (base_area(scene, 2, bounds) >= least && base_area(scene, 1, bounds) < least) {
      view.up = z;
      view.up_reason = "+z: the mesh stands on a flat base at its lowest z";
    }
  }
  // The default front across up: +z, or -y for an up along z.
  const Vec3<double> toward = std::fabs(dot(view.up, z)) < 0.9 ? z : Vec3<double>{0.0, -1.0, 0.0};
  view.front = unit(toward - view.up * dot(toward, view.up));
  view.front_reason = axis_name(view.front) + ", the default";
  if (mesh) {
    const Vec3<double> side = cross(view.up, view.front);
    const auto [along_front, along_side] = top_lean(scene, view.up, view.front, side);
    const bool front_axis = std::fabs(along_front) >= std::fabs(along_side);
    const double lean = front_axis ? along_front : along_side;
    if (std::fabs(lean) >= kViewLean) {
      view.front = (front_axis ? view.front : side) * (lean > 0.0 ? 1.0 : -1.0);
      view.front_reason = axis_name(view.front) + ": the mesh's top leans that way";
    }
  }
  return view;
}

namespace {

// The default eye and the light beside it lie up to about 2.5 view
// distances from the centre: both must stay finite in float, or the error
// names the scene's file.
void check_camera_fits_float(const SceneDesc& scene, const double center[3], double radius, double distance) {
  if (distance * 2.5 + length(center) < double(std::numeric_limits<float>::max())) return;
  const std::string name = scene.source_files.empty() ? std::string("the scene") : scene.source_files.front();
  std::ostringstream size;
  size << std::setprecision(3) << 2.0 * radius;
  throw std::invalid_argument(name + ": expected a model that a default view can frame, found one " + size.str() +
                              " across, too large for a camera in float; give the scene a camera, or scale it");
}

}  // namespace

std::optional<DefaultView> add_default_view(SceneDesc& scene, int width, int height,
                                            const std::optional<Vec3<double>>& up) {
  if (width < 1 || height < 1 || width > kMaxImageSide || height > kMaxImageSide) {
    throw std::invalid_argument("add_default_view: width and height must lie in [1, 65536]");
  }
  if (up && !(dot(*up, *up) > 0.0 && std::isfinite(dot(*up, *up)))) {
    throw std::invalid_argument("add_default_view: the up axis must be finite and not zero");
  }
  std::optional<DefaultView> chosen;
  if (!scene.camera) chosen = choose_default_view(scene, up);
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

  // Three-quarter view: 35 degrees round from the front towards the model's
  // left (+x for the default front +z and up +y), 25 degrees up.
  const double azimuth = 35.0 * std::numbers::pi / 180.0, elevation = 25.0 * std::numbers::pi / 180.0;
  const DefaultView view = chosen ? *chosen : DefaultView{{0.0, 1.0, 0.0}, {0.0, 0.0, 1.0}, {}, {}};
  const Vec3<double> side = cross(view.up, view.front);
  double toward_eye[3];
  for (int a = 0; a < 3; ++a) {
    toward_eye[a] = std::cos(elevation) * (std::cos(azimuth) * view.front[a] + std::sin(azimuth) * side[a]) +
                    std::sin(elevation) * view.up[a];
  }
  // Tangent of the half field of view across the shorter side (CameraDesc:
  // the angle spans the outermost pixel centres of the longer side).
  const int longer = std::max(width, height), shorter = std::min(width, height);
  const double half_angle = double(kDefaultViewAngleDegrees) * std::numbers::pi / 360.0;
  const double tangent = std::tan(half_angle) * double(std::max(shorter - 1, 1)) / double(std::max(longer - 1, 1));
  // The sphere fits a cone of that half-angle at distance r / sin(angle); 10% margin.
  const double distance = 1.1 * radius * std::sqrt(1.0 + tangent * tangent) / tangent;

  double eye[3];
  for (int a = 0; a < 3; ++a) eye[a] = center[a] + distance * toward_eye[a];
  if (!scene.camera) check_camera_fits_float(scene, center, radius, distance);
  if (!scene.camera) {
    CameraDesc camera{};
    camera.from = to_float(eye);
    camera.at = to_float(center);
    camera.up = {static_cast<float>(view.up.x), static_cast<float>(view.up.y), static_cast<float>(view.up.z)};
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
  return chosen;
}

}  // namespace quiver
