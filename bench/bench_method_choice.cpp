// What the per-scene sphere method saves (bench/ACCURACY.md, "Choosing per
// scene"): method_choice/<scene>/w<W>/<robust|chosen>, whole renders on one
// thread with the robust sphere test forced and with the per-scene choice,
// and method_choice_rays/... the same pair on the intersector alone (the
// scene's bench/bench_rays.h ray sets), for the scenes where the choice is
// the algebraic test (where it is robust both are the same code), with the
// scene's distance ratio as a counter. Candidates: the built-in scene,
// io/examples/*.toml, SPD balls-s1/s2 (when QUIVER_SHARED_DIR or ../shared
// has them) and a compact cluster of eight mirror and glass spheres (which
// qualify: bench/ACCURACY.md). Run with --benchmark_repetitions=N
// --benchmark_enable_random_interleaving=true and compare medians.
#include <algorithm>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>

#include "bench/bench_rays.h"
#include "bench/bench_support.h"
#include "scene/default_scene.h"
#include "integrator/render.h"
#include "io/scene_loader.h"

namespace quiver::bench {
namespace {

const std::filesystem::path kExamplesDir = std::filesystem::path(QUIVER_SOURCE_DIR) / "io" / "examples";

// Eight spheres of radius 1 at (+-1.25, +-1.25, +-1.25), alternately mirror
// and glass, no floor, the camera 6 units away: every sphere within ~9 radii
// of every ray origin, and most rays bounce between spheres.
SceneDesc sphere_cluster() {
  SceneDesc d;
  d.camera = CameraDesc{{2.f, 1.5f, 6.f}, {0.f, 0.f, 0.f}, {0.f, 1.f, 0.f}, 45.f, 0.01f, 640, 480};
  d.background = {0.25f, 0.3f, 0.45f};
  d.lights.push_back({});
  d.lights.back().position = {2.f, 2.f, 5.f};
  d.materials = {MaterialDesc{.color = {0.9f, 0.6f, 0.4f}, .kd = 0.3f, .ks = 0.5f, .kr = 0.6f},
                 MaterialDesc{.kd = 0.1f, .kt = 0.8f, .ior = 1.5f}};
  for (int k = 0; k < 8; ++k) {
    const Vec3<float> c{k & 1 ? 1.25f : -1.25f, k & 2 ? 1.25f : -1.25f, k & 4 ? 1.25f : -1.25f};
    d.spheres.push_back({{c, 1.f}, std::size_t((k ^ (k >> 1) ^ (k >> 2)) & 1)});
  }
  return d;
}

void render_benchmark(benchmark::State& state, std::shared_ptr<const Scene> scene, KernelUnit unit,
                      MethodChoice choice, int width, int height) {
  RenderSettings settings;
  settings.width = width;
  settings.height = height;
  settings.isa = isa_of(unit);
  settings.threads = 1;
  settings.methods = choice;
  std::uint64_t rays = 0;
  for (auto _ : state) {
    const RenderResult r = render(*scene, settings);
    rays += r.stats.rays.total();
    benchmark::DoNotOptimize(r.image.rgb.data());
  }
  state.counters["rays"] = benchmark::Counter(double(rays), benchmark::Counter::kIsRate);
  state.counters["algebraic"] = choose_sphere_method(*scene, choice) == SphereMethod::algebraic ? 1.0 : 0.0;
  state.counters["distance_ratio"] = sphere_origin_distance_ratio(*scene);
}

// The intersector alone on the scene's ray sets (bench/bench_rays.h): closest
// hits of the primary, reflection and diffuse rays, any hit of the shadow rays.
void rays_benchmark(benchmark::State& state, std::shared_ptr<const Scene> scene,
                    std::shared_ptr<const SceneRays> rays, KernelUnit unit, MethodChoice choice) {
  const SceneIntersector intersector(unit, choose_sphere_method(*scene, choice));
  HitSoA hits;
  OcclusionSoA occlusion(rays->shadow);
  std::size_t count = 0;
  for (auto _ : state) {
    for (const RaySoA* set : {&rays->primary, &rays->reflection, &rays->diffuse}) {
      hits.reset(*set);
      intersector.closest(*scene, *set, hits);
      benchmark::DoNotOptimize(hits.t.data());
      count += set->count;
    }
    occlusion = OcclusionSoA(rays->shadow);
    intersector.occluded(*scene, rays->shadow, occlusion, Layers::both);
    count += rays->shadow.count;
  }
  state.counters["rays"] = benchmark::Counter(double(count), benchmark::Counter::kIsRate);
}

void consider(const std::string& name, const SceneDesc& desc) {
  auto scene = std::make_shared<const Scene>(build_scene(desc, {}));
  if (choose_sphere_method(*scene, MethodChoice::per_scene) != SphereMethod::algebraic) return;
  const int width = 320, height = std::max(1, width * desc.camera->height / desc.camera->width);
  const auto rays = std::make_shared<const SceneRays>(make_scene_rays(*scene, width, height, 1));
  for (KernelUnit unit : bench_units()) {
    for (MethodChoice choice : {MethodChoice::most_robust, MethodChoice::per_scene}) {
      const std::string id = "method_choice/" + name + "/w" + std::to_string(lane_width(unit)) + "/" +
                             (choice == MethodChoice::per_scene ? "chosen" : "robust");
      benchmark::RegisterBenchmark(id.c_str(), render_benchmark, scene, unit, choice, width, height)
          ->Unit(benchmark::kMillisecond)
          ->UseRealTime();
      benchmark::RegisterBenchmark(("method_choice_rays" + id.substr(id.find('/'))).c_str(), rays_benchmark, scene,
                                   rays, unit, choice)
          ->Unit(benchmark::kMillisecond)
          ->UseRealTime();
    }
  }
}

const bool registered = [] {
  consider("default", default_scene());
  std::vector<std::filesystem::path> examples;
  if (std::filesystem::is_directory(kExamplesDir)) {
    for (const auto& e : std::filesystem::directory_iterator(kExamplesDir)) {
      if (e.path().extension() == ".toml") examples.push_back(e.path());
    }
  }
  std::sort(examples.begin(), examples.end());
  for (const auto& path : examples) consider(path.stem().string(), load_scene(path));
  for (const char* balls : {"balls-s1", "balls-s2"}) {
    const std::filesystem::path path = shared_dir() / "scenes/spd" / (std::string(balls) + ".nff");
    if (std::filesystem::exists(path)) consider(balls, load_scene(path));
  }
  consider("sphere_cluster", sphere_cluster());
  return true;
}();

}  // namespace
}  // namespace quiver::bench
