// Corner sampling (integrator/corner_sampling.h): when an adaptive square
// splits, and what an adaptive pixel is made of.
#include <array>
#include <cmath>
#include <cstddef>
#include <vector>

#include <gtest/gtest.h>

#include "integrator/camera.h"
#include "integrator/corner_sampling.h"
#include "integrator/render.h"
#include "integrator/scene_intersector.h"
#include "integrator/tracer.h"
#include "scene/anti_aliasing.h"
#include "scene/scene.h"
#include "tests/support/checker_floor.h"

namespace quiver {
namespace {

TEST(CornerSampling, ASquareSplitsWhenAnyTwoCornersDifferByMoreThanTheThreshold) {
  const Vec3<float> grey{0.5f, 0.5f, 0.5f};
  const float threshold = 0.25f;
  // One corner apart from the other three, in one channel: every corner
  // and every channel is compared.
  for (int lone = 0; lone < 4; ++lone) {
    for (int channel = 0; channel < 3; ++channel) {
      std::array<Vec3<float>, 4> corners{grey, grey, grey, grey};
      corners[std::size_t(lone)][channel] = 0.5f + 0.375f;
      EXPECT_TRUE(corners_differ(corners, threshold)) << "corner " << lone << ", channel " << channel;
      // A difference of exactly the threshold is not more than it.
      corners[std::size_t(lone)][channel] = 0.5f + threshold;
      EXPECT_FALSE(corners_differ(corners, threshold)) << "corner " << lone << ", channel " << channel;
    }
  }
  // Equal corners never split, even at threshold 0.
  EXPECT_FALSE(corners_differ({grey, grey, grey, grey}, 0.f));
}

// The SPD rule: each pixel the mean of its own four corners. Every corner
// of a 3 x 2 image's 4 x 3 lattice holds a distinct power of two in one
// channel (and its index in the others), so a pixel that took a wrong or
// repeated corner shows it exactly.
TEST(CornerSampling, EachPixelIsTheMeanOfItsFourCorners) {
  Framebuffer image;
  image.width = 3;
  image.height = 2;
  image.rgb.assign(3 * 3 * 2, -1.f);
  const std::size_t cw = 4, ch = 3;
  std::vector<Vec3<float>> corners(cw * ch);
  for (std::size_t i = 0; i < corners.size(); ++i) {
    corners[i] = {float(1u << i), float(i), -float(i)};
  }
  average_corners(corners, image);
  for (std::size_t y = 0; y < 2; ++y) {
    for (std::size_t x = 0; x < 3; ++x) {
      const std::size_t i = y * cw + x;
      const std::array<std::size_t, 4> own{i, i + 1, i + cw, i + cw + 1};
      float bits = 0.f, index = 0.f;
      for (std::size_t c : own) {
        bits += float(1u << c);
        index += float(c);
      }
      const float* p = &image.rgb[(y * 3 + x) * 3];
      EXPECT_EQ(p[0], bits * 0.25f) << "pixel " << x << ", " << y;
      EXPECT_EQ(p[1], index * 0.25f) << "pixel " << x << ", " << y;
      EXPECT_EQ(p[2], -index * 0.25f) << "pixel " << x << ", " << y;
    }
  }
}

// A white background behind a black sphere (no light, no ambient): the
// split pixels along its outline are area-weighted means of their samples,
// so each lies between black and white, and a pixel of one colour stays it.
TEST(CornerSampling, AnAdaptivePixelIsAWeightedMeanOfItsSamples) {
  SceneDesc desc;
  desc.camera = CameraDesc{{0.f, 0.f, 5.f}, {0.f, 0.f, 0.f}, {0.f, 1.f, 0.f}, 40.f, 0.f, 24, 24};
  desc.background = {1.f, 1.f, 1.f};
  desc.ambient = {0.f, 0.f, 0.f};
  MaterialDesc black;
  black.color = {0.f, 0.f, 0.f};
  desc.materials.push_back(black);
  desc.spheres.push_back({{{0.3f, 0.2f, 0.f}, 1.f}, 0});
  RenderSettings settings;
  settings.width = settings.height = 24;
  settings.threads = 1;
  settings.aa = parse_anti_aliasing("adaptive:0.1:3");
  const RenderResult result = render(build_scene(desc, {}), settings);
  const std::size_t corners = 25 * 25;
  ASSERT_GT(result.stats.rays.primary, corners);  // some squares split
  std::size_t between = 0;
  for (float value : result.image.rgb) {
    EXPECT_GE(value, 0.f);
    EXPECT_LE(value, 1.f);
    between += value > 0.f && value < 1.f ? 1 : 0;
  }
  EXPECT_GT(between, 0u);
  // Squares split down to the finest level, 1/8 of a pixel's side at depth
  // 3: its corner means come in 1/256ths of a pixel (weights are powers of
  // two, so the sums are exact), which a level coarser (1/64ths) never gives.
  std::size_t finest = 0;
  for (float value : result.image.rgb) finest += std::fmod(value * 64.f, 1.f) != 0.f ? 1 : 0;
  EXPECT_GT(finest, 0u);
  EXPECT_EQ(result.image.rgb[0], 1.f);                      // a corner of the image: background
  EXPECT_EQ(result.image.rgb[(12 * 24 + 12) * 3], 0.f);  // the sphere's middle
}

// A checker floor to the horizon, ambient light only, at adaptive depth 1
// with threshold 0: each pixel is its corners' mean, or where they differ
// the mean of its four half-size squares' corners. Every lattice point is
// filtered over the side of the squares it was first asked for: a pixel
// corner over a pixel, a point added by a split over half of one. The
// image, recomputed here from those points traced one by one with those
// footprints, is the renderer's.
TEST(CornerSampling, LatticePointsFilterTexturesOverTheirSquaresSide) {
  constexpr int kWidth = 24, kHeight = 16;
  const SceneDesc desc = testing::checker_floor(false, kWidth, kHeight);
  const Scene scene = build_scene(desc, {});
  RenderSettings settings;
  settings.width = kWidth;
  settings.height = kHeight;
  settings.threads = 1;
  settings.aa = parse_anti_aliasing("adaptive:0:1");
  const Framebuffer image = render(scene, settings).image;

  // The lattice at half-pixel steps, (2W + 1) x (2H + 1) points.
  const int lw = 2 * kWidth + 1, lh = 2 * kHeight + 1;
  FilmSamples film;
  film.clear(true);
  for (int Y = 0; Y < lh; ++Y) {
    for (int X = 0; X < lw; ++X) {
      const double x = X / 2.0, y = Y / 2.0;
      film.push(x, y, x, y, X % 2 == 0 && Y % 2 == 0 ? 1.0 : 0.5);
    }
  }
  const Camera camera(scene.camera, kWidth, kHeight);
  const SceneIntersector intersector(kernel_unit_for(settings.isa), choose_sphere_method(scene, settings.methods));
  Tracer tracer(scene, intersector, settings.trace);
  std::vector<Vec3<float>> colors(film.size());
  TraceStats stats;
  tracer.trace(camera, film, colors, stats);
  const auto at = [&](int X, int Y) { return colors[std::size_t(Y) * std::size_t(lw) + std::size_t(X)]; };
  const auto corner_mean = [&](int X, int Y, int side) {
    return (at(X, Y) + at(X + side, Y) + at(X, Y + side) + at(X + side, Y + side)) * 0.25f;
  };
  std::size_t split = 0;
  for (int y = 0; y < kHeight; ++y) {
    for (int x = 0; x < kWidth; ++x) {
      const int X = 2 * x, Y = 2 * y;
      Vec3<float> expected = corner_mean(X, Y, 2);
      if (corners_differ({at(X, Y), at(X + 2, Y), at(X, Y + 2), at(X + 2, Y + 2)}, 0.f)) {
        ++split;
        expected = (corner_mean(X, Y, 1) + corner_mean(X + 1, Y, 1) + corner_mean(X, Y + 1, 1) +
                    corner_mean(X + 1, Y + 1, 1)) *
                   0.25f;
      }
      const float* p = &image.rgb[(std::size_t(y) * kWidth + std::size_t(x)) * 3];
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(p[c], expected[c], 1e-5f) << "pixel " << x << ", " << y;
    }
  }
  EXPECT_GT(split, std::size_t(kWidth * kHeight / 4));
}

}  // namespace
}  // namespace quiver
