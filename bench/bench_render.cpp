// Whole-render benchmarks: render/<scene>/w<W>/threads:<N>, the default
// scene (and balls-s2 from the SPD set when QUIVER_SHARED_DIR or ../shared
// has it) for every kernel unit this CPU runs, on 1 thread and on all.
// Counters: rays per second in total and by kind (primary, shadow,
// reflection, refraction), and lane utilisation of the secondary waves and
// of the shadow waves, compacted (as issued) and uncompacted (what a masked
// per-packet recursion would issue).
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <string>

#include <benchmark/benchmark.h>
#include <tbb/info.h>

#include "bench/bench_support.h"
#include "scene/default_scene.h"
#include "integrator/render.h"
#include "io/nff_reader.h"

namespace quiver::bench {
namespace {

void render_benchmark(benchmark::State& state, std::shared_ptr<const Scene> scene, KernelUnit unit, int threads,
                      int size, const char* aa) {
  RenderSettings settings;
  settings.width = size;
  settings.height = size * 3 / 4;
  settings.aa = parse_anti_aliasing(aa);
  settings.isa = isa_of(unit);
  settings.threads = threads;
  TraceStats stats;
  for (auto _ : state) {
    const RenderResult r = render(*scene, settings);
    stats.add(r.stats);
    benchmark::DoNotOptimize(r.image.rgb.data());
  }
  using benchmark::Counter;
  state.counters["rays"] = Counter(double(stats.rays.total()), Counter::kIsRate);
  state.counters["primary"] = Counter(double(stats.rays.primary), Counter::kIsRate);
  state.counters["shadow"] = Counter(double(stats.rays.shadow), Counter::kIsRate);
  state.counters["reflection"] = Counter(double(stats.rays.reflection), Counter::kIsRate);
  state.counters["refraction"] = Counter(double(stats.rays.refraction), Counter::kIsRate);
  WaveLanes secondary;
  for (std::size_t d = 1; d < stats.waves.size(); ++d) {
    secondary.active += stats.waves[d].active;
    secondary.issued_compacted += stats.waves[d].issued_compacted;
    secondary.issued_uncompacted += stats.waves[d].issued_uncompacted;
  }
  auto ratio = [](std::uint64_t a, std::uint64_t b) { return b == 0 ? 1.0 : double(a) / double(b); };
  state.counters["util_secondary_compacted"] = ratio(secondary.active, secondary.issued_compacted);
  state.counters["util_secondary_uncompacted"] = ratio(secondary.active, secondary.issued_uncompacted);
  state.counters["util_shadow_compacted"] = ratio(stats.shadow.active, stats.shadow.issued_compacted);
  state.counters["util_shadow_uncompacted"] = ratio(stats.shadow.active, stats.shadow.issued_uncompacted);
}

void register_scene(const std::string& name, std::shared_ptr<const Scene> scene, int size, const char* aa) {
  const int all = tbb::info::default_concurrency();
  for (KernelUnit unit : bench_units()) {
    for (int threads : {1, all}) {
      if (threads == all && all == 1) continue;
      const std::string id = "render/" + name + "/w" + std::to_string(lane_width(unit)) + "/threads:" +
                             std::to_string(threads);
      benchmark::RegisterBenchmark(id.c_str(), render_benchmark, scene, unit, threads, size, aa)
          ->Unit(benchmark::kMillisecond)
          ->UseRealTime();
    }
  }
}

const bool registered = [] {
  register_scene("default", std::make_shared<const Scene>(build_scene(default_scene(), {})), 160, "none");
  const std::filesystem::path balls = shared_dir() / "scenes/spd/balls-s2.nff";
  if (std::filesystem::exists(balls)) {
    register_scene("balls-s2", std::make_shared<const Scene>(build_scene(read_nff(balls), {})), 128, "none");
  }
  return true;
}();

}  // namespace
}  // namespace quiver::bench
