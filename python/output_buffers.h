// Memory for scene.intersect's output arrays, kept for the next call once
// NumPy frees them. Fresh memory costs the kernel a zeroed page per 4 KiB
// touched, which was the largest part of what intersect adds to trace's
// work (docs/PYTHON.md, "Speed"); a program querying in a loop gets the
// pages of its previous results back instead. At most kKeptOutputBytes are
// kept; a buffer that would exceed it is freed.
#pragma once

#include <cstddef>

namespace quiver {

inline constexpr std::size_t kKeptOutputBytes = std::size_t{64} << 20;

struct OutputBuffer {
  void* data = nullptr;
  std::size_t bytes = 0;
};

// A kept buffer of at least bytes and at most twice as many, else a new
// one; throws std::bad_alloc. Thread-safe.
OutputBuffer acquire_output_buffer(std::size_t bytes);

// Keeps the buffer for acquire_output_buffer, or frees it. Thread-safe.
void release_output_buffer(OutputBuffer buffer);

}  // namespace quiver
