#include "integrator/supersampling.h"

#include <cstdint>

#include "integrator/sample_hash.h"

namespace quiver {

Supersampler::Supersampler(const AntiAliasing& aa)
    : jitter_(aa.mode == AntiAliasing::Mode::jitter),
      cells_per_side_(aa.mode == AntiAliasing::Mode::none ? 1 : aa.n) {
  const int n = cells_per_side_;
  for (int j = 0; j < n * n; ++j) cells_.push_back({j % n, j / n, (j % n + 0.5) / n, (j / n + 0.5) / n});
}

void Supersampler::render(const TileTarget& target, const PixelTile& tile, SampleBatch& batch) const {
  const int n = cells_per_side_;
  const int x1 = tile.x0 + tile.width, y1 = tile.y0 + tile.height;
  const double spacing = 1.0 / n;
  const std::uint64_t seed = target.settings.trace.seed;
  target.start_batch(batch);
  batch.film.resize(std::size_t(tile.width) * std::size_t(tile.height) * std::size_t(n * n));
  std::size_t next = 0;
  for_each_pixel_in_groups(tile.x0, tile.y0, x1, y1, [&](int x, int y) {
    const std::uint64_t pixel = std::uint64_t(y) * std::uint64_t(target.image.width) + std::uint64_t(x);
    for (int j = 0; j < n * n; ++j) {
      const Cell& cell = cells_[std::size_t(j)];
      double ox = cell.cx, oy = cell.cy;
      if (jitter_) {
        ox = (cell.i + hash_uniform(seed, pixel, 2 * j)) / n;
        oy = (cell.j + hash_uniform(seed, pixel, 2 * j + 1)) / n;
      }
      batch.film.set(next++, x + ox, y + oy, x + cell.cx, y + cell.cy, spacing);
    }
  });
  target.trace(batch);
  const float inv = 1.f / float(n * n);
  std::size_t k = 0;
  for_each_pixel_in_groups(tile.x0, tile.y0, x1, y1, [&](int x, int y) {
    Vec3<float> sum{0.f, 0.f, 0.f};
    for (int j = 0; j < n * n; ++j) sum = sum + batch.colors[k++];
    target.set_pixel(x, y, sum * inv);
  });
}

}  // namespace quiver
