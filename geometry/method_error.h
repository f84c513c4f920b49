// The error a product function reports when asked for a method only the
// accuracy study and the benchmarks build.
#pragma once

namespace quiver {

// std::invalid_argument naming the method and where it is built. Out of
// line (geometry/streams.cpp), so no kernel unit's flags compile the
// library code it calls.
[[noreturn]] void throw_study_method(const char* kind, const char* method);

}  // namespace quiver
