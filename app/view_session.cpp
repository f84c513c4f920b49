#include "app/view_session.h"

#include <filesystem>

#include "app/progress_bar.h"
#include "app/render_command_line.h"
#include "app/render_options.h"

namespace quiver {

ViewSession::ViewSession(const RenderArgs& args, Isa isa) : args_(args), isa_(isa) {
  output_ = (args.output.empty() ? default_output(args.scene) : std::filesystem::path(args.output)).string();
  const ProgressStyle style = progress_style_for(stderr, args.quiet);
  SceneDesc desc = load_scene_timed(
      args.scene, {args.options.crease_angle, args.options.strict, args.options.allow_outside_paths}, load_ms_,
      style);
  print_scene_warnings(desc);
  view_desc_.camera = desc.camera;
  view_desc_.background = desc.background;
  view_desc_.ambient = desc.ambient;
  view_desc_.lights = desc.lights;
  view_desc_.render = desc.render;
  // The steps of prepare_render, keeping the scene as read without its primitives.
  const RenderPlan plan = plan_render(args.options, desc, isa);
  set_view(desc, args.options.camera, plan.settings.width, plan.settings.height);
  first_camera_ = *desc.camera;
  scene_ = build_scene_timed(desc, plan.build, args.scene, build_ms_, style);
  initial_.from = first_camera_.from;
  initial_.at = first_camera_.at;
  initial_.up = first_camera_.up;
  initial_.fov = first_camera_.angle_degrees;
  initial_.width = plan.settings.width;
  initial_.height = plan.settings.height;
  initial_.aa = plan.settings.aa;
  initial_.max_depth = plan.settings.trace.max_depth;
}

RenderOptions ViewSession::options_for(const ViewRequest& view) const {
  RenderOptions options = args_.options;
  options.camera = view.camera();
  options.width = view.width;
  options.height = view.height;
  if (!options.preset_spd) {
    options.aa = view.aa ? view.aa : initial_.aa;
    options.max_depth = view.max_depth ? view.max_depth : initial_.max_depth;
  }
  return options;
}

RenderSettings ViewSession::settings_for(const ViewRequest& view, ViewStage stage) const {
  RenderSettings settings = plan_render(options_for(view), view_desc_, isa_).settings;
  if (stage != ViewStage::final) settings.aa = AntiAliasing{};
  if (stage == ViewStage::coarse) {
    settings.width = (settings.width + kCoarseScale - 1) / kCoarseScale;
    settings.height = (settings.height + kCoarseScale - 1) / kCoarseScale;
  }
  return settings;
}

RenderResult ViewSession::render(const ViewRequest& view, ViewStage stage, const std::atomic<bool>* stop) {
  const RenderSettings settings = settings_for(view, stage);
  // set_view over the scene as read, its camera already there (the default
  // view's primitives are not kept): the flags over it, then the default rig.
  SceneDesc lit = view_desc_;
  if (!lit.camera) lit.camera = first_camera_;
  set_view(lit, view.camera(), settings.width, settings.height);
  set_scene_view(scene_, lit);
  return ::quiver::render(scene_, settings, {}, stop);
}

std::vector<std::string> ViewSession::command(const ViewRequest& view) const {
  return render_command_words(args_.scene, options_for(view), output_);
}

}  // namespace quiver
