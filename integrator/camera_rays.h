// Primary rays in lanes: for a batch of film points, the pinhole camera's
// rays (origin the eye, unit_direction of camera.h in double rounded to float,
// t in (0, inf)), written into a ray stream. integrator/camera_rays.cpp is
// compiled per kernel unit; its lanes are the unit's doubles (half its
// float lanes, one for the scalar units, the reference). IEEE +, -, *, /
// and sqrt only, so every width gives the same bits. No masks: a last
// partial packet computes copies of the last film point and keeps its
// own lanes.
#pragma once

#include <span>

#include "geometry/soa.h"
#include "integrator/camera.h"
#include "integrator/wave.h"

namespace quiver {

// rays = the rays through (x[i], y[i]), padded; x and y equally long.
template <KernelUnit U>
void camera_rays(const Camera& camera, std::span<const double> x, std::span<const double> y, RaySoA& rays);

using CameraRaysFunction = void (*)(const Camera&, std::span<const double>, std::span<const double>, RaySoA&);

// Those rays' direction differentials: along_x and along_y are resized to
// x.size() and hold Camera::direction_differentials(x[i], y[i], spacing[i]),
// the same bits (unit_direction_changes in the unit's double lanes).
template <KernelUnit U>
void camera_direction_changes(const Camera& camera, std::span<const double> x, std::span<const double> y,
                              std::span<const double> spacing, Vec3Columns& along_x, Vec3Columns& along_y);

using CameraDirectionChangesFunction = void (*)(const Camera&, std::span<const double>, std::span<const double>,
                                                std::span<const double>, Vec3Columns&, Vec3Columns&);

}  // namespace quiver
