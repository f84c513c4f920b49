#include "bench/bench_support.h"

#include <cstdlib>
#include <limits>
#include <string_view>

namespace quiver::bench {

std::filesystem::path shared_dir() {
  if (const char* env = std::getenv("QUIVER_SHARED_DIR")) return env;
  return QUIVER_SHARED_DIR;
}

std::vector<KernelUnit> bench_units() {
  const char* forced = std::getenv("QUIVER_SIMD");
  if (forced && std::string_view(forced) != "auto" && *forced != '\0') {
    return {kernel_unit_for(resolve_isa(forced))};  // throws on an unknown or unsupported choice
  }
  std::vector<KernelUnit> units;
  for (Isa isa : kIsas) {
    if (isa_supported(isa)) units.push_back(kernel_unit_for(isa));
  }
  return units;
}

RaySoA camera_rays(const Vec3<float>& center, float half_extent) {
  constexpr int kSide = 64;  // kSide * kSide == kBenchRays
  static_assert(kSide * kSide == kBenchRays);
  const Vec3<float> eye = center + Vec3<float>{0.f, 0.f, 4.f * half_extent};
  const float pixel = 2.4f * half_extent / float(kSide);
  RaySoA rays(kBenchRays);
  std::size_t i = 0;
  for (int tile_y = 0; tile_y < kSide; tile_y += 2) {
    for (int tile_x = 0; tile_x < kSide; tile_x += 4) {
      for (int y = tile_y; y < tile_y + 2; ++y) {
        for (int x = tile_x; x < tile_x + 4; ++x) {
          const Vec3<float> target = center + Vec3<float>{(float(x) + 0.5f) * pixel - 1.2f * half_extent,
                                                          (float(y) + 0.5f) * pixel - 1.2f * half_extent, 0.f};
          rays.set(i++, {eye, target - eye, 0.f, std::numeric_limits<float>::infinity()});
        }
      }
    }
  }
  rays.pad();
  return rays;
}

}  // namespace quiver::bench
