// Primary rays in lanes: every kernel unit writes Camera::ray's bits for
// every film point of a batch, a last partial packet included, and pads
// the stream with copies of its last ray; and their direction
// differentials, Camera::direction_differentials' bits.
#include <algorithm>
#include <bit>
#include <cstdint>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "integrator/camera_rays.h"

namespace quiver {
namespace {

class CameraRaysUnits : public ::testing::TestWithParam<KernelUnit> {};

std::uint32_t bits(float v) { return std::bit_cast<std::uint32_t>(v); }

// A tilted view whose up is not perpendicular, at an odd size.
Camera tilted_camera() {
  return Camera(CameraDesc{{1.f, 2.f, 3.f}, {0.f, 0.5f, -4.f}, {0.2f, 1.f, 0.3f}, 50.f, 0.f, 37, 23}, 37, 23);
}

// 37 film points: no width divides it, so the last packet is partial;
// jittered offsets, pixel corners and the far edge of the film.
struct FilmPoints {
  std::vector<double> x, y, spacing;
};
FilmPoints film_points() {
  FilmPoints p;
  for (int i = 0; i < 37; ++i) {
    p.x.push_back(i + (i % 3) * 0.3183098861837907);
    p.y.push_back((i * 7) % 23 + (i % 2) * 0.75);
    p.spacing.push_back(1.0 / double(1 + i % 4));
  }
  p.x.back() = 37.0;
  p.y.back() = 23.0;
  return p;
}

TEST_P(CameraRaysUnits, GiveCameraRayBitsForEveryFilmPoint) {
  const KernelUnit unit = GetParam();
  if (!kernel_unit_supported(unit)) GTEST_SKIP() << "this CPU cannot run " << kernel_unit_name(unit);
  const Camera camera = tilted_camera();
  const FilmPoints points = film_points();
  const std::vector<double>& x = points.x;
  const std::vector<double>& y = points.y;
  RaySoA rays;
  rays.push(Ray<float>{{9.f, 9.f, 9.f}, {1.f, 0.f, 0.f}, 0.5f, 2.f});  // overwritten, not appended to
  with_kernel_unit(unit, [&](auto u) { camera_rays<decltype(u)::value>(camera, x, y, rays); });
  ASSERT_EQ(rays.count, x.size());
  ASSERT_EQ(rays.ox.size(), padded_size(x.size()));
  for (std::size_t i = 0; i < rays.ox.size(); ++i) {
    const std::size_t point = std::min(i, x.size() - 1);  // padding lanes repeat the last ray
    const Ray<float> expected = camera.ray(x[point], y[point]);
    const Ray<float> got = rays.get(i);
    const std::string where = std::string(kernel_unit_name(unit)) + " ray " + std::to_string(i);
    EXPECT_EQ(bits(got.origin.x), bits(expected.origin.x)) << where;
    EXPECT_EQ(bits(got.origin.y), bits(expected.origin.y)) << where;
    EXPECT_EQ(bits(got.origin.z), bits(expected.origin.z)) << where;
    EXPECT_EQ(bits(got.direction.x), bits(expected.direction.x)) << where;
    EXPECT_EQ(bits(got.direction.y), bits(expected.direction.y)) << where;
    EXPECT_EQ(bits(got.direction.z), bits(expected.direction.z)) << where;
    EXPECT_EQ(bits(got.tmin), bits(expected.tmin)) << where;
    EXPECT_EQ(bits(got.tmax), bits(expected.tmax)) << where;
  }
}

TEST_P(CameraRaysUnits, GiveDirectionDifferentialBitsForEveryFilmPoint) {
  const KernelUnit unit = GetParam();
  if (!kernel_unit_supported(unit)) GTEST_SKIP() << "this CPU cannot run " << kernel_unit_name(unit);
  const Camera camera = tilted_camera();
  const FilmPoints p = film_points();
  Vec3Columns along_x, along_y;
  along_x.push({9.f, 9.f, 9.f});  // replaced, not appended to
  with_kernel_unit(unit, [&](auto u) {
    camera_direction_changes<decltype(u)::value>(camera, p.x, p.y, p.spacing, along_x, along_y);
  });
  ASSERT_EQ(along_x.x.size(), p.x.size());
  ASSERT_EQ(along_y.z.size(), p.x.size());
  for (std::size_t i = 0; i < p.x.size(); ++i) {
    const Camera::DirectionDifferentials expected = camera.direction_differentials(p.x[i], p.y[i], p.spacing[i]);
    const std::string where = std::string(kernel_unit_name(unit)) + " point " + std::to_string(i);
    for (int axis = 0; axis < 3; ++axis) {
      EXPECT_EQ(bits(along_x.get(i)[axis]), bits(expected.dx[axis])) << where << " axis " << axis;
      EXPECT_EQ(bits(along_y.get(i)[axis]), bits(expected.dy[axis])) << where << " axis " << axis;
    }
  }
}

TEST(CameraRays, AnEmptyBatchGivesAnEmptyStream) {
  const Camera camera(CameraDesc{{0.f, 0.f, 5.f}, {0.f, 0.f, 0.f}, {0.f, 1.f, 0.f}, 40.f, 0.f, 8, 8}, 8, 8);
  RaySoA rays;
  rays.push(Ray<float>{{0.f, 0.f, 0.f}, {1.f, 0.f, 0.f}, 0.f, 1.f});
  camera_rays<KernelUnit::scalar>(camera, {}, {}, rays);
  EXPECT_EQ(rays.count, 0u);
  EXPECT_TRUE(rays.ox.empty());
}

INSTANTIATE_TEST_SUITE_P(EveryUnit, CameraRaysUnits, ::testing::ValuesIn(kKernelUnits),
                         [](const ::testing::TestParamInfo<KernelUnit>& info) {
                           return std::string(kernel_unit_name(info.param));
                         });

}  // namespace
}  // namespace quiver
