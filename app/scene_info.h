// The `quiver info SCENE` report: what the reader found (SceneDesc) next to
// what the builders kept (Scene), the opaque/transmissive split, bounds,
// camera, lights, materials, textures, the memory of each structure, and
// the load and build times.
#pragma once

#include <array>
#include <cstddef>
#include <optional>
#include <ostream>
#include <string>
#include <string_view>

#include "scene/auto_view.h"
#include "scene/scene.h"
#include "scene/scene_desc.h"

namespace quiver {

// Per kind, in list order (geometry/kinds.h), indexed by PrimitiveKind.
template <class T>
using ByKind = std::array<T, kKindCount>;

// Bytes of one layer's stores per kind: the SoA columns' capacity plus the
// source and origin arrays. Sums to GeometryLayer::memory_bytes().
ByKind<std::size_t> memory_by_kind(const GeometryLayer& layer);

// Each kind's primitives as read.
ByKind<std::size_t> read_counts(const SceneDesc& desc);

struct SceneInfoContext {
  std::string scene;  // the file as named on the command line
  double load_ms = 0.0, build_ms = 0.0;
  std::optional<DefaultView> default_view;  // the file had no camera: the view added
  std::optional<std::size_t> peak_resident_bytes;  // the process's most resident memory, after load and build
  ByKind<std::size_t> read{};  // read_counts of the scene as read, taken before its build released its triangles
  // The most resident while the scene was built, and when its build began.
  std::optional<std::size_t> build_peak_resident_bytes, build_start_resident_bytes;
};

// The most memory the process has held resident so far (getrusage's
// ru_maxrss, which Linux gives in KiB), in bytes.
std::size_t peak_resident_bytes();

// Sets the kernel's resident high-water mark (VmHWM) to the memory resident
// now, so that a later reading of it gives the most held since;
// false where /proc/self/clear_refs refuses.
bool restart_resident_high_water();

// A memory figure of /proc/self/status ("VmHWM": the high-water mark,
// "VmRSS": resident now), in bytes; empty where it cannot be read.
std::optional<std::size_t> process_status_bytes(std::string_view key);

// desc is the scene as read (before any default view was added), its
// triangles perhaps released by the build (their count is context.read's).
void write_scene_info(std::ostream& out, const SceneDesc& desc, const Scene& scene, const SceneInfoContext& context);

}  // namespace quiver
