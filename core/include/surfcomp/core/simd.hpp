// The SIMD instruction sets of the processor the program runs on. The project's SIMD kernels
// (Highway) are compiled for several x86 targets and pick one by this at run time.
#pragma once

namespace surfcomp {

/// The best group of instructions the processor (and the operating system) supports, as
/// Highway's x86 targets group them.
enum class SimdLevel : int {
  baseline = 0,  ///< x86-64's SSE2 (Highway's portable EMU128 target)
  sse4 = 1,      ///< SSSE3, SSE4.1/4.2, CLMUL, AES (Highway's SSE4)
  avx2 = 2,      ///< and AVX, AVX2, BMI1/2, FMA, F16C, LZCNT (Highway's AVX2)
  avx3 = 3,      ///< and AVX-512 F, VL, DQ, BW (Highway's AVX3)
};

/// The level of this processor, detected once (thread-safe).
SimdLevel simd_level();

}  // namespace surfcomp
