#include "scene/camera_frame.h"

#include <cmath>
#include <stdexcept>

namespace quiver {

namespace {

// v / |v|; false (v unchanged) when |v| is zero or not finite.
bool normalize_in_place(Vec3<double>& v) {
  const double l = std::sqrt(dot(v, v));
  if (!(l > 0.0) || !std::isfinite(l)) return false;
  v = v / l;
  return true;
}

Vec3<double> to_double(const Vec3<float>& v) { return {v.x, v.y, v.z}; }

}  // namespace

CameraFrame camera_frame(const CameraDesc& camera) {
  CameraFrame frame;
  frame.eye = to_double(camera.from);
  frame.forward = to_double(camera.at) - frame.eye;
  if (!normalize_in_place(frame.forward)) throw std::invalid_argument("camera 'at' must differ from 'from', at a finite distance");
  frame.right = cross(frame.forward, to_double(camera.up));
  if (!normalize_in_place(frame.right)) {
    throw std::invalid_argument("camera 'up' must not be parallel to the view direction");
  }
  frame.up = cross(frame.right, frame.forward);
  return frame;
}

}  // namespace quiver
