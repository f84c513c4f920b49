#include "integrator/camera.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

namespace quiver {

Camera::Camera(const CameraDesc& desc, int width, int height) : width_(width), height_(height) {
  if (width < 1 || height < 1) throw std::invalid_argument("image size must be at least 1 x 1");
  if (!(desc.angle_degrees > 0.f && desc.angle_degrees < 180.f)) {
    throw std::invalid_argument("camera angle must lie in (0, 180) degrees");
  }
  frame_ = camera_frame(desc);
  // Outermost pixel centres of the wider side at +-tan(angle / 2).
  const int span = std::max(width, height) - 1;
  const double half_angle = double(desc.angle_degrees) * std::numbers::pi / 360.0;
  pixel_size_ = 2.0 * std::tan(half_angle) / double(std::max(span, 1));
}

Ray<float> Camera::ray(double x, double y) const {
  const Vec3<double> d = unit_direction(*this, x, y);
  return {eye(),
          {float(d.x), float(d.y), float(d.z)},
          0.f,
          std::numeric_limits<float>::infinity()};
}

Camera::DirectionDifferentials Camera::direction_differentials(double x, double y, double spacing) const {
  const Vec3<double> d = view_direction(*this, x, y);
  const double length = std::sqrt(dot(d, d));
  const Vec3<double> unit = d / length;
  auto unit_change = [&](const Vec3<double>& change) {
    const Vec3<double> dd = (change - unit * dot(unit, change)) / length;
    return Vec3<float>(float(dd.x), float(dd.y), float(dd.z));
  };
  return {unit_change(frame_.right * (pixel_size_ * spacing)), unit_change(frame_.up * (-pixel_size_ * spacing))};
}

}  // namespace quiver
