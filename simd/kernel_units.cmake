# The kernel units, their one list: CMakeLists.txt compiles the kernel
# sources once per unit with its flags, and generates from this list the
# C++ table of units (simd/kernel_unit_table.h.in, included by
# simd/kernel_units.h), which simd/isa.cpp, with_kernel_unit and the typed
# tests read. Narrowest first; per unit: the --simd choice it runs (an Isa),
# its lanes, its compiler flags and the CPU features its instructions need
# (CpuFeature names: GCC's __builtin_cpu_supports names; avx also means the
# OS saves AVX state). Adding a unit: a line here and its lane type
# (UnitLanes in simd/lanes.h).
#
# Two scalar units: scalar runs on any x86-64 and is the reference;
# scalar_fma is the same source built with -mfma, so the kernels' explicit
# fma is an instruction rather than a libm call (they agree bit for bit:
# std::fma is correctly rounded either way). The 4-wide unit needs FMA3 so
# that fma is fused as in scalar code (-mfma implies the AVX encoding).
#                   unit        isa     lanes flags                                                        features
quiver_kernel_unit(scalar      scalar  1     ""                                                           "")
quiver_kernel_unit(scalar_fma  scalar  1     "-mfma"                                                      "avx fma")
quiver_kernel_unit(sse4        sse4    4     "-msse4.2 -mfma"                                             "sse4_2 avx fma")
quiver_kernel_unit(avx2        avx2    8     "-mavx2 -mfma"                                               "avx2 fma")
quiver_kernel_unit(avx512      avx512  16    "-mavx512f -mavx512cd -mavx512dq -mavx512bw -mavx512vl -mfma" "avx2 fma avx512f avx512cd avx512dq avx512bw avx512vl")
