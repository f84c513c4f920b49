// BVH traversal benchmarks on the shared scenes (bunny, fandisk, SPD
// balls-s4, gears-s4, teapot-s12; each only when QUIVER_SHARED_DIR or ../shared has
// it), one thread, rays from bench/bench_rays.h at 256 x 256:
//   bvh/<scene>/n<N>/leaf<L>/<rays>/w<W>:   node width N and leaf size L,
//                                           automatic traversal (the choice
//                                           of N and L);
//   bvh/<scene>/<traversal>/<rays>/w<W>:    packets, single or automatic at
//                                           the default N and L (the choice
//                                           of the per-packet switch);
//   build/<scene>:                          build_scene at the defaults on
//                                           every thread (stores and BVH).
// items_per_second is rays per second; closest hits for primary,
// reflection and diffuse rays, any hit for shadow rays; for builds, the
// scene's primitives per second.
#include <filesystem>
#include <functional>
#include <memory>
#include <mutex>
#include <string>

#include <benchmark/benchmark.h>

#include "bench/bench_rays.h"
#include "bench/bench_support.h"
#include "integrator/scene_intersector.h"
#include "scene/auto_view.h"
#include "io/scene_loader.h"
#include "tests/support/study_streams.h"

namespace quiver::bench {
namespace {

constexpr int kImageSide = 256;

// Built on first use, so that registering costs nothing.
template <class T>
class Lazy {
 public:
  explicit Lazy(std::function<T()> make) : make_(std::move(make)) {}
  const T& get() {
    std::call_once(once_, [this] { value_ = std::make_unique<T>(make_()); });
    return *value_;
  }

 private:
  std::function<T()> make_;
  std::once_flag once_;
  std::unique_ptr<T> value_;
};

struct BvhCase {
  std::shared_ptr<Lazy<Scene>> scene;
  std::shared_ptr<Lazy<SceneRays>> rays;
};

void trace(benchmark::State& state, const BvhCase& lazy, KernelUnit unit, BvhTraversal traversal,
           const std::string& kind) {
  const struct {
    const Scene* scene;
    const SceneRays* rays;
  } c{&lazy.scene->get(), &lazy.rays->get()};
  // The study's streams walk every node width (the product's, width 8 only).
  SceneIntersector intersector(unit, SphereMethod::robust, study_scene_streams(unit, SphereMethod::robust));
  intersector.set_traversal(traversal);
  const RaySoA& rays = kind == "primary"      ? c.rays->primary
                       : kind == "reflection" ? c.rays->reflection
                       : kind == "diffuse"    ? c.rays->diffuse
                                              : c.rays->shadow;
  HitSoA hits(rays);
  OcclusionSoA occlusion(rays);
  std::size_t found = 0;
  for (auto _ : state) {
    if (kind == "shadow") {
      occlusion.reset(rays);
      intersector.occluded(*c.scene, rays, occlusion, Layers::both);
      benchmark::DoNotOptimize(occlusion.occluded.data());
    } else {
      hits.reset(rays);
      intersector.closest(*c.scene, rays, hits);
      benchmark::DoNotOptimize(hits.t.data());
    }
  }
  if (kind == "shadow") {
    for (std::size_t i = 0; i < rays.count; ++i) found += occlusion.occluded[i] != 0;
  } else {
    found = hits.hit_count();
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * rays.count));
  state.counters["hit_fraction"] = rays.count == 0 ? 0.0 : double(found) / double(rays.count);
  state.counters["bvh_bytes"] = double(c.scene->acceleration_bytes());
}

void register_scene(const std::string& name, const std::filesystem::path& path) {
  const auto desc = std::make_shared<SceneDesc>();
  const auto loaded = std::make_shared<Lazy<bool>>([=] {
    *desc = load_scene(path);
    add_default_view(*desc, kImageSide, kImageSide);
    return true;
  });
  const SceneBuildOptions defaults;
  auto build = [=](int width, int leaf) {
    return std::make_shared<Lazy<Scene>>([=] {
      loaded->get();
      SceneBuildOptions options;
      options.bvh.width = width;
      options.bvh.max_leaf_size = leaf;
      return build_scene(*desc, options);
    });
  };
  const auto default_scene = build(defaults.bvh.width, defaults.bvh.max_leaf_size);
  benchmark::RegisterBenchmark(("build/" + name).c_str(), [=](benchmark::State& state) {
    loaded->get();
    std::size_t primitives = 0;
    for (auto _ : state) {
      const Scene scene = build_scene(*desc, defaults);
      primitives = scene.primitive_count();
      benchmark::DoNotOptimize(scene.kind_bvhs.data());
    }
    state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * primitives));
  })->Unit(benchmark::kMillisecond)->UseRealTime();
  const auto rays = std::make_shared<Lazy<SceneRays>>(
      [=] { return make_scene_rays(default_scene->get(), kImageSide, kImageSide, 7); });
  const char* kinds[] = {"primary", "reflection", "diffuse", "shadow"};
  for (KernelUnit unit : bench_units()) {
    std::string w = "w";  // appended, not "w" + to_string(...): g++ 12 warns -Wrestrict on that
    w += std::to_string(lane_width(unit));
    for (int width : {2, 4, 8}) {
      for (int leaf : {4, 8}) {
        const BvhCase c{build(width, leaf), rays};
        for (const char* kind : kinds) {
          const std::string label = "bvh/" + name + "/n" + std::to_string(width) + "/leaf" + std::to_string(leaf) +
                                    "/" + kind + "/" + w;
          benchmark::RegisterBenchmark(label.c_str(), [=](benchmark::State& state) {
            trace(state, c, unit, BvhTraversal::automatic, kind);
          })->Unit(benchmark::kMillisecond);
        }
      }
    }
    const BvhCase c{default_scene, rays};
    const std::pair<const char*, BvhTraversal> traversals[] = {
        {"packets", BvhTraversal::packets}, {"single", BvhTraversal::single}, {"automatic", BvhTraversal::automatic}};
    for (const auto& [traversal_name, traversal] : traversals) {
      for (const char* kind : kinds) {
        const std::string label = "bvh/" + name + "/" + traversal_name + "/" + kind + "/" + w;
        benchmark::RegisterBenchmark(label.c_str(), [=](benchmark::State& state) {
          trace(state, c, unit, traversal, kind);
        })->Unit(benchmark::kMillisecond);
      }
    }
  }
}

[[maybe_unused]] const bool registered = [] {
  const std::filesystem::path dir = shared_dir();
  const std::pair<const char*, std::filesystem::path> scenes[] = {
      {"bunny", dir / "meshes/stanford-bunny.obj"},
      {"fandisk", dir / "meshes/fandisk.obj"},
      {"balls-s4", dir / "scenes/spd/balls-s4.nff"},
      {"gears-s4", dir / "scenes/spd/gears-s4.nff"},
      {"teapot-s12", dir / "scenes/spd/teapot-s12.nff"}};
  for (const auto& [name, path] : scenes) {
    if (std::filesystem::exists(path)) register_scene(name, path);
  }
  return true;
}();

}  // namespace
}  // namespace quiver::bench
