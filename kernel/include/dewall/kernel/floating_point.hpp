// What the proofs assume of floating-point arithmetic, and how it is ensured.
//
// Every error bound in this project (error_bounds.hpp, interval.hpp, the
// filters of dewall/detail/) assumes IEEE 754 binary64 arithmetic as C++
// compilers give it by default:
//  (a) each operation rounded once, to nearest, without excess precision;
//  (b) no reassociation, no reciprocal tricks, signed zeros, NaN and infinity
//      honoured (isnan is not assumed false);
//  (c) gradual underflow: subnormal inputs and results are kept, not flushed
//      to zero (x86 MXCSR FTZ/DAZ, the AArch64 FZ bit).
// Contraction of a·b + c into one fused multiply-add (-ffp-contract=fast, the
// GCC default in GNU modes with -march=native) is harmless: an FMA is the
// unfused evaluation with the product's rounding error δ set to 0, and every
// bound here holds for any |δ| ≤ u, so for δ = 0 too.
//
// Two things can break the assumptions, and each is handled where it arises:
//  * Compile flags of the translation unit (-ffast-math, -Ofast,
//    -funsafe-math-optimizations, -ffinite-math-only, x87 excess precision).
//    The project's own kernel, triangulator and certifier are compiled into
//    libraries built with the project's flags, so a user's flags cannot reach
//    them. Headers whose floating-point code would be compiled in the user's
//    translation unit (templates over a user's kernel) refuse to compile when
//    a flag the compiler announces is set (DEWALL_UNSAFE_FP_FLAGS below names
//    it). Clang announces -fassociative-math, -freciprocal-math and
//    -fno-signed-zeros by no macro: those headers therefore bracket their code
//    with float_control(precise), which switches them off for that code.
//  * The run-time environment, which is per thread and set by whoever runs
//    first: linking with -ffast-math or -Ofast adds crtfastmath.o, which turns
//    FTZ/DAZ on for the whole process before main; games and audio code set
//    DAZ themselves; fesetround changes the rounding. Fp_environment_guard
//    establishes (c) and round-to-nearest for its lifetime, and every entry
//    point of the libraries (each predicate, triangulate, certify, each
//    parallel task) holds one.
#pragma once

#include <cfenv>
#include <cstdint>

#if defined(__x86_64__) || defined(_M_X64) || (defined(__i386__) && defined(__SSE2__))
#include <xmmintrin.h>
#define DEWALL_FP_ENV_MXCSR 1
#elif defined(__aarch64__)
#define DEWALL_FP_ENV_FPCR 1
#endif

// DEWALL_UNSAFE_FP_FLAGS: defined, as a description of the flag, when this
// translation unit is compiled with flags that break (a) or (b).
#if defined(__FAST_MATH__)
#define DEWALL_UNSAFE_FP_FLAGS "-ffast-math or -Ofast (__FAST_MATH__ is defined)"
#elif defined(__FINITE_MATH_ONLY__) && __FINITE_MATH_ONLY__
#define DEWALL_UNSAFE_FP_FLAGS "-ffinite-math-only (__FINITE_MATH_ONLY__ is 1)"
#elif !defined(__clang__) && defined(__GCC_IEC_559) && __GCC_IEC_559 == 0
#define DEWALL_UNSAFE_FP_FLAGS                                                                       \
  "-funsafe-math-optimizations, -fassociative-math, -freciprocal-math, -fno-signed-zeros or " \
  "-ffinite-math-only (__GCC_IEC_559 is 0)"
#elif defined(__FLT_EVAL_METHOD__) && __FLT_EVAL_METHOD__ != 0 && __FLT_EVAL_METHOD__ != -1
#define DEWALL_UNSAFE_FP_FLAGS "excess precision, e.g. x87 arithmetic (__FLT_EVAL_METHOD__ is not 0)"
#endif

// Brackets a header's floating-point code. Where the flags are unsafe, the
// header refuses to compile, naming the flag; with clang, the code in between
// is compiled with precise semantics whatever -fassociative-math and the like
// say (GCC announces those through __GCC_IEC_559, handled above).
#ifdef DEWALL_UNSAFE_FP_FLAGS
#define DEWALL_FLOATING_POINT_CODE_BEGIN                                                               \
  static_assert(false, "dewall: this header compiles floating-point code whose error bounds need IEEE " \
                       "arithmetic, but this file is compiled with " DEWALL_UNSAFE_FP_FLAGS            \
                       ". Compile this file without that flag, or use the default kernel "            \
                       "(dewall::kernel::Filtered_kernel_d), whose code is compiled into the dewall "  \
                       "libraries with safe flags and works whatever your flags are.");
#define DEWALL_FLOATING_POINT_CODE_END
#elif defined(__clang__)
#define DEWALL_FLOATING_POINT_CODE_BEGIN _Pragma("float_control(precise, on, push)")
#define DEWALL_FLOATING_POINT_CODE_END _Pragma("float_control(pop)")
#else
#define DEWALL_FLOATING_POINT_CODE_BEGIN
#define DEWALL_FLOATING_POINT_CODE_END
#endif

namespace dewall::kernel {

/// For the duration of its scope: round to nearest, subnormals kept (no
/// flush-to-zero, no denormals-are-zero) and floating-point exceptions masked
/// (no trap on an overflow the interval stage expects) in the calling thread;
/// the caller's settings come back at the end of the scope.
/// Cost when the environment is already the default: one read of the control
/// register and a compare (x86-64, AArch64).
class Fp_environment_guard {
 public:
  Fp_environment_guard() {
#if defined(DEWALL_FP_ENV_MXCSR)
    // MXCSR: DAZ bit 6, exception masks bits 7–12, rounding bits 13–14, FTZ bit 15.
    constexpr unsigned daz = 1u << 6, masks = 0x3fu << 7, rounding = 3u << 13, ftz = 1u << 15;
    saved_ = _mm_getcsr();
    const unsigned wanted = (saved_ | masks) & ~(daz | rounding | ftz);
    if (wanted != saved_) {
      _mm_setcsr(wanted);
      changed_ = true;
    }
#elif defined(DEWALL_FP_ENV_FPCR)
    // FPCR: trap enables bits 8–12 and 15, rounding bits 22–23, flush-to-zero bit 24.
    constexpr std::uint64_t traps = 0x9f00u, rounding = 3u << 22, flush = 1u << 24;
    saved_ = __builtin_aarch64_get_fpcr64();
    const std::uint64_t wanted = saved_ & ~(traps | rounding | flush);
    if (wanted != saved_) {
      __builtin_aarch64_set_fpcr64(wanted);
      changed_ = true;
    }
#else
    saved_ = std::fegetround();
    if (saved_ != FE_TONEAREST) {
      std::fesetround(FE_TONEAREST);
      changed_ = true;
    }
#endif
  }
  ~Fp_environment_guard() {
    if (!changed_) return;
#if defined(DEWALL_FP_ENV_MXCSR)
    _mm_setcsr(static_cast<unsigned>(saved_));
#elif defined(DEWALL_FP_ENV_FPCR)
    __builtin_aarch64_set_fpcr64(saved_);
#else
    std::fesetround(static_cast<int>(saved_));
#endif
  }
  Fp_environment_guard(const Fp_environment_guard&) = delete;
  Fp_environment_guard& operator=(const Fp_environment_guard&) = delete;

 private:
#if defined(DEWALL_FP_ENV_FPCR)
  std::uint64_t saved_ = 0;
#else
  unsigned saved_ = 0;
#endif
  bool changed_ = false;
};

}  // namespace dewall::kernel
