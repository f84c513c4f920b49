// Command-line options -> RenderSettings (app/render_options.h): defaults,
// the scene's RenderDesc, the aspect rule, bounds, --preset spd and its
// conflicts, the AOV list, the seed and the ISA choice.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "app/render_options.h"
#include "io/mesh_import.h"
#include "io/parse_error.h"
#include "io/scene_loader.h"
#include "scene/anti_aliasing.h"
#include "scene/auto_view.h"

namespace quiver {
namespace {

CameraDesc camera(int width, int height) {
  CameraDesc c{};
  c.from = {0.f, 0.f, 5.f};
  c.at = {0.f, 0.f, 0.f};
  c.up = {0.f, 1.f, 0.f};
  c.angle_degrees = 45.f;
  c.hither = 0.f;
  c.width = width;
  c.height = height;
  return c;
}

SceneDesc scene_with_camera(int width, int height) {
  SceneDesc scene;
  scene.camera = camera(width, height);
  return scene;
}

// True when fn throws UsageError (exit 2), not some other error.
template <class Fn>
bool throws_usage_error(Fn fn) {
  try {
    fn();
  } catch (const UsageError&) {
    return true;
  } catch (...) {
    return false;
  }
  return false;
}

TEST(RenderOptions, DefaultsWithoutFlagsOrSceneSettings) {
  const RenderPlan plan = plan_render({}, scene_with_camera(640, 480), Isa::scalar);
  const RenderSettings& s = plan.settings;
  EXPECT_EQ(s.width, 640);
  EXPECT_EQ(s.height, 480);
  const AntiAliasing default_aa = parse_anti_aliasing(kDefaultAntiAliasing);
  EXPECT_NE(default_aa.mode, AntiAliasing::Mode::none);
  EXPECT_EQ(s.aa.mode, default_aa.mode);
  EXPECT_EQ(s.aa.n, default_aa.n);
  EXPECT_EQ(s.trace.max_depth, kDefaultMaxDepth);
  EXPECT_EQ(s.trace.min_weight, kDefaultMinWeight);
  EXPECT_EQ(s.trace.seed, 0u);
  EXPECT_EQ(s.threads, 0);
  EXPECT_EQ(s.isa, Isa::scalar);
  EXPECT_FALSE(s.aov_depth || s.aov_normal || s.aov_id);
  EXPECT_FALSE(plan.build.all_two_sided);
  EXPECT_EQ(s.methods, MethodChoice::per_scene);
}

TEST(RenderOptions, SceneRenderDescAppliesWhenNoFlagIsGiven) {
  SceneDesc scene = scene_with_camera(64, 48);
  scene.render.aa = parse_anti_aliasing("jitter:5");
  scene.render.max_depth = 2;
  scene.render.min_weight = 0.25f;
  const RenderSettings s = plan_render({}, scene, Isa::scalar).settings;
  EXPECT_EQ(s.aa.mode, AntiAliasing::Mode::jitter);
  EXPECT_EQ(s.aa.n, 5);
  EXPECT_EQ(s.trace.max_depth, 2);
  EXPECT_EQ(s.trace.min_weight, 0.25f);
}

TEST(RenderOptions, FlagsOverrideTheScene) {
  SceneDesc scene = scene_with_camera(64, 48);
  scene.render.aa = parse_anti_aliasing("grid:3");
  scene.render.max_depth = 2;
  scene.render.min_weight = 0.25f;
  RenderOptions options;
  options.aa = parse_aa_flag("jitter:2");
  options.max_depth = 0;
  options.min_weight = 0.0;
  options.seed = 77;
  options.threads = 3;
  options.aov = parse_aov_list("id,depth");
  options.two_sided = true;
  options.robust_methods = true;
  const RenderPlan plan = plan_render(options, scene, Isa::sse4);
  const RenderSettings& s = plan.settings;
  EXPECT_EQ(s.aa.mode, AntiAliasing::Mode::jitter);
  EXPECT_EQ(s.aa.n, 2);
  EXPECT_EQ(s.trace.max_depth, 0);
  EXPECT_EQ(s.trace.min_weight, 0.f);
  EXPECT_EQ(s.trace.seed, 77u);
  EXPECT_EQ(s.threads, 3);
  EXPECT_EQ(s.isa, Isa::sse4);
  EXPECT_TRUE(s.aov_depth);
  EXPECT_FALSE(s.aov_normal);
  EXPECT_TRUE(s.aov_id);
  EXPECT_TRUE(plan.build.all_two_sided);
  EXPECT_EQ(s.methods, MethodChoice::most_robust);
}

TEST(RenderOptions, BadSceneSettingsAreSceneErrorsNotUsageErrors) {
  for (int variant = 0; variant < 4; ++variant) {
    SceneDesc scene = scene_with_camera(8, 8);
    if (variant == 0) scene.render.min_weight = 1.5f;  // a weight is at most 1
    if (variant == 1) scene.render.max_depth = kMaxMaxDepth + 1;
    if (variant == 2) scene.render.min_weight = -1.f;
    if (variant == 3) scene.render.min_weight = std::numeric_limits<float>::quiet_NaN();
    EXPECT_THROW(plan_render({}, scene, Isa::scalar), std::runtime_error) << variant;
    EXPECT_FALSE(throws_usage_error([&] { plan_render({}, scene, Isa::scalar); })) << variant;
  }
}

TEST(RenderOptions, OneSideKeepsTheCameraAspect) {
  const std::optional<CameraDesc> cam = camera(640, 480);
  RenderOptions options;
  options.width = 320;
  EXPECT_EQ(image_size(options, cam), std::make_pair(320, 240));
  options = {};
  options.height = 100;  // 133.33 -> 133
  EXPECT_EQ(image_size(options, cam), std::make_pair(133, 100));
  options = {};
  options.width = 1;  // 0.75 -> 1 (at least one pixel)
  EXPECT_EQ(image_size(options, cam), std::make_pair(1, 1));
  options = {};
  options.width = 101;  // 75.75 -> 76: the nearest side, not the truncated one
  EXPECT_EQ(image_size(options, cam), std::make_pair(101, 76));
  options = {};
  options.width = 10;
  options.height = 90;  // both given: as given
  EXPECT_EQ(image_size(options, cam), std::make_pair(10, 90));
  EXPECT_EQ(image_size({}, cam), std::make_pair(640, 480));
  // A scaled side up to the side bound is kept; past it, refused, not clamped.
  options = {};
  options.width = 4096;
  EXPECT_EQ(image_size(options, camera(4096, kMaxImageSide)), std::make_pair(4096, kMaxImageSide));
  EXPECT_TRUE(throws_usage_error([&] { image_size(options, camera(4096, kMaxImageSide + 1)); }));
  EXPECT_TRUE(throws_usage_error([&] { image_size(options, camera(4096, 2 * kMaxImageSide)); }));
  options = {};
  options.height = 4096;
  EXPECT_EQ(image_size(options, camera(kMaxImageSide, 4096)), std::make_pair(kMaxImageSide, 4096));
  EXPECT_TRUE(throws_usage_error([&] { image_size(options, camera(kMaxImageSide + 1, 4096)); }));
}

TEST(RenderOptions, WithoutACameraTheDefaultIsSquare) {
  EXPECT_EQ(image_size({}, std::nullopt), std::make_pair(kDefaultImageSide, kDefaultImageSide));
  RenderOptions options;
  options.height = 77;
  EXPECT_EQ(image_size(options, std::nullopt), std::make_pair(77, 77));
  const RenderPlan plan = plan_render(options, SceneDesc{}, Isa::scalar);
  EXPECT_EQ(plan.settings.width, 77);
  EXPECT_EQ(plan.settings.height, 77);
}

// Without a camera in the scene, --fov frames the default view at that
// angle (the eye nearer for a wider one), not only widens the lens.
TEST(RenderOptions, TheFovFlagFramesTheDefaultViewAtItsAngle) {
  SceneDesc scene;
  scene.materials.push_back({});
  scene.spheres.push_back({{{1.f, 2.f, 3.f}, 2.f}, 0});
  for (const double fov : {20.0, 70.0}) {
    SCOPED_TRACE(fov);
    SceneDesc flagged = scene;
    CameraFlags flags;
    flags.fov = fov;
    ASSERT_TRUE(set_view(flagged, flags, 64, 48).has_value());
    SceneDesc framed = scene;
    add_default_camera(framed, 64, 48, std::nullopt, static_cast<float>(fov));
    ASSERT_TRUE(flagged.camera && framed.camera);
    for (int a = 0; a < 3; ++a) EXPECT_EQ(flagged.camera->from[a], framed.camera->from[a]);
    EXPECT_EQ(flagged.camera->angle_degrees, static_cast<float>(fov));
  }
}

TEST(RenderOptions, ImageSizeBounds) {
  for (int side : {0, -1, kMaxImageSide + 1}) {
    RenderOptions options;
    options.width = side;
    EXPECT_TRUE(throws_usage_error([&] { check_render_options(options); })) << side;
    options = {};
    options.height = side;
    EXPECT_TRUE(throws_usage_error([&] { check_render_options(options); })) << side;
  }
  RenderOptions options;
  options.width = kMaxImageSide;
  options.height = 4096;  // exactly 2^28 pixels
  EXPECT_NO_THROW(check_render_options(options));
  options.height = 4097;
  EXPECT_TRUE(throws_usage_error([&] { check_render_options(options); }));
  // A side derived from the aspect is checked too: 65536 wide at 1:2 is 131072 tall.
  options = {};
  options.width = kMaxImageSide;
  EXPECT_TRUE(throws_usage_error([&] { image_size(options, camera(100, 200)); }));
}

TEST(RenderOptions, DepthWeightAndThreadBounds) {
  auto with = [](auto set) {
    RenderOptions options;
    set(options);
    return options;
  };
  EXPECT_NO_THROW(check_render_options(with([](RenderOptions& o) { o.max_depth = 0; })));
  EXPECT_NO_THROW(check_render_options(with([](RenderOptions& o) { o.max_depth = kMaxMaxDepth; })));
  EXPECT_NO_THROW(check_render_options(with([](RenderOptions& o) { o.min_weight = 0.0; })));
  EXPECT_NO_THROW(check_render_options(with([](RenderOptions& o) { o.min_weight = 1.0; })));
  EXPECT_NO_THROW(check_render_options(with([](RenderOptions& o) { o.threads = kMaxThreads; })));
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  for (const RenderOptions& bad : {with([](RenderOptions& o) { o.max_depth = -1; }),
                                   with([](RenderOptions& o) { o.max_depth = kMaxMaxDepth + 1; }),
                                   with([&](RenderOptions& o) { o.min_weight = nan; }),
                                   with([&](RenderOptions& o) { o.min_weight = inf; }),
                                   with([](RenderOptions& o) { o.min_weight = -0.5; }),
                                   with([](RenderOptions& o) { o.min_weight = 1.5; }),  // a weight is at most 1
                                   with([](RenderOptions& o) { o.threads = -1; }),
                                   with([](RenderOptions& o) { o.threads = kMaxThreads + 1; })}) {
    EXPECT_TRUE(throws_usage_error([&] { check_render_options(bad); }));
  }
  // Text flags are refused where they are parsed, once.
  EXPECT_TRUE(throws_usage_error([] { parse_aa_flag("grid"); }));
  EXPECT_TRUE(throws_usage_error([] { parse_aov_list("depth,depth"); }));
}

TEST(RenderOptions, CreaseAngleIsDegreesFromZeroTo180) {
  for (const double ok : {0.0, 1e-9, 60.0, 180.0}) {
    RenderOptions options;
    options.crease_angle = ok;
    EXPECT_NO_THROW(check_render_options(options)) << ok;
    EXPECT_NO_THROW(check_crease_angle(ok)) << ok;
  }
  EXPECT_NO_THROW(check_crease_angle(std::nullopt));
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  for (const double bad : {-1.0, -1e-9, 180.001, 360.0, nan, inf, -inf}) {
    RenderOptions options;
    options.crease_angle = bad;
    EXPECT_TRUE(throws_usage_error([&] { check_render_options(options); })) << bad;
  }
  try {
    check_crease_angle(200.0);
    ADD_FAILURE() << "no UsageError";
  } catch (const UsageError& error) {
    EXPECT_EQ(std::string(error.what()), "--crease-angle: expected degrees in [0, 180], found 200");
  }
}

bool same_vector(const Vec3<float>& a, const Vec3<float>& b) { return a.x == b.x && a.y == b.y && a.z == b.z; }

// --look-from, --look-at, --up: three finite numbers; --fov: (0, 180).
TEST(RenderOptions, CameraFlagsAreCheckedBeforeTheScene) {
  EXPECT_TRUE(same_vector(parse_vector_flag("--up", "0,1,0"), Vec3<float>{0.f, 1.f, 0.f}));
  EXPECT_TRUE(same_vector(parse_vector_flag("--look-at", "-1.5,2e3,0.25"), Vec3<float>{-1.5f, 2000.f, 0.25f}));
  for (const char* bad : {"", "1,2", "1,2,3,4", "1,,3", "1, 2,3", "a,b,c", "1,2,nan", "1,2,inf", "1e39,0,0", ",1,2"}) {
    EXPECT_TRUE(throws_usage_error([&] { parse_vector_flag("--look-from", bad); })) << bad;
  }
  try {
    parse_vector_flag("--look-from", "1,2");
    ADD_FAILURE() << "no UsageError";
  } catch (const UsageError& error) {
    EXPECT_EQ(std::string(error.what()), "--look-from: expected three finite numbers x,y,z, found '1,2'");
  }
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (const double fov : {0.0, -10.0, 180.0, 270.0, nan}) {
    RenderOptions options;
    options.camera.fov = fov;
    EXPECT_TRUE(throws_usage_error([&] { check_render_options(options); })) << fov;
  }
  RenderOptions options;
  options.camera.fov = 1e-3;
  EXPECT_NO_THROW(check_render_options(options));
  // check_camera_flags alone (quiver info's check), with its message.
  CameraFlags flags;
  flags.fov = 179.99;
  EXPECT_NO_THROW(check_camera_flags(flags));
  flags.fov = 180.0;
  try {
    check_camera_flags(flags);
    ADD_FAILURE() << "no UsageError";
  } catch (const UsageError& error) {
    EXPECT_EQ(std::string(error.what()), "--fov: expected degrees in (0, 180), found 180");
  }
}

TEST(RenderOptions, PresetNamesSpdOnly) {
  EXPECT_NO_THROW(check_preset("spd"));
  for (const char* bad : {"SPD", "", "spd ", "pov"}) {
    try {
      check_preset(bad);
      ADD_FAILURE() << "'" << bad << "' accepted";
    } catch (const UsageError& error) {
      EXPECT_EQ(std::string(error.what()), std::string("--preset: expected spd, found '") + bad + "'");
    }
  }
}

// Each camera flag replaces its field of the scene's camera, the others
// stay; a camera with no view direction is a usage error.
TEST(RenderOptions, CameraFlagsOverrideTheScenesCamera) {
  const CameraDesc scene_camera{{0, 0, 5}, {0, 0, 0}, {0, 1, 0}, 45.f, 0.f, 64, 48};
  CameraDesc camera = scene_camera;
  CameraFlags options;
  apply_camera_flags(options, camera);
  EXPECT_TRUE(same_vector(camera.from, scene_camera.from));
  EXPECT_EQ(camera.angle_degrees, 45.f);
  options.look_from = Vec3<float>{3, 4, 5};
  options.fov = 30.0;
  apply_camera_flags(options, camera);
  EXPECT_TRUE(same_vector(camera.from, Vec3<float>{3, 4, 5}));
  EXPECT_TRUE(same_vector(camera.at, scene_camera.at));
  EXPECT_TRUE(same_vector(camera.up, scene_camera.up));
  EXPECT_EQ(camera.angle_degrees, 30.f);
  EXPECT_EQ(camera.width, 64);
  CameraFlags onto_eye;
  onto_eye.look_at = Vec3<float>{3, 4, 5};
  EXPECT_TRUE(throws_usage_error([&] { apply_camera_flags(onto_eye, camera); }));
  CameraFlags along_view;
  along_view.up = Vec3<float>{-3, -4, -5};
  camera = scene_camera;
  camera.from = {3, 4, 5};
  EXPECT_TRUE(throws_usage_error([&] { apply_camera_flags(along_view, camera); }));
}

// Without a camera or lights, the default camera is placed before the
// camera flags and the rig after them: a view from behind the model has
// its key light above and to the right of that eye and its fill at it.
TEST(RenderOptions, TheDefaultLightsFollowTheCameraFlags) {
  SceneDesc scene;
  scene.materials.emplace_back();
  scene.spheres.push_back({{{0.f, 0.f, 0.f}, 1.f}, 0});
  CameraFlags behind;
  behind.look_from = Vec3<float>{0.f, 0.f, -6.f};
  const std::optional<DefaultView> view = set_view(scene, behind, 64, 64);
  ASSERT_TRUE(view.has_value());
  ASSERT_EQ(scene.lights.size(), 2u);
  EXPECT_TRUE(same_vector(scene.lights[1].position, Vec3<float>{0.f, 0.f, -6.f}));
  // Looking along +z with up +y, the camera's right is -x.
  EXPECT_LT(scene.lights[0].position.x, 0.f);
  EXPECT_GT(scene.lights[0].position.y, 0.f);
  EXPECT_FLOAT_EQ(scene.lights[0].position.z, -6.f);
  // A scene with a camera of its own keeps it; the rig still follows the flags.
  SceneDesc framed = scene_with_camera(32, 32);
  framed.spheres = scene.spheres;
  EXPECT_FALSE(set_view(framed, behind, 32, 32).has_value());
  ASSERT_EQ(framed.lights.size(), 2u);
  EXPECT_TRUE(same_vector(framed.lights[1].position, Vec3<float>{0.f, 0.f, -6.f}));
}

// What a first look shows, over the meshes a user brings: every model of
// ../shared/meshes and of Debian's assimp-testmodels that loads, rendered
// with no flags at 96x96, white and matte so that only the light counts.
// A model pixel (finite depth) receives direct light when it is brighter
// than with the lights turned off; the model's image spans the covered
// pixels' box.
struct FirstLook {
  double lit_share = 0.0;  // of the model's pixels
  double span = 0.0;       // the box's larger side over the image's shorter side
};

FirstLook first_look(SceneDesc desc) {
  constexpr int kSide = 96;
  set_view(desc, {}, kSide, kSide);
  for (MaterialDesc& m : desc.materials) {
    m = MaterialDesc{};
    m.color = {1.f, 1.f, 1.f};
    m.kd = 1.f;
    m.ks = 0.f;
  }
  RenderSettings settings;
  settings.width = settings.height = kSide;
  settings.aa = parse_anti_aliasing("none");
  settings.aov_depth = true;
  const Framebuffer lit = render(build_scene(desc, {}), settings).image;
  for (LightDesc& light : desc.lights) light.color = {0.f, 0.f, 0.f};
  const Framebuffer dark = render(build_scene(desc, {}), settings).image;
  std::size_t model = 0, reached = 0;
  int lo[2] = {kSide, kSide}, hi[2] = {-1, -1};
  for (int y = 0; y < kSide; ++y) {
    for (int x = 0; x < kSide; ++x) {
      const std::size_t p = std::size_t(y) * kSide + std::size_t(x);
      if (!std::isfinite(lit.depth[p])) continue;
      ++model;
      reached += lit.rgb[3 * p] > dark.rgb[3 * p];
      lo[0] = std::min(lo[0], x);
      hi[0] = std::max(hi[0], x);
      lo[1] = std::min(lo[1], y);
      hi[1] = std::max(hi[1], y);
    }
  }
  FirstLook look;
  if (model == 0) return look;
  look.lit_share = double(reached) / double(model);
  look.span = double(std::max(hi[0] - lo[0], hi[1] - lo[1]) + 1) / double(kSide);
  return look;
}

std::filesystem::path folder_from(const char* variable, const char* configured) {
  const char* env = std::getenv(variable);
  return env != nullptr && *env != '\0' ? std::filesystem::path(env) : std::filesystem::path(configured);
}

TEST(FirstLook, EveryMeshIsLitAndFramed) {
  std::vector<std::filesystem::path> models;
  const std::filesystem::path shared = folder_from("QUIVER_SHARED_DIR", QUIVER_SHARED_DIR) / "meshes";
  const std::filesystem::path assimp = folder_from("QUIVER_ASSIMP_MODELS_DIR", QUIVER_ASSIMP_MODELS_DIR);
  for (const std::filesystem::path& root : {shared, assimp}) {
    if (!std::filesystem::is_directory(root)) {
      GTEST_SKIP() << "no " << root << ": set QUIVER_SHARED_DIR to the folder holding meshes/ and install "
                   << "assimp-testmodels (or set QUIVER_ASSIMP_MODELS_DIR)";
    }
    for (const auto& entry : std::filesystem::recursive_directory_iterator(root)) {
      std::string extension = entry.path().extension().string();
      for (char& c : extension) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
      if (entry.is_regular_file() && (extension == ".obj" || is_imported_mesh_extension(extension))) {
        models.push_back(entry.path());
      }
    }
  }
  std::sort(models.begin(), models.end());
  std::size_t looked = 0;
  double least_lit = 1.0, least_span = 1.0;
  for (const std::filesystem::path& model : models) {
    SceneDesc desc;
    try {
      desc = load_scene(model);
    } catch (const ParseError&) {
      continue;  // broken on purpose, or a feature not read: io_mesh_import_test checks the error
    }
    if (desc.camera || !desc.lights.empty()) continue;  // not a first look at a bare model
    const FirstLook look = first_look(desc);
    ++looked;
    least_lit = std::min(least_lit, look.lit_share);
    least_span = std::min(least_span, look.span);
    EXPECT_GE(look.lit_share, 0.95) << model;
    EXPECT_GE(look.span, 0.8) << model;
  }
  RecordProperty("models", std::to_string(looked));
  RecordProperty("least_lit_share", std::to_string(least_lit));
  RecordProperty("least_span", std::to_string(least_span));
  EXPECT_GE(looked, 40u);
}

TEST(RenderOptions, PresetSpdSetsTheProcedureAndOverridesTheScene) {
  SceneDesc scene = scene_with_camera(20, 10);
  scene.render.aa = parse_anti_aliasing("grid:4");
  scene.render.max_depth = 9;
  scene.render.min_weight = 0.5f;
  RenderOptions options;
  options.preset_spd = true;
  const RenderPlan plan = plan_render(options, scene, Isa::scalar);
  EXPECT_EQ(plan.settings.aa.mode, AntiAliasing::Mode::corners);
  EXPECT_EQ(plan.settings.trace.max_depth, 4);
  EXPECT_EQ(plan.settings.trace.min_weight, 0.f);
  EXPECT_TRUE(plan.settings.trace.spawn_every_ray);
  EXPECT_TRUE(plan.build.all_two_sided);
  // Without the preset, the scene's settings, and rays of no weight are not spawned.
  const RenderPlan own = plan_render({}, scene, Isa::scalar);
  EXPECT_EQ(own.settings.aa.mode, AntiAliasing::Mode::grid);
  EXPECT_EQ(own.settings.trace.max_depth, 9);
  EXPECT_FALSE(own.settings.trace.spawn_every_ray);
}

TEST(RenderOptions, PresetSpdAcceptsAgreeingFlagsAndRejectsContradictions) {
  RenderOptions agreeing;
  agreeing.preset_spd = true;
  agreeing.aa = parse_aa_flag("corners");
  agreeing.max_depth = 4;
  agreeing.min_weight = 0.0;
  EXPECT_NO_THROW(check_render_options(agreeing));

  RenderOptions options;
  options.preset_spd = true;
  options.aa = parse_aa_flag("grid:2");
  EXPECT_TRUE(throws_usage_error([&] { check_render_options(options); }));
  options.aa.reset();
  options.max_depth = 5;
  EXPECT_TRUE(throws_usage_error([&] { check_render_options(options); }));
  options.max_depth.reset();
  options.min_weight = 0.001;
  EXPECT_TRUE(throws_usage_error([&] { check_render_options(options); }));
  // Without the preset the same flags are fine.
  options.preset_spd = false;
  options.aa = parse_aa_flag("grid:2");
  options.max_depth = 5;
  EXPECT_NO_THROW(check_render_options(options));
}

TEST(RenderOptions, AovList) {
  const AovSelection all = parse_aov_list("normal,id,depth");
  EXPECT_TRUE(all.depth && all.normal && all.id);
  const AovSelection one = parse_aov_list("normal");
  EXPECT_TRUE(one.normal);
  EXPECT_FALSE(one.depth || one.id);
  for (const char* bad : {"", ",", "depth,", ",depth", "depth,,id", "id,id", "Depth", "depth normal", "uv"}) {
    EXPECT_TRUE(throws_usage_error([&] { parse_aov_list(bad); })) << bad;
  }
}

TEST(RenderOptions, Seed) {
  EXPECT_EQ(parse_seed("0"), 0u);
  EXPECT_EQ(parse_seed("18446744073709551615"), std::numeric_limits<std::uint64_t>::max());
  for (const char* bad : {"", "-1", "+1", " 1", "1 ", "18446744073709551616", "0x10", "1.0"}) {
    EXPECT_TRUE(throws_usage_error([&] { parse_seed(bad); })) << bad;
  }
}

TEST(RenderOptions, IsaChoiceFlagThenEnvironmentThenAuto) {
  EXPECT_EQ(choose_isa(std::string("scalar"), nullptr), Isa::scalar);
  EXPECT_EQ(choose_isa(std::nullopt, "scalar"), Isa::scalar);
  EXPECT_EQ(choose_isa(std::string("scalar"), "bogus"), Isa::scalar);  // the flag wins
  EXPECT_EQ(choose_isa(std::nullopt, nullptr), best_supported_isa());
  EXPECT_EQ(choose_isa(std::string("auto"), "scalar"), best_supported_isa());
  EXPECT_TRUE(throws_usage_error([] { choose_isa(std::string("avx1024"), nullptr); }));
  EXPECT_TRUE(throws_usage_error([] { choose_isa(std::nullopt, "bogus"); }));
  for (Isa isa : {Isa::sse4, Isa::avx2, Isa::avx512}) {
    const std::string name(isa_name(isa));
    if (isa_supported(isa)) {
      EXPECT_EQ(choose_isa(name, nullptr), isa);
    } else {
      EXPECT_TRUE(throws_usage_error([&] { choose_isa(name, nullptr); })) << name;
    }
  }
}

}  // namespace
}  // namespace quiver
