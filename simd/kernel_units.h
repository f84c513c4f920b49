// The kernel units: the kernel sources compiled once per unit, each with its
// own compiler flags, one of them picked at run time (simd/isa.h). Their one
// list is simd/kernel_units.cmake: CMake compiles the units from it and
// generates the table kKernelUnitSpecs included here, which simd/isa.cpp
// reads (names, widths, ISA choice, CPU features), with_kernel_unit
// dispatches over and the typed tests enumerate. A unit's lane type is
// UnitLanes<U> (simd/lanes.h).
//
// Every function compiled in a kernel unit lives in an inline namespace
// named after the unit (quiver::unit_avx2, ...; quiver::unit_host for code
// built with the baseline flags outside the units), as Embree does per ISA:
// functions built with different flags are never one symbol, so the linker
// cannot hand one unit's instructions to another. Data types shared across
// units (Vec3, Ray, Hit, the SoA stores) stay in quiver itself.
// tests/geometry_streams_unit_symbols_test.cmake checks the objects.
#pragma once

#include <array>
#include <cstddef>
#include <initializer_list>
#include <string_view>
#include <type_traits>
#include <utility>

// CMake defines QUIVER_KERNEL_UNIT (a KernelUnit name) and
// QUIVER_UNIT_NAMESPACE (unit_<name>) for a unit's sources.
#ifndef QUIVER_UNIT_NAMESPACE
#define QUIVER_UNIT_NAMESPACE unit_host
#endif

namespace quiver {

// The --simd choices (QUIVER_SIMD), by lane width.
enum class Isa { scalar, sse4, avx2, avx512 };

// CPU features a unit's instructions need (GCC's __builtin_cpu_supports
// names; avx also means the OS saves AVX state).
enum class CpuFeature : unsigned { avx, fma, sse4_2, avx2, avx512f, avx512cd, avx512dq, avx512bw, avx512vl };

constexpr unsigned cpu_features(std::initializer_list<CpuFeature> features) {
  unsigned bits = 0;
  for (CpuFeature f : features) bits |= 1u << static_cast<unsigned>(f);
  return bits;
}

}  // namespace quiver

#include "simd/kernel_unit_table.h"  // generated: KernelUnit, KernelUnitSpec, kKernelUnitSpecs

namespace quiver {

constexpr const KernelUnitSpec& spec_of(KernelUnit unit) {
  for (const KernelUnitSpec& spec : kKernelUnitSpecs) {
    if (spec.unit == unit) return spec;
  }
  return kKernelUnitSpecs[0];
}

// Every kernel unit, narrowest first.
inline constexpr auto kKernelUnits = [] {
  std::array<KernelUnit, kKernelUnitSpecs.size()> units{};
  for (std::size_t i = 0; i < units.size(); ++i) units[i] = kKernelUnitSpecs[i].unit;
  return units;
}();

template <KernelUnit U>
using Unit = std::integral_constant<KernelUnit, U>;

// Calls fn(Unit<U>{}) for a run-time kernel unit.
template <std::size_t I = 0, class Fn>
decltype(auto) with_kernel_unit(KernelUnit unit, Fn&& fn) {
  if constexpr (I < kKernelUnitSpecs.size()) {
    if (unit == kKernelUnitSpecs[I].unit) return fn(Unit<kKernelUnitSpecs[I].unit>{});
    return with_kernel_unit<I + 1>(unit, std::forward<Fn>(fn));
  } else {
    return fn(Unit<KernelUnit::scalar>{});  // not a unit: the reference
  }
}

// Applies Template to Unit<U> of every unit: Template<Unit<scalar>, ...>.
template <template <class...> class Template, std::size_t... I>
auto over_kernel_units(std::index_sequence<I...>) -> Template<Unit<kKernelUnitSpecs[I].unit>...>;
template <template <class...> class Template>
using OverKernelUnits = decltype(over_kernel_units<Template>(std::make_index_sequence<kKernelUnitSpecs.size()>()));

#ifdef QUIVER_KERNEL_UNIT
// The unit this translation unit is compiled for.
inline constexpr KernelUnit kThisUnit = KernelUnit::QUIVER_KERNEL_UNIT;
#endif

}  // namespace quiver
