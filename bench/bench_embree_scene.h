// The same geometry as a built quiver Scene, as an Intel Embree 3 scene, for
// bench/bench_embree.cpp. Mapping: spheres -> one RTC_GEOMETRY_TYPE_SPHERE_POINT
// geometry (x, y, z, r); triangles (also NFF `pp` patches, which quiver
// stores as triangles) -> one RTC_GEOMETRY_TYPE_TRIANGLE mesh, 3 vertices per
// triangle (quiver's TriangleSoA is unshared too); polygons -> the same mesh,
// ear-clipped by quiver's own triangulate_polygon (geometry/kinds/polygon.h);
// infinite planes and cones have no Embree counterpart here and are counted
// as skipped (the benchmark warns: hit counts then cannot agree). Only the
// primitives quiver's builders kept are passed on. Memory is what Embree's
// device memory monitor reports (rtcSetDeviceMemoryMonitorFunction).
#pragma once

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>

#include <embree3/rtcore.h>

#include "scene/scene.h"
#include "scene/scene_desc.h"

namespace quiver::bench {

// An Embree device whose memory monitor adds every allocation and release.
// max_isa caps Embree's run-time ISA choice ("" = its own, the widest the CPU has).
class EmbreeDevice {
 public:
  explicit EmbreeDevice(const std::string& max_isa = "");
  ~EmbreeDevice();
  EmbreeDevice(const EmbreeDevice&) = delete;
  EmbreeDevice& operator=(const EmbreeDevice&) = delete;

  RTCDevice get() const { return device_; }
  // Bytes Embree holds now, as its memory monitor counted them.
  std::int64_t monitored_bytes() const { return bytes_.load(); }
  // Whether rtcIntersect<width> and rtcOccluded<width> (width 4, 8 or 16) run
  // Embree's packet kernels of that width on this CPU and Embree build
  // (RTC_DEVICE_PROPERTY_NATIVE_RAY<width>_SUPPORTED), not a fallback.
  bool native_packets(int width) const;

 private:
  static bool monitor(void* user, ssize_t bytes, bool post);
  RTCDevice device_;
  std::atomic<std::int64_t> bytes_{0};
};

struct ReleaseEmbreeScene {
  void operator()(RTCScene scene) const { rtcReleaseScene(scene); }
};

struct EmbreeScene {
  std::unique_ptr<RTCSceneTy, ReleaseEmbreeScene> scene;
  std::size_t spheres = 0, triangles = 0;  // Embree primitives
  std::size_t polygons_triangulated = 0;   // quiver polygons among the triangles
  std::size_t skipped_planes = 0, skipped_cones = 0;
  std::size_t buffer_bytes = 0;      // vertex and index buffers handed to Embree
  std::int64_t monitored_bytes = 0;  // monitor total after commit, buffers included
  double build_ms = 0.0;             // buffers filled + rtcCommitScene
  double commit_ms = 0.0;            // rtcCommitScene alone
};

// desc must be the SceneDesc `scene` was built from. robust adds
// RTC_SCENE_FLAG_ROBUST (Embree's watertight mode); quality is the scene's
// build quality (Embree's default: medium). Throws std::runtime_error on an
// Embree error.
EmbreeScene build_embree_scene(const EmbreeDevice& device, const SceneDesc& desc, const Scene& scene, bool robust,
                               RTCBuildQuality quality = RTC_BUILD_QUALITY_MEDIUM);

}  // namespace quiver::bench
