// Pinhole camera with NFF's convention: `angle` is the full field of view
// between the centres of the outermost pixel columns (rows when the image is
// taller than wide); pixels are square; `up` need not be perpendicular to the
// view direction (its perpendicular part is used).
// Film coordinates are in pixels: (0, 0) is the top-left corner of the
// image, pixel (i, j) covers [i, i+1) x [j, j+1) and its centre is
// (i + 0.5, j + 0.5); x grows right, y grows down.
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <vector>

#include "scene/camera_frame.h"
#include "scene/scene_desc.h"
#include "simd/ray.h"

namespace quiver {

class Camera {
 public:
  // Throws std::invalid_argument for a degenerate view (see CameraDesc).
  Camera(const CameraDesc& desc, int width, int height);

  // The unit-direction primary ray through film point (x, y), t in (0, inf).
  Ray<float> ray(double x, double y) const;

  // The change of that ray's unit direction when (x, y) moves by `spacing`
  // pixels along x and along y (a pinhole's origin does not change):
  // unit_direction_changes in double, rounded to float.
  struct DirectionDifferentials {
    Vec3<float> dx, dy;
  };
  DirectionDifferentials direction_differentials(double x, double y, double spacing) const;

  // Every primary ray's origin.
  Vec3<float> eye() const { return {float(frame_.eye.x), float(frame_.eye.y), float(frame_.eye.z)}; }

  int width() const { return width_; }
  int height() const { return height_; }
  const CameraFrame& frame() const { return frame_; }
  double pixel_size() const { return pixel_size_; }

 private:
  int width_, height_;
  CameraFrame frame_;
  double pixel_size_;  // tangent-plane size of one pixel at unit distance
};

inline namespace QUIVER_UNIT_NAMESPACE {

// The camera's direction through film point (x, y), in double, before
// normalising: forward + sx right + sy up for (sx, sy) the film point on the
// tangent plane at unit distance. D is double (one point, the reference:
// Camera::ray) or a batch of doubles (integrator/camera_rays.h), one
// formula for both.
template <class D>
Vec3<D> view_direction(const Camera& camera, const D& x, const D& y) {
  const CameraFrame& f = camera.frame();
  const D size(camera.pixel_size());
  const D sx = (x - D(0.5 * camera.width())) * size;
  const D sy = (D(0.5 * camera.height()) - y) * size;
  return {D(f.forward.x) + D(f.right.x) * sx + D(f.up.x) * sy, D(f.forward.y) + D(f.right.y) * sx + D(f.up.y) * sy,
          D(f.forward.z) + D(f.right.z) * sx + D(f.up.z) * sy};
}

// That direction over its length.
template <class D>
Vec3<D> unit_direction(const Camera& camera, const D& x, const D& y) {
  using std::sqrt;
  const Vec3<D> d = view_direction(camera, x, y);
  const D length = sqrt(d.x * d.x + d.y * d.y + d.z * d.z);
  return {d.x / length, d.y / length, d.z / length};
}

// That unit direction's change when (x, y) moves by `spacing` pixels along
// film x and along film y: dD = (dd - D (D.dd)) / |d| for d the direction
// before normalising and dd its change (Camera::direction_differentials).
template <class D>
std::array<Vec3<D>, 2> unit_direction_changes(const Camera& camera, const D& x, const D& y, const D& spacing) {
  using std::sqrt;
  const CameraFrame& f = camera.frame();
  const Vec3<D> d = view_direction(camera, x, y);
  const D length = sqrt(dot(d, d));
  const Vec3<D> unit = d / length;
  const auto unit_change = [&](const Vec3<double>& axis, const D& step) {
    const Vec3<D> change = Vec3<D>(D(axis.x), D(axis.y), D(axis.z)) * step;
    return (change - unit * dot(unit, change)) / length;
  };
  const D size(camera.pixel_size());
  return {unit_change(f.right, size * spacing), unit_change(f.up, -size * spacing)};
}

}  // namespace QUIVER_UNIT_NAMESPACE

// Camera samples to trace, in columns: their film points and, when rays
// carry differentials, the cell each one's texture footprint covers (its
// centre and side, in pixels; the side is the spacing of the samples).
struct FilmSamples {
  std::vector<double> x, y;
  bool footprints = false;  // the cells below are kept
  std::vector<double> cell_x, cell_y, spacing;

  // Empties the batch, keeping capacity; with_footprints: keep the cells.
  void clear(bool with_footprints) {
    footprints = with_footprints;
    for (std::vector<double>* c : {&x, &y, &cell_x, &cell_y, &spacing}) c->clear();
  }
  // A sample at film (px, py) in a cell of side `side` centred at (cx, cy).
  void push(double px, double py, double cx, double cy, double side) {
    x.push_back(px);
    y.push_back(py);
    if (!footprints) return;
    cell_x.push_back(cx);
    cell_y.push_back(cy);
    spacing.push_back(side);
  }
  // Or, for a batch whose size is known: resize(n), then set() samples [0, n).
  void resize(std::size_t n) {
    x.resize(n);
    y.resize(n);
    if (!footprints) return;
    for (std::vector<double>* c : {&cell_x, &cell_y, &spacing}) c->resize(n);
  }
  void set(std::size_t i, double px, double py, double cx, double cy, double side) {
    x[i] = px;
    y[i] = py;
    if (!footprints) return;
    cell_x[i] = cx;
    cell_y[i] = cy;
    spacing[i] = side;
  }
  std::size_t size() const { return x.size(); }
};

}  // namespace quiver
