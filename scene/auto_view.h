// A default view for scenes that bring no camera or no lights (OBJ meshes,
// NFF files without `v`): a camera framing every primitive and a point
// light beside it.
#pragma once

#include "scene/scene_desc.h"

namespace quiver {

// Field of view of the default camera, in degrees (CameraDesc's meaning).
inline constexpr float kDefaultViewAngleDegrees = 40.f;

// When scene.camera is empty: a camera of width x height pixels looking at
// the centre of the primitives' bounding box from the front (+z), above
// (+y) and to the right (+x), far enough that the box's bounding sphere
// fits inside the image; up is +y; planes, being infinite, count only by
// their point. A scene without bounded primitives gets the same view of the
// unit sphere around the origin.
// When scene.lights is empty: one white point light above and to the right
// of the scene's camera (half the eye-to-target distance each way), whose
// intensity is 1 minus the largest ambient
// component (at least 0.3); a zero ambient becomes 0.1.
// Nothing is changed where the scene has its own camera or lights. Throws
// std::invalid_argument for width or height outside [1, kMaxImageSide], and
// as camera_frame (scene/camera_frame.h) when a light is added beside a
// degenerate camera of the scene's own.
void add_default_view(SceneDesc& scene, int width, int height);

}  // namespace quiver
