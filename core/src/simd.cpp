#include "surfcomp/core/simd.hpp"

#if defined(__x86_64__) || defined(__i386__)
#include <cpuid.h>
#endif

namespace surfcomp {
namespace {

#if defined(__x86_64__) || defined(__i386__)
/// F16C (CPUID 1, ECX bit 29) and LZCNT (CPUID 0x80000001, ECX bit 5), which Highway's AVX2
/// target needs beside AVX2 and which not every compiler's __builtin_cpu_supports names.
bool has_f16c_and_lzcnt() {
  unsigned a = 0, b = 0, c = 0, d = 0;
  if (__get_cpuid(1, &a, &b, &c, &d) == 0 || (c & (1U << 29U)) == 0) return false;
  if (__get_cpuid(0x80000001U, &a, &b, &c, &d) == 0) return false;
  return (c & (1U << 5U)) != 0;
}
#endif

SimdLevel detect() {
#if defined(__x86_64__) || defined(__i386__)
  __builtin_cpu_init();
  const bool sse4 = __builtin_cpu_supports("ssse3") && __builtin_cpu_supports("sse4.1") &&
                    __builtin_cpu_supports("sse4.2") && __builtin_cpu_supports("pclmul") &&
                    __builtin_cpu_supports("aes");
  if (!sse4) return SimdLevel::baseline;
  const bool avx2 = __builtin_cpu_supports("avx") && __builtin_cpu_supports("avx2") &&
                    __builtin_cpu_supports("bmi") && __builtin_cpu_supports("bmi2") &&
                    __builtin_cpu_supports("fma") && has_f16c_and_lzcnt();
  if (!avx2) return SimdLevel::sse4;
  const bool avx3 = __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512vl") &&
                    __builtin_cpu_supports("avx512dq") && __builtin_cpu_supports("avx512bw");
  return avx3 ? SimdLevel::avx3 : SimdLevel::avx2;
#else
  return SimdLevel::baseline;
#endif
}

}  // namespace

SimdLevel simd_level() {
  static const SimdLevel level = detect();
  return level;
}

}  // namespace surfcomp
