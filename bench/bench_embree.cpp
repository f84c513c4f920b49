// quiver against Intel Embree 3 on the same rays (bench/README.md, "Against
// Embree"). Per scene the ray sets of bench/bench_rays.h (quiver's camera
// and hit points): primary rays through the pixel centres (coherent), then
// from quiver's primary hits mirror reflections, random hemisphere
// directions (incoherent) and shadow rays toward one point light (any-hit).
// Each set is cut into blocks of 256 rays spread over oneTBB threads (one
// arena per thread count) and traced by
//   quiver  SceneIntersector::closest (shadow: occluded on both layers) on
//           each block's RaySoA, in the kernel unit QUIVER_SIMD names,
//           else the widest the CPU has,
//   e1      rtcIntersect1 / rtcOccluded1 per ray,
//   e8      rtcIntersect8 / rtcOccluded8 per 8 consecutive rays,
// each pass filling its ray state and writing every ray's result out, so
// the three do the same bookkeeping. Repeats interleave the three tracers;
// the table shows medians. Agreement: rays that hit in one tracer and miss
// in the other (expected: a few at silhouettes and at the edges of quiver's
// polygons, which Embree sees ear-clipped) and closest-hit distances
// differing by more than a relative 1e-4.
// Usage: quiver_bench_embree [--width W] [--height H] [--repeat R]
//   [--scenes a,b,...] [--robust] [--embree-isa native|avx2|sse4.2] [--json FILE]
//   (--help lists them). Scenes are names in $QUIVER_SHARED_DIR/meshes (.obj)
//   or scenes/spd (.nff), or paths.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/info.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "bench/bench_embree_scene.h"
#include "bench/bench_rays.h"
#include "integrator/scene_intersector.h"
#include "scene/auto_view.h"
#include "io/scene_loader.h"
#include "app/trace_command.h"

namespace quiver::bench {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

constexpr std::size_t kBlockRays = 256;
constexpr float kMiss = std::numeric_limits<float>::infinity();
constexpr double kDistanceTolerance = 1e-4;  // relative
constexpr std::uint32_t kRaySeed = 7;        // for the diffuse directions

struct Options {
  int width = 512, height = 512, repeat = 5;
  std::vector<std::string> scenes{"stanford-bunny", "balls-s4", "gears-s4"};
  bool robust = false;
  std::string embree_isa = "native";  // or a max_isa Embree accepts
  std::string json_path;
};

fs::path shared_dir() {
  if (const char* env = std::getenv("QUIVER_SHARED_DIR")) return env;
  return QUIVER_SHARED_DIR;
}

fs::path scene_path(const std::string& name) {
  if (fs::exists(name)) return name;
  for (const fs::path& candidate :
       {shared_dir() / "meshes" / (name + ".obj"), shared_dir() / "scenes" / "spd" / (name + ".nff")}) {
    if (fs::exists(candidate)) return candidate;
  }
  throw std::runtime_error("scene '" + name + "' is neither a file nor in " + (shared_dir() / "meshes").string() +
                           " or " + (shared_dir() / "scenes" / "spd").string() + " (set QUIVER_SHARED_DIR)");
}

struct RaySet {
  std::string name;
  bool coherent = false;
  bool any_hit = false;  // occlusion only (shadow rays)
  std::vector<RaySoA> blocks;
  std::size_t count = 0;
};

RaySet blocks_of(std::string name, const RaySoA& rays, bool coherent, bool any_hit) {
  RaySet set{std::move(name), coherent, any_hit, {}, rays.count};
  for (std::size_t first = 0; first < rays.count; first += kBlockRays) {
    RaySoA& block = set.blocks.emplace_back();
    for (std::size_t i = first; i < std::min(rays.count, first + kBlockRays); ++i) block.push(rays.get(i));
    block.pad();
  }
  return set;
}

// Per block, per ray: the hit distance, kMiss on a miss.
using Distances = std::vector<std::vector<float>>;

Distances sized_like(const RaySet& set) {
  Distances d(set.blocks.size());
  for (std::size_t b = 0; b < set.blocks.size(); ++b) d[b].assign(set.blocks[b].count, kMiss);
  return d;
}

// One timed pass: trace(block index, distances of that block) over every block.
double timed_pass(tbb::task_arena& arena, const RaySet& set, Distances& out,
                  const std::function<void(std::size_t, std::vector<float>&)>& trace) {
  const auto start = Clock::now();
  arena.execute([&] {
    tbb::parallel_for(
        tbb::blocked_range<std::size_t>(0, set.blocks.size(), 1),
        [&](const tbb::blocked_range<std::size_t>& range) {
          for (std::size_t b = range.begin(); b != range.end(); ++b) trace(b, out[b]);
        },
        tbb::simple_partitioner());
  });
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

void set_embree_ray(const RaySoA& rays, std::size_t i, RTCRay& ray) {
  ray.org_x = rays.ox[i];
  ray.org_y = rays.oy[i];
  ray.org_z = rays.oz[i];
  ray.dir_x = rays.dx[i];
  ray.dir_y = rays.dy[i];
  ray.dir_z = rays.dz[i];
  ray.tnear = rays.tmin[i];
  ray.tfar = rays.tmax[i];
  ray.time = 0.f;
  ray.mask = ~0u;
  ray.id = 0;
  ray.flags = 0;
}

// Rays first..first+7; columns are padded to a multiple of 8, so lanes past
// the end read valid numbers and are masked off in `valid`.
void set_embree_ray8(const RaySoA& rays, std::size_t first, RTCRay8& ray, int* valid) {
  for (std::size_t k = 0; k < 8; ++k) {
    const std::size_t i = first + k;
    valid[k] = i < rays.count ? -1 : 0;
    ray.org_x[k] = rays.ox[i];
    ray.org_y[k] = rays.oy[i];
    ray.org_z[k] = rays.oz[i];
    ray.dir_x[k] = rays.dx[i];
    ray.dir_y[k] = rays.dy[i];
    ray.dir_z[k] = rays.dz[i];
    ray.tnear[k] = rays.tmin[i];
    ray.tfar[k] = rays.tmax[i];
    ray.time[k] = 0.f;
    ray.mask[k] = ~0u;
    ray.id[k] = 0;
    ray.flags[k] = 0;
  }
}

struct Agreement {
  std::size_t both = 0, only_first = 0, only_second = 0, distance_differs = 0;
  double largest_relative_difference = 0.0;  // among rays both hit
};

Agreement compare(const Distances& a, const Distances& b) {
  Agreement g;
  for (std::size_t k = 0; k < a.size(); ++k) {
    for (std::size_t i = 0; i < a[k].size(); ++i) {
      const bool ha = a[k][i] != kMiss, hb = b[k][i] != kMiss;
      if (ha && hb) {
        ++g.both;
        const double relative = std::fabs(double(a[k][i]) - double(b[k][i])) / std::fabs(double(b[k][i]));
        if (relative > kDistanceTolerance) ++g.distance_differs;
        g.largest_relative_difference = std::max(g.largest_relative_difference, relative);
      } else if (ha) {
        ++g.only_first;
      } else if (hb) {
        ++g.only_second;
      }
    }
  }
  return g;
}

struct TracerTimes {
  std::vector<double> quiver, e1, e8;
};

nlohmann::ordered_json run_set(const RaySet& set, const Scene& scene, const SceneIntersector& intersector,
                               RTCScene embree, int threads, int repeat) {
  tbb::task_arena arena(threads);
  tbb::enumerable_thread_specific<HitSoA> thread_hits;
  tbb::enumerable_thread_specific<OcclusionSoA> thread_occlusion;
  Distances quiver_t = sized_like(set), e1_t = sized_like(set), e8_t = sized_like(set);
  const int flags = set.coherent ? RTC_INTERSECT_CONTEXT_FLAG_COHERENT : RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT;
  // Any-hit results are written as distance 0 (blocked) or kMiss.
  constexpr float kBlocked = 0.f;

  auto quiver_block = [&](std::size_t b, std::vector<float>& out) {
    const RaySoA& rays = set.blocks[b];
    if (set.any_hit) {
      OcclusionSoA& result = thread_occlusion.local();
      result.reset(rays);
      intersector.occluded(scene, rays, result, Layers::both);
      for (std::size_t i = 0; i < rays.count; ++i) out[i] = result.occluded[i] ? kBlocked : kMiss;
      return;
    }
    HitSoA& hits = thread_hits.local();
    hits.reset(rays);
    intersector.closest(scene, rays, hits);
    for (std::size_t i = 0; i < rays.count; ++i) out[i] = hits.id[i] == kNoHit ? kMiss : hits.t[i];
  };
  auto e1_block = [&](std::size_t b, std::vector<float>& out) {
    const RaySoA& rays = set.blocks[b];
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    context.flags = RTCIntersectContextFlags(flags);
    for (std::size_t i = 0; i < rays.count; ++i) {
      RTCRayHit rh;
      set_embree_ray(rays, i, rh.ray);
      if (set.any_hit) {
        rtcOccluded1(embree, &context, &rh.ray);
        out[i] = rh.ray.tfar < 0.f ? kBlocked : kMiss;  // Embree sets tfar to -inf when blocked
        continue;
      }
      rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
      rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
      rtcIntersect1(embree, &context, &rh);
      out[i] = rh.hit.geomID == RTC_INVALID_GEOMETRY_ID ? kMiss : rh.ray.tfar;
    }
  };
  auto e8_block = [&](std::size_t b, std::vector<float>& out) {
    const RaySoA& rays = set.blocks[b];
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    context.flags = RTCIntersectContextFlags(flags);
    alignas(32) RTCRayHit8 rh;
    alignas(32) int valid[8];
    for (std::size_t first = 0; first < rays.count; first += 8) {
      set_embree_ray8(rays, first, rh.ray, valid);
      const std::size_t lanes = std::min<std::size_t>(8, rays.count - first);
      if (set.any_hit) {
        rtcOccluded8(valid, embree, &context, &rh.ray);
        for (std::size_t k = 0; k < lanes; ++k) out[first + k] = rh.ray.tfar[k] < 0.f ? kBlocked : kMiss;
        continue;
      }
      for (std::size_t k = 0; k < 8; ++k) {
        rh.hit.geomID[k] = RTC_INVALID_GEOMETRY_ID;
        rh.hit.instID[0][k] = RTC_INVALID_GEOMETRY_ID;
      }
      rtcIntersect8(valid, embree, &context, &rh);
      for (std::size_t k = 0; k < lanes; ++k) {
        out[first + k] = rh.hit.geomID[k] == RTC_INVALID_GEOMETRY_ID ? kMiss : rh.ray.tfar[k];
      }
    }
  };

  TracerTimes times;
  for (int r = 0; r < repeat; ++r) {
    times.quiver.push_back(timed_pass(arena, set, quiver_t, quiver_block));
    times.e1.push_back(timed_pass(arena, set, e1_t, e1_block));
    times.e8.push_back(timed_pass(arena, set, e8_t, e8_block));
  }
  auto mrays = [&](const std::vector<double>& ms) { return double(set.count) / (median(ms) * 1e3); };
  const Agreement with_e1 = compare(quiver_t, e1_t), with_e8 = compare(quiver_t, e8_t);
  nlohmann::ordered_json row;
  row["rays"] = set.name;
  row["count"] = set.count;
  row["threads"] = threads;
  row["quiver_mrays_per_s"] = mrays(times.quiver);
  row["embree1_mrays_per_s"] = mrays(times.e1);
  row["embree8_mrays_per_s"] = mrays(times.e8);
  row["quiver_over_embree1"] = median(times.e1) / median(times.quiver);
  row["quiver_over_embree8"] = median(times.e8) / median(times.quiver);
  row["ms"] = {{"quiver", times.quiver}, {"embree1", times.e1}, {"embree8", times.e8}};
  row["hits"] = {{"both", with_e1.both},
                 {"quiver_only", with_e1.only_first},
                 {"embree1_only", with_e1.only_second},
                 {"distance_differs", with_e1.distance_differs},
                 {"largest_relative_difference", with_e1.largest_relative_difference},
                 {"embree8_vs_quiver_mismatches", with_e8.only_first + with_e8.only_second}};
  return row;
}

nlohmann::ordered_json run_scene(const std::string& name, const Options& options, const EmbreeDevice& device) {
  const fs::path path = scene_path(name);
  SceneDesc desc = load_scene(path);
  if (!desc.camera) add_default_view(desc, options.width, options.height);
  // Both builds run --repeat times (the first also warms up each library's threads); medians reported.
  const SceneBuildOptions build_options{};
  std::optional<Scene> built;
  std::optional<EmbreeScene> embree_built;
  std::vector<double> quiver_build_ms, embree_build_ms, embree_commit_ms;
  for (int r = 0; r < options.repeat; ++r) {
    built.reset();
    const auto build_start = Clock::now();
    built.emplace(build_scene(desc, build_options));
    quiver_build_ms.push_back(std::chrono::duration<double, std::milli>(Clock::now() - build_start).count());
    embree_built.reset();
    embree_built.emplace(build_embree_scene(device, desc, *built, options.robust));
    embree_build_ms.push_back(embree_built->build_ms);
    embree_commit_ms.push_back(embree_built->commit_ms);
  }
  const Scene& scene = *built;
  const EmbreeScene& embree = *embree_built;
  if (embree.skipped_planes + embree.skipped_cones > 0) {
    std::fprintf(stderr, "warning: %s: %zu planes and %zu cones have no Embree counterpart here: hits will differ\n",
                 name.c_str(), embree.skipped_planes, embree.skipped_cones);
  }

  const KernelUnit unit = kernel_unit_for(isa_from_environment());  // QUIVER_SIMD, else the widest
  const SceneIntersector intersector(unit);
  const SceneRays rays = make_scene_rays(scene, options.width, options.height, kRaySeed);
  const RaySet primary = blocks_of("primary", rays.primary, true, false);
  const RaySet reflection = blocks_of("reflection", rays.reflection, false, false);
  const RaySet diffuse = blocks_of("diffuse", rays.diffuse, false, false);
  const RaySet shadow = blocks_of("shadow", rays.shadow, false, true);

  const std::size_t primitives = scene.primitive_count();
  nlohmann::ordered_json result;
  result["scene"] = name;
  result["file"] = path.string();
  result["width"] = options.width;
  result["height"] = options.height;
  result["quiver_acceleration"] = build_options.acceleration == Acceleration::bvh ? "bvh" : "none (brute force)";
  result["quiver_unit"] = std::string(kernel_unit_name(unit));
  result["primitives"] = primitives;
  result["embree_spheres"] = embree.spheres;
  result["embree_triangles"] = embree.triangles;
  result["embree_robust"] = options.robust;
  result["embree_max_isa"] = options.embree_isa;
  result["embree_avx512"] = device.avx512();
  result["quiver_build_ms"] = median(quiver_build_ms);
  result["embree_build_ms"] = median(embree_build_ms);
  result["embree_commit_ms"] = median(embree_commit_ms);
  result["quiver_geometry_bytes"] = scene.memory_bytes();
  result["quiver_acceleration_bytes"] = scene.acceleration_bytes();
  result["embree_buffer_bytes"] = embree.buffer_bytes;
  result["embree_monitored_bytes"] = embree.monitored_bytes;
  nlohmann::ordered_json rows = nlohmann::ordered_json::array();
  const int all = tbb::info::default_concurrency();
  for (const RaySet* set : {&primary, &reflection, &diffuse, &shadow}) {
    for (int threads : {1, all}) {
      if (threads == all && all == 1) continue;
      std::fprintf(stderr, "%s: %s rays, %d thread(s)...\n", name.c_str(), set->name.c_str(), threads);
      rows.push_back(run_set(*set, scene, intersector, embree.scene.get(), threads, options.repeat));
    }
  }
  result["runs"] = rows;
  return result;
}

void print_tables(const nlohmann::ordered_json& results) {
  std::printf(
      "\n| scene | rays | count | threads | quiver Mrays/s | e1 Mrays/s | e8 Mrays/s | quiver/e1 | quiver/e8 "
      "| hit only in quiver / only in e1 | distance differs |\n");
  std::printf("| --- | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |\n");
  for (const auto& s : results) {
    for (const auto& r : s["runs"]) {
      std::printf("| %s | %s | %zu | %d | %.2f | %.2f | %.2f | %.2fx | %.2fx | %zu / %zu | %zu |\n",
                  s["scene"].get<std::string>().c_str(), r["rays"].get<std::string>().c_str(),
                  r["count"].get<std::size_t>(), r["threads"].get<int>(), r["quiver_mrays_per_s"].get<double>(),
                  r["embree1_mrays_per_s"].get<double>(), r["embree8_mrays_per_s"].get<double>(),
                  r["quiver_over_embree1"].get<double>(), r["quiver_over_embree8"].get<double>(),
                  r["hits"]["quiver_only"].get<std::size_t>(), r["hits"]["embree1_only"].get<std::size_t>(),
                  r["hits"]["distance_differs"].get<std::size_t>());
    }
  }
  std::printf(
      "\n| scene | primitives | Embree spheres + triangles | quiver build ms | Embree build ms (commit) "
      "| quiver geometry B/prim | quiver BVH B/prim | Embree buffers B/prim | Embree rest B/prim |\n");
  std::printf("| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |\n");
  for (const auto& s : results) {
    const double n = std::max(1.0, s["primitives"].get<double>());
    const double buffers = s["embree_buffer_bytes"].get<double>();
    std::printf("| %s | %zu | %zu + %zu | %.1f | %.1f (%.1f) | %.1f | %.1f | %.1f | %.1f |\n",
                s["scene"].get<std::string>().c_str(), s["primitives"].get<std::size_t>(),
                s["embree_spheres"].get<std::size_t>(), s["embree_triangles"].get<std::size_t>(),
                s["quiver_build_ms"].get<double>(), s["embree_build_ms"].get<double>(),
                s["embree_commit_ms"].get<double>(), s["quiver_geometry_bytes"].get<double>() / n,
                s["quiver_acceleration_bytes"].get<double>() / n, buffers / n,
                (s["embree_monitored_bytes"].get<double>() - buffers) / n);
  }
  std::printf("\nquiver acceleration: %s\n",
              results.empty() ? "-" : results[0]["quiver_acceleration"].get<std::string>().c_str());
}

}  // namespace
}  // namespace quiver::bench

int main(int argc, char** argv) {
  using namespace quiver::bench;
  Options options;
  CLI::App app{
      "Trace the same primary, reflection, diffuse and shadow rays through quiver and Intel Embree 3 "
      "(rtcIntersect1 and rtcIntersect8) on 1 thread and on all, and print Mrays/s, the ratios, the hit "
      "agreement, build times and bytes per primitive (bench/README.md, \"Against Embree\")",
      "quiver_bench_embree"};
  app.add_option("--width", options.width, "Image width of the ray sets")
      ->check(CLI::Range(1, 16384))
      ->capture_default_str();
  app.add_option("--height", options.height, "Image height of the ray sets")
      ->check(CLI::Range(1, 16384))
      ->capture_default_str();
  app.add_option("--repeat", options.repeat, "Timed passes per tracer; the tables give medians")
      ->check(CLI::Range(1, 10000))->capture_default_str();
  app.add_option("--scenes", options.scenes,
                 "Comma-separated scene names in $QUIVER_SHARED_DIR/meshes (.obj) or scenes/spd (.nff), or paths")
      ->delimiter(',')->capture_default_str();
  app.add_flag("--robust", options.robust, "Build the Embree scene with RTC_SCENE_FLAG_ROBUST");
  app.add_option("--embree-isa", options.embree_isa,
                 "Embree's widest ISA: native (its own choice, AVX-512 where the CPU has it), avx2 (as quiver "
                 "with QUIVER_SIMD=avx2), sse4.2")
      ->check(CLI::IsMember({"native", "avx2", "sse4.2"}))->capture_default_str();
  app.add_option("--json", options.json_path, "Also write every measurement to this JSON file");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& error) {
    return app.exit(error) == 0 ? 0 : 2;
  }
  try {
    const EmbreeDevice device(options.embree_isa == "native" ? "" : options.embree_isa);
    std::printf("Embree ISA: %s (%s)\n", options.embree_isa.c_str(),
                device.avx512() ? "AVX-512 kernels, 16-wide" : "no AVX-512 kernels");
    nlohmann::ordered_json results = nlohmann::ordered_json::array();
    for (const std::string& name : options.scenes) results.push_back(run_scene(name, options, device));
    print_tables(results);
    if (!options.json_path.empty()) {
      std::ofstream out(options.json_path);
      out << results.dump(2) << "\n";
      if (!out) throw std::runtime_error("cannot write " + options.json_path);
    }
    return 0;
  } catch (const std::exception& error) {
    std::fprintf(stderr, "quiver_bench_embree: %s\n", error.what());
    return 1;
  }
}
