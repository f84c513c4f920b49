#include "bench/bench_support.h"

#include <cstdlib>
#include <string_view>

namespace quiver::bench {

std::vector<int> bench_widths() {
  const char* forced = std::getenv("QUIVER_SIMD");
  if (forced && std::string_view(forced) != "auto" && *forced != '\0') {
    return {lane_width(resolve_isa(forced))};  // throws on an unknown or unsupported choice
  }
  std::vector<int> widths;
  for (int width : {1, 4, 8}) {
    if (isa_supported(isa_for_width(width))) widths.push_back(width);
  }
  return widths;
}

}  // namespace quiver::bench
