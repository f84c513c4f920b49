// Welding by exact position (geometry/position_welding.h): equal positions
// share a number (-0 as +0), others do not, numbered in the order of their
// first vertex whatever the partition or the thread count; renumbering by
// the triangles' first use drops unused positions.
#include <gtest/gtest.h>
#include <oneapi/tbb/task_arena.h>

#include <array>
#include <bit>
#include <cstdint>
#include <random>
#include <vector>

#include "geometry/position_welding.h"

namespace quiver {
namespace {

WeldedPositions weld(const std::vector<Vec3<float>>& positions) {
  return weld_positions(positions.size(), [&](std::size_t i) { return positions[i]; });
}

bool same_bits(const Vec3<float>& a, const Vec3<float>& b) {
  return std::bit_cast<std::uint32_t>(a.x) == std::bit_cast<std::uint32_t>(b.x) &&
         std::bit_cast<std::uint32_t>(a.y) == std::bit_cast<std::uint32_t>(b.y) &&
         std::bit_cast<std::uint32_t>(a.z) == std::bit_cast<std::uint32_t>(b.z);
}

TEST(PositionWelding, EqualPositionsShareANumberInTheOrderFirstMet) {
  const std::vector<Vec3<float>> positions{{1, 2, 3},           {0, 0, 0},
                                           {1, 2, 3},           {-0.f, 0, -0.f},
                                           {1, 2, 3.0000002f}, {0, 0, 0}};
  const WeldedPositions welded = weld(positions);
  EXPECT_EQ(welded.index_of, (std::vector<std::uint32_t>{0, 1, 0, 1, 2, 1}));
  ASSERT_EQ(welded.positions.size(), 3u);
  EXPECT_TRUE(same_bits(welded.positions[0], {1, 2, 3}));
  EXPECT_TRUE(same_bits(welded.positions[1], {0, 0, 0})) << "-0 welds as +0";
  EXPECT_TRUE(same_bits(welded.positions[2], {1, 2, 3.0000002f}));
  EXPECT_TRUE(weld({}).index_of.empty());
}

// Many vertices over fewer positions, spread over every partition: each
// vertex's number names its own position, numbers first met in order, and
// the result is the same on one thread and on several.
TEST(PositionWelding, LargeMeshesWeldAlikeOnAnyThreadCount) {
  std::mt19937 random(7);
  std::uniform_int_distribution<int> coordinate(-40, 40);
  std::vector<Vec3<float>> positions(200000);
  for (Vec3<float>& p : positions) {
    p = {float(coordinate(random)) * 0.5f, float(coordinate(random)), float(coordinate(random) % 3)};
  }
  const auto on = [&](int threads) {
    tbb::task_arena arena(threads);
    return arena.execute([&] { return weld(positions); });
  };
  const WeldedPositions one = on(1), two = on(2);
  EXPECT_EQ(one.index_of, two.index_of);
  ASSERT_EQ(one.positions.size(), two.positions.size());
  std::uint32_t next = 0;
  for (std::size_t i = 0; i < positions.size(); ++i) {
    const std::uint32_t n = one.index_of[i];
    ASSERT_LT(n, one.positions.size());
    ASSERT_TRUE(same_bits(one.positions[n], positions[i])) << "vertex " << i;
    ASSERT_LE(n, next) << "a number before its position's first vertex, at vertex " << i;
    if (n == next) ++next;
  }
  EXPECT_EQ(next, one.positions.size());
  EXPECT_LT(one.positions.size(), positions.size() / 2) << "the test means many shared positions";
}

TEST(PositionWelding, NumberedByFirstUseTheUnusedDropped) {
  std::vector<Vec3<float>> positions{{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {3, 0, 0}, {4, 0, 0}};
  std::vector<std::array<std::uint32_t, 3>> triangles{{4, 2, 0}, {2, 4, 3}};
  number_by_first_use(positions, triangles);
  EXPECT_EQ(triangles, (std::vector<std::array<std::uint32_t, 3>>{{0, 1, 2}, {1, 0, 3}}));
  ASSERT_EQ(positions.size(), 4u);
  EXPECT_EQ(positions[0].x, 4.f);
  EXPECT_EQ(positions[1].x, 2.f);
  EXPECT_EQ(positions[2].x, 0.f);
  EXPECT_EQ(positions[3].x, 3.f);
}

}  // namespace
}  // namespace quiver
