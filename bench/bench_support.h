// Registration of kernel microbenchmarks: every kernel x method x width x
// ray mix, named kind/method/wW/mix[/scan|/occluded], reporting ray-primitive
// tests per second as items_per_second and the fraction of rays that hit.
// Mixes: camera (coherent primary rays in 4x2 pixel tiles, as a packet
// tracer issues them), hits (incoherent rays aimed at primitives) and misses.
#pragma once

#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>

#include "geometry/streams.h"
#include "simd/isa.h"

namespace quiver::bench {

// The shared data folder (scenes/spd, meshes): QUIVER_SHARED_DIR from the
// environment, else the one CMake saw beside the source tree.
std::filesystem::path shared_dir();

inline constexpr std::size_t kBenchRays = 4096;
inline constexpr std::size_t kBenchPrimitives = 64;

struct RayMixes {
  RaySoA camera;  // coherent primary rays through the primitives (camera_rays)
  RaySoA hits;    // incoherent rays aimed at primitives: most hit one
  RaySoA misses;  // rays that miss every primitive
};

// The kBenchRays primary rays of a 64 x 64 pinhole camera at
// center + (0, 0, 4 half_extent) looking down -z through the square of side
// 2.4 half_extent around center, in 4 x 2 pixel tiles.
RaySoA camera_rays(const Vec3<float>& center, float half_extent);

// The kernel units to register: the unit each ISA this CPU supports runs
// with (scalar_fma for scalar where FMA exists), or only the one QUIVER_SIMD
// names (auto or unset means all). Names carry the unit's lane width.
std::vector<KernelUnit> bench_units();


// Registers closest-hit packets on every mix, scan on the incoherent
// mixes, and any-hit packets on the miss mix (where no early exit makes the test count inexact), for
// each unit of bench_units(). Items are rays x tests_per_ray, by default
// rays x primitives (a store of triangulated polygons counts polygons).
template <class S>
void register_kernel_benchmarks(const std::string& kind_and_method,
                                const std::function<KernelStreams<S>(KernelUnit)>& streams_for_unit,
                                std::shared_ptr<const S> prims, std::shared_ptr<const RayMixes> rays,
                                std::size_t tests_per_ray = 0) {
  if (tests_per_ray == 0) tests_per_ray = prims->size();
  for (KernelUnit unit : bench_units()) {
    const KernelStreams<S> streams = streams_for_unit(unit);
    const std::string prefix = kind_and_method + "/w" + std::to_string(lane_width(unit));
    for (const std::string mix_name : {"camera", "hits", "misses"}) {
      const RaySoA* mix = mix_name == "camera" ? &rays->camera : (mix_name == "hits" ? &rays->hits : &rays->misses);
      if (mix->count == 0) continue;
      const std::string name = prefix + "/" + mix_name;
      const double tests = double(mix->count) * double(tests_per_ray);
      auto closest = [=](benchmark::State& state, auto stream) {
        const auto keep_alive = rays;
        HitSoA hits(*mix);
        for (auto _ : state) {
          stream(*mix, *prims, hits);
          benchmark::DoNotOptimize(hits.t.data());
          benchmark::ClobberMemory();
        }
        state.SetItemsProcessed(static_cast<std::int64_t>(tests * double(state.iterations())));
        state.counters["hit_fraction"] = double(hits.hit_count()) / double(mix->count);
      };
      benchmark::RegisterBenchmark(name.c_str(), [=](benchmark::State& st) { closest(st, streams.closest_packets); });
      if (streams.closest_scan && mix_name != "camera") {
        benchmark::RegisterBenchmark((name + "/scan").c_str(),
                                     [=](benchmark::State& st) { closest(st, streams.closest_scan); });
      }
      if (mix_name == "misses") {
        benchmark::RegisterBenchmark((name + "/occluded").c_str(), [=](benchmark::State& state) {
          const auto keep_alive = rays;
          for (auto _ : state) {
            OcclusionSoA occlusion(*mix);
            streams.occluded_packets(*mix, *prims, occlusion);
            benchmark::DoNotOptimize(occlusion.occluded.data());
          }
          state.SetItemsProcessed(static_cast<std::int64_t>(tests * double(state.iterations())));
        });
      }
    }
  }
}

// Dispatches a kind's streams template (e.g. study_plane_streams<U>) on a run-time unit.
template <class S, class Method, class StreamsOf>
std::function<KernelStreams<S>(KernelUnit)> streams_by_unit(Method method, StreamsOf streams_of) {
  return [=](KernelUnit unit) {
    return with_kernel_unit(unit, [&](auto u) { return streams_of(u, method); });
  };
}

}  // namespace quiver::bench
