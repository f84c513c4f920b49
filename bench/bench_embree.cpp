// quiver against Intel Embree 3 on the same rays (bench/README.md, "Against
// Embree"). Per scene the ray sets of bench/bench_rays.h (quiver's camera
// and hit points): primary rays through the pixel centres, each 4x4 pixel
// group 16 consecutive rays row by row (coherent), then from quiver's
// primary hits mirror reflections, random hemisphere directions
// (incoherent) and shadow rays toward one point light (any-hit). Each set
// is cut into blocks of 256 rays spread over oneTBB threads (one arena per
// thread count) and traced by
//   quiver  SceneIntersector::closest (shadow: occluded on both layers) on
//           each block's RaySoA, in the kernel unit QUIVER_SIMD names,
//           else the widest the CPU has;
//   e1      rtcIntersect1 / rtcOccluded1 per ray;
//   e4, e8, e16
//           rtcIntersect4/8/16 / rtcOccluded4/8/16 per packet, each width
//           only where Embree runs it natively on this CPU and Embree build
//           (rtcGetDeviceProperty, RTC_DEVICE_PROPERTY_NATIVE_RAY4/8/16_SUPPORTED;
//           --embree-isa caps the ISA). A packet of primary rays is a pixel
//           block of one 4x4 group (e16 the group, e8 4x2, e4 2x2); a packet
//           of secondary rays is consecutive rays.
// Embree traces primary rays with RTC_INTERSECT_CONTEXT_FLAG_COHERENT, the
// others with RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT. Each pass fills its
// ray state and writes every ray's result out, so all tracers do the same
// bookkeeping. Repeats interleave the tracers; the table shows medians and,
// per scene, ray set and thread count, quiver's rays per second over those
// of the fastest Embree API there, that API named beside the ratio.
// Agreement, quiver against e1: rays that hit in one tracer and miss in the
// other (expected: a few at silhouettes and at the edges of quiver's
// polygons, which Embree sees ear-clipped) and closest-hit distances
// differing by more than a relative 1e-4; against each packet API, rays
// that hit in one and miss in the other.
// Builds, --repeat times each (medians): quiver's build_scene, and Embree's
// buffers plus rtcCommitScene at its default (medium) quality, the scene
// traced, with low and high quality builds timed beside it.
// Usage: quiver_bench_embree [--width W] [--height H] [--repeat R]
//   [--scenes a,b,...] [--robust] [--embree-isa native|avx2|sse4.2] [--json FILE]
//   (--help lists them). Scenes are names in $QUIVER_SHARED_DIR/meshes (.obj)
//   or scenes/spd (.nff), or paths.
#include <algorithm>
#include <array>
#include <bit>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/info.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "bench/bench_embree_scene.h"
#include "bench/bench_rays.h"
#include "integrator/render.h"
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
  bool camera = false;   // primary rays in 4x4 pixel groups: coherent, packets are pixel blocks
  bool any_hit = false;  // occlusion only (shadow rays)
  std::vector<RaySoA> blocks;
  std::size_t count = 0;
};

RaySet blocks_of(std::string name, const RaySoA& rays, bool camera, bool any_hit) {
  RaySet set{std::move(name), camera, any_hit, {}, rays.count};
  for (std::size_t first = 0; first < rays.count; first += kBlockRays) {
    RaySoA& block = set.blocks.emplace_back();
    for (std::size_t i = first; i < std::min(rays.count, first + kBlockRays); ++i) block.push(rays.get(i));
    block.pad();
  }
  return set;
}

// Per block, per ray: the hit distance, kMiss on a miss.
using Distances = std::vector<std::vector<float>>;

// Any-hit results are written as distance 0 (blocked) or kMiss.
constexpr float kBlocked = 0.f;

Distances sized_like(const RaySet& set) {
  Distances d(set.blocks.size());
  for (std::size_t b = 0; b < set.blocks.size(); ++b) d[b].assign(set.blocks[b].count, kMiss);
  return d;
}

// Traces one block (its index) and writes that block's distances.
using BlockTrace = std::function<void(std::size_t, std::vector<float>&)>;

// One timed pass: trace(block index, distances of that block) over every block.
double timed_pass(tbb::task_arena& arena, const RaySet& set, Distances& out, const BlockTrace& trace) {
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

// Embree's calls for Width rays at a time: rtcIntersect1/rtcOccluded1 (no
// valid mask) for one, the packet calls of that width else.
template <int Width>
struct EmbreeCalls;

template <>
struct EmbreeCalls<1> {
  using RayHit = RTCRayHit;
  static void intersect(const int*, RTCScene scene, RTCIntersectContext* context, RTCRayHit* rays) {
    rtcIntersect1(scene, context, rays);
  }
  static void occluded(const int*, RTCScene scene, RTCIntersectContext* context, RTCRay* rays) {
    rtcOccluded1(scene, context, rays);
  }
};

template <>
struct EmbreeCalls<4> {
  using RayHit = RTCRayHit4;
  static constexpr auto intersect = rtcIntersect4;
  static constexpr auto occluded = rtcOccluded4;
};

template <>
struct EmbreeCalls<8> {
  using RayHit = RTCRayHit8;
  static constexpr auto intersect = rtcIntersect8;
  static constexpr auto occluded = rtcOccluded8;
};

template <>
struct EmbreeCalls<16> {
  using RayHit = RTCRayHit16;
  static constexpr auto intersect = rtcIntersect16;
  static constexpr auto occluded = rtcOccluded16;
};

// Lane k of an Embree ray field: the field itself in RTCRay and RTCHit,
// element k of the array in a packet.
template <typename Field>
auto& lane(Field& field, std::size_t k) {
  if constexpr (std::is_array_v<Field>) {
    return field[k];
  } else {
    return field;
  }
}

// Ray i of `rays` into lane k of an Embree ray or packet.
template <typename EmbreeRay>
void set_lane(EmbreeRay& ray, std::size_t k, const RaySoA& rays, std::size_t i) {
  lane(ray.org_x, k) = rays.ox[i];
  lane(ray.org_y, k) = rays.oy[i];
  lane(ray.org_z, k) = rays.oz[i];
  lane(ray.dir_x, k) = rays.dx[i];
  lane(ray.dir_y, k) = rays.dy[i];
  lane(ray.dir_z, k) = rays.dz[i];
  lane(ray.tnear, k) = rays.tmin[i];
  lane(ray.tfar, k) = rays.tmax[i];
  lane(ray.time, k) = 0.f;
  lane(ray.mask, k) = ~0u;
  lane(ray.id, k) = 0u;
  lane(ray.flags, k) = 0u;
}

constexpr std::size_t kGroupRays = std::size_t(kPixelGroupWidth) * kPixelGroupHeight;

// A packet of primary rays covers the squarest pixel block of a group that
// is at least as wide as tall: 16 lanes 4x4, 8 lanes 4x2, 4 lanes 2x2.
template <int Width>
constexpr std::size_t kPacketColumns = std::size_t(1) << (std::bit_width(unsigned(Width)) / 2);

// The ray in lane k of the primary packet that starts at ray `first` of a
// block of `count`. make_scene_rays emits each 4x4 pixel group as 16
// consecutive rays, row by row; the rays of a partial group (at the set's
// end, or when a side is not a multiple of 4) stay in their order.
template <int Width>
std::size_t camera_ray(std::size_t count, std::size_t first, std::size_t k) {
  constexpr std::size_t columns = kPacketColumns<Width>, rows = Width / columns;
  static_assert(columns <= kPixelGroupWidth && rows <= kPixelGroupHeight && kGroupRays % Width == 0);
  const std::size_t group = first / kGroupRays * kGroupRays;
  if (group + kGroupRays > count) return first + k;
  const std::size_t packet = (first - group) / Width, packets_per_row = kPixelGroupWidth / columns;
  const std::size_t x = packet % packets_per_row * columns + k % columns;
  const std::size_t y = packet / packets_per_row * rows + k / columns;
  return group + y * kPixelGroupWidth + x;
}

// One block through Embree, Width rays per call; each ray's distance into
// out (shadow rays: kBlocked or kMiss).
template <int Width>
void embree_block(RTCScene scene, const RaySet& set, const RaySoA& rays, std::vector<float>& out) {
  using Calls = EmbreeCalls<Width>;
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  context.flags = set.camera ? RTC_INTERSECT_CONTEXT_FLAG_COHERENT : RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT;
  alignas(64) typename Calls::RayHit packet;
  alignas(64) std::array<int, Width> valid;
  std::array<std::size_t, Width> ray_of_lane;
  for (std::size_t first = 0; first < rays.count; first += Width) {
    for (std::size_t k = 0; k < Width; ++k) {
      ray_of_lane[k] = set.camera ? camera_ray<Width>(rays.count, first, k) : first + k;
      valid[k] = ray_of_lane[k] < rays.count ? -1 : 0;
      set_lane(packet.ray, k, rays, ray_of_lane[k]);  // lanes past the end read the padding, masked off
    }
    if (set.any_hit) {
      Calls::occluded(valid.data(), scene, &context, &packet.ray);
    } else {
      for (std::size_t k = 0; k < Width; ++k) {
        lane(packet.hit.geomID, k) = RTC_INVALID_GEOMETRY_ID;
        lane(packet.hit.instID[0], k) = RTC_INVALID_GEOMETRY_ID;
      }
      Calls::intersect(valid.data(), scene, &context, &packet);
    }
    for (std::size_t k = 0; k < Width; ++k) {
      if (valid[k] == 0) continue;
      float& result = out[ray_of_lane[k]];
      if (set.any_hit) {
        result = lane(packet.ray.tfar, k) < 0.f ? kBlocked : kMiss;  // Embree sets tfar to -inf when blocked
      } else {
        result = lane(packet.hit.geomID, k) == RTC_INVALID_GEOMETRY_ID ? kMiss : lane(packet.ray.tfar, k);
      }
    }
  }
}

struct EmbreeApi {
  int width;  // rays per call
  void (*trace)(RTCScene, const RaySet&, const RaySoA&, std::vector<float>&);
};

constexpr std::array<EmbreeApi, 4> kEmbreeApis{
    {{1, embree_block<1>}, {4, embree_block<4>}, {8, embree_block<8>}, {16, embree_block<16>}}};

// The APIs this device runs natively: always rtcIntersect1, the packets where Embree says so.
std::vector<EmbreeApi> native_apis(const EmbreeDevice& device) {
  std::vector<EmbreeApi> apis;
  for (const EmbreeApi& api : kEmbreeApis) {
    if (api.width == 1 || device.native_packets(api.width)) apis.push_back(api);
  }
  return apis;
}

// An API's name in the table (e16) and in the JSON keys (embree16).
std::string api_label(int width) { return "e" + std::to_string(width); }
std::string api_key(int width) { return "embree" + std::to_string(width); }

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

// One tracer of a ray set: its passes' times and the distances of its last pass.
struct Tracer {
  std::string key;       // "quiver", "embree1", "embree16", ...
  int embree_width = 0;  // 0 for quiver
  BlockTrace trace;
  Distances distances;
  std::vector<double> ms;
};

nlohmann::ordered_json run_set(const RaySet& set, const Scene& scene, const SceneIntersector& intersector,
                               RTCScene embree, const std::vector<EmbreeApi>& apis, int threads, int repeat) {
  tbb::task_arena arena(threads);
  tbb::enumerable_thread_specific<HitSoA> thread_hits;
  tbb::enumerable_thread_specific<OcclusionSoA> thread_occlusion;

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
  std::vector<Tracer> tracers{{"quiver", 0, quiver_block, sized_like(set), {}}};
  for (const EmbreeApi& api : apis) {
    auto embree_api_block = [&set, embree, trace = api.trace](std::size_t b, std::vector<float>& out) {
      trace(embree, set, set.blocks[b], out);
    };
    tracers.push_back({api_key(api.width), api.width, embree_api_block, sized_like(set), {}});
  }

  // Each repetition runs every tracer once, so drift in the machine's speed reaches them alike.
  for (int r = 0; r < repeat; ++r) {
    for (Tracer& tracer : tracers) tracer.ms.push_back(timed_pass(arena, set, tracer.distances, tracer.trace));
  }
  const Tracer& quiver = tracers.front();
  const std::span<const Tracer> embree_tracers(tracers.begin() + 1, tracers.end());
  const Tracer& fastest = *std::ranges::min_element(embree_tracers, {}, [](const Tracer& t) { return median(t.ms); });
  auto mrays = [&](const Tracer& t) { return double(set.count) / (median(t.ms) * 1e3); };
  auto quiver_over = [&](const Tracer& t) { return median(t.ms) / median(quiver.ms); };

  nlohmann::ordered_json row;
  row["rays"] = set.name;
  row["count"] = set.count;
  row["threads"] = threads;
  row["quiver_mrays_per_s"] = mrays(quiver);
  for (const Tracer& t : embree_tracers) row[t.key + "_mrays_per_s"] = mrays(t);
  for (const Tracer& t : embree_tracers) row["quiver_over_" + t.key] = quiver_over(t);
  row["fastest_embree"] = api_label(fastest.embree_width);
  row["quiver_over_fastest_embree"] = quiver_over(fastest);
  nlohmann::ordered_json& ms = row["ms"];
  for (const Tracer& t : tracers) ms[t.key] = t.ms;
  const Agreement with_e1 = compare(quiver.distances, embree_tracers.front().distances);
  nlohmann::ordered_json& hits = row["hits"];
  hits["both"] = with_e1.both;
  hits["quiver_only"] = with_e1.only_first;
  hits["embree1_only"] = with_e1.only_second;
  hits["distance_differs"] = with_e1.distance_differs;
  hits["largest_relative_difference"] = with_e1.largest_relative_difference;
  for (const Tracer& t : embree_tracers.subspan(1)) {
    const Agreement with_packets = compare(quiver.distances, t.distances);
    hits[t.key + "_vs_quiver_mismatches"] = with_packets.only_first + with_packets.only_second;
  }
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
  std::vector<double> quiver_build_ms, embree_build_ms, embree_commit_ms, embree_low_ms, embree_high_ms;
  for (int r = 0; r < options.repeat; ++r) {
    built.reset();
    const auto build_start = Clock::now();
    built.emplace(build_scene(desc, build_options));
    quiver_build_ms.push_back(std::chrono::duration<double, std::milli>(Clock::now() - build_start).count());
    embree_built.reset();
    embree_built.emplace(build_embree_scene(device, desc, *built, options.robust));
    embree_build_ms.push_back(embree_built->build_ms);
    embree_commit_ms.push_back(embree_built->commit_ms);
    // The other qualities, built and dropped; the medium build above is the one traced.
    embree_low_ms.push_back(build_embree_scene(device, desc, *built, options.robust, RTC_BUILD_QUALITY_LOW).build_ms);
    embree_high_ms.push_back(build_embree_scene(device, desc, *built, options.robust, RTC_BUILD_QUALITY_HIGH).build_ms);
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
  const std::vector<EmbreeApi> apis = native_apis(device);
  nlohmann::ordered_json& api_widths = result["embree_api_widths"] = nlohmann::ordered_json::array();
  for (const EmbreeApi& api : apis) api_widths.push_back(api.width);
  result["quiver_build_ms"] = median(quiver_build_ms);
  result["embree_build_ms"] = median(embree_build_ms);
  result["embree_commit_ms"] = median(embree_commit_ms);
  result["embree_low_quality_build_ms"] = median(embree_low_ms);
  result["embree_high_quality_build_ms"] = median(embree_high_ms);
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
      rows.push_back(run_set(*set, scene, intersector, embree.scene.get(), apis, threads, options.repeat));
    }
  }
  result["runs"] = rows;
  return result;
}

void print_tables(const nlohmann::ordered_json& results) {
  if (results.empty()) return;
  // Every scene ran the same Embree APIs (one device): the first names the columns.
  const auto widths = results[0]["embree_api_widths"].get<std::vector<int>>();
  std::printf("\n| scene | rays | count | threads | quiver Mrays/s |");
  for (int width : widths) std::printf(" %s Mrays/s |", api_label(width).c_str());
  std::printf(" quiver/fastest Embree | hit only in quiver / only in e1 | distance differs |");
  for (std::size_t a = 1; a < widths.size(); ++a) {
    std::printf(" hit differs, quiver / %s |", api_label(widths[a]).c_str());
  }
  std::printf("\n| --- | --- | ---: | ---: | ---: |");
  for (std::size_t a = 0; a < 2 * widths.size() + 2; ++a) std::printf(" ---: |");
  std::printf("\n");
  for (const auto& s : results) {
    for (const auto& r : s["runs"]) {
      std::printf("| %s | %s | %zu | %d | %.2f |", s["scene"].get<std::string>().c_str(),
                  r["rays"].get<std::string>().c_str(), r["count"].get<std::size_t>(), r["threads"].get<int>(),
                  r["quiver_mrays_per_s"].get<double>());
      for (int width : widths) std::printf(" %.2f |", r[api_key(width) + "_mrays_per_s"].get<double>());
      std::printf(" %.2fx (%s) | %zu / %zu | %zu |", r["quiver_over_fastest_embree"].get<double>(),
                  r["fastest_embree"].get<std::string>().c_str(), r["hits"]["quiver_only"].get<std::size_t>(),
                  r["hits"]["embree1_only"].get<std::size_t>(), r["hits"]["distance_differs"].get<std::size_t>());
      for (std::size_t a = 1; a < widths.size(); ++a) {
        std::printf(" %zu |", r["hits"][api_key(widths[a]) + "_vs_quiver_mismatches"].get<std::size_t>());
      }
      std::printf("\n");
    }
  }
  std::printf(
      "\n| scene | primitives | Embree spheres + triangles | quiver build ms | Embree build ms (commit) "
      "| Embree low / high quality build ms | quiver geometry B/prim | quiver BVH B/prim | Embree buffers B/prim "
      "| Embree rest B/prim |\n");
  std::printf("| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |\n");
  for (const auto& s : results) {
    const double n = std::max(1.0, s["primitives"].get<double>());
    const double buffers = s["embree_buffer_bytes"].get<double>();
    std::printf("| %s | %zu | %zu + %zu | %.1f | %.1f (%.1f) | %.1f / %.1f | %.1f | %.1f | %.1f | %.1f |\n",
                s["scene"].get<std::string>().c_str(), s["primitives"].get<std::size_t>(),
                s["embree_spheres"].get<std::size_t>(), s["embree_triangles"].get<std::size_t>(),
                s["quiver_build_ms"].get<double>(), s["embree_build_ms"].get<double>(),
                s["embree_commit_ms"].get<double>(), s["embree_low_quality_build_ms"].get<double>(),
                s["embree_high_quality_build_ms"].get<double>(), s["quiver_geometry_bytes"].get<double>() / n,
                s["quiver_acceleration_bytes"].get<double>() / n, buffers / n,
                (s["embree_monitored_bytes"].get<double>() - buffers) / n);
  }
  std::printf("\nquiver acceleration: %s\n", results[0]["quiver_acceleration"].get<std::string>().c_str());
}

}  // namespace
}  // namespace quiver::bench

int main(int argc, char** argv) {
  using namespace quiver::bench;
  Options options;
  CLI::App app{
      "Trace the same primary, reflection, diffuse and shadow rays through quiver and through Intel Embree 3's "
      "rtcIntersect1 and rtcIntersect4/8/16 (rtcOccluded1/4/8/16 for shadow rays; each packet width where "
      "Embree runs it natively on this CPU; primary packets are pixel blocks, 4x4 for 16 lanes, traced with "
      "Embree's coherent flag) on 1 thread and on all, and print Mrays/s of each, quiver over the fastest "
      "Embree API (named beside it), the hit agreement, build times (Embree's at medium quality, traced, and "
      "at low and high) and bytes per primitive (bench/README.md, "
      "\"Against Embree\")",
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
    std::printf("Embree ISA: %s; APIs measured: e1", options.embree_isa.c_str());
    for (const EmbreeApi& api : native_apis(device)) {
      if (api.width > 1) std::printf(" e%d", api.width);
    }
    std::printf(" (packet widths Embree runs natively here)\n");
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
