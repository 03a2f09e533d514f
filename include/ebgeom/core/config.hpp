// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
/// \file
/// Compile-time configuration shared by every ebgeom header: version, inlining and assertion
/// macros. Nothing here changes a type's layout.

#include <cstdio>
#include <cstdlib>

#include "ebgeom/version.hpp"

#if defined(__GNUC__) || defined(__clang__)
#define EBGEOM_FORCE_INLINE inline __attribute__((always_inline))
/// On a kernel: inline every call in it, recursively (its callees then compile for its target).
#define EBGEOM_FLATTEN __attribute__((flatten))
/// On a kernel with its own options (`EBGEOM_VECTOR_KERNEL`): never inlined, so that `flatten`
/// callers do not compile it with theirs.
#define EBGEOM_NOINLINE __attribute__((noinline))
#define EBGEOM_LIKELY(x) __builtin_expect(!!(x), 1)
#define EBGEOM_UNLIKELY(x) __builtin_expect(!!(x), 0)
#define EBGEOM_RESTRICT __restrict__
#elif defined(_MSC_VER)
#define EBGEOM_FORCE_INLINE __forceinline
#define EBGEOM_FLATTEN
#define EBGEOM_NOINLINE __declspec(noinline)
#define EBGEOM_LIKELY(x) (x)
#define EBGEOM_UNLIKELY(x) (x)
#define EBGEOM_RESTRICT __restrict
#else
#define EBGEOM_FORCE_INLINE inline
#define EBGEOM_FLATTEN
#define EBGEOM_NOINLINE
#define EBGEOM_LIKELY(x) (x)
#define EBGEOM_UNLIKELY(x) (x)
#define EBGEOM_RESTRICT
#endif

/// On a kernel whose selects must become vector blends: GCC will not if-convert (and so not
/// vectorise) a loop whose branches hold FP operations that might trap, unless told that FP
/// exceptions are not observed. This changes no value (rounding, order and signed zeros are kept).
/// The attribute forbids inlining into callers with other options, so such kernels are plain
/// `inline` functions called once per block. Other compilers vectorise without it.
///
/// Both this and `EBGEOM_EXACT_KERNEL` (on the scalar twin of such a kernel) also turn off
/// floating-point contraction: with FMA enabled (-march=haswell and later) GCC fuses a*b + c
/// differently in a vectorised loop and in scalar code, and the block kernel would then differ
/// from the scalar kernel (and the BVH from the brute force) in the last bit. Clang has no such
/// function attribute: see `EBGEOM_BEGIN_EXACT_FP`.
#if defined(__GNUC__) && !defined(__clang__)
#define EBGEOM_VECTOR_KERNEL __attribute__((optimize("no-trapping-math", "fp-contract=off")))
#define EBGEOM_EXACT_KERNEL __attribute__((optimize("fp-contract=off")))
#else
#define EBGEOM_VECTOR_KERNEL
#define EBGEOM_EXACT_KERNEL
#endif

/// Around the code of the headers whose arithmetic runs inside the run-time dispatched kernels
/// (`core/isa.hpp`) and must give the same bits there as in the caller's own build: with Clang,
/// no contraction into fused multiply-adds. Clang contracts within an expression by default, so a
/// function inlined into an AVX2 kernel (FMA) would round differently from the same function in
/// a build without FMA, and the dispatched search would differ from the brute force in the last
/// bit. The pragmas are scoped (pushed and popped), so code after the header is not affected.
/// GCC: the kernels' own attributes above.
#if defined(__clang__)
#define EBGEOM_BEGIN_EXACT_FP _Pragma("float_control(push)") _Pragma("clang fp contract(off)")
#define EBGEOM_END_EXACT_FP _Pragma("float_control(pop)")
#else
#define EBGEOM_BEGIN_EXACT_FP
#define EBGEOM_END_EXACT_FP
#endif

/// A documented precondition on a value the caller controls that has no error channel (an enum
/// outside its listed values, passed to a `noexcept` kernel): checked in every build, never
/// replaced by a silent default. The checked entry points (`make` functions) return an error for
/// the same values before they reach such a kernel.
#define EBGEOM_PRECONDITION(cond, msg)                                                             \
  do {                                                                                             \
    if (!(cond)) {                                                                                 \
      std::fprintf(stderr, "ebgeom: precondition violated: %s\n", msg);                            \
      std::abort();                                                                                \
    }                                                                                              \
  } while (0)

/// Internal invariants only (never user data). On when EBGEOM_ENABLE_ASSERTS is defined, which our
/// Debug, test and fuzz builds do; users get it with -DEBGEOM_ENABLE_ASSERTS.
#if defined(EBGEOM_ENABLE_ASSERTS)
#define EBGEOM_ASSERT(cond)                                                                        \
  do {                                                                                             \
    if (!(cond)) {                                                                                 \
      std::fprintf(stderr, "%s:%d: ebgeom internal assertion failed: %s\n", __FILE__, __LINE__,    \
                   #cond);                                                                         \
      std::abort();                                                                                \
    }                                                                                              \
  } while (0)
#else
#define EBGEOM_ASSERT(cond) ((void)0)
#endif
