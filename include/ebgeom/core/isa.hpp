// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
/// \file
/// Run-time instruction-set dispatch. The hot kernels of the mesh SDF (triangle blocks, lane masks,
/// child-box distances, the traversal, tile evaluation) are compiled, inside this header-only
/// library, for several instruction sets (`Isa`): the translation unit's own flags (`baseline`),
/// AVX2 with FMA and AVX-512 (GCC and Clang on x86-64, through `__attribute__((target))`), and the
/// best one the CPU supports is chosen once, at the first query (`active_isa`). Layouts never
/// depend on it (block widths are fixed per type), and the results are the same bit for bit on
/// every instruction set: the vector kernels never contract into fused multiply-adds, and the
/// search is exact whatever the rounding of box distances.
///
/// - `EBGEOM_NO_ISA_DISPATCH` (define it before including ebgeom): compile only the translation
///   unit's own instruction set (`native_isa`), as `-march=...` chooses.
/// - Environment variable `EBGEOM_ISA` = `baseline`, `avx2` or `avx512`: caps the choice (read at
///   the first query); `set_isa` changes it at run time (tests, benchmarks).

#include <atomic>
#include <cstdlib>
#include <cstring>
#include <initializer_list>
#include <type_traits>

#include "ebgeom/core/config.hpp"

namespace ebgeom {

/// An instruction set the dispatched kernels are compiled for, in increasing order.
enum class Isa : int {
  baseline = 0, ///< the translation unit's own flags (x86-64: SSE2 unless `-m`/`-march` say more)
  avx2 = 1,     ///< AVX2 + FMA (+ BMI1/2, LZCNT, POPCNT): Haswell, Zen and later
  avx512 = 2,   ///< AVX-512 F, VL, DQ, BW, CD: Skylake-SP, Ice Lake, Zen 4 and later
};

inline const char* to_string(Isa i) noexcept {
  return i == Isa::avx512 ? "avx512" : (i == Isa::avx2 ? "avx2" : "baseline");
}

/// The instruction set the translation unit's flags already allow (`-march=native` on a recent
/// x86 CPU: `avx512`).
inline constexpr Isa native_isa =
#if defined(__AVX512F__) && defined(__AVX512VL__) && defined(__AVX512DQ__) && defined(__AVX512BW__)
    Isa::avx512;
#elif defined(__AVX2__) && defined(__FMA__)
    Isa::avx2;
#else
    Isa::baseline;
#endif

#if !defined(EBGEOM_NO_ISA_DISPATCH) && (defined(__GNUC__) || defined(__clang__)) &&               \
    defined(__x86_64__)
/// 1 when the kernels are compiled for several instruction sets and chosen at run time.
#define EBGEOM_ISA_DISPATCH 1
#define EBGEOM_TARGET_AVX __attribute__((target("avx")))
#define EBGEOM_TARGET_AVX2 __attribute__((target("avx2,fma,bmi,bmi2,lzcnt,popcnt,f16c")))
// The AVX-512 kernels use 512-bit vectors throughout, whatever the translation unit's tuning:
// GCC's tuning for Intel's AVX-512 CPUs (`-march=native` on Skylake-SP to Sapphire Rapids)
// prefers 256-bit vectors for the loops it vectorises, while the kernels' intrinsics are 512-bit,
// and data passed between the two widths through memory most likely waits for the stores (a
// 512-bit store read back as two 256-bit halves, or the reverse, is not forwarded): on a Sapphire
// Rapids VM the mixed kernels made the fast winding band take about a third longer than with
// either width alone (docs/performance.md, "One vector width in the AVX-512 kernels"). Clang has
// no such option in `target` (it would ignore the whole attribute), nor GCC before 8, so there
// the loops follow the translation unit's tuning.
#if defined(__clang__) || __GNUC__ < 8
#define EBGEOM_AVX512_VECTOR_WIDTH
#else
#define EBGEOM_AVX512_VECTOR_WIDTH ",prefer-vector-width=512"
#endif
#define EBGEOM_TARGET_AVX512                                                                       \
  __attribute__((target("avx512f,avx512vl,avx512dq,avx512bw,avx512cd,avx2,fma,bmi,bmi2,lzcnt,"     \
                        "popcnt,f16c" EBGEOM_AVX512_VECTOR_WIDTH)))
#else
#define EBGEOM_ISA_DISPATCH 0
#define EBGEOM_TARGET_AVX
#define EBGEOM_TARGET_AVX2
#define EBGEOM_TARGET_AVX512
#endif

/// The most capable instruction set that is both compiled in and supported by this CPU.
inline Isa detected_isa() noexcept {
#if EBGEOM_ISA_DISPATCH
  static const Isa best = [] {
    __builtin_cpu_init();
    const bool avx2 = __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma") &&
                      __builtin_cpu_supports("bmi2") && __builtin_cpu_supports("popcnt");
    const bool avx512 = avx2 && __builtin_cpu_supports("avx512f") &&
                        __builtin_cpu_supports("avx512vl") && __builtin_cpu_supports("avx512dq") &&
                        __builtin_cpu_supports("avx512bw") && __builtin_cpu_supports("avx512cd");
    const Isa cpu = avx512 ? Isa::avx512 : (avx2 ? Isa::avx2 : Isa::baseline);
    return int(cpu) > int(native_isa) ? cpu : native_isa; // the TU's flags are a promise too
  }();
  return best;
#else
  return native_isa;
#endif
}

namespace detail {
/// The chosen instruction set, -1 until the first query reads `EBGEOM_ISA`.
inline std::atomic<int> active_isa_state{-1};

/// `EBGEOM_ISA` as an `Isa` (capped at `detected_isa()`), or `detected_isa()` when unset or not
/// one of the names.
inline Isa isa_from_environment() noexcept {
  const Isa best = detected_isa();
  const char* e = std::getenv("EBGEOM_ISA");
  if (e == nullptr) return best;
  for (Isa i : {Isa::baseline, Isa::avx2, Isa::avx512})
    if (std::strcmp(e, to_string(i)) == 0) return int(i) < int(best) ? i : best;
  return best;
}
} // namespace detail

/// The instruction set the dispatched kernels run now: `detected_isa()`, lowered by `EBGEOM_ISA`
/// or `set_isa`. Thread-safe; one relaxed load after the first call.
inline Isa active_isa() noexcept {
  if (!EBGEOM_ISA_DISPATCH) return native_isa;
  int s = detail::active_isa_state.load(std::memory_order_relaxed);
  if (EBGEOM_UNLIKELY(s < 0)) {
    s = int(detail::isa_from_environment());
    detail::active_isa_state.store(s, std::memory_order_relaxed);
  }
  return Isa(s);
}

/// Makes the dispatched kernels run `i` from now on (all threads). Returns false, changing
/// nothing, when this CPU lacks `i` or it is not compiled in (without dispatch only `native_isa`
/// is). For tests and benchmarks: every instruction set gives the same results.
inline bool set_isa(Isa i) noexcept {
  if (int(i) > int(detected_isa()) || (!EBGEOM_ISA_DISPATCH && i != native_isa)) return false;
  detail::active_isa_state.store(int(i), std::memory_order_relaxed);
  return true;
}

/// Calls `fn(std::integral_constant<Isa, I>{})` with I = `active_isa()` (one of those compiled
/// in): the kernels' template argument.
template <class Fn> decltype(auto) with_active_isa(Fn&& fn) {
#if EBGEOM_ISA_DISPATCH
  switch (active_isa()) {
  case Isa::avx512:
    return fn(std::integral_constant<Isa, Isa::avx512>{});
  case Isa::avx2:
    return fn(std::integral_constant<Isa, Isa::avx2>{});
  case Isa::baseline:
    break;
  }
  return fn(std::integral_constant<Isa, Isa::baseline>{});
#else
  return fn(std::integral_constant<Isa, native_isa>{});
#endif
}

} // namespace ebgeom
