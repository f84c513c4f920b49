// The worker threads of a render (integrator/thread_arena.h): each thread
// count has its own kept arena of exactly that many threads, the same one
// every time it is asked for, and work in it runs on at most that many.
#include <algorithm>
#include <atomic>
#include <chrono>
#include <thread>

#include <gtest/gtest.h>
#include <tbb/parallel_for.h>

#include "integrator/thread_arena.h"

namespace quiver {
namespace {

TEST(ThreadArena, EachThreadCountKeepsItsOwnArenaOfThatMany) {
  for (const int threads : {3, 1, 2, 3, 1}) {
    tbb::task_arena& arena = kept_task_arena(threads);
    EXPECT_EQ(arena.max_concurrency(), threads);
    EXPECT_EQ(&arena, &kept_task_arena(threads)) << threads;
  }
  EXPECT_NE(&kept_task_arena(1), &kept_task_arena(2));
}

TEST(ThreadArena, WorkRunsOnAtMostTheThreadsAsked) {
  for (const int threads : {1, 2}) {
    ThreadArena arena(threads);
    EXPECT_EQ(arena.threads(), threads);
    std::atomic<int> running{0}, most{0};
    arena.execute([&] {
      tbb::parallel_for(0, 32, [&](int) {
        const int now = ++running;
        int seen = most.load();
        while (now > seen && !most.compare_exchange_weak(seen, now)) {
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
        --running;
      });
    });
    EXPECT_GE(most.load(), 1);
    EXPECT_LE(most.load(), threads);
  }
}

}  // namespace
}  // namespace quiver
