// Elementary functions (atan2, atan, sin, cos, sincos, asin, acos) whose bits are fixed by this
// file. glibc picks FMA or non-FMA code per CPU, so its results may differ between machines; these
// use only IEEE-754 +, -, *, / and sqrt in a written order (we build with -ffp-contract=off).
#pragma once

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>

namespace scallop {

// ---------------------------------------------------------------------------------------------
// Public API. Every function is a pure function of its argument's bits: no libm call (std::sqrt
// is the correctly rounded IEEE square root), no FMA, no long double, no CPU dispatch, no table
// computed at run time, no state. Branches only choose between paths that are each fixed.
// Every translation unit that includes this header must be compiled with -ffp-contract=off (the
// top-level CMakeLists.txt sets it for all targets; a test checks it): with contraction, GCC and
// Clang fuse a * b + c wherever the target has FMA, and the bits change. So built, the outputs
// of 2.2 * 10^7 varied calls hashed identically under GCC 12 and Clang 14, -O0 to -O3, for
// x86-64, x86-64-v3 and -march=native (AVX-512).
//
// Errors ("ulp": unit in the last place of the exact result) are measured against glibc's long
// double functions (64-bit significand, so the reference is good to ~2^-11 ulp) by
// tests/deterministic_math_test.cc on 2^22 seeded inputs per function (the distributions are
// listed there) and asserts them to stay below the maxima quoted here plus ~0.1 ulp; the maxima
// are those of that test and of a one-off sweep of 4 * 10^7 further inputs per function (up to
// 0.08 ulp higher). The error analysis beside each implementation gives a bound for all inputs.
// Speed against glibc is measured by bench/deterministic_math_bench.cc; the figures are at the
// end of this file.
// ---------------------------------------------------------------------------------------------

// The angle of (x, y) in [-pi, pi], like std::atan2 on every input including signed zeros,
// infinities and NaN: atan2(+-0, +0) = +-0, atan2(+-0, -0) = +-pi, atan2(+-0, x < 0) = +-pi,
// atan2(+-y, 0) = +-pi/2, atan2(+-inf, +-inf) = +-pi/4 or +-3pi/4, NaN in gives NaN out.
// Exact symmetries: DetAtan2(-y, x) == -DetAtan2(y, x); scaling x and y by one power of two leaves
// the bits unchanged while min(|x|, |y|) stays above 2^-968 and max(|x|, |y|) below 2^994 (so
// points on a ray through the origin, a power of two apart, get one angle).
// Monotone (nondecreasing in y for x > 0, etc.) as far as the tests probe, including across every
// internal breakpoint. Error: < 0.84 ulp measured, < 1.1 ulp by the analysis at the definition.
// Cost: three divisions (two in sequence), a table lookup and a degree-13 odd polynomial.
inline double DetAtan2(double y, double x);

// atan(x) in [-pi/2, pi/2]; odd exactly; atan(+-inf) = +-pi/2; NaN gives NaN. Monotone as far as
// the tests probe. Error: < 0.86 ulp measured, < 1.05 ulp by analysis. Cost: one division, two
// table lookups and a degree-13 odd polynomial.
inline double DetAtan(double x);

// sin(t), cos(t) for |t| <= kDetTrigDomain = 2^20 radians; NaN beyond it (and for inf or NaN),
// so an angle that has run away is loud instead of silently inaccurate. Within the domain the
// reduction is exact enough for every double, including the one closest to a multiple of pi/2
// (|t - n pi/2| = 2^-60.5).
// Exact symmetries: DetSin(-t) == -DetSin(t), DetCos(-t) == DetCos(t).
// Error: < 0.83 ulp measured (both), < 1 ulp by analysis.
// Cost: a two-piece Cody-Waite reduction (four pieces within 2^-12 of a multiple of pi/2 or for
// |t| > 2^12, out of line) and one degree-13 or degree-12 polynomial picked without a branch.
inline constexpr double kDetTrigDomain = 0x1p20;
inline double DetSin(double t);
inline double DetCos(double t);
// Both for little more than the cost of one (the two polynomials run side by side in one vector
// register); *s and *c are bit-identical to DetSin(t) and DetCos(t).
inline void DetSinCos(double t, double* s, double* c);

// asin(x) in [-pi/2, pi/2] and acos(x) in [0, pi] for x in [-1, 1]; NaN outside (and for NaN).
// asin is odd exactly; asin(+-0) = +-0, acos(1) = +0, acos(-1) = pi rounded. Both monotone as far
// as the tests probe. Error: asin < 0.70 ulp, acos < 0.78 ulp measured; < 0.9 and < 0.85 ulp by
// analysis.
// Cost: a degree-25 odd polynomial, plus a sqrt and a division for |x| > 1/2.
inline double DetAsin(double x);
inline double DetAcos(double x);

// ---------------------------------------------------------------------------------------------
// Implementation. Inline so the samplers can fold it into their loops; the tables are constexpr
// so there is no initialisation order and no global mutable state.
// ---------------------------------------------------------------------------------------------
namespace deterministic_math_internal {

// A value as the unevaluated sum hi + lo (in the tables: hi rounded to nearest, lo the rest).
struct DoubleDouble {
  double hi;
  double lo;
};

// pi/2 and pi as round-to-nearest head plus the rounded remainder (mpmath at 500 bits).
inline constexpr DoubleDouble kHalfPi = {0x1.921fb54442d18p+0, 0x1.1a62633145c07p-54};
inline constexpr DoubleDouble kPi = {0x1.921fb54442d18p+1, 0x1.1a62633145c07p-53};
inline constexpr double kQuarterPi = 0x1.921fb54442d18p-1;       // pi/4 rounded to nearest
inline constexpr double kThreeQuarterPi = 0x1.2d97c7f3321d2p+1;  // 3pi/4 rounded to nearest

// ----- atan -----------------------------------------------------------------------------------
// For t in [0, 1], atan(t) = atan(c) + atan(r) with c = k/16 nearest to t and
// r = (t - c) / (1 + t c), so |r| <= 1/32. For k = 1 we take c = 0 instead: near t = 1/16 the
// sum atan(c) + atan(r) would cancel, and the relative error of r would reach the result. So the
// polynomial covers |r| <= 3/32 and every other r is below a third of the result.
inline constexpr double kAtanBreak[17] = {
    0.0,      0.0,      0x1p-3,   0x1.8p-3, 0x1p-2,   0x1.4p-2, 0x1.8p-2, 0x1.cp-2, 0x1p-1,
    0x1.2p-1, 0x1.4p-1, 0x1.6p-1, 0x1.8p-1, 0x1.ap-1, 0x1.cp-1, 0x1.ep-1, 0x1p+0};

// The result's base for each octant of (x, y) folded to t = min/max in [0, 1]:
// octant 0: atan(c) + atan(r), 1: pi/2 - atan(c) - atan(r), 2: pi - atan(c) - atan(r),
// 3: pi/2 + atan(c) + atan(r). Tabulated as double-doubles (mpmath at 500 bits, hi rounded to
// nearest, lo the rounded remainder) so that adding atan(r) costs one rounding, not two.
inline constexpr double kAtanSign[4] = {1.0, -1.0, -1.0, 1.0};
inline constexpr DoubleDouble kAtanBase[4][17] = {
    {
        {0x0.0p+0, 0x0.0p+0},                            // atan(0)
        {0x0.0p+0, 0x0.0p+0},                            // atan(0), used for k = 1
        {0x1.fd5ba9aac2f6ep-4, -0x1.cd37686760c17p-59},  // atan(2/16)
        {0x1.7b97b4bce5b02p-3, 0x1.347b0b4f881cap-58},   // atan(3/16)
        {0x1.f5b75f92c80ddp-3, 0x1.8ab6e3cf7afbdp-57},   // atan(4/16)
        {0x1.362773707ebccp-2, -0x1.963a544b672d8p-57},  // atan(5/16)
        {0x1.6f61941e4def1p-2, -0x1.c63aae6f6e918p-56},  // atan(6/16)
        {0x1.a64eec3cc23fdp-2, -0x1.24dec1b50b7ffp-56},  // atan(7/16)
        {0x1.dac670561bb4fp-2, 0x1.a2b7f222f65e2p-56},   // atan(8/16)
        {0x1.0657e94db30d0p-1, -0x1.d5b495f6349e6p-56},  // atan(9/16)
        {0x1.1e00babdefeb4p-1, -0x1.928df287a668fp-58},  // atan(10/16)
        {0x1.345f01cce37bbp-1, 0x1.1021137c71102p-55},   // atan(11/16)
        {0x1.4978fa3269ee1p-1, 0x1.2419a87f2a458p-56},   // atan(12/16)
        {0x1.5d58987169b18p-1, 0x1.0028e4bc5e7cap-57},   // atan(13/16)
        {0x1.700a7c5784634p-1, -0x1.8c34d25aadef6p-56},  // atan(14/16)
        {0x1.819d0b7158a4dp-1, -0x1.bf76229d3b917p-56},  // atan(15/16)
        {0x1.921fb54442d18p-1, 0x1.1a62633145c07p-55},   // atan(16/16)
    },
    {
        {0x1.921fb54442d18p+0, 0x1.1a62633145c07p-54},   // pi/2 - atan(0)
        {0x1.921fb54442d18p+0, 0x1.1a62633145c07p-54},   // pi/2 - atan(0)
        {0x1.7249faa996a21p+0, 0x1.a8cc1e7480c68p-54},   // pi/2 - atan(2/16)
        {0x1.62acbeaca61b8p+0, 0x1.c6ac9f134fa91p-60},   // pi/2 - atan(3/16)
        {0x1.5368c951e9cfdp+0, -0x1.96f47948a99f1p-54},  // pi/2 - atan(4/16)
        {0x1.4495d86823225p+0, 0x1.4d29adbab2a62p-54},   // pi/2 - atan(5/16)
        {0x1.3647503caf55cp+0, 0x1.17e21d9a42c9ap-55},   // pi/2 - atan(6/16)
        {0x1.288bfa3512419p+0, 0x1.8e684e7a2281bp-56},   // pi/2 - atan(7/16)
        {0x1.1b6e192ebbe44p+0, 0x1.b1b466a88828ep-54},   // pi/2 - atan(8/16)
        {0x1.0ef3c09d694b0p+0, 0x1.8fcf88aed2e80p-54},   // pi/2 - atan(9/16)
        {0x1.031f57e54adbep+0, 0x1.338b4259c0270p-54},   // pi/2 - atan(10/16)
        {0x1.efe068bba2275p-1, 0x1.24a3b2e61a70bp-55},   // pi/2 - atan(11/16)
        {0x1.dac670561bb4fp-1, 0x1.a2b7f222f65e2p-55},   // pi/2 - atan(12/16)
        {0x1.c6e6d2171bf18p-1, 0x1.f4ba8d3373e1bp-55},   // pi/2 - atan(13/16)
        {0x1.b434ee31013fdp-1, -0x1.0520d0701d877p-55},  // pi/2 - atan(14/16)
        {0x1.a2a25f172cfe4p-1, -0x1.d700509dad6cep-56},  // pi/2 - atan(15/16)
        {0x1.921fb54442d18p-1, 0x1.1a62633145c07p-55},   // pi/2 - atan(16/16)
    },
    {
        {0x1.921fb54442d18p+1, 0x1.1a62633145c07p-53},   // pi - atan(0)
        {0x1.921fb54442d18p+1, 0x1.1a62633145c07p-53},   // pi - atan(0)
        {0x1.8234d7f6ecb9dp+1, -0x1.3cd17e5a39792p-54},  // pi - atan(2/16)
        {0x1.7a6639f874768p+1, 0x1.217d15ad92ff1p-54},   // pi - atan(3/16)
        {0x1.72c43f4b1650ap+1, 0x1.c1b6f4f44e10bp-53},   // pi - atan(4/16)
        {0x1.6b5ac6d632f9fp+1, -0x1.9873ef1407997p-54},  // pi - atan(5/16)
        {0x1.643382c07913ap+1, 0x1.a65371fe67254p-54},   // pi - atan(6/16)
        {0x1.5d55d7bcaa899p+1, -0x1.4101c49818cf9p-53},  // pi - atan(7/16)
        {0x1.56c6e7397f5aep+1, 0x1.660b64ece6f4bp-53},   // pi - atan(8/16)
        {0x1.5089baf0d60e4p+1, 0x1.5518f5f00c544p-53},   // pi - atan(9/16)
        {0x1.4a9f8694c6d6bp+1, 0x1.26f6d2c582f3bp-53},   // pi - atan(10/16)
        {0x1.4507f4d109f29p+1, 0x1.d65a1e52297c6p-53},   // pi - atan(11/16)
        {0x1.3fc176b7a8560p+1, -0x1.441a3bd3f1083p-58},  // pi - atan(12/16)
        {0x1.3ac98f27e8652p+1, 0x1.0a5fd4e57fd8ap-53},   // pi - atan(13/16)
        {0x1.361d162e61b8bp+1, 0x1.4be8fd7c9b7e6p-53},   // pi - atan(14/16)
        {0x1.31b87267eca85p+1, 0x1.49449e13b4ca7p-55},   // pi - atan(15/16)
        {0x1.2d97c7f3321d2p+1, 0x1.a79394c9e8a0ap-54},   // pi - atan(16/16)
    },
    {
        {0x1.921fb54442d18p+0, 0x1.1a62633145c07p-54},   // pi/2 + atan(0)
        {0x1.921fb54442d18p+0, 0x1.1a62633145c07p-54},   // pi/2 + atan(0)
        {0x1.b1f56fdeef00fp+0, 0x1.17f14fdc1574cp-55},   // pi/2 + atan(2/16)
        {0x1.c192abdbdf879p+0, -0x1.d255ec19c1bddp-54},  // pi/2 + atan(3/16)
        {0x1.d0d6a1369bd34p+0, -0x1.a23602a65700cp-57},  // pi/2 + atan(4/16)
        {0x1.dfa992206280bp+0, 0x1.cf36314fb1b58p-55},   // pi/2 + atan(5/16)
        {0x1.edf81a4bd64d4p+0, 0x1.a8d3b7956a1c1p-54},   // pi/2 + atan(6/16)
        {0x1.fbb3705373617p+0, 0x1.d12ab2c402e07p-54},   // pi/2 + atan(7/16)
        {0x1.0468a8ace4df6p+1, 0x1.0620bf7406affp-55},   // pi/2 + atan(8/16)
        {0x1.0aa5d4f58e2c0p+1, 0x1.49ea7b677131bp-55},   // pi/2 + atan(9/16)
        {0x1.109009519d639p+1, 0x1.01398408cb59ep-54},   // pi/2 + atan(10/16)
        {0x1.16279b155a47bp+1, -0x1.76344c4206ddfp-56},  // pi/2 + atan(11/16)
        {0x1.1b6e192ebbe44p+1, 0x1.b1b466a88828ep-53},   // pi/2 + atan(12/16)
        {0x1.206600be7bd52p+1, 0x1.3a677fc8d1900p-54},   // pi/2 + atan(13/16)
        {0x1.251279b802819p+1, 0x1.6eaa5d3534893p-55},   // pi/2 + atan(14/16)
        {0x1.29771d7e7791fp+1, 0x1.55426d44fb6e1p-53},   // pi/2 + atan(15/16)
        {0x1.2d97c7f3321d2p+1, 0x1.a79394c9e8a0ap-54},   // pi/2 + atan(16/16)
    },
};

// atan(r) = r + r z Q(z), z = r^2, |r| <= 3/32 (plus rounding slack 2^-40 relative).
// Q: weighted minimax of the relative error of atan (Remez, see the script at the end of this
// file), leading two coefficients rounded first and the rest refitted. Max relative error of
// the polynomial with these double coefficients: 2^-64.6.
inline constexpr double kAtanQ[6] = {
    -0x1.5555555555551p-2, 0x1.9999999994db6p-3,  -0x1.24924916d286cp-3,
    0x1.c71c4d344784cp-4,  -0x1.744480c1f5d24p-4, 0x1.32edebc92af76p-4,
};

// c = k/16 as hi + lo with hi and lo signed powers of two (or zero), so that hi x and lo x are
// exact. k = 11 and 13 need three terms; DetAtan's cell table never picks them for |x| > 1,
// the only case that uses this split.
inline constexpr DoubleDouble kAtanBreakSplit[17] = {
    {0.0, 0.0},       {0.0, 0.0},       {0x1p-3, 0.0},     {0x1p-3, 0x1p-4}, {0x1p-2, 0.0},
    {0x1p-2, 0x1p-4}, {0x1p-2, 0x1p-3}, {0x1p-1, -0x1p-4}, {0x1p-1, 0.0},    {0x1p-1, 0x1p-4},
    {0x1p-1, 0x1p-3}, {0.0, 0.0},       {0x1p0, -0x1p-2},  {0.0, 0.0},       {0x1p0, -0x1p-3},
    {0x1p0, -0x1p-4}, {0x1p0, 0.0}};

// For DetAtan: the breakpoint index k for |x| in each cell [2^e (1 + m/16), 2^e (1 + (m+1)/16)),
// e = -5..4, m = 0..15 (one row per e), read from the top bits of |x| instead of dividing first;
// cells outside get k = 0. For |x| < 1 it is round(16 |x|), constant on each cell (the cells never
// straddle a half), as DetAtan2 would pick. For |x| >= 1 it minimises max |1/x - c| over the
// cell among k other than 11 and 13 (so that kAtanBreakSplit applies), giving |r| < 1/16.
// Generated with exact fractions (python3 fractions); tests/deterministic_math_test.cc checks it.
inline constexpr int kAtanCellCount = 160;
inline constexpr uint64_t kAtanFirstCell = (1023 - 5) << 4;  // (biased exponent, 4 bits) of 2^-5
inline constexpr uint8_t kAtanCellBreak[kAtanCellCount] = {
    1,  1,  1,  1,  1,  1,  1,  1,  1,  1,  1,  1,  1,  1,  1,  1,   // 2^-5
    1,  1,  1,  1,  1,  1,  1,  1,  2,  2,  2,  2,  2,  2,  2,  2,   // 2^-4
    2,  2,  2,  2,  3,  3,  3,  3,  3,  3,  3,  3,  4,  4,  4,  4,   // 2^-3
    4,  4,  5,  5,  5,  5,  6,  6,  6,  6,  7,  7,  7,  7,  8,  8,   // 2^-2
    8,  9,  9,  10, 10, 11, 11, 12, 12, 13, 13, 14, 14, 15, 15, 16,  // 2^-1
    16, 15, 14, 14, 12, 12, 12, 10, 10, 10, 10, 9,  9,  9,  8,  8,   // 2^0
    8,  7,  7,  7,  6,  6,  6,  5,  5,  5,  5,  5,  4,  4,  4,  4,   // 2^1
    4,  4,  3,  3,  3,  3,  3,  3,  3,  3,  2,  2,  2,  2,  2,  2,   // 2^2
    2,  2,  2,  2,  2,  2,  2,  2,  2,  2,  2,  2,  2,  2,  2,  2,   // 2^3
    0,  0,  0,  0,  0,  0,  0,  0,  0,  0,  0,  0,  0,  0,  0,  0,   // 2^4
};

// +1 and -1, indexed by a sign bit.
inline constexpr double kSignOf[2] = {1.0, -1.0};

// atan of the reduced r = (u - c) / (1 + u c), c = kAtanBreak[k], placed in `octant`
// (see kAtanBase), plus `slope_correction` (already divided by 1 + u^2; 0 when u is exact), all
// times `sign` = +-1. Multiplying the terms by the sign negates every rounded result exactly, so
// this is the negated value bit for bit, without a copysign after the last addition; a result
// of zero would come out +0, so zeros are left to the callers.
inline double AtanOfReduced(double r, int k, int octant, double slope_correction, double sign) {
  const double z = r * r;
  const double z2 = z * z;
  const double q = ((kAtanQ[0] + kAtanQ[1] * z) + z2 * (kAtanQ[2] + kAtanQ[3] * z)) +
                   (z2 * z2) * (kAtanQ[4] + kAtanQ[5] * z);
  const DoubleDouble base = kAtanBase[octant][k];
  const double base_hi = sign * base.hi;
  const double base_lo = sign * base.lo;
  const double term_sign = sign * kAtanSign[octant];
  const double sr = term_sign * r;
  const double hi = base_hi + sr;
  const double lo = (base_hi - hi) + sr;  // exact: |base.hi| >= |r| or base.hi == 0
  return hi + (lo + ((base_lo + term_sign * slope_correction) + (sr * z) * q));
}

// t * b - p exactly for p = t * b rounded (Dekker's product with Veltkamp's split, no FMA),
// provided |t|, |b| < 2^995 and the partial products do not underflow (t b >= 2^-969).
inline double ProductError(double t, double b, double p) {
  constexpr double kSplitter = 0x1p27 + 1.0;
  const double gt = kSplitter * t;
  const double th = gt - (gt - t);
  const double tl = t - th;
  const double gb = kSplitter * b;
  const double bh = gb - (gb - b);
  const double bl = b - bh;
  return (((th * bh - p) + th * bl) + tl * bh) + tl * bl;
}

// The rounding error of t = num / den (0 <= num <= den) carried through atan: atan(num / den)
// = atan(t) + e / (den (1 + t^2)) + O(e^2), with e = num - t den exactly representable (t is
// correctly rounded) and computed exactly by ProductError. Without it, t's 0.5 ulp would reach
// the result almost unchanged wherever atan(t) ~ t (up to 1.45 ulp measured).
inline double QuotientCorrection(double num, double den, double t) {
  const double p = t * den;
  return ((num - p) - ProductError(t, den, p)) / (den + t * num);  // num - p: Sterbenz
}

// As QuotientCorrection for any num, den: scaled by a power of two (exact, t unchanged) into
// ProductError's range. It returns 0 when t is exact (den infinite) or num stays below 2^-968:
// then t < 2^-68, atan t = t to 2^-136 relative, and t is already the correctly rounded quotient.
[[gnu::noinline]] inline double QuotientCorrectionScaled(double num, double den, double t) {
  if (std::isinf(den)) return 0.0;  // num finite: t = 0 exactly
  if (den > 0x1p994) {
    num *= 0x1p-600;
    den *= 0x1p-600;
  } else if (den < 0x1p-900) {
    num *= 0x1p600;
    den *= 0x1p600;
  }
  if (!(num >= 0x1p-968)) return 0.0;  // den >= 2^-900 unscaled, >= 2^-474 scaled: t < 2^-68
  return QuotientCorrection(num, den, t);
}

// The inputs for which t = min / max is not in (0, 1]: a NaN; both zero or both infinite; or one
// coordinate zero, or so much smaller than the other that t underflows to 0, where the result is
// the axis angle (0, pi/2 or pi, to which atan2 rounds when t < 2^-1075) and signed zeros decide.
[[gnu::cold, gnu::noinline]] inline double Atan2Special(double y, double x) {
  if (std::isnan(x) || std::isnan(y)) return x + y;
  const double ax = std::abs(x);
  const double ay = std::abs(y);
  if (ay > ax) return std::copysign(kHalfPi.hi, y);
  if (ay < ax || y == 0.0) return std::copysign(std::signbit(x) ? kPi.hi : 0.0, y);
  return std::copysign(std::signbit(x) ? kThreeQuarterPi : kQuarterPi, y);  // both infinite
}

// ----- sin and cos ----------------------------------------------------------------------------
// Cody-Waite reduction t = n pi/2 + r with pi/2 = P1 + P2 + P3 + P4 (mpmath at 500 bits):
// P1, P2, P3 are pi/2 and its successive remainders rounded to multiples of 2^-32, 2^-65 and
// 2^-98 (31, 32 and 28 significant bits), P4 the remainder rounded to a double; the sum is
// within 2^-159.9 of pi/2. For n < 2^21, n P1, n P2 and n P3 are exact, and t - n P1 is exact
// (Sterbenz). An exhaustive integer search over n <= 2^20 / (pi/2) finds the closest approach of
// a double to a multiple of pi/2 at |r| = 2^-60.5 (n = 29, and 29 * 2^j): r needs about 115
// correct bits there, which the four pieces give (error < 2^-130).
inline constexpr double kTwoOverPi = 0x1.45f306dc9c883p-1;
inline constexpr double kHalfPiPiece1 = 0x1.921fb54400000p+0;
inline constexpr double kHalfPiPiece2 = 0x1.0b4611a600000p-34;
inline constexpr double kHalfPiPiece3 = 0x1.3198a2e000000p-69;
inline constexpr double kHalfPiPiece4 = 0x1.b839a252049c1p-104;
inline constexpr double kHalfPiRest = 0x1.0b4611a626331p-34;  // pi/2 - P1 rounded to 53 bits
// Adding and subtracting 1.5 * 2^52 rounds a double below 2^51 to the nearest integer.
inline constexpr double kRoundToIntShifter = 0x1.8p52;
// Up to here the two-piece reduction is accurate enough (see ReduceByHalfPiQuickly).
inline constexpr double kQuickReductionLimit = 0x1p12;

// s + e = a + b exactly (Knuth's TwoSum; no ordering precondition).
inline DoubleDouble TwoSum(double a, double b) {
  const double s = a + b;
  const double bb = s - a;
  const double e = (a - (s - bb)) + (b - bb);
  return {s, e};
}

// The quick reduction: t - n pi/2 as rh + rl with |rl| <= ulp(rh) / 2 + 2^-74 and
// |rh| <= pi/4 + 2^-32, and n mod 4 (n is signed, so no separate sign of t to track). False
// (with *r unspecified) unless |t| <= 2^12 and |r| >= 2^-12, so also for zero, infinities, NaN.
//
// a = t - n P1 is exact and b = n (pi/2 - P1) (|n| < 2^12) is rounded with error < 2^-75, as
// big again from pi/2 - P1's own rounding; rh = a - b and its exact error (a - rh) - b
// (Fast2Sum: |a| > |b| since |b| < 2^-21.9) then carry r to 2^-74 absolute, 2^-62 relative.
inline bool ReduceByHalfPiQuickly(double t, DoubleDouble* r, uint64_t* quadrant) {
  // |t| * 2/pi is below 2^51 where it matters, so the shifter leaves the nearest integer (ties
  // to even). A product rounded near a half-integer may pick the other neighbour: |r| then
  // exceeds pi/4 by < 2^-32, which the polynomials cover.
  const double shifted = t * kTwoOverPi + kRoundToIntShifter;
  const double fn = shifted - kRoundToIntShifter;
  // The significand of shifted holds 3 * 2^51 + n, so its low bits are n mod 4 (also for n < 0);
  // reading them there is quicker than converting fn.
  *quadrant = std::bit_cast<uint64_t>(shifted) & 3u;
  const double a = t - fn * kHalfPiPiece1;  // exact
  const double b = fn * kHalfPiRest;
  const double head = a - b;
  *r = {head, (a - head) - b};
  // |head| >= 2^-12 and |t| <= 2^12 (false for NaN), compared as integers (magnitude bits shifted
  // past the sign), which keeps the floating-point ports free for the arithmetic.
  return (std::bit_cast<uint64_t>(head) << 1) >= (std::bit_cast<uint64_t>(0x1p-12) << 1) &&
         (std::bit_cast<uint64_t>(t) << 1) <= (std::bit_cast<uint64_t>(kQuickReductionLimit) << 1);
}

// The careful reduction, for |t| <= 2^20: all four pieces and two TwoSums, exact up to n P4's
// rounding (< 2^-130), then normalised so |rl| <= ulp(rh) / 2.
inline DoubleDouble ReduceByHalfPiCarefully(double t, uint64_t* quadrant) {
  const double shifted = t * kTwoOverPi + kRoundToIntShifter;
  const double fn = shifted - kRoundToIntShifter;
  *quadrant = std::bit_cast<uint64_t>(shifted) & 3u;
  const double a = t - fn * kHalfPiPiece1;  // exact
  const DoubleDouble first = TwoSum(a, -(fn * kHalfPiPiece2));
  const DoubleDouble second = TwoSum(first.hi, -(fn * kHalfPiPiece3));
  const double low = (first.lo + second.lo) - fn * kHalfPiPiece4;
  const double rh = second.hi + low;  // |second.hi| >= 2^-61 > 2^-100 > |low|, or both are 0
  return {rh, low - (rh - second.hi)};
}

// Rows S, C, -S, -C: the quadrant (and so the argument's sign) picks a row without a branch, and
// the sign rides along in the coefficients instead of costing a multiplication at the end. The
// last two entries of each row are that sign s and s/2, so one address serves every lookup.
inline constexpr double kSinCosPoly[4][8] = {
    {-0x1.5555555555548p-3, 0x1.111111110f730p-7, -0x1.a01a019be9217p-13, 0x1.71de35552b4d9p-19,
     -0x1.ae5e4b83dce7bp-26, 0x1.5d8b5591239c9p-33, 1.0, 0.5},
    {0x1.555555555554bp-5, -0x1.6c16c16c15015p-10, 0x1.a01a019c8f254p-16, -0x1.27e4f7f191520p-22,
     0x1.1ee9dbcf05d2bp-29, -0x1.8fa6848e38ee5p-37, 1.0, 0.5},
    {0x1.5555555555548p-3, -0x1.111111110f730p-7, 0x1.a01a019be9217p-13, -0x1.71de35552b4d9p-19,
     0x1.ae5e4b83dce7bp-26, -0x1.5d8b5591239c9p-33, -1.0, -0.5},
    {-0x1.555555555554bp-5, 0x1.6c16c16c15015p-10, -0x1.a01a019c8f254p-16, 0x1.27e4f7f191520p-22,
     -0x1.1ee9dbcf05d2bp-29, 0x1.8fa6848e38ee5p-37, -1.0, -0.5},
};

// For h + tau with |h| <= pi/4 + 2^-31 and |tau| <= ulp(h) / 2 + 2^-74:
// sin(h + tau), cos(h + tau), -sin(h + tau), -cos(h + tau) for kind = 0, 1, 2, 3.
// sin(h + tau) = sin h + tau cos h and cos(h + tau) = cos h - tau sin h to tau^2 < 2^-106; the
// factors cos h and sin h are taken as w = 1 - z/2 and h, off by < z^2/24 and h z/6, which times
// |tau| <= 2^-54 is below 2^-57 absolute.
//
// Both are written as head + (low + mult * P(z)), z = h^2, with P's coefficients and the three
// terms picked by kind (by indexing, not branching: random angles would mispredict half the
// time), so only one polynomial is evaluated. The sign s = +-1 of kinds 2 and 3 is in P's row and
// in s (1 - z/2) = s - (s/2) z, which rounds to exactly -w when s = -1, so it costs nothing.
//
// Error bound: sin = h + (tau w + h z S(z)): the parenthesis is below 0.115 of the result and
// carries <= 4 u of its own error (z, S's evaluation, two products, the sum), i.e. <= 0.46 u of
// the result; plus the final rounding 0.5 ulp and 2^-57.9 from the fit: < 1 ulp.
// cos = w + ((((1 - w) - z/2) - tau h) + z^2 C(z)) with w = 1 - z/2: (1 - w) - z/2 recovers w's
// rounding exactly (Sterbenz twice), leaving z's own rounding (<= 2^-55 absolute, 0.25 ulp of a
// result >= 0.70) plus the final rounding: < 0.8 ulp.
inline double SinOrCosOfReduced(DoubleDouble r, uint64_t kind) {
  const double h = r.hi;
  const double tau = r.lo;
  const double z = h * h;
  const double z2 = z * z;
  const double* k = kSinCosPoly[kind];
  const double poly = (k[0] + k[1] * z) + z2 * ((k[2] + k[3] * z) + z2 * (k[4] + k[5] * z));
  const double sign = k[6];
  const double signed_half_z = k[7] * z;  // exact
  const double signed_w = sign - signed_half_z;
  const double signed_h = sign * h;
  const double sin_low = tau * signed_w;
  const double cos_low = ((sign - signed_w) - signed_half_z) - tau * signed_h;
  const double head[2] = {signed_h, signed_w};
  const double low[2] = {sin_low, cos_low};
  const double mult[2] = {h * z, z2};
  const uint64_t odd = kind & 1u;
  return head[odd] + (low[odd] + mult[odd] * poly);
}

// {sin(t), cos(t)} for t = n pi/2 + h + tau and quadrant = n mod 4, for DetSinCos: the same
// operations in the same order as SinOrCosOfReduced for kinds 0 and 1, but side by side in the
// two lanes of a vector (GCC's vector extension: two IEEE doubles, one instruction for both on
// SSE2 or NEON), then swapped and negated for the quadrant. Negating inputs and coefficients
// negates every rounded result exactly, so the bits equal DetSin's and DetCos's.
using Double2 = double __attribute__((vector_size(16)));
inline constexpr Double2 kSinCosLanes[6] = {
    {kSinCosPoly[0][0], kSinCosPoly[1][0]}, {kSinCosPoly[0][1], kSinCosPoly[1][1]},
    {kSinCosPoly[0][2], kSinCosPoly[1][2]}, {kSinCosPoly[0][3], kSinCosPoly[1][3]},
    {kSinCosPoly[0][4], kSinCosPoly[1][4]}, {kSinCosPoly[0][5], kSinCosPoly[1][5]}};
inline void SinAndCosOfReduced(DoubleDouble r, uint64_t quadrant, double* s, double* c) {
  const double h = r.hi;
  const double tau = r.lo;
  const double z = h * h;
  const Double2 zz = {z, z};
  const Double2 zz2 = zz * zz;
  const Double2* k = kSinCosLanes;
  const Double2 poly = (k[0] + k[1] * zz) + zz2 * ((k[2] + k[3] * zz) + zz2 * (k[4] + k[5] * zz));
  const double half_z = 0.5 * z;
  const double w = 1.0 - half_z;
  const Double2 head = {h, w};
  const Double2 low = {tau * w, ((1.0 - w) - half_z) - tau * h};
  const Double2 mult = {h * z, zz2[0]};
  const Double2 sin_cos = head + (low + mult * poly);
  // sin(r + n pi/2) = sin r, cos r, -sin r, -cos r and cos(r + n pi/2) = cos r, -sin r, -cos r,
  // sin r for n mod 4 = 0..3.
  const double both[2] = {sin_cos[0], sin_cos[1]};
  const uint64_t odd = quadrant & 1u;
  *s = both[odd] * kSignOf[(quadrant >> 1) & 1u];
  *c = both[odd ^ 1u] * kSignOf[((quadrant + 1) >> 1) & 1u];
}

// sin(t) (cosine false) or cos(t) (cosine true) for every t the quick reduction declines: out of
// the domain (NaN), zero (whose sign the signed sums in SinOrCosOfReduced would lose), or within
// 2^-12 of a nonzero multiple of pi/2, or beyond 2^12. Kept out of line: it is rarely taken.
[[gnu::noinline]] inline double SinOrCosCarefully(double t, bool cosine) {
  const double at = std::abs(t);
  if (!(at <= kDetTrigDomain)) return std::numeric_limits<double>::quiet_NaN();
  if (t == 0.0) return cosine ? 1.0 : t;
  uint64_t quadrant;
  const DoubleDouble r = ReduceByHalfPiCarefully(t, &quadrant);
  return SinOrCosOfReduced(r, cosine ? (quadrant + 1) & 3u : quadrant);
}

// ----- asin and acos --------------------------------------------------------------------------
// asin(s) = s + s z P(z), z = s^2 <= 1/4: weighted minimax of the relative error of asin on
// [0, 1/2] (Remez, script below; two leading coefficients rounded first). Max relative error of
// the polynomial with these double coefficients: 2^-59.9.
inline constexpr double kAsinP[13] = {
    0x1.5555555555577p-3, 0x1.333333332e131p-4, 0x1.6db6db7212680p-5, 0x1.f1c71a94f2d60p-6,
    0x1.6e8bdee04479fp-6, 0x1.1c49f05c5f0c8p-6, 0x1.ca1f8d804fad5p-7, 0x1.758589066e562p-7,
    0x1.613c905812678p-7, 0x1.e5f54d75e9b75p-9, 0x1.639c825864b9dp-6, -0x1.57fd8e9cb0c19p-6,
    0x1.0b46c1745a970p-5,
};

// P(z), Estrin's scheme in a fixed order (shorter dependency chain than Horner).
inline double AsinPoly(double z) {
  const double z2 = z * z;
  const double z4 = z2 * z2;
  const double z8 = z4 * z4;
  const double a0 = kAsinP[0] + kAsinP[1] * z;
  const double a1 = kAsinP[2] + kAsinP[3] * z;
  const double a2 = kAsinP[4] + kAsinP[5] * z;
  const double a3 = kAsinP[6] + kAsinP[7] * z;
  const double a4 = kAsinP[8] + kAsinP[9] * z;
  const double a5 = kAsinP[10] + kAsinP[11] * z;
  const double b0 = a0 + z2 * a1;
  const double b1 = a2 + z2 * a3;
  const double b2 = a4 + z2 * a5;
  const double c0 = b0 + z4 * b1;
  const double c1 = b2 + z4 * kAsinP[12];
  return c0 + z8 * c1;
}

// For ax in (1/2, 1]: z = (1 - ax) / 2 (exact), s = sqrt(z) rounded, and the head and tail of
// the exact square root: head = s with its low 32 bits cleared (so head^2 is exact) and
// tail = (z - head^2) / (s + head), from sqrt(z) - head = (z - head^2) / (sqrt(z) + head).
// With s alone, 2 asin(s) would inherit sqrt's 0.5 ulp rounding; head + tail is good to 2^-70.
struct HalfAngleRoot {
  double z;
  double s;
  double head;
  double tail;
};
inline HalfAngleRoot HalfAngleRootOf(double ax) {
  const double z = (1.0 - ax) * 0.5;  // 1 - ax is exact (Sterbenz)
  // sqrtsd; GCC also emits a call to libm's sqrt behind a test for a negative argument (to set
  // errno), which z >= 0 never takes.
  const double s = std::sqrt(z);
  const double head = std::bit_cast<double>(std::bit_cast<uint64_t>(s) & 0xffffffff00000000u);
  // z == 0 only at ax == 1, where s == head == 0 and 0/0 must not happen.
  const double tail = z > 0.0 ? (z - head * head) / (s + head) : 0.0;
  return {z, s, head, tail};
}

}  // namespace deterministic_math_internal

// ---------------------------------------------------------------------------------------------
// Definitions.
// ---------------------------------------------------------------------------------------------

// Error bound: the quotient's rounding is corrected (QuotientCorrection); what is left is
// AtanOfReduced's: r = (t - c) / (1 + t c) has t - c exact (Sterbenz) and relative error <= 1.5 u
// (u = 2^-53) from the product, sum and quotient; for k >= 2, |r| / atan(t) <= 0.34, so that is
// <= 0.51 u of the result in octant 0 (the other octants add a base at least as large, which only
// shrinks it). The base hi + r is summed exactly (Fast2Sum), the tail, the correction's own error
// (2^-5 of half an ulp) and the polynomial add < 0.05 u, the final rounding 0.5 ulp: < 1.1 ulp.
inline double DetAtan2(double y, double x) {
  namespace in = deterministic_math_internal;
  const double ax = std::abs(x);
  const double ay = std::abs(y);
  const bool steep = ay > ax;  // fold to t = min / max in [0, 1]
  const double num = steep ? ax : ay;
  const double den = steep ? ay : ax;
  const double t = num / den;
  // Zeros, infinities, NaN and underflowing quotients (see Atan2Special) leave (0, 1].
  if (!(t > 0.0 && t <= 1.0)) [[unlikely]] {
    return in::Atan2Special(y, x);
  }
  const double correction = (num >= 0x1p-968 && den <= 0x1p994)
                                ? in::QuotientCorrection(num, den, t)
                                : in::QuotientCorrectionScaled(num, den, t);
  const int octant = static_cast<int>(steep) + 2 * static_cast<int>(std::signbit(x));
  const int k = static_cast<int>(t * 16.0 + 0.5);  // 0..16; t*16 is exact
  const double c = in::kAtanBreak[k];
  const double r = (t - c) / (1.0 + t * c);
  return in::AtanOfReduced(r, k, octant, correction, in::kSignOf[std::signbit(y)]);
}

// Error bound: no quotient is rounded before the reduction. |x| <= 1: r = (x - c) / (1 + x c)
// as in DetAtan2 (< 1.05 ulp). |x| > 1: atan x = pi/2 - atan(1/x), r = (1/x - c) / (1 + c/x) =
// (1 - c x) / (x + c), with c x = hi x + lo x from kAtanBreakSplit: 1 - hi x is exact (Sterbenz,
// hi x in [1/2, 2]) and the rest costs 1.5 u of r, which is < 0.08 of the result (>= pi/4), so
// the final rounding dominates: < 0.7 ulp.
inline double DetAtan(double x) {
  namespace in = deterministic_math_internal;
  const double ax = std::abs(x);
  // Beyond 2^60, pi/2 - 1/x rounds to pi/2 (1/x < 2^-60 is far below half an ulp).
  if (!(ax <= 0x1p60)) [[unlikely]] {
    return std::isnan(x) ? x + x : std::copysign(in::kHalfPi.hi, x);
  }
  const uint64_t cell = (std::bit_cast<uint64_t>(ax) >> 48) - in::kAtanFirstCell;
  const int k = cell < in::kAtanCellCount ? in::kAtanCellBreak[cell] : 0;
  const double c = in::kAtanBreak[k];
  const in::DoubleDouble split = in::kAtanBreakSplit[k];
  const bool steep = ax > 1.0;
  const double num = steep ? (1.0 - split.hi * ax) - split.lo * ax : ax - c;
  const double den = steep ? ax + c : 1.0 + ax * c;
  return std::copysign(in::AtanOfReduced(num / den, k, static_cast<int>(steep), 0.0, 1.0), x);
}

inline double DetSin(double t) {
  namespace in = deterministic_math_internal;
  in::DoubleDouble r;
  uint64_t quadrant;
  if (!in::ReduceByHalfPiQuickly(t, &r, &quadrant)) [[unlikely]] {
    return in::SinOrCosCarefully(t, false);
  }
  // sin(r + n pi/2) = sin r, cos r, -sin r, -cos r for n mod 4 = 0..3.
  return in::SinOrCosOfReduced(r, quadrant);
}

inline double DetCos(double t) {
  namespace in = deterministic_math_internal;
  in::DoubleDouble r;
  uint64_t quadrant;
  if (!in::ReduceByHalfPiQuickly(t, &r, &quadrant)) [[unlikely]] {
    return in::SinOrCosCarefully(t, true);
  }
  // cos(r + n pi/2) = cos r, -sin r, -cos r, sin r for n mod 4 = 0..3.
  return in::SinOrCosOfReduced(r, (quadrant + 1) & 3u);
}

inline void DetSinCos(double t, double* s, double* c) {
  namespace in = deterministic_math_internal;
  in::DoubleDouble r;
  uint64_t quadrant;
  if (!in::ReduceByHalfPiQuickly(t, &r, &quadrant)) [[unlikely]] {
    *s = in::SinOrCosCarefully(t, false);
    *c = in::SinOrCosCarefully(t, true);
    return;
  }
  in::SinAndCosOfReduced(r, quadrant, s, c);
}

// Error bound: |x| <= 1/2: x + x z P has the same shape as sin above with a correction below
// 0.046 of the result carrying <= 5 u: < 0.75 ulp. |x| > 1/2: asin = pi/2 - 2 asin(s), computed
// as (pi/2.hi - 2 head) + (pi/2.lo - 2 (tail + s z P)); the first difference is exact (2 head has
// 21 significant bits, no finer than 2^-52 for s >= 2^-27), the second is below 0.09 of a result
// >= pi/6 and carries <= 4 u: < 0.9 ulp.
inline double DetAsin(double x) {
  namespace in = deterministic_math_internal;
  const double ax = std::abs(x);
  if (!(ax <= 1.0)) [[unlikely]] {
    return std::isnan(x) ? x + x : std::numeric_limits<double>::quiet_NaN();
  }
  double result;
  if (ax <= 0.5) {
    const double z = ax * ax;
    result = ax + (ax * z) * in::AsinPoly(z);
  } else {
    const in::HalfAngleRoot h = in::HalfAngleRootOf(ax);
    const double correction = h.tail + (h.s * h.z) * in::AsinPoly(h.z);
    result = (in::kHalfPi.hi - 2.0 * h.head) + (in::kHalfPi.lo - 2.0 * correction);
  }
  return std::copysign(result, x);
}

// Error bound: |x| <= 1/2: pi/2 - asin(x), where rounding x + x z P - pi/2.lo (< 0.52) costs at
// most a quarter of the result's ulp (the result is >= pi/3): < 0.8 ulp. x > 1/2: 2 asin(s) =
// 2 head + 2 (tail + s z P), one rounding plus 4 u on a part below 0.045 of the result:
// < 0.7 ulp. x < -1/2: pi - 2 asin(s) = (pi.hi - 2 head) + (pi.lo - 2 (tail + s z P)), the first
// difference exact as in DetAsin (2 head is on a grid no finer than 2^-51): < 0.6 ulp.
inline double DetAcos(double x) {
  namespace in = deterministic_math_internal;
  const double ax = std::abs(x);
  if (!(ax <= 1.0)) [[unlikely]] {
    return std::isnan(x) ? x + x : std::numeric_limits<double>::quiet_NaN();
  }
  if (ax <= 0.5) {
    const double z = x * x;
    return in::kHalfPi.hi - (x - (in::kHalfPi.lo - (x * z) * in::AsinPoly(z)));
  }
  const in::HalfAngleRoot h = in::HalfAngleRootOf(ax);
  const double w = (h.s * h.z) * in::AsinPoly(h.z);
  if (x > 0.0) return 2.0 * h.head + 2.0 * (h.tail + w);
  return (in::kPi.hi - 2.0 * h.head) + (in::kPi.lo - 2.0 * (h.tail + w));
}

}  // namespace scallop

// ---------------------------------------------------------------------------------------------
// How the constants were derived (python3-mpmath 1.3.0, Debian 12). Tables: mpmath at 500 bits,
// hi = float(v), lo = float(v - hi). Polynomials: Remez exchange minimising
// max |w(z) (p(z) - f(z))| on [1e-12 b, b], where w makes it the relative error of the whole
// function; the two leading coefficients are rounded to double one at a time, each time
// refitting the rest on (f - fixed part) / z^i with weight w z^i, then the rest are rounded.
//   atan: f = (atan(r) - r) / r^3, w = r^3 / atan(r), r = sqrt(z), b = (3/32 (1 + 2^-40))^2, deg 5
//   sin:  f = (sin(r) - r) / r^3,  w = r^3 / sin(r),  b = (pi/4 + 2^-30)^2, deg 5
//   cos:  f = (cos(r) - 1 + z/2) / z^2, w = z^2 / cos(r), b = (pi/4 + 2^-30)^2, deg 5
//   asin: f = (asin(r) - r) / r^3, w = r^3 / asin(r), b = 1/4, deg 12
// The Remez loop (mp.dps = 60): start from Chebyshev nodes; solve
//   sum_j c_j x_i^j + (-1)^i E / w(x_i) = f(x_i) for the deg + 2 nodes;
// sample the error on 4001 Chebyshev points, take the largest |error| of each run of one sign as
// the new nodes (dropping the smaller end run while there are too many); stop when the largest
// sampled |error| is within 1e-6 of |E|. The rounded polynomial's error quoted beside each table
// is the maximum over 4001 uniform points of the same weighted error, in mpmath.
// The closest approach of a double to n pi/2 (for the careful reduction) came from exact
// integers: for each n <= 2^20 / (pi/2), v = n floor(pi/2 2^300), the distance of v to the
// nearest multiple of the double spacing at v's binade, scaled back by 2^-300.
// kAtanCellBreak: for each cell, Python fractions; below 1, round(16 x) at both ends (asserted
// equal); above 1, the k (not 11 or 13) minimising max(|1/lo - c_k|, |1/hi - c_k|), first on ties.
//
// Speed (bench/deterministic_math_bench.cc on a virtual machine with 2 vCPUs of an Intel Xeon,
// family 6 model 207, shared with other work; GCC 12 -O3; glibc 2.36, which uses its FMA code
// there). Ratio glibc time / ours (> 1: faster), fastest of 20 interleaved repetitions, two runs
// of `deterministic_math_bench --benchmark_repetitions=20 --benchmark_min_time=0.05
// --benchmark_enable_random_interleaving=true`:
//   function   throughput   latency        function   throughput   latency
//   atan2      1.77 - 1.80  1.07 - 1.08    sincos     1.31         1.00 - 1.01
//   atan       1.02 - 1.09  1.08 - 1.09    asin       1.51 - 1.52  1.17
//   sin        1.08 - 1.09  1.01           acos       1.66 - 1.71  1.22 - 1.23
//   cos        1.03 - 1.13  1.07           sin for |t| <= 8 pi: 1.51 - 1.62 and 1.30 - 1.31
// Medians instead of minima move by up to 15% either way from run to run on this shared machine;
// sin and cos, which glibc computes with FMA and a table, are the ones that can dip below 1.
