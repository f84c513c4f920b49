// quiver-mpi's tile queue (app/tile_schedule.h): costliest first, batches
// shrinking to one tile, resumed tiles skipped, a tile still out given again
// to an idle rank once nothing waits, and the first result winning.
#include <algorithm>
#include <cstdint>
#include <set>
#include <vector>

#include <gtest/gtest.h>

#include "app/tile_schedule.h"

namespace quiver {
namespace {

// n tiles for rank, one batch at a time.
std::vector<std::uint32_t> take_tiles(TileSchedule& schedule, int rank, std::size_t n) {
  std::vector<std::uint32_t> tiles;
  while (tiles.size() < n) {
    const std::vector<std::uint32_t> batch = schedule.take(rank, n - tiles.size());
    if (batch.empty()) break;
    tiles.insert(tiles.end(), batch.begin(), batch.end());
  }
  return tiles;
}

TEST(TileSchedule, GivesTheCostliestTilesFirstAndSkipsDoneOnes) {
  const std::vector<double> costs{1, 5, 3, 5, 2, 9};
  std::vector<bool> done(6, false);
  done[5] = true;  // resumed: the costliest, never given
  TileSchedule schedule(6, done, costs, 2);
  EXPECT_EQ(schedule.tile_count(), 6u);
  EXPECT_EQ(schedule.done_count(), 1u);
  EXPECT_EQ(schedule.waiting(), 5u);
  EXPECT_TRUE(schedule.is_done(5));
  EXPECT_FALSE(schedule.is_done(0));
  std::vector<std::uint32_t> order;
  while (schedule.waiting() > 0) {
    for (std::uint32_t t : schedule.take(1, 100)) order.push_back(t);
  }
  EXPECT_EQ(order, (std::vector<std::uint32_t>{1, 3, 2, 4, 0}));  // ties keep tile order
  EXPECT_EQ(schedule.outstanding(1), 5u);
  EXPECT_TRUE(schedule.take(1, 100).empty());
  EXPECT_TRUE(schedule.complete(3, 1));
  EXPECT_TRUE(schedule.is_done(3));
  EXPECT_FALSE(schedule.is_done(1));
}

TEST(TileSchedule, WorkDoneWeighsTilesByTheirEstimatedCost) {
  // Weights cost + 0.01: 9.01, 1.01, 0.01, 0.01 (a negative estimate counts as 0).
  TileSchedule schedule(4, {false, false, false, true}, {9.0, 1.0, -5.0, 0.0}, 1);
  EXPECT_DOUBLE_EQ(schedule.work_done(), 0.01 / 10.04);  // the tile resumed as done
  ASSERT_EQ(schedule.take(0, 1), std::vector<std::uint32_t>{0});
  EXPECT_TRUE(schedule.complete(0, 0));
  EXPECT_DOUBLE_EQ(schedule.work_done(), 9.02 / 10.04);
  EXPECT_FALSE(schedule.complete(0, 0));  // a repeat adds nothing
  EXPECT_DOUBLE_EQ(schedule.work_done(), 9.02 / 10.04);
  for (std::uint32_t t : {1u, 2u}) EXPECT_TRUE(schedule.complete(t, 0));
  EXPECT_DOUBLE_EQ(schedule.work_done(), 1.0);

  TileSchedule by_count(4, {}, {}, 2);  // no costs: every tile weighs the same
  EXPECT_DOUBLE_EQ(by_count.work_done(), 0.0);
  EXPECT_TRUE(by_count.complete(3, 1));
  EXPECT_DOUBLE_EQ(by_count.work_done(), 0.25);
}

TEST(TileSchedule, BatchesShrinkToOneTileAsTheQueueEmpties) {
  TileSchedule schedule(4000, {}, {}, 2);
  EXPECT_EQ(schedule.batch_size(), 16u);
  EXPECT_EQ(schedule.take(1, 100).size(), 16u);
  EXPECT_EQ(schedule.take(1, 3).size(), 3u);  // at most what is asked
  while (schedule.waiting() > 20) schedule.take(0, 100);
  EXPECT_EQ(schedule.batch_size(), 1u);
  EXPECT_EQ(schedule.take(1, 100).size(), 1u);
}

TEST(TileSchedule, TheCostliestTilesGoOutOneByOneCheapOnesInBatches) {
  // 4 tiles of cost 100, 396 of cost 1: 796 in all, 2 ranks: a batch holds at most 796 / 16.
  std::vector<double> costs(400, 1.0);
  for (std::size_t t : {5, 77, 200, 399}) costs[t] = 100.0;
  TileSchedule schedule(400, {}, costs, 2);
  for (std::uint32_t expected : {5u, 77u, 200u, 399u}) {
    EXPECT_EQ(schedule.take(1 + int(expected % 2), 100), (std::vector<std::uint32_t>{expected}));
  }
  EXPECT_EQ(schedule.take(1, 100).size(), 16u);  // at most 16 tiles
  while (schedule.waiting() > 40) schedule.take(0, 100);
  const std::size_t late = schedule.take(1, 100).size();  // about 40 / 16 left per batch
  EXPECT_GE(late, 1u);
  EXPECT_LE(late, 3u);
}

TEST(TileSchedule, EveryTileIsDoneOnceAndRepeatsAreDropped) {
  TileSchedule schedule(3, {}, {}, 3);
  const std::vector<std::uint32_t> a = take_tiles(schedule, 1, 2), b = take_tiles(schedule, 2, 2);
  ASSERT_EQ(a.size() + b.size(), 3u);
  EXPECT_FALSE(schedule.all_done());
  for (std::uint32_t t : a) EXPECT_TRUE(schedule.complete(t, 1));
  EXPECT_FALSE(schedule.complete(a.front(), 1));
  for (std::uint32_t t : b) EXPECT_TRUE(schedule.complete(t, 2));
  EXPECT_TRUE(schedule.all_done());
  EXPECT_EQ(schedule.outstanding(1), 0u);
  EXPECT_EQ(schedule.outstanding(2), 0u);
  EXPECT_THROW(schedule.complete(3, 1), std::out_of_range);
}

TEST(TileSchedule, AnIdleRankGetsATileStillOutOnASlowOneAndTheFirstResultWins) {
  TileSchedule schedule(4, {}, {}, 3);
  const std::vector<std::uint32_t> slow = take_tiles(schedule, 1, 2);
  EXPECT_FALSE(schedule.reissue(2).has_value());  // tiles still wait
  const std::vector<std::uint32_t> fast = take_tiles(schedule, 2, 2);
  ASSERT_EQ(schedule.waiting(), 0u);
  ASSERT_EQ(slow.size(), 2u);
  for (std::uint32_t t : fast) schedule.complete(t, 2);
  EXPECT_FALSE(schedule.reissue(1).has_value());  // only rank 1's own tiles are out
  // Rank 2 is idle: it gets the tiles out on rank 1, the last given first, each once.
  const std::optional<std::uint32_t> again = schedule.reissue(2);
  ASSERT_TRUE(again.has_value());
  EXPECT_EQ(*again, slow.back());
  EXPECT_EQ(schedule.outstanding(2), 1u);
  const std::optional<std::uint32_t> next = schedule.reissue(0);
  ASSERT_TRUE(next.has_value());
  EXPECT_EQ(*next, slow.front());
  EXPECT_FALSE(schedule.reissue(2).has_value());
  EXPECT_TRUE(schedule.complete(slow.back(), 2));   // the idle rank wins
  EXPECT_FALSE(schedule.complete(slow.back(), 1));  // the slow rank's result is dropped
  EXPECT_EQ(schedule.outstanding(1), 1u);
  EXPECT_TRUE(schedule.complete(slow.front(), 1));  // the slow rank wins this one
  EXPECT_FALSE(schedule.complete(slow.front(), 0));
  EXPECT_TRUE(schedule.all_done());
  EXPECT_EQ(schedule.outstanding(0), 0u);
  EXPECT_EQ(schedule.outstanding(1), 0u);
  EXPECT_EQ(schedule.outstanding(2), 0u);
}

}  // namespace
}  // namespace quiver
