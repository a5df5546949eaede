// For the project's Highway kernel files only (a .cpp that includes itself through
// hwy/foreach_target.h): the choice of the compiled target at run time, by simd_level(), in
// place of Highway's HWY_DYNAMIC_DISPATCH, whose library (libhwy) calibrates a timer in a
// static initialiser every time the program starts. Include it before hwy/foreach_target.h and
// hwy/highway.h.
#pragma once

#include "surfcomp/core/simd.hpp"

// The targets compiled: AVX-512, AVX2, SSE4 and the portable baseline (SSSE3 adds little over
// the baseline; AVX3_DL is not compiled unless asked for).
#ifndef HWY_DISABLED_TARGETS
#define HWY_DISABLED_TARGETS HWY_SSSE3
#endif

#include <hwy/detect_targets.h>

#if HWY_TARGETS & HWY_AVX3
#define SURFCOMP_IF_AVX3(...) __VA_ARGS__
#else
#define SURFCOMP_IF_AVX3(...)
#endif
#if HWY_TARGETS & HWY_AVX2
#define SURFCOMP_IF_AVX2(...) __VA_ARGS__
#else
#define SURFCOMP_IF_AVX2(...)
#endif
#if HWY_TARGETS & HWY_SSE4
#define SURFCOMP_IF_SSE4(...) __VA_ARGS__
#else
#define SURFCOMP_IF_SSE4(...)
#endif

/// In the file's HWY_ONCE part: calls `function(arguments...)` as compiled for the best target
/// the processor runs, or for the static (baseline) target.
#define SURFCOMP_SIMD_CALL(function, ...)                                                 \
  [&] {                                                                                   \
    const ::surfcomp::SimdLevel level_ = ::surfcomp::simd_level();                        \
    SURFCOMP_IF_AVX3(                                                                     \
        if (level_ >= ::surfcomp::SimdLevel::avx3) return N_AVX3::function(__VA_ARGS__);) \
    SURFCOMP_IF_AVX2(                                                                     \
        if (level_ >= ::surfcomp::SimdLevel::avx2) return N_AVX2::function(__VA_ARGS__);) \
    SURFCOMP_IF_SSE4(                                                                     \
        if (level_ >= ::surfcomp::SimdLevel::sse4) return N_SSE4::function(__VA_ARGS__);) \
    return HWY_NAMESPACE::function(__VA_ARGS__);                                          \
  }()
