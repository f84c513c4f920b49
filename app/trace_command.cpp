#include "app/trace_command.h"

#include <algorithm>
#include <chrono>
#include <random>
#include <tuple>
#include <stdexcept>

#include <nlohmann/json.hpp>
#include <tbb/parallel_for.h>

#include "integrator/ray_batches.h"
#include "integrator/thread_arena.h"

namespace quiver {

namespace {

// The flags `quiver render` shares with `quiver trace`, for its checks.
RenderOptions shared_render_options(const TraceOptions& options) {
  RenderOptions shared;
  shared.width = options.width;
  shared.height = options.height;
  shared.threads = options.threads;
  shared.simd = options.simd;
  shared.crease_angle = options.crease_angle;
  shared.camera = options.camera;
  return shared;
}

}  // namespace

void check_trace_options(const TraceOptions& options) {
  check_render_options(shared_render_options(options));
  if (options.repeat < 1 || options.repeat > kMaxTraceRepeat) {
    throw UsageError("--repeat: expected an integer in [1, " + std::to_string(kMaxTraceRepeat) + "], found " +
                     std::to_string(options.repeat));
  }
}

std::pair<int, int> trace_image_size(const TraceOptions& options, const std::optional<CameraDesc>& camera) {
  const auto [width, height] = image_size(shared_render_options(options), camera);
  if (std::int64_t(width) * std::int64_t(height) > kMaxTracePixels) {
    throw UsageError("image size " + std::to_string(width) + "x" + std::to_string(height) +
                     ": quiver trace holds every ray at once, expected at most 2^24 (16777216) pixels");
  }
  return {width, height};
}

std::pair<int, int> set_trace_view(const TraceOptions& options, SceneDesc& desc) {
  const auto [width, height] = trace_image_size(options, desc.camera);
  set_view(desc, options.camera, width, height);
  return {width, height};
}

void tile_primary_rays(const Camera& camera, const PixelTile& tile, RaySoA& rays) {
  rays.clear();
  for_each_pixel_in_groups(tile.x0, tile.y0, tile.x0 + tile.width, tile.y0 + tile.height,
                           [&](int x, int y) { rays.push(camera.ray(x + 0.5, y + 0.5)); });
  rays.pad();
}

double median(std::vector<double> values) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  const std::size_t n = values.size();
  return n % 2 == 1 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

std::vector<RaySoA> primary_batches(const Camera& camera, int width, int height, ThreadArena& arena, bool shuffled) {
  const std::vector<PixelTile> tiles = pixel_tiles(width, height, kTraceTileSide);
  std::vector<RaySoA> tile_rays(tiles.size());
  arena.execute([&] {
    tbb::parallel_for(std::size_t(0), tiles.size(),
                      [&](std::size_t t) { tile_primary_rays(camera, tiles[t], tile_rays[t]); });
  });
  if (!shuffled) return tile_rays;
  std::vector<Ray<float>> rays;
  for (const RaySoA& tile : tile_rays) {
    for (std::size_t i = 0; i < tile.count; ++i) rays.push_back(tile.get(i));
  }
  std::mt19937_64 random(kTraceShuffleSeed);
  std::shuffle(rays.begin(), rays.end(), random);
  constexpr std::size_t kBatch = std::size_t(kTraceTileSide) * kTraceTileSide;
  std::vector<RaySoA> batches((rays.size() + kBatch - 1) / kBatch);
  for (std::size_t b = 0; b < batches.size(); ++b) {
    for (std::size_t i = b * kBatch; i < std::min(rays.size(), (b + 1) * kBatch); ++i) batches[b].push(rays[i]);
    batches[b].pad();
  }
  return batches;
}

namespace {

// Times `repeat` passes of Answers queries over the batches; count(rays,
// answers) gives a batch's hits and t sum.
template <class Answers, class Count>
void time_queries(const Scene& scene, const std::vector<RaySoA>& batches, ThreadArena& arena, Isa isa, int repeat,
                  const Count& count, PrimaryTraceResult& result) {
  std::vector<std::uint64_t> batch_hits(batches.size(), 0);
  std::vector<double> batch_t_sum(batches.size(), 0.0);
  const SceneIntersector intersector(kernel_unit_for(isa));
  for (int r = 0; r < repeat; ++r) {
    const auto start = std::chrono::steady_clock::now();
    query_batches<Answers>(
        arena, intersector, scene, batches.size(), [&](std::size_t b) -> const RaySoA& { return batches[b]; },
        [&](std::size_t b, const RaySoA& rays, const Answers& answers) {
          std::tie(batch_hits[b], batch_t_sum[b]) = count(rays, answers);
        });
    result.ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
  }
  for (std::size_t b = 0; b < batches.size(); ++b) {
    result.rays += batches[b].count;
    result.hits += batch_hits[b];
    result.t_sum += batch_t_sum[b];
  }
}

}  // namespace

PrimaryTraceResult trace_primary(const Scene& scene, int width, int height, Isa isa, int threads, int repeat,
                                 TraceQuery query) {
  if (repeat < 1) throw std::invalid_argument("repeat must be at least 1");
  PrimaryTraceResult result;
  result.isa = isa;
  ThreadArena arena(threads);
  result.threads = arena.threads();
  const std::vector<RaySoA> batches = primary_batches(Camera(scene.camera, width, height), width, height, arena,
                                                      query.shuffled);
  if (query.occluded) {
    time_queries<OcclusionSoA>(scene, batches, arena, isa, repeat, [](const RaySoA& rays, const OcclusionSoA& answers) {
      std::uint64_t count = 0;
      for (std::size_t i = 0; i < rays.count; ++i) count += answers.occluded[i] != 0 ? 1 : 0;
      return std::pair(count, 0.0);
    }, result);
  } else {
    time_queries<HitSoA>(scene, batches, arena, isa, repeat, [](const RaySoA& rays, const HitSoA& hits) {
      std::uint64_t count = 0;
      double sum = 0.0;
      for (std::size_t i = 0; i < rays.count; ++i) {
        if (hits.id[i] == kNoHit) continue;
        ++count;
        sum += double(hits.t[i]);
      }
      return std::pair(count, sum);
    }, result);
  }
  return result;
}

std::string trace_json_line(const PrimaryTraceResult& result, const Scene& scene, int width, int height,
                            double build_ms, TraceQuery query) {
  std::vector<double> mrays;
  for (double ms : result.ms) mrays.push_back(ms > 0.0 ? double(result.rays) / (ms * 1e3) : 0.0);
  nlohmann::ordered_json line;
  line["mrays_per_s"] = median(mrays);
  line["hits"] = result.hits;
  line["t_sum"] = result.t_sum;
  line["rays"] = result.rays;
  line["ms_median"] = median(result.ms);
  line["threads"] = result.threads;
  line["simd"] = std::string(isa_name(result.isa));
  line["lanes"] = lane_width(result.isa);
  line["build_ms"] = build_ms;
  line["width"] = width;
  line["height"] = height;
  line["repeat"] = result.ms.size();
  line["primitives"] = scene.primitive_count();
  line["acceleration_bytes"] = scene.acceleration_bytes();
  line["memory_bytes"] = scene.memory_bytes();
  line["instances"] = scene.instances.size();
  line["instance_table_bytes"] = scene.instances.memory_bytes() + scene.instance_bvh.memory_bytes();
  line["query"] = query.occluded ? "occluded" : "closest";
  line["order"] = query.shuffled ? "shuffled" : "tiles";
  return line.dump();
}

}  // namespace quiver
