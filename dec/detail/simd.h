// dec/detail/simd.h — hot loops compiled twice, for AVX2 with FMA and for the library's SSE2
// baseline, the variant chosen once at run time. GCC's target_clones cannot do this on every CPU:
// its "arch=haswell" clone is chosen by CPU model (never on AMD), and its "avx2" clone has no FMA.
// Usage: write the loop as an always-inlined body, then
//   POLYDEC_SIMD_VARIANTS(name, (params), (args), body)
// defines name(params) that calls body(args) from the right variant. The two variants round
// differently (FMA contracts a * b + c), so results may differ between CPUs in the last bits.
// POLYDEC_SIMD=baseline in the environment forces the baseline variant (its tests run so).
#pragma once

#include <cstdlib>
#include <cstring>

namespace polydec::detail {

// True when the CPU runs AVX2 and FMA instructions and POLYDEC_SIMD is not "baseline" (x86 only;
// false elsewhere). Checked once.
inline bool cpu_has_avx2_fma() {
#if (defined(__GNUC__) || defined(__clang__)) && (defined(__x86_64__) || defined(__i386__))
  static const bool has = [] {
    const char* forced = std::getenv("POLYDEC_SIMD");
    if (forced && std::strcmp(forced, "baseline") == 0) return false;
    return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
  }();
  return has;
#else
  return false;
#endif
}

}  // namespace polydec::detail

#if (defined(__GNUC__) || defined(__clang__)) && (defined(__x86_64__) || defined(__i386__))
#define POLYDEC_SIMD_UNPAREN(...) __VA_ARGS__
#define POLYDEC_SIMD_VARIANTS(name, params, args, body)                                                 \
  __attribute__((target("avx2,fma"))) void name##_avx2_fma(POLYDEC_SIMD_UNPAREN params) {             \
    body(POLYDEC_SIMD_UNPAREN args);                                                                    \
  }                                                                                                     \
  void name##_baseline(POLYDEC_SIMD_UNPAREN params) { body(POLYDEC_SIMD_UNPAREN args); }               \
  void name(POLYDEC_SIMD_UNPAREN params) {                                                              \
    if (::polydec::detail::cpu_has_avx2_fma())                                                          \
      name##_avx2_fma(POLYDEC_SIMD_UNPAREN args);                                                       \
    else                                                                                                \
      name##_baseline(POLYDEC_SIMD_UNPAREN args);                                                       \
  }
#else
#define POLYDEC_SIMD_UNPAREN(...) __VA_ARGS__
#define POLYDEC_SIMD_VARIANTS(name, params, args, body) \
  void name(POLYDEC_SIMD_UNPAREN params) { body(POLYDEC_SIMD_UNPAREN args); }
#endif
