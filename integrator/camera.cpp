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
  const std::array<Vec3<double>, 2> c = unit_direction_changes(*this, x, y, spacing);
  return {{float(c[0].x), float(c[0].y), float(c[0].z)}, {float(c[1].x), float(c[1].y), float(c[1].z)}};
}

}  // namespace quiver
