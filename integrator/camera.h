// Pinhole camera with NFF's convention: `angle` is the full field of view
// between the centres of the outermost pixel columns (rows when the image is
// taller than wide); pixels are square; `up` need not be perpendicular to the
// view direction (its perpendicular part is used).
// Film coordinates are in pixels: (0, 0) is the top-left corner of the
// image, pixel (i, j) covers [i, i+1) x [j, j+1) and its centre is
// (i + 0.5, j + 0.5); x grows right, y grows down.
#pragma once

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
  // dD = (dd - D (D.dd)) / |d| for d the unnormalised direction.
  struct DirectionDifferentials {
    Vec3<float> dx, dy;
  };
  DirectionDifferentials direction_differentials(double x, double y, double spacing) const;

  int width() const { return width_; }
  int height() const { return height_; }

 private:
  // Film point (x, y) on the tangent plane at unit distance: (sx, sy, 0).
  Vec3<double> film_point(double x, double y) const;

  int width_, height_;
  CameraFrame frame_;
  double pixel_size_;  // tangent-plane size of one pixel at unit distance
};

}  // namespace quiver
