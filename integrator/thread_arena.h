// The worker threads of one render or trace: a oneTBB arena of exactly the
// threads asked for. oneTBB caps workers at the core count unless told
// otherwise (and then warns on stderr), so the arena also raises that cap
// for as long as it lives.
#pragma once

#include <cstddef>

#include <tbb/global_control.h>
#include <tbb/info.h>
#include <tbb/task_arena.h>

namespace quiver {

class ThreadArena {
 public:
  // threads 0: one per core.
  explicit ThreadArena(int threads)
      : threads_(threads > 0 ? threads : tbb::info::default_concurrency()),
        allowed_(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(threads_)),
        arena_(threads_) {}

  int threads() const { return threads_; }

  template <class Work>
  void execute(const Work& work) {
    arena_.execute(work);
  }

 private:
  int threads_;
  tbb::global_control allowed_;
  tbb::task_arena arena_;
};

}  // namespace quiver
