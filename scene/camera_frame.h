// A pinhole camera's orthonormal frame in double (CameraDesc's convention:
// `up` need not be perpendicular to the view direction; its perpendicular
// part is used).
#pragma once

#include "scene/scene_desc.h"
#include "simd/vec3.h"

namespace quiver {

struct CameraFrame {
  Vec3<double> eye;
  Vec3<double> forward;  // unit, toward `at`
  Vec3<double> right;    // unit, forward x up
  Vec3<double> up;       // unit, right x forward
};

// Throws std::invalid_argument when `at` equals `from`, or `up` is parallel
// to the view direction (or the frame is not finite).
CameraFrame camera_frame(const CameraDesc& camera);

}  // namespace quiver
