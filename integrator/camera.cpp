#include "integrator/camera.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

namespace quiver {

namespace {

double length(const double v[3]) { return std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]); }

bool normalize(double v[3]) {
  const double l = length(v);
  if (!(l > 0.0) || !std::isfinite(l)) return false;
  for (int a = 0; a < 3; ++a) v[a] /= l;
  return true;
}

void cross(const double a[3], const double b[3], double out[3]) {
  out[0] = a[1] * b[2] - a[2] * b[1];
  out[1] = a[2] * b[0] - a[0] * b[2];
  out[2] = a[0] * b[1] - a[1] * b[0];
}

}  // namespace

Camera::Camera(const CameraDesc& desc, int width, int height) : width_(width), height_(height) {
  if (width < 1 || height < 1) throw std::invalid_argument("image size must be at least 1 x 1");
  if (!(desc.angle_degrees > 0.f && desc.angle_degrees < 180.f)) {
    throw std::invalid_argument("camera angle must lie in (0, 180) degrees");
  }
  const double up_hint[3] = {desc.up.x, desc.up.y, desc.up.z};
  for (int a = 0; a < 3; ++a) {
    eye_[a] = desc.from[a];
    forward_[a] = double(desc.at[a]) - double(desc.from[a]);
  }
  if (!normalize(forward_)) throw std::invalid_argument("camera 'at' must differ from 'from'");
  cross(forward_, up_hint, right_);
  if (!normalize(right_)) throw std::invalid_argument("camera 'up' must not be parallel to the view direction");
  cross(right_, forward_, up_);
  // Outermost pixel centres of the wider side at +-tan(angle / 2).
  const int span = std::max(width, height) - 1;
  const double half_angle = double(desc.angle_degrees) * std::numbers::pi / 360.0;
  pixel_size_ = 2.0 * std::tan(half_angle) / double(std::max(span, 1));
}

Ray<float> Camera::ray(double x, double y) const {
  const double sx = (x - 0.5 * width_) * pixel_size_;
  const double sy = (0.5 * height_ - y) * pixel_size_;
  double d[3];
  for (int a = 0; a < 3; ++a) d[a] = forward_[a] + sx * right_[a] + sy * up_[a];
  normalize(d);
  return {{float(eye_[0]), float(eye_[1]), float(eye_[2])},
          {float(d[0]), float(d[1]), float(d[2])},
          0.f,
          std::numeric_limits<float>::infinity()};
}

}  // namespace quiver
