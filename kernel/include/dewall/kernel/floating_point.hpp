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
// bound here holds for any |δ| ≤ u, so for δ = 0 too. (The one exception,
// Veltkamp's splitting in running_error.hpp, is compiled only for targets
// without an FMA instruction, where nothing can be contracted.)
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
//    establishes (c) and round-to-nearest for its lifetime. Reading the control
//    register costs about as much as a whole filtered predicate (measured:
//    +4 ns on a 7 ns 3D orientation), so the predicates' static filters are
//    instead proven for any rounding mode and with FTZ/DAZ on
//    (error_bounds.hpp; exact comparisons go through the bits, point.hpp), and
//    only what follows an undecided filter holds a guard; so do triangulate,
//    certify and each parallel task, for the algorithm's own filters.
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
/// the caller's settings come back at the end of the scope. Direct calls of
/// the predicates hold none on their fast path (the static filter is proven for
/// any rounding mode and FTZ/DAZ), so they expect traps masked, as C and C++
/// programs have them unless they call feenableexcept.
/// Cost when the environment is already the default: one read of the control
/// register and a compare (x86-64, AArch64).
class Fp_environment_guard {
 public:
  Fp_environment_guard() {
    const Control c = read();
    if (c != wanted(c)) [[unlikely]] enter(c);
  }
  ~Fp_environment_guard() {
    if (changed_) [[unlikely]] leave();
  }
  Fp_environment_guard(const Fp_environment_guard&) = delete;
  Fp_environment_guard& operator=(const Fp_environment_guard&) = delete;

 private:
  // The common case (nothing to change) stays inline and small: one read of
  // the control register and a compare; the rest is out of line. Out-of-line
  // calls are also what keeps the compiler from moving floating-point
  // arithmetic across the change (there is no FENV_ACCESS in C++).
#if defined(DEWALL_FP_ENV_MXCSR)
  using Control = unsigned;
  // MXCSR: DAZ bit 6, exception masks bits 7–12, rounding bits 13–14, FTZ bit 15.
  // The sticky flags (bits 0–5) are left alone.
  static Control read() { return _mm_getcsr(); }
  static void write(Control c) { _mm_setcsr(c); }
  static constexpr Control wanted(Control c) {
    return (c | 0x3fu << 7) & ~(1u << 6 | 3u << 13 | 1u << 15);
  }
#elif defined(DEWALL_FP_ENV_FPCR)
  using Control = std::uint64_t;
  // FPCR: FIZ bit 0 and AH bit 1 (FEAT_AFP: inputs flushed, alternate
  // handling), trap enables bits 8–12 and 15, rounding bits 22–23,
  // flush-to-zero bit 24. Inline assembly: GCC and Clang name the builtins differently.
  static Control read() {
    Control c;
    asm volatile("mrs %0, fpcr" : "=r"(c));
    return c;
  }
  static void write(Control c) { asm volatile("msr fpcr, %0" : : "r"(c)); }
  static constexpr Control wanted(Control c) {
    return c & ~(Control{3} | Control{0x9f00} | Control{3} << 22 | Control{1} << 24);
  }
#else
  using Control = int;  // the rounding mode: all <cfenv> says portably
  static Control read() { return std::fegetround(); }
  static void write(Control c) { std::fesetround(c); }
  static constexpr Control wanted(Control) { return FE_TONEAREST; }
#endif
  [[gnu::noinline, gnu::cold]] void enter(Control c) {
    saved_ = c;
    changed_ = true;
    write(wanted(c));
  }
  [[gnu::noinline, gnu::cold]] void leave() const { write(saved_); }

  Control saved_{};
  bool changed_ = false;
};

}  // namespace dewall::kernel
