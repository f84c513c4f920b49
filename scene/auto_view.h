// A default view for scenes that bring no camera or no lights (OBJ meshes,
// NFF files without `v`): a camera framing every primitive, and a rig of
// lights that follows whatever camera the scene ends up with.
#pragma once

#include <algorithm>
#include <cstddef>
#include <optional>
#include <string>

#include "scene/scene_desc.h"

namespace quiver {

// Field of view of the default camera, in degrees (CameraDesc's meaning).
inline constexpr float kDefaultViewAngleDegrees = 40.f;

// How the default camera was placed: the model's up axis and front (unit
// vectors), and why each was chosen, in words for `quiver info`.
struct DefaultView {
  Vec3<double> up, front;
  std::string up_reason, front_reason;
};

// The up axis and front a default camera takes. Up: the given one, else the
// one the file's format states (SceneDesc::model_up), else +y unless the
// scene is a mesh (triangles only, at least kViewMeshTriangles)
// standing on a flat base at its lowest z and not at its lowest y (a base:
// faces within 2 degrees of the axis, within 1% of the extent of the box's
// side, at least 2% of the mesh's area), which is +z's convention (scans
// and printed parts). Front: the side towards which a mesh's top (its
// upper two fifths, area-weighted) leans from its area-weighted centre, by at
// least kViewLean of the box's half-extent (a figure's head is at its
// front), along the larger lean of the two axes across up; else +z (-y for
// a +z up; the default front projected across any other up).
DefaultView choose_default_view(const SceneDesc& scene, const std::optional<Vec3<double>>& up = std::nullopt);
inline constexpr std::size_t kViewMeshTriangles = 64;
inline constexpr double kViewLean = 0.15;

// When scene.camera is empty: a camera of width x height pixels and the
// given angle (CameraDesc's meaning) looking from the front and above of
// choose_default_view (35 degrees round towards the model's left, 25 above)
// at the model, placed so that the primitives' image is centred and fills
// kDefaultViewFill of the image along the side it fills first (spheres and
// cones as their bounding balls, planes, being infinite, by their point,
// instances by their mesh's placed box). A scene without bounded primitives
// gets the same view of the unit sphere around the origin. Returns the view
// chosen, or nothing when the scene had a camera. up: the model's up axis
// when the user gave one (non-zero). Throws std::invalid_argument for width
// or height outside [1, kMaxImageSide], an angle outside (0, 180), and a
// model too large for a default camera in float ("<scene file>: ...").
std::optional<DefaultView> add_default_camera(SceneDesc& scene, int width, int height,
                                              const std::optional<Vec3<double>>& up = std::nullopt,
                                              float angle_degrees = kDefaultViewAngleDegrees);
inline constexpr double kDefaultViewFill = 0.9;

// When scene.lights is empty, the default rig around scene.camera (which
// must be set): a key light above and to the right of the eye (half the
// eye-to-target distance each way) with kDefaultKeyShare of the light, and
// a fill light at the eye with the rest, so that whatever the camera sees
// is lit; the light in all is 1 minus the largest ambient component (at
// least 0.3), and a zero ambient becomes 0.1. A scene without a background
// gets kDefaultRigBackground, a neutral grey that dark and light models
// both stand out against. Returns whether the rig was added; throws as
// camera_frame (scene/camera_frame.h) for a degenerate camera.
bool add_default_lights(SceneDesc& scene);
// The rig's light in all for a scene of this ambient: 1 minus its largest
// component (taken as at least 0.1), at least 0.3.
inline float default_light_total(const Vec3<float>& ambient) {
  return std::max(0.3f, 1.f - std::max({ambient.x, ambient.y, ambient.z, 0.1f}));
}
inline constexpr float kDefaultKeyShare = 0.7f;
inline constexpr float kDefaultRigBackground = 0.18f;

// add_default_camera, then add_default_lights.
std::optional<DefaultView> add_default_view(SceneDesc& scene, int width, int height,
                                            const std::optional<Vec3<double>>& up = std::nullopt);

}  // namespace quiver
