#include "integrator/thread_arena.h"

#include <map>
#include <mutex>

namespace quiver {

tbb::task_arena& kept_task_arena(int threads) {
  static std::mutex mutex;
  // Never destroyed: an arena torn down after oneTBB's own exit handlers
  // may touch a finished scheduler. At most kMaxThreads (1024) of them.
  static auto* arenas = new std::map<int, tbb::task_arena*>;
  const std::lock_guard<std::mutex> lock(mutex);
  tbb::task_arena*& arena = (*arenas)[threads];
  if (arena == nullptr) {
    arena = new tbb::task_arena(threads);
    arena->initialize();
  }
  return *arena;
}

}  // namespace quiver
