// A view `quiver view`'s page asks for: the camera, the image size and how
// its pixels are sampled, as the query parameters of a request
// (from, at, up: "x,y,z"; fov in degrees; width, height; aa; max_depth;
// stage).
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <string_view>

#include "app/render_options.h"
#include "scene/anti_aliasing.h"
#include "simd/vec3.h"

namespace quiver {

struct ViewRequest {
  Vec3<float> from, at, up;
  double fov = 0.0;  // degrees
  int width = 0, height = 0;
  std::optional<AntiAliasing> aa;  // absent: the session's
  std::optional<int> max_depth;    // absent: the session's

  // The camera flags (--look-from, --look-at, --up, --fov) that give this view.
  CameraFlags camera() const { return {from, at, up, fov}; }
};

// How far a view is refined: coarse (1/kCoarseScale of each side, rounded
// up; no anti-aliasing), full (every pixel, no anti-aliasing), final (the
// view's anti-aliasing: the image `quiver render` writes).
enum class ViewStage { coarse, full, final };
inline constexpr int kCoarseScale = 8;

// A query parameter by name, or nothing when the request lacks it.
using QueryParameter = std::function<std::optional<std::string>(std::string_view name)>;

// The request's parameters as written: from, at, up, fov, width and
// height required, aa and max_depth optional. Throws UsageError naming the
// parameter for one missing or malformed; ranges are the session's to
// check (plan_render, as for the CLI's flags).
ViewRequest parse_view_request(const QueryParameter& parameter);

// stage: "coarse", "full" or "final"; throws UsageError.
ViewStage parse_view_stage(std::string_view text);

}  // namespace quiver
