// quiver view's session (app/view_session.h): a view's final frame is the
// image of the `quiver render` command it offers, bit for bit, whether the
// scene brings its camera and lights or gets the default ones (which follow
// the view); the stages shrink and drop anti-aliasing; the stop flag stops
// a frame; views the CLI would refuse are usage errors; a preset keeps its
// sampling.
#include "app/view_session.h"

#include <gtest/gtest.h>

#include <atomic>
#include <string>
#include <vector>

#include "app/render_command_line.h"
#include "support/render_command_parse.h"

namespace quiver {
namespace {

const std::string kMesh = std::string(QUIVER_TEST_DATA_DIR) + "/mesh/roof.ply";  // no camera, no lights

RenderArgs args_for(const std::string& scene) {
  RenderArgs args;
  args.scene = scene;
  args.options.width = 40;
  args.options.height = 30;
  return args;
}

// What `quiver render` does with the command's words: the image it writes, as floats.
Framebuffer command_image(const std::vector<std::string>& words) {
  const RenderArgs args = testing::parse_render_command(words);
  const CheckedRenderArgs checked = check_render_args(args, nullptr);
  const PreparedRender prepared = prepare_render(args, checked);
  return render(prepared.scene, prepared.plan.settings).image;
}

// The initial view turned round its look-at point and moved, with other sampling.
ViewRequest moved(ViewRequest view) {
  view.from = view.at + Vec3<float>{view.at.z - view.from.z, view.from.y - view.at.y + 0.5f, view.from.x - view.at.x};
  view.at = view.at + Vec3<float>{0.05f, -0.02f, 0.01f};
  view.fov = 31.5;
  view.width = 36;
  view.height = 28;
  view.aa = parse_aa_flag("jitter:2");
  view.max_depth = 3;
  return view;
}

void expect_command_gives_frame(ViewSession& session, const ViewRequest& view) {
  const RenderResult frame = session.render(view, ViewStage::final);
  const Framebuffer expected = command_image(session.command(view));
  ASSERT_EQ(frame.image.width, expected.width);
  ASSERT_EQ(frame.image.height, expected.height);
  std::size_t differing = 0;
  for (std::size_t i = 0; i < expected.rgb.size(); ++i) differing += frame.image.rgb[i] != expected.rgb[i];
  EXPECT_EQ(differing, 0u) << shell_command_line(session.command(view));
}

TEST(ViewSession, FinalFrameIsTheImageOfItsCommand) {
  for (const std::string& scene : {std::string(), kMesh}) {
    SCOPED_TRACE(scene.empty() ? "built-in scene" : scene);
    ViewSession session(args_for(scene), Isa::scalar);
    expect_command_gives_frame(session, session.initial_view());
    expect_command_gives_frame(session, moved(session.initial_view()));
  }
}

TEST(ViewSession, InitialViewIsTheFlagsView) {
  RenderArgs args = args_for(kMesh);
  args.options.camera.look_from = Vec3<float>{3.f, 2.f, 1.f};
  args.options.camera.fov = 25.0;
  args.options.aa = parse_aa_flag("grid:2");
  const ViewSession session(args, Isa::scalar);
  const ViewRequest view = session.initial_view();
  EXPECT_EQ(view.from.x, 3.f);
  EXPECT_EQ(view.from.y, 2.f);
  EXPECT_EQ(view.from.z, 1.f);
  EXPECT_EQ(view.fov, 25.0);
  EXPECT_EQ(view.width, 40);
  EXPECT_EQ(view.height, 30);
  ASSERT_TRUE(view.aa.has_value());
  EXPECT_EQ(to_string(*view.aa), "grid:2");
  // Without the view's flags, `quiver render` with the session's flags renders the same image.
  ViewSession same(args, Isa::scalar);
  const RenderResult frame = same.render(view, ViewStage::final);
  EXPECT_EQ(frame.image.rgb, command_image(render_command_words(kMesh, args.options, "roof.png")).rgb);
}

TEST(ViewSession, StagesShrinkAndDropAntiAliasing) {
  ViewSession session(args_for(""), Isa::scalar);
  ViewRequest view = session.initial_view();
  view.width = 41;
  view.height = 17;
  view.aa = parse_aa_flag("grid:3");
  const RenderSettings coarse = session.settings_for(view, ViewStage::coarse);
  EXPECT_EQ(coarse.width, 6);  // 41 / 8 rounded up
  EXPECT_EQ(coarse.height, 3);
  EXPECT_EQ(coarse.aa.mode, AntiAliasing::Mode::none);
  EXPECT_EQ(session.settings_for(view, ViewStage::full).aa.mode, AntiAliasing::Mode::none);
  EXPECT_EQ(session.settings_for(view, ViewStage::final).aa.mode, AntiAliasing::Mode::grid);
  const RenderResult small = session.render(view, ViewStage::coarse);
  EXPECT_EQ(small.image.width, 6);
  EXPECT_EQ(small.image.height, 3);
  view.aa = AntiAliasing{};
  EXPECT_EQ(session.render(view, ViewStage::full).image.rgb, session.render(view, ViewStage::final).image.rgb);
}

TEST(ViewSession, StopFlagStopsTheFrame) {
  ViewSession session(args_for(""), Isa::scalar);
  const std::atomic<bool> stop{true};
  const RenderResult result = session.render(session.initial_view(), ViewStage::final, &stop);
  EXPECT_TRUE(result.stopped());
  EXPECT_EQ(result.tiles_done, 0u);
}

TEST(ViewSession, ViewsTheCliRefusesAreUsageErrors) {
  ViewSession session(args_for(""), Isa::scalar);
  const ViewRequest good = session.initial_view();
  const auto refused = [&](const char* what, auto change) {
    ViewRequest view = good;
    change(view);
    EXPECT_THROW(session.render(view, ViewStage::coarse), UsageError) << what;
  };
  refused("fov", [](ViewRequest& v) { v.fov = 180.0; });
  refused("width", [](ViewRequest& v) { v.width = 0; });
  refused("height", [](ViewRequest& v) { v.height = kMaxImageSide + 1; });
  refused("depth", [](ViewRequest& v) { v.max_depth = kMaxMaxDepth + 1; });
  refused("up along the view", [](ViewRequest& v) {
    v.from = v.at + Vec3<float>{0.f, 5.f, 0.f};
    v.up = Vec3<float>{0.f, 2.f, 0.f};
  });
  refused("from at at", [](ViewRequest& v) { v.at = v.from; });
}

TEST(ViewSession, PresetKeepsItsSampling) {
  RenderArgs args = args_for("");
  args.options.preset_spd = true;
  const ViewSession session(args, Isa::scalar);
  ViewRequest view = session.initial_view();
  view.aa = parse_aa_flag("grid:4");
  view.max_depth = 9;
  const RenderSettings settings = session.settings_for(view, ViewStage::final);
  EXPECT_EQ(settings.aa.mode, AntiAliasing::Mode::corners);
  EXPECT_EQ(settings.trace.max_depth, kSpdMaxDepth);
  const RenderArgs command = testing::parse_render_command(session.command(view));
  EXPECT_TRUE(command.options.preset_spd);
  EXPECT_FALSE(command.options.aa.has_value());
  EXPECT_FALSE(command.options.max_depth.has_value());
}

}  // namespace
}  // namespace quiver
