// The errors of the streams' headers (geometry/streams.h,
// geometry/bvh/bvh_streams.h), compiled without any kernel unit's flags.
#include <stdexcept>
#include <string>

#include "geometry/bvh/bvh_streams.h"

namespace quiver {

void throw_study_method(const char* kind, const char* method) {
  throw std::invalid_argument(std::string("the ") + method + " " + kind +
                              " test is not built into the product (tests/support/study_streams.h has it)");
}

void throw_missing_node_width(int width) {
  throw std::invalid_argument("no BVH walk of node width " + std::to_string(width) +
                              " in these streams (the product walks width " + std::to_string(kProductNodeWidth) +
                              "; tests/support/study_streams.h has the others)");
}

}  // namespace quiver
