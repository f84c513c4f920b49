#include "bench/bench_support.h"

#include <cstdlib>
#include <string_view>

namespace quiver::bench {

std::vector<KernelUnit> bench_units() {
  const char* forced = std::getenv("QUIVER_SIMD");
  if (forced && std::string_view(forced) != "auto" && *forced != '\0') {
    return {kernel_unit_for(resolve_isa(forced))};  // throws on an unknown or unsupported choice
  }
  std::vector<KernelUnit> units;
  for (Isa isa : {Isa::scalar, Isa::sse4, Isa::avx2}) {
    if (isa_supported(isa)) units.push_back(kernel_unit_for(isa));
  }
  return units;
}

}  // namespace quiver::bench
