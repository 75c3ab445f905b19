// Checks scallop/base/deterministic_math.h: ulp error against glibc's long double functions on
// millions of seeded random inputs and on special points, IEEE special cases, exact symmetries,
// monotonicity of the angle functions, and pinned output bits (golden values).
#include "scallop/base/deterministic_math.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include "scallop/random/rng.h"

namespace scallop {
namespace {

namespace in = deterministic_math_internal;

// Sanitizer builds run the same checks on fewer inputs so the suite stays fast there too.
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_UNDEFINED__)
constexpr int kScale = 16;
#else
constexpr int kScale = 1;
#endif
constexpr int64_t kMillion = 1 << 20;

// The bounds each function is held to: the measured maximum (quoted in the header) plus a margin
// of about 0.1 ulp, so a change that degrades accuracy fails while reseeding does not.
constexpr double kAtan2Bound = 0.95;
constexpr double kAtanBound = 0.95;
constexpr double kSinBound = 0.9;
constexpr double kCosBound = 0.9;
constexpr double kAsinBound = 0.8;
constexpr double kAcosBound = 0.85;

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kMinSubnormal = std::numeric_limits<double>::denorm_min();
constexpr double kMinNormal = std::numeric_limits<double>::min();
constexpr double kMax = std::numeric_limits<double>::max();

uint64_t Bits(double v) { return std::bit_cast<uint64_t>(v); }
bool SameBits(double a, double b) { return Bits(a) == Bits(b); }
std::string Hex(double v) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%a", v);
  return buffer;
}

// |got - exact| in units of the last place of the exact value rounded to double (2^-1074 for
// subnormal results). The long double reference has 11 more bits than a double.
double UlpError(double got, long double exact) {
  if (std::isnan(exact)) return std::isnan(got) ? 0.0 : kInf;
  if (std::isnan(got)) return kInf;
  if (std::isinf(exact) || std::isinf(got)) return got == exact ? 0.0 : kInf;
  int exponent = 0;
  std::frexp(static_cast<double>(exact), &exponent);  // exact = m 2^exponent, m in [0.5, 1)
  const long double ulp = std::ldexp(1.0L, std::max(exponent - 53, -1074));
  return static_cast<double>(std::fabs(static_cast<long double>(got) - exact) / ulp);
}

// The largest error seen and the input that produced it.
struct ErrorStats {
  double max_ulp = 0.0;
  double worst_x = 0.0;
  double worst_y = 0.0;
  int64_t count = 0;
  void Add(double ulp, double x, double y = 0.0) {
    ++count;
    if (ulp > max_ulp || std::isnan(ulp)) {
      max_ulp = std::isnan(ulp) ? kInf : ulp;
      worst_x = x;
      worst_y = y;
    }
  }
  std::string Worst() const { return "at (" + Hex(worst_x) + ", " + Hex(worst_y) + ")"; }
};

using Unary = std::function<double(double)>;
using Binary = std::function<double(double, double)>;

// ----- input generators (fixed seeds; never the clock) -----------------------------------------

// A double with magnitude 2^e, e uniform in [lo, hi), and uniform significand; random sign.
double LogUniform(Rng& rng, int lo, int hi, bool random_sign = true) {
  const int exponent = lo + static_cast<int>(rng.Below(static_cast<uint64_t>(hi - lo)));
  const double v = std::ldexp(1.0 + rng.Uniform(), exponent);
  return random_sign && (rng.NextBits() & 1) ? -v : v;
}

// A double whose bits are uniform over all finite doubles of either sign (so 1/2 of them are
// above 2^0, and subnormals and the largest binades are all reached).
double AnyFinite(Rng& rng) {
  for (;;) {
    const double v = std::bit_cast<double>(rng.NextBits());
    if (std::isfinite(v)) return v;
  }
}

// Steps v by `ulps` units in the last place (toward +inf when positive).
double StepUlps(double v, int ulps) {
  while (ulps > 0) v = std::nextafter(v, kInf), --ulps;
  while (ulps < 0) v = std::nextafter(v, -kInf), ++ulps;
  return v;
}

// ----- harnesses, shared by the real checks and the planted-fault checks ------------------------

ErrorStats MeasureAtan2(const Binary& f, int64_t n, uint64_t seed) {
  Rng rng(seed);
  ErrorStats stats;
  auto check = [&](double y, double x) { stats.Add(UlpError(f(y, x), atan2l(y, x)), y, x); };
  for (int64_t i = 0; i < n; ++i) {
    switch (i % 6) {
      case 0:  // the unit square
        check(rng.Uniform(-1.0, 1.0), rng.Uniform(-1.0, 1.0));
        break;
      case 1: {  // uniform angle, radius 2^-40 .. 2^40
        // Through DetSinCos, so that the inputs are the same on every machine.
        const double angle = rng.Uniform(-std::numbers::pi, std::numbers::pi);
        const double radius = LogUniform(rng, -40, 40, false);
        double sine, cosine;
        DetSinCos(angle, &sine, &cosine);
        check(radius * sine, radius * cosine);
        break;
      }
      case 2:  // any finite pair: huge and tiny ratios, subnormals, the largest doubles
        check(AnyFinite(rng), AnyFinite(rng));
        break;
      case 3: {  // ratio next to a table breakpoint (2k+1)/32 or its reciprocal
        const double x = LogUniform(rng, -20, 20);
        const double ratio = (2.0 * static_cast<double>(rng.Below(16)) + 1.0) / 32.0 *
                             (1.0 + rng.Uniform(-0x1p-20, 0x1p-20));
        const double y = x * ratio * ((rng.NextBits() & 1) ? -1.0 : 1.0);
        if (rng.NextBits() & 1)
          check(y, x);
        else
          check(x, y);
        break;
      }
      case 4: {  // near the diagonals |y| = |x|
        const double x = LogUniform(rng, -20, 20);
        const double y = StepUlps(x, static_cast<int>(rng.Below(65)) - 32);
        check((rng.NextBits() & 1) ? -y : y, x);
        break;
      }
      default: {  // near the axes: ratio 2^-60 .. 2^-1
        const double x = LogUniform(rng, -10, 10);
        const double y = x * LogUniform(rng, -60, -1);
        if (rng.NextBits() & 1)
          check(y, x);
        else
          check(x, y);
        break;
      }
    }
  }
  return stats;
}

ErrorStats MeasureAtan(const Unary& f, int64_t n, uint64_t seed) {
  Rng rng(seed);
  ErrorStats stats;
  auto check = [&](double x) { stats.Add(UlpError(f(x), atanl(x)), x); };
  for (int64_t i = 0; i < n; ++i) {
    switch (i % 4) {
      case 0:
        check(rng.Uniform(-1.0, 1.0));
        break;
      case 1:
        check(LogUniform(rng, -40, 40));
        break;
      case 2:
        check(AnyFinite(rng));
        break;
      default: {  // next to a breakpoint (2k+1)/32, or its reciprocal
        const double b = (2.0 * static_cast<double>(rng.Below(16)) + 1.0) / 32.0;
        const double x = b * (1.0 + rng.Uniform(-0x1p-20, 0x1p-20));
        check((rng.NextBits() & 1) ? x : 1.0 / x);
        break;
      }
    }
  }
  return stats;
}

// Doubles nearest to n pi/2 for random n, stepped a few ulps: where |sin| or |cos| is tiny and
// the reduction has to carry the most bits.
double NearMultipleOfHalfPi(Rng& rng, uint64_t max_n) {
  const long double half_pi = 1.57079632679489661923132169163975144L;
  const auto n = static_cast<long double>(1 + rng.Below(max_n));
  return StepUlps(static_cast<double>(n * half_pi), static_cast<int>(rng.Below(9)) - 4);
}

ErrorStats MeasureTrig(const Unary& f, long double (*exact)(long double), int64_t n,
                       uint64_t seed) {
  Rng rng(seed);
  ErrorStats stats;
  auto check = [&](double t) { stats.Add(UlpError(f(t), exact(t)), t); };
  for (int64_t i = 0; i < n; ++i) {
    switch (i % 5) {
      case 0:
      case 1:
        check(rng.Uniform(-8.0 * std::numbers::pi, 8.0 * std::numbers::pi));
        break;
      case 2:
        check(LogUniform(rng, -30, 20));
        break;
      case 3:  // n pi/2 up to the domain's end, 2^20
        check(NearMultipleOfHalfPi(rng, 667544));
        break;
      default:
        check(NearMultipleOfHalfPi(rng, 16) * ((rng.NextBits() & 1) ? -1.0 : 1.0));
        break;
    }
  }
  return stats;
}

ErrorStats MeasureArc(const Unary& f, long double (*exact)(long double), int64_t n, uint64_t seed) {
  Rng rng(seed);
  ErrorStats stats;
  auto check = [&](double x) { stats.Add(UlpError(f(x), exact(x)), x); };
  for (int64_t i = 0; i < n; ++i) {
    const double sign = (rng.NextBits() & 1) ? -1.0 : 1.0;
    switch (i % 5) {
      case 0:
      case 1:
        check(rng.Uniform(-1.0, 1.0));
        break;
      case 2:  // the branch at 1/2
        check(sign * (0.5 + rng.Uniform(-0x1p-8, 0x1p-8)));
        break;
      case 3:  // toward +-1
        check(sign * (1.0 - LogUniform(rng, -53, -1, false)));
        break;
      default:
        check(LogUniform(rng, -70, -1));
        break;
    }
  }
  return stats;
}

// Where a sequence that should be nondecreasing decreases: how often, and the first place.
struct MonotonicityStats {
  int64_t violations = 0;
  std::string first;
};
void CheckNondecreasing(const std::vector<double>& inputs, const std::vector<double>& outputs,
                        MonotonicityStats* stats) {
  for (size_t i = 1; i < outputs.size(); ++i) {
    if (outputs[i] < outputs[i - 1]) {
      if (stats->violations++ == 0) {
        stats->first = "f(" + Hex(inputs[i - 1]) + ") = " + Hex(outputs[i - 1]) + " > f(" +
                       Hex(inputs[i]) + ") = " + Hex(outputs[i]);
      }
    }
  }
}

// Along lines parallel to an axis the angle is monotone: increasing in y for x > 0, decreasing in
// x for y > 0 (the geometry's sector tests and angle sorting rely on this). Checks random lines,
// both at random offsets and over runs of consecutive doubles across every table breakpoint.
MonotonicityStats MeasureAtan2Monotonicity(const Binary& f, int lines, uint64_t seed) {
  Rng rng(seed);
  MonotonicityStats stats;
  for (int line = 0; line < lines; ++line) {
    const double fixed = LogUniform(rng, -30, 30, false);
    std::vector<double> offsets;
    for (int i = 0; i < 512; ++i) offsets.push_back(fixed * LogUniform(rng, -40, 40));
    for (int k = 0; k < 16; ++k) {  // across breakpoints t = (2k+1)/32 and t = 1, both folds
      const double b = (2.0 * k + 1.0) / 32.0;
      for (double centre : {fixed * b, fixed / b, fixed, -fixed * b, -fixed / b, -fixed}) {
        double v = StepUlps(centre, -24);
        for (int j = 0; j < 48; ++j, v = std::nextafter(v, kInf)) offsets.push_back(v);
      }
    }
    std::sort(offsets.begin(), offsets.end());
    std::vector<double> up(offsets.size()), down(offsets.size()), left(offsets.size()),
        right(offsets.size());
    std::vector<double> reversed(offsets.rbegin(), offsets.rend());
    for (size_t i = 0; i < offsets.size(); ++i) {
      up[i] = f(offsets[i], fixed);      // x > 0: increasing in y
      down[i] = f(reversed[i], -fixed);  // x < 0: rises as y decreases, on each side of the seam
      left[i] = f(fixed, reversed[i]);   // y > 0: decreasing in x
      right[i] = f(-fixed, offsets[i]);  // y < 0: increasing in x
    }
    CheckNondecreasing(offsets, up, &stats);
    // x < 0 has the +-pi seam at y = 0: check each side separately.
    std::vector<double> upper_in, upper_out, lower_in, lower_out;
    for (size_t i = 0; i < reversed.size(); ++i) {
      (reversed[i] >= 0 ? upper_in : lower_in).push_back(reversed[i]);
      (reversed[i] >= 0 ? upper_out : lower_out).push_back(down[i]);
    }
    CheckNondecreasing(upper_in, upper_out, &stats);
    CheckNondecreasing(lower_in, lower_out, &stats);
    CheckNondecreasing(reversed, left, &stats);
    CheckNondecreasing(offsets, right, &stats);
  }
  return stats;
}

// atan along the line: random points, and runs of consecutive doubles across the breakpoints
// (2k+1)/32 and their reciprocals, and across every cell edge of DetAtan's table above 1, where
// the reduction switches.
MonotonicityStats MeasureAtanMonotonicity(const Unary& f, uint64_t seed) {
  Rng rng(seed);
  std::vector<double> inputs;
  for (int i = 0; i < kMillion / 4 / kScale; ++i) inputs.push_back(LogUniform(rng, -30, 30));
  std::vector<double> centres;
  for (int k = 0; k < 16; ++k) {
    const double b = (2.0 * k + 1.0) / 32.0;
    centres.insert(centres.end(), {b, 1.0 / b, -b, -1.0 / b});
  }
  for (int e = 0; e <= 5; ++e) {
    for (int m = 0; m < 16; ++m) centres.push_back(std::ldexp(1.0 + m / 16.0, e));
  }
  for (double centre : centres) {
    double v = StepUlps(centre, -1000);
    for (int j = 0; j < 2000; ++j, v = std::nextafter(v, kInf)) inputs.push_back(v);
  }
  std::sort(inputs.begin(), inputs.end());
  std::vector<double> outputs(inputs.size());
  for (size_t i = 0; i < inputs.size(); ++i) outputs[i] = f(inputs[i]);
  MonotonicityStats stats;
  CheckNondecreasing(inputs, outputs, &stats);
  return stats;
}

// ----- accuracy on random inputs ----------------------------------------------------------------

void Report(const char* name, const ErrorStats& ours, const ErrorStats& glibc) {
  std::printf("%-6s max error %.3f ulp %s over %lld inputs; glibc double: %.3f ulp\n", name,
              ours.max_ulp, ours.Worst().c_str(), static_cast<long long>(ours.count),
              glibc.max_ulp);
}

TEST(DeterministicMath, Atan2AccuracyOnRandomInputs) {
  const int64_t n = 4 * kMillion / kScale;
  const ErrorStats ours = MeasureAtan2(DetAtan2, n, 101);
  Report("atan2", ours, MeasureAtan2([](double y, double x) { return std::atan2(y, x); }, n, 101));
  EXPECT_LE(ours.max_ulp, kAtan2Bound) << ours.Worst();
}

TEST(DeterministicMath, AtanAccuracyOnRandomInputs) {
  const int64_t n = 4 * kMillion / kScale;
  const ErrorStats ours = MeasureAtan(DetAtan, n, 102);
  Report("atan", ours, MeasureAtan([](double x) { return std::atan(x); }, n, 102));
  EXPECT_LE(ours.max_ulp, kAtanBound) << ours.Worst();
}

TEST(DeterministicMath, SinAccuracyOnRandomInputs) {
  const int64_t n = 4 * kMillion / kScale;
  const ErrorStats ours = MeasureTrig(DetSin, sinl, n, 103);
  Report("sin", ours, MeasureTrig([](double t) { return std::sin(t); }, sinl, n, 103));
  EXPECT_LE(ours.max_ulp, kSinBound) << ours.Worst();
}

TEST(DeterministicMath, CosAccuracyOnRandomInputs) {
  const int64_t n = 4 * kMillion / kScale;
  const ErrorStats ours = MeasureTrig(DetCos, cosl, n, 104);
  Report("cos", ours, MeasureTrig([](double t) { return std::cos(t); }, cosl, n, 104));
  EXPECT_LE(ours.max_ulp, kCosBound) << ours.Worst();
}

TEST(DeterministicMath, AsinAccuracyOnRandomInputs) {
  const int64_t n = 4 * kMillion / kScale;
  const ErrorStats ours = MeasureArc(DetAsin, asinl, n, 105);
  Report("asin", ours, MeasureArc([](double x) { return std::asin(x); }, asinl, n, 105));
  EXPECT_LE(ours.max_ulp, kAsinBound) << ours.Worst();
}

TEST(DeterministicMath, AcosAccuracyOnRandomInputs) {
  const int64_t n = 4 * kMillion / kScale;
  const ErrorStats ours = MeasureArc(DetAcos, acosl, n, 106);
  Report("acos", ours, MeasureArc([](double x) { return std::acos(x); }, acosl, n, 106));
  EXPECT_LE(ours.max_ulp, kAcosBound) << ours.Worst();
}

// ----- special points ---------------------------------------------------------------------------

// On these inputs glibc's result is exact or correctly rounded and IEEE/C99 Annex F fixes it,
// so ours must match it bit for bit (including the sign of zero and NaN-ness).
TEST(DeterministicMath, Atan2MatchesAnnexFSpecialCases) {
  const std::vector<double> values = {0.0,   -0.0, kMinSubnormal, -kMinSubnormal, kMinNormal,
                                      1.0,   -1.0, 2.5,           -2.5,           kMax,
                                      -kMax, kInf, -kInf};
  for (double y : values) {
    for (double x : values) {
      const double ours = DetAtan2(y, x);
      const double libm = std::atan2(y, x);
      const bool special = y == 0.0 || x == 0.0 || std::isinf(x) || std::isinf(y);
      if (special) {
        EXPECT_TRUE(SameBits(ours, libm)) << "atan2(" << Hex(y) << ", " << Hex(x)
                                          << ") = " << Hex(ours) << ", libm " << Hex(libm);
      } else {
        EXPECT_LE(UlpError(ours, atan2l(y, x)), kAtan2Bound) << Hex(y) << ", " << Hex(x);
      }
    }
    EXPECT_TRUE(std::isnan(DetAtan2(y, kNaN)));
    EXPECT_TRUE(std::isnan(DetAtan2(kNaN, y)));
  }
  EXPECT_TRUE(std::isnan(DetAtan2(kNaN, kNaN)));
  // The seam: rays along -x give +pi above (y = +0) and -pi below (y = -0).
  EXPECT_EQ(DetAtan2(0.0, -1.0), in::kPi.hi);
  EXPECT_EQ(DetAtan2(-0.0, -1.0), -in::kPi.hi);
  EXPECT_EQ(DetAtan2(1.0, 0.0), in::kHalfPi.hi);
  EXPECT_EQ(DetAtan2(-1.0, -0.0), -in::kHalfPi.hi);
  EXPECT_EQ(DetAtan2(1.0, 1.0), in::kQuarterPi);
  // Quotients that underflow to 0: the exact angle is within 2^-1075 of an axis angle.
  EXPECT_TRUE(SameBits(DetAtan2(1e-300, 1e300), 0.0));
  EXPECT_TRUE(SameBits(DetAtan2(-1e-300, 1e300), -0.0));
  EXPECT_EQ(DetAtan2(1e-300, -1e300), in::kPi.hi);
  EXPECT_EQ(DetAtan2(-1e-300, -1e300), -in::kPi.hi);
  EXPECT_EQ(DetAtan2(1e300, 1e-300), in::kHalfPi.hi);
  EXPECT_EQ(DetAtan2(-1e300, -1e-300), -in::kHalfPi.hi);
  EXPECT_EQ(DetAtan2(1.0, -1.0), in::kThreeQuarterPi);
}

TEST(DeterministicMath, AtanSpecialPoints) {
  EXPECT_TRUE(SameBits(DetAtan(0.0), 0.0));
  EXPECT_TRUE(SameBits(DetAtan(-0.0), -0.0));
  EXPECT_EQ(DetAtan(kInf), in::kHalfPi.hi);
  EXPECT_EQ(DetAtan(-kInf), -in::kHalfPi.hi);
  EXPECT_EQ(DetAtan(1.0), in::kQuarterPi);
  EXPECT_EQ(DetAtan(-1.0), -in::kQuarterPi);
  EXPECT_TRUE(std::isnan(DetAtan(kNaN)));
  for (double x : {kMinSubnormal, 3 * kMinSubnormal, kMinNormal, 0x1p-30, kMax}) {
    EXPECT_TRUE(SameBits(DetAtan(x), std::atan(x))) << Hex(x);  // x itself, or pi/2
    EXPECT_LE(UlpError(DetAtan(x), atanl(x)), kAtanBound) << Hex(x);
  }
}

TEST(DeterministicMath, SinCosSpecialPoints) {
  EXPECT_TRUE(SameBits(DetSin(0.0), 0.0));
  EXPECT_TRUE(SameBits(DetSin(-0.0), -0.0));
  EXPECT_EQ(DetCos(0.0), 1.0);
  EXPECT_EQ(DetCos(-0.0), 1.0);
  for (double t : {kMinSubnormal, -kMinSubnormal, kMinNormal, 0x1p-27, -0x1p-27}) {
    EXPECT_TRUE(SameBits(DetSin(t), t)) << Hex(t);  // sin t = t to within 2^-54 relative
    EXPECT_EQ(DetCos(t), 1.0) << Hex(t);
  }
  // Multiples of pi/4 (as doubles), including the first worst case of the reduction,
  // t = 29 pi/2 rounded, |t - 29 pi/2| = 2^-60.5, and its doublings.
  for (int n = -64; n <= 64; ++n) {
    const double t = static_cast<double>(n * 0.78539816339744830961566084581987572L);
    EXPECT_LE(UlpError(DetSin(t), sinl(t)), kSinBound) << n;
    EXPECT_LE(UlpError(DetCos(t), cosl(t)), kCosBound) << n;
  }
  for (int j = 0; j <= 14; ++j) {
    const double t =
        std::ldexp(static_cast<double>(29 * 1.57079632679489661923132169163975144L), j);
    EXPECT_LE(UlpError(DetSin(t), sinl(t)), kSinBound) << Hex(t);
    EXPECT_LE(UlpError(DetCos(t), cosl(t)), kCosBound) << Hex(t);
  }
  // The edge of the domain, and beyond it: NaN (documented), never a silently wrong value.
  for (double t : {kDetTrigDomain, -kDetTrigDomain, std::nextafter(kDetTrigDomain, 0.0)}) {
    EXPECT_LE(UlpError(DetSin(t), sinl(t)), kSinBound) << Hex(t);
    EXPECT_LE(UlpError(DetCos(t), cosl(t)), kCosBound) << Hex(t);
  }
  for (double t : {std::nextafter(kDetTrigDomain, kInf), -0x1p21, 1e300, kInf, -kInf, kNaN}) {
    EXPECT_TRUE(std::isnan(DetSin(t))) << Hex(t);
    EXPECT_TRUE(std::isnan(DetCos(t))) << Hex(t);
  }
}

TEST(DeterministicMath, AsinAcosSpecialPoints) {
  EXPECT_TRUE(SameBits(DetAsin(0.0), 0.0));
  EXPECT_TRUE(SameBits(DetAsin(-0.0), -0.0));
  EXPECT_EQ(DetAsin(1.0), in::kHalfPi.hi);
  EXPECT_EQ(DetAsin(-1.0), -in::kHalfPi.hi);
  EXPECT_TRUE(SameBits(DetAcos(1.0), 0.0));
  EXPECT_EQ(DetAcos(-1.0), in::kPi.hi);
  EXPECT_EQ(DetAcos(0.0), in::kHalfPi.hi);
  EXPECT_EQ(DetAcos(-0.0), in::kHalfPi.hi);
  for (double x : {kMinSubnormal, -kMinSubnormal, kMinNormal, 0x1p-30}) {
    EXPECT_TRUE(SameBits(DetAsin(x), x)) << Hex(x);  // asin x = x to within 2^-61 relative
  }
  for (double x : {kMinSubnormal, -kMinSubnormal, kMinNormal, 0x1p-60}) {
    EXPECT_EQ(DetAcos(x), in::kHalfPi.hi) << Hex(x);  // pi/2 - x rounds to pi/2
  }
  for (double x : {0.5, -0.5, std::nextafter(0.5, 1.0), std::nextafter(0.5, 0.0),
                   std::nextafter(1.0, 0.0), std::nextafter(-1.0, 0.0)}) {
    EXPECT_LE(UlpError(DetAsin(x), asinl(x)), kAsinBound) << Hex(x);
    EXPECT_LE(UlpError(DetAcos(x), acosl(x)), kAcosBound) << Hex(x);
  }
  for (double x : {std::nextafter(1.0, 2.0), -std::nextafter(1.0, 2.0), 2.0, kInf, -kInf, kNaN}) {
    EXPECT_TRUE(std::isnan(DetAsin(x))) << Hex(x);
    EXPECT_TRUE(std::isnan(DetAcos(x))) << Hex(x);
  }
}

// ----- the build ----------------------------------------------------------------------------

// The bits above hold only if no multiply-add is fused (-ffp-contract=off, set for every target
// in the top-level CMakeLists.txt): GCC and Clang fuse by default wherever the target has FMA, and
// every aarch64 does. a * b = 1 - 2^-60 rounds to 1, so the unfused sum is 0; fused it is -2^-60.
TEST(DeterministicMath, BuildDoesNotFuseMultiplyAdd) {
  volatile double a = 1.0 + 0x1p-30;
  volatile double b = 1.0 - 0x1p-30;
  volatile double c = -1.0;
  const double sum = a * b + c;
  EXPECT_EQ(sum, 0.0) << "built with floating-point contraction: results depend on the CPU";
}

// ----- exact symmetries and consistency ---------------------------------------------------------

TEST(DeterministicMath, SymmetriesAreExact) {
  Rng rng(107);
  for (int i = 0; i < kMillion / kScale; ++i) {
    const double a = LogUniform(rng, -30, 20, false);
    const double b = LogUniform(rng, -30, 20, false);
    ASSERT_TRUE(SameBits(DetAtan2(-a, b), -DetAtan2(a, b))) << Hex(a) << " " << Hex(b);
    ASSERT_TRUE(SameBits(DetAtan2(-a, -b), -DetAtan2(a, -b))) << Hex(a) << " " << Hex(b);
    // Points on one ray through the origin, a power of two apart, have one angle.
    ASSERT_TRUE(SameBits(DetAtan2(0x1p40 * a, 0x1p40 * b), DetAtan2(a, b)));
    ASSERT_TRUE(SameBits(DetAtan2(0x1p-40 * a, 0x1p-40 * b), DetAtan2(a, b)));
    ASSERT_TRUE(SameBits(DetAtan(-a), -DetAtan(a))) << Hex(a);
    ASSERT_TRUE(SameBits(DetSin(-a), -DetSin(a))) << Hex(a);
    ASSERT_TRUE(SameBits(DetCos(-a), DetCos(a))) << Hex(a);
    double s, c;
    DetSinCos(a, &s, &c);
    ASSERT_TRUE(SameBits(s, DetSin(a)) && SameBits(c, DetCos(a))) << Hex(a);
    const double x = rng.Uniform(-1.0, 1.0);
    ASSERT_TRUE(SameBits(DetAsin(-x), -DetAsin(x))) << Hex(x);
    // Pythagoras to a few ulps of 1 (each term is within 1 ulp of exact).
    ASSERT_NEAR(s * s + c * c, 1.0, 0x1p-50) << Hex(a);
  }
}

// ----- monotonicity -----------------------------------------------------------------------------

TEST(DeterministicMath, Atan2IsMonotoneAlongAxisParallelLines) {
  const MonotonicityStats stats = MeasureAtan2Monotonicity(DetAtan2, 400 / kScale, 108);
  EXPECT_EQ(stats.violations, 0) << stats.first;
}

TEST(DeterministicMath, AtanIsMonotone) {
  const MonotonicityStats stats = MeasureAtanMonotonicity(DetAtan, 109);
  EXPECT_EQ(stats.violations, 0) << stats.first;
}

TEST(DeterministicMath, AsinAcosAreMonotone) {
  Rng rng(110);
  std::vector<double> inputs;
  for (int i = 0; i < kMillion / 4 / kScale; ++i) inputs.push_back(rng.Uniform(-1.0, 1.0));
  for (double centre : {-1.0, -0.5, 0.0, 0.5, 1.0}) {
    double v = StepUlps(centre, -2000);
    for (int j = 0; j < 4000; ++j, v = std::nextafter(v, kInf)) {
      if (std::abs(v) <= 1.0) inputs.push_back(v);
    }
  }
  std::sort(inputs.begin(), inputs.end());
  std::vector<double> asin_out(inputs.size()), minus_acos_out(inputs.size());
  for (size_t i = 0; i < inputs.size(); ++i) {
    asin_out[i] = DetAsin(inputs[i]);
    minus_acos_out[i] = -DetAcos(inputs[i]);
  }
  MonotonicityStats stats;
  CheckNondecreasing(inputs, asin_out, &stats);
  CheckNondecreasing(inputs, minus_acos_out, &stats);
  EXPECT_EQ(stats.violations, 0) << stats.first;
}

// ----- the constants ----------------------------------------------------------------------------

// A typo in a table entry would cost accuracy only near its breakpoint; check every entry
// against long double (hi + lo carries ~106 bits, long double 64, so they agree to ~2^-63).
TEST(DeterministicMath, TablesMatchLongDouble) {
  const long double half_pi = 1.57079632679489661923132169163975144L;
  const long double pi = 2 * half_pi;
  for (int k = 0; k <= 16; ++k) {
    const long double c = in::kAtanBreak[k];
    EXPECT_EQ(c, k == 1 ? 0.0L : k / 16.0L);
    const long double a = atanl(c);
    const long double expected[4] = {a, half_pi - a, pi - a, half_pi + a};
    for (int o = 0; o < 4; ++o) {
      const in::DoubleDouble v = in::kAtanBase[o][k];
      EXPECT_EQ(v.hi, static_cast<double>(expected[o])) << o << " " << k;
      EXPECT_LE(std::fabs((static_cast<long double>(v.hi) + v.lo) - expected[o]), 0x1p-62L)
          << o << " " << k;
    }
  }
  const long double pieces = static_cast<long double>(in::kHalfPiPiece1) + in::kHalfPiPiece2 +
                             in::kHalfPiPiece3 + in::kHalfPiPiece4;
  EXPECT_LE(std::fabs(pieces - half_pi), 0x1p-63L);
  EXPECT_EQ(in::kHalfPi.hi, static_cast<double>(half_pi));
  EXPECT_EQ(in::kPi.hi, static_cast<double>(pi));
  EXPECT_EQ(in::kTwoOverPi, static_cast<double>(1 / half_pi));
  EXPECT_EQ(in::kPi.lo, 2 * in::kHalfPi.lo);
  // The pieces must be short enough that n * piece is exact for every n below 2^21.
  for (double piece : {in::kHalfPiPiece1, in::kHalfPiPiece2, in::kHalfPiPiece3}) {
    int exponent = 0;
    const double m = std::frexp(piece, &exponent);
    EXPECT_EQ(std::ldexp(m, 32), std::trunc(std::ldexp(m, 32))) << Hex(piece);
  }
}

// DetAtan reads its breakpoint from the top bits of |x|; on every cell (checked at both ends,
// r is monotone in between) the reduced argument must stay in the polynomial's domain
// |r| <= 3/32, x - c must be exact (Sterbenz: c/2 <= x <= 2c) below 1, and 1 - hi x exact above.
TEST(DeterministicMath, AtanCellTableKeepsTheReductionExactAndSmall) {
  for (int e = -5; e <= 4; ++e) {
    for (int m = 0; m < 16; ++m) {
      const int k = in::kAtanCellBreak[(e + 5) * 16 + m];
      const double c = in::kAtanBreak[k];
      const in::DoubleDouble split = in::kAtanBreakSplit[k];
      EXPECT_EQ(split.hi + split.lo, k == 11 || k == 13 ? 0.0 : c) << k;
      const double lo = std::ldexp(1.0 + m / 16.0, e);
      const double hi = std::ldexp(1.0 + (m + 1) / 16.0, e);
      for (double x : {lo, std::nextafter(hi, 0.0)}) {
        const double u = x > 1.0 ? 1.0 / x : x;
        EXPECT_LE(std::abs((u - c) / (1.0 + u * c)), 3.0 / 32.0) << Hex(x);
        if (x <= 1.0 && c != 0.0) {
          EXPECT_TRUE(x >= c / 2 && x <= 2 * c) << Hex(x);
        }
        if (x > 1.0) {
          EXPECT_NE(k, 11);
          EXPECT_NE(k, 13);
          if (c != 0.0) {
            EXPECT_TRUE(split.hi * x >= 0.5 && split.hi * x <= 2.0) << Hex(x);
          }
        }
      }
    }
  }
}

// ----- golden values ----------------------------------------------------------------------------

// Output bits pinned so that any change to the algorithms or constants is noticed: a world's
// points depend on these bits, so changing them must be deliberate (bump the generator version).
// Each value was checked against mpmath at 200 bits: all are within 0.51 ulp of the exact result.
TEST(DeterministicMath, GoldenValues) {
  struct Golden {
    const char* name;
    double got;
    uint64_t bits;
  };
  const Golden goldens[] = {
      {"atan2(1, 2)", DetAtan2(1.0, 2.0), 0x3fddac670561bb4full},
      {"atan2(-0.3, -0.7)", DetAtan2(-0.3, -0.7), 0xc005e4c36ca0118aull},
      {"atan2(5e-324, 3)", DetAtan2(kMinSubnormal, 3.0), 0x0000000000000000ull},
      {"atan2(7, 1e-3)", DetAtan2(7.0, 1e-3), 0x3ff9216588582346ull},
      {"atan(0.1)", DetAtan(0.1), 0x3fb983e282e2cc4dull},
      {"atan(-3.5)", DetAtan(-3.5), 0xbff4ae10fc6589a5ull},
      {"sin(1)", DetSin(1.0), 0x3feaed548f090ceeull},
      {"sin(29 pi/2)", DetSin(0x1.6c6cbc45dc8dep+5), 0x3ff0000000000000ull},
      {"cos(29 pi/2)", DetCos(0x1.6c6cbc45dc8dep+5), 0xbc26d61b58c99c43ull},
      {"sin(-100)", DetSin(-100.0), 0x3fe03425b78c4db8ull},
      {"cos(2.5)", DetCos(2.5), 0xbfe9a2f7ef858b7dull},
      {"cos(12345.678)", DetCos(12345.678), 0x3fe6b94c3bbe24b8ull},
      {"asin(0.3)", DetAsin(0.3), 0x3fd380159e14f6feull},
      {"asin(-0.9)", DetAsin(-0.9), 0xbff1ea93705fa172ull},
      {"acos(0.7)", DetAcos(0.7), 0x3fe973e83f5d5c9bull},
      {"acos(-0.99)", DetAcos(-0.99), 0x4008001be1bc011bull},
  };
  for (const Golden& g : goldens) {
    EXPECT_EQ(Bits(g.got), g.bits)
        << g.name << " = " << Hex(g.got) << " bits 0x" << std::hex << Bits(g.got);
  }
}

// ----- the checks catch planted faults ----------------------------------------------------------

double UlpsAway(double v, int ulps) { return StepUlps(v, ulps); }

TEST(DeterministicMath, ChecksCatchPlantedFaults) {
  const int64_t n = kMillion / 16;
  // Two ulps too high everywhere: every accuracy harness must see it.
  EXPECT_GT(
      MeasureAtan2([](double y, double x) { return UlpsAway(DetAtan2(y, x), 2); }, n, 1).max_ulp,
      kAtan2Bound);
  EXPECT_GT(MeasureAtan([](double x) { return UlpsAway(DetAtan(x), 2); }, n, 1).max_ulp,
            kAtanBound);
  EXPECT_GT(MeasureTrig([](double t) { return UlpsAway(DetSin(t), 2); }, sinl, n, 1).max_ulp,
            kSinBound);
  EXPECT_GT(MeasureArc([](double x) { return UlpsAway(DetAcos(x), 2); }, acosl, n, 1).max_ulp,
            kAcosBound);
  // A reduction with a 2-piece pi/2 loses the bits near multiples of pi/2: the near-multiple
  // inputs must expose it.
  const auto short_reduction = [](double t) {
    const double fn = std::nearbyint(t * in::kTwoOverPi);
    const double r = (t - fn * in::kHalfPiPiece1) - fn * in::kHalfPiPiece2;
    return in::SinOrCosOfReduced({r, 0.0}, static_cast<uint64_t>(static_cast<int64_t>(fn)) & 3u);
  };
  EXPECT_GT(MeasureTrig(short_reduction, sinl, n, 1).max_ulp, kSinBound);
  // Rounding r to the table breakpoint's neighbour by one ulp just above each breakpoint breaks
  // monotonicity there: the monotonicity harnesses must see it.
  const auto kinked = [](double x) {
    const double t = std::abs(x) > 1 ? 1 / std::abs(x) : std::abs(x);
    const double frac = t * 16.0 - std::floor(t * 16.0);
    return frac > 0.5 && frac < 0.5 + 0x1p-30 ? UlpsAway(DetAtan(x), x > 0 ? -3 : 3) : DetAtan(x);
  };
  EXPECT_GT(MeasureAtanMonotonicity(kinked, 1).violations, 0);
  const auto kinked2 = [](double y, double x) {
    const double t = std::min(std::abs(x), std::abs(y)) / std::max(std::abs(x), std::abs(y));
    const double frac = t * 16.0 - std::floor(t * 16.0);
    return frac > 0.5 && frac < 0.5 + 0x1p-30 ? UlpsAway(DetAtan2(y, x), -3) : DetAtan2(y, x);
  };
  EXPECT_GT(MeasureAtan2Monotonicity(kinked2, 4, 1).violations, 0);
  // A golden value catches a one-ulp change.
  EXPECT_NE(Bits(UlpsAway(DetSin(1.0), 1)), 0x3feaed548f090ceeull);
}

}  // namespace
}  // namespace scallop
