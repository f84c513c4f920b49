#include "python/output_buffers.h"

#include <cstdlib>
#include <mutex>
#include <new>
#include <vector>

namespace quiver {

namespace {

struct KeptBuffers {
  std::mutex mutex;
  std::vector<OutputBuffer> buffers;
  std::size_t bytes = 0;
};

KeptBuffers& kept() {
  static KeptBuffers* buffers = new KeptBuffers;  // never destroyed: arrays may outlive static teardown
  return *buffers;
}

}  // namespace

OutputBuffer acquire_output_buffer(std::size_t bytes) {
  KeptBuffers& pool = kept();
  {
    const std::lock_guard<std::mutex> lock(pool.mutex);
    for (std::size_t i = 0; i < pool.buffers.size(); ++i) {
      const OutputBuffer buffer = pool.buffers[i];
      if (buffer.bytes < bytes || buffer.bytes / 2 > bytes) continue;
      pool.buffers.erase(pool.buffers.begin() + std::ptrdiff_t(i));
      pool.bytes -= buffer.bytes;
      return buffer;
    }
  }
  void* data = std::malloc(bytes == 0 ? 1 : bytes);
  if (data == nullptr) throw std::bad_alloc();
  return {data, bytes};
}

void release_output_buffer(OutputBuffer buffer) {
  KeptBuffers& pool = kept();
  {
    const std::lock_guard<std::mutex> lock(pool.mutex);
    if (pool.bytes + buffer.bytes <= kKeptOutputBytes) {
      pool.buffers.push_back(buffer);
      pool.bytes += buffer.bytes;
      return;
    }
  }
  std::free(buffer.data);
}

}  // namespace quiver
