// What `quiver view` renders: the scene read and built once, then any view
// the page asks for, with the settings, camera and default lights that
// `quiver render` given the same flags and that view's camera and sampling
// flags would use, so a view's final frame is that command's image bit for
// bit. A new view changes only the built scene's camera, lights and
// background (the default rig follows the camera, scene/auto_view.h).
#pragma once

#include <atomic>
#include <string>
#include <vector>

#include "app/render_job.h"
#include "app/view_request.h"
#include "integrator/render.h"
#include "scene/scene.h"
#include "scene/scene_desc.h"

namespace quiver {

class ViewSession {
 public:
  // Reads and builds the scene as `quiver render` would with these
  // arguments (args.output names the copied command's image); throws as
  // prepare_render does. Prints the readers' warnings.
  ViewSession(const RenderArgs& args, Isa isa);

  // The view the flags give: the command's camera, size and sampling.
  ViewRequest initial_view() const { return initial_; }
  // --preset spd fixes the sampling: a view's aa and max_depth are ignored.
  bool preset_fixes_sampling() const { return args_.options.preset_spd; }

  // The render flags of this view: the session's flags with the view's
  // camera, size and (unless the preset fixes them) sampling.
  RenderOptions options_for(const ViewRequest& view) const;
  // The settings a stage of the view renders with; throws UsageError for a
  // view the CLI would refuse (sizes, field of view, depth, a degenerate camera).
  RenderSettings settings_for(const ViewRequest& view, ViewStage stage) const;

  // Renders a stage of the view; stop as render()'s. One call at a time
  // (the scene's camera and lights are set for each).
  RenderResult render(const ViewRequest& view, ViewStage stage, const std::atomic<bool>* stop = nullptr);

  // `quiver render` with options_for(view) and -o the session's output.
  std::vector<std::string> command(const ViewRequest& view) const;

  const Scene& scene() const { return scene_; }
  const std::string& scene_name() const { return args_.scene; }  // empty: the built-in scene
  const std::string& output() const { return output_; }
  double load_ms() const { return load_ms_; }
  double build_ms() const { return build_ms_; }

 private:
  RenderArgs args_;
  Isa isa_;
  std::string output_;
  // The scene as read, without its primitives: its camera (if any), lights,
  // background, ambient and render settings, which each view starts from.
  SceneDesc view_desc_;
  CameraDesc first_camera_;  // the flags' camera (the default view's when the scene has none)
  Scene scene_;
  ViewRequest initial_;
  double load_ms_ = 0.0, build_ms_ = 0.0;
};

}  // namespace quiver
