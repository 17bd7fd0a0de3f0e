// dec/detail/simd.h — hot loops compiled twice, for AVX2 with FMA and for the library's SSE2
// baseline, the variant chosen once at run time; loops written for a vector width, three times,
// with AVX-512 too. GCC's target_clones cannot do this on every CPU: its "arch=haswell" clone is
// chosen by CPU model (never on AMD), and its "avx2" clone has no FMA.
// Usage: write the loop as an always-inlined body, then
//   POLYDEC_SIMD_VARIANTS(name, (params), (args), body)
// defines name(params) that calls body(args) from the right variant; for a body templated on its
// vector width in bytes (body<64> for AVX-512, body<32> for AVX2 with FMA and for the baseline)
//   POLYDEC_SIMD_WIDE_VARIANTS(name, (params), (args), body).
// The baseline rounds differently (FMA contracts a * b + c), so results may differ between CPUs in
// the last bits. POLYDEC_SIMD=baseline in the environment forces the baseline, POLYDEC_SIMD=avx2
// AVX2 with FMA on a CPU with AVX-512 (their tests run so).
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

// True when besides (cpu_has_avx2_fma) the CPU and the operating system run AVX-512 F, VL and DQ
// and POLYDEC_SIMD is neither "baseline" nor "avx2". Checked once.
inline bool cpu_has_avx512() {
#if (defined(__GNUC__) || defined(__clang__)) && (defined(__x86_64__) || defined(__i386__))
  static const bool has = [] {
    const char* forced = std::getenv("POLYDEC_SIMD");
    if (forced && std::strcmp(forced, "avx2") == 0) return false;
    return cpu_has_avx2_fma() && __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512vl") &&
           __builtin_cpu_supports("avx512dq");
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
#define POLYDEC_SIMD_WIDE_VARIANTS(name, params, args, body)                                            \
  __attribute__((target("avx512f,avx512vl,avx512dq,avx2,fma"))) void name##_avx512(                     \
      POLYDEC_SIMD_UNPAREN params) {                                                                    \
    body<64>(POLYDEC_SIMD_UNPAREN args);                                                                \
  }                                                                                                     \
  __attribute__((target("avx2,fma"))) void name##_avx2_fma(POLYDEC_SIMD_UNPAREN params) {             \
    body<32>(POLYDEC_SIMD_UNPAREN args);                                                                \
  }                                                                                                     \
  void name##_baseline(POLYDEC_SIMD_UNPAREN params) { body<32>(POLYDEC_SIMD_UNPAREN args); }           \
  void name(POLYDEC_SIMD_UNPAREN params) {                                                              \
    if (::polydec::detail::cpu_has_avx512())                                                            \
      name##_avx512(POLYDEC_SIMD_UNPAREN args);                                                         \
    else if (::polydec::detail::cpu_has_avx2_fma())                                                     \
      name##_avx2_fma(POLYDEC_SIMD_UNPAREN args);                                                       \
    else                                                                                                \
      name##_baseline(POLYDEC_SIMD_UNPAREN args);                                                       \
  }
#else
#define POLYDEC_SIMD_UNPAREN(...) __VA_ARGS__
#define POLYDEC_SIMD_VARIANTS(name, params, args, body) \
  void name(POLYDEC_SIMD_UNPAREN params) { body(POLYDEC_SIMD_UNPAREN args); }
#define POLYDEC_SIMD_WIDE_VARIANTS(name, params, args, body) \
  void name(POLYDEC_SIMD_UNPAREN params) { body<32>(POLYDEC_SIMD_UNPAREN args); }
#endif
