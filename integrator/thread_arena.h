// The worker threads of one render or trace: a oneTBB arena of exactly the
// threads asked for. oneTBB caps workers at the core count unless told
// otherwise (and then warns on stderr), so the arena also raises that cap
// for as long as it lives. The oneTBB arena itself is made once per thread
// count and kept for the process's life (kept_task_arena): oneTBB 2021.8
// keeps about 7 KiB per arena its workers joined after the arena is gone
// (1,000 arenas of 2 threads grow the resident size by 7 MiB), which a
// program calling quiver many times, as Python does, must not pay per call.
#pragma once

#include <cstddef>

#include <tbb/global_control.h>
#include <tbb/info.h>
#include <tbb/task_arena.h>

namespace quiver {

// The process's arena of this many threads (>= 1), made on first use;
// thread-safe.
tbb::task_arena& kept_task_arena(int threads);

class ThreadArena {
 public:
  // threads 0: one per core.
  explicit ThreadArena(int threads)
      : threads_(threads > 0 ? threads : tbb::info::default_concurrency()),
        allowed_(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(threads_)),
        arena_(kept_task_arena(threads_)) {}

  int threads() const { return threads_; }

  template <class Work>
  void execute(const Work& work) {
    arena_.execute(work);
  }

 private:
  int threads_;
  tbb::global_control allowed_;
  tbb::task_arena& arena_;
};

}  // namespace quiver
