// Golden images: the built-in scene and every io/examples scene (one seed
// effect each) rendered small and compared with the EXR references in
// tests/data/golden. Tolerance: at most 0.5% of the channel values may
// differ by more than 0.02 and the mean absolute difference must stay below
// 0.002, which leaves room for another libm's last-bit differences in
// atan2/pow (a texel or edge decision may flip) but not for a changed effect.
// QUIVER_UPDATE_GOLDEN=1 rewrites the references instead (then the test
// reports that it wrote them and skips).
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include "scene/default_scene.h"
#include "integrator/render.h"
#include "io/image_output.h"
#include "io/scene_loader.h"

namespace quiver {
namespace {

namespace fs = std::filesystem;

const fs::path kGoldenDir = fs::path(QUIVER_TEST_DATA_DIR) / "golden";
const fs::path kExamplesDir = fs::path(QUIVER_TEST_DATA_DIR) / ".." / ".." / "io" / "examples";

Framebuffer render_small(const SceneDesc& desc) {
  const Scene scene = build_scene(desc, {});
  RenderSettings settings;
  settings.width = 64;
  settings.height = std::max(1, 64 * desc.camera->height / desc.camera->width);
  settings.aa = parse_anti_aliasing("grid:2");
  settings.isa = best_supported_isa();
  settings.trace.max_depth = desc.render.max_depth.value_or(5);
  return render(scene, settings).image;
}

std::vector<float> read_rgb(const fs::path& path, int& width, int& height) {
  auto in = OIIO::ImageInput::open(path.string());
  if (!in) return {};
  const OIIO::ImageSpec& spec = in->spec();
  width = spec.width;
  height = spec.height;
  std::vector<float> rgb(std::size_t(width) * std::size_t(height) * 3);
  in->read_image(0, 0, 0, 3, OIIO::TypeDesc::FLOAT, rgb.data());
  return rgb;
}

void check_against_golden(const std::string& name, const SceneDesc& desc) {
  const Framebuffer image = render_small(desc);
  const fs::path golden = kGoldenDir / (name + ".exr");
  if (const char* update = std::getenv("QUIVER_UPDATE_GOLDEN"); update && std::string(update) == "1") {
    fs::create_directories(kGoldenDir);
    write_image(golden, image);
    GTEST_SKIP() << "QUIVER_UPDATE_GOLDEN=1: wrote " << golden;
  }
  int w = 0, h = 0;
  const std::vector<float> reference = read_rgb(golden, w, h);
  ASSERT_FALSE(reference.empty()) << "missing golden image " << golden << " (QUIVER_UPDATE_GOLDEN=1 writes it)";
  ASSERT_EQ(w, image.width) << name;
  ASSERT_EQ(h, image.height) << name;
  std::size_t far = 0;
  double sum = 0.0;
  for (std::size_t i = 0; i < reference.size(); ++i) {
    const double d = std::fabs(double(reference[i]) - double(image.rgb[i]));
    sum += d;
    far += d > 0.02;
  }
  EXPECT_LE(far, reference.size() / 200) << name << ": channel values off by more than 0.02";
  EXPECT_LT(sum / double(reference.size()), 0.002) << name << ": mean absolute difference";
}

TEST(Golden, BuiltInScene) { check_against_golden("default", default_scene()); }

TEST(Golden, EveryExampleScene) {
  std::size_t examples = 0;
  for (const fs::directory_entry& e : fs::directory_iterator(kExamplesDir)) {
    if (e.path().extension() != ".toml") continue;
    ++examples;
    SCOPED_TRACE(e.path().filename().string());
    check_against_golden(e.path().stem().string(), load_scene(e.path()));
  }
  EXPECT_GE(examples, 7u) << "io/examples should hold a scene per seed effect";
}

}  // namespace
}  // namespace quiver
