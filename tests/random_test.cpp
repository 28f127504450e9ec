// Tests for plantarch/Random.h: the PCG32 stream against the pcg-cpp reference, and every
// distribution transform against its analytic moments.
//
// The statistical checks draw 200k samples and allow 5 standard errors of the estimator, so
// a wrong transform (off by a factor, a wrong exponent, a biased range reduction) fails while
// a correct one passes with any seed. Seeds are fixed, so the tests are also deterministic.

#include "plantarch/Random.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <numbers>
#include <pcg_random.hpp>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "plantarch/Error.h"

namespace {

using plantarch::Error;
using plantarch::RandomFloat;
using plantarch::RandomInt;
using plantarch::Rng;

constexpr int kSamples = 200000;
constexpr double kSigmas = 5.0;  // allowed deviation, in standard errors
constexpr float kInf = std::numeric_limits<float>::infinity();
constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

// ---- statistics helpers -----------------------------------------------------------------------

// Analytic moments of a distribution: mean, variance and fourth central moment (the last sets
// the standard error of the sample variance).
struct Moments {
    double mean;
    double variance;
    double fourthCentral;
};

Moments uniformMoments(double lo, double hi) {
    const double w = hi - lo;
    return {(lo + hi) / 2.0, w * w / 12.0, w * w * w * w / 80.0};
}

Moments normalMoments(double mean, double stddev) {
    const double v = stddev * stddev;
    return {mean, v, 3.0 * v * v};
}

// Moments of a draw limited to [lo, hi]: `expect(g)` is E[g(X)] of the limited variable.
Moments momentsOf(const std::function<double(const std::function<double(double)>&)>& expect) {
    const double mean = expect([](double x) { return x; });
    const double variance = expect([&](double x) { return (x - mean) * (x - mean); });
    const double fourth = expect([&](double x) { return std::pow(x - mean, 4.0); });
    return {mean, variance, fourth};
}

// Normal(mean, stddev) limited to mean +- 3 stddev: the density inside (midpoint rule) and
// each tail's probability, 0.5 erfc(3 / sqrt 2), at its limit.
Moments limitedNormalMoments(double mean, double stddev) {
    return momentsOf([&](const std::function<double(double)>& g) {
        const int n = 20000;
        const double h = 6.0 / n;
        double sum = 0.0;
        for (int i = 0; i < n; ++i) {
            const double z = -3.0 + (i + 0.5) * h;
            sum += g(mean + stddev * z) * std::exp(-0.5 * z * z) * h;
        }
        sum /= std::sqrt(2.0 * std::numbers::pi);
        const double tail = 0.5 * std::erfc(3.0 / std::sqrt(2.0));
        return sum + tail * (g(mean - 3.0 * stddev) + g(mean + 3.0 * stddev));
    });
}

// Weibull(shape, scale) limited to its 99.9 % quantile: the quantile function integrated
// over u in [0, 0.999] (midpoint rule), and 0.001 at the limit.
Moments limitedWeibullMoments(double shape, double scale) {
    const auto quantile = [&](double u) {
        return scale * std::pow(-std::log(1.0 - u), 1.0 / shape);
    };
    return momentsOf([&](const std::function<double(double)>& g) {
        const int n = 200000;
        const double h = 0.999 / n;
        double sum = 0.0;
        for (int i = 0; i < n; ++i) sum += g(quantile((i + 0.5) * h)) * h;
        return sum + 0.001 * g(quantile(0.999));
    });
}

// A discrete uniform on n consecutive integers starting at lo.
Moments discreteUniformMoments(double lo, double n) {
    const double variance = (n * n - 1.0) / 12.0;
    // Fourth central moment of a discrete uniform: (n^2 - 1)(3 n^2 - 7) / 240.
    return {lo + (n - 1.0) / 2.0, variance, (n * n - 1.0) * (3.0 * n * n - 7.0) / 240.0};
}

// Draws kSamples values and checks sample mean and variance against `expected`.
void expectMoments(const std::function<double()>& draw, const Moments& expected) {
    std::vector<double> values(kSamples);
    for (double& v : values) v = draw();
    double sum = 0.0;
    for (double v : values) sum += v;
    const double mean = sum / kSamples;
    double squares = 0.0;
    for (double v : values) squares += (v - mean) * (v - mean);
    const double variance = squares / (kSamples - 1);

    const double meanError = std::sqrt(expected.variance / kSamples);
    const double varianceError =
        std::sqrt((expected.fourthCentral - expected.variance * expected.variance) / kSamples);
    EXPECT_NEAR(mean, expected.mean, kSigmas * meanError);
    EXPECT_NEAR(variance, expected.variance, kSigmas * varianceError);
}

// Checks an observed count of successes against probability p in `trials` trials.
void expectFrequency(int count, int trials, double p) {
    const double expected = p * trials;
    const double error = std::sqrt(trials * p * (1.0 - p));
    EXPECT_NEAR(count, expected, kSigmas * error) << "p = " << p;
}

// The first `n` outputs of a generator.
std::vector<std::uint32_t> firstOutputs(pcg32& reference, int n) {
    std::vector<std::uint32_t> out(static_cast<std::size_t>(n));
    for (auto& v : out) v = reference();
    return out;
}

std::vector<std::uint32_t> firstOutputs(Rng rng, int n) {
    std::vector<std::uint32_t> out(static_cast<std::size_t>(n));
    for (auto& v : out) v = rng.nextU32();
    return out;
}

int countEqualPositions(const std::vector<std::uint32_t>& a, const std::vector<std::uint32_t>& b) {
    int equal = 0;
    for (std::size_t i = 0; i < a.size(); ++i) equal += a[i] == b[i] ? 1 : 0;
    return equal;
}

// A generator advanced by `draws` 32-bit outputs.
Rng advanced(Rng rng, int draws) {
    for (int i = 0; i < draws; ++i) rng.nextU32();
    return rng;
}

// ---- generator: agreement with the pcg-cpp reference ------------------------------------------

TEST(RngTest, MatchesPcgCppFirst1000Outputs) {
    const std::vector<std::array<std::uint64_t, 2>> cases = {
        {42, 0},
        {0, 0},
        {1, 1},
        {42, 54},
        {0x853c49e6748fea9bULL, 0xda3e39cb94b95bdbULL},
        {~0ULL, ~0ULL},
        {123456789, 1ULL << 62},
    };
    for (const auto& [seed, stream] : cases) {
        SCOPED_TRACE("seed " + std::to_string(seed) + ", stream " + std::to_string(stream));
        pcg32 reference(seed, stream);
        EXPECT_EQ(firstOutputs(Rng(seed, stream), 1000), firstOutputs(reference, 1000));
    }
}

TEST(RngTest, StateAndIncrementMatchPcgCpp) {
    // pcg-cpp writes an engine as "multiplier increment state".
    Rng rng(2024, 7);
    pcg32 reference(2024, 7);
    for (int step = 0; step < 3; ++step) {
        std::ostringstream text;
        text << reference;
        std::istringstream in(text.str());
        std::uint64_t multiplier = 0, increment = 0, state = 0;
        in >> multiplier >> increment >> state;
        EXPECT_EQ(multiplier, 6364136223846793005ULL);
        EXPECT_EQ(rng.increment(), increment);
        EXPECT_EQ(rng.state(), state);
        rng.nextU32();
        reference();
    }
}

TEST(RngTest, GoldenValuesSeed42Stream0) {
    // Taken from pcg-cpp's pcg32(42, 0). If this fails the generator changed, and every
    // stored scene built from a seed would change with it.
    const std::vector<std::uint32_t> golden = {565663470u, 3244226384u, 2504567229u, 903561869u,
                                               4026996297u};
    EXPECT_EQ(firstOutputs(Rng(42, 0), 5), golden);
}

TEST(RngTest, IncrementEncodesStream) {
    EXPECT_EQ(Rng(5, 0).increment(), 1u);
    EXPECT_EQ(Rng(5, 3).increment(), 7u);
    EXPECT_EQ(Rng().increment(), 1u);
    EXPECT_EQ(Rng(), Rng(0x853c49e6748fea9bULL, 0));
}

// ---- generator: determinism and independence --------------------------------------------------

TEST(RngTest, SameSeedGivesSameSequence) {
    EXPECT_EQ(firstOutputs(Rng(99, 3), 1000), firstOutputs(Rng(99, 3), 1000));
    EXPECT_EQ(Rng(99, 3), Rng(99, 3));
}

TEST(RngTest, DifferentStreamsGiveDifferentSequences) {
    std::vector<std::vector<std::uint32_t>> sequences;
    for (std::uint64_t stream = 0; stream < 8; ++stream)
        sequences.push_back(firstOutputs(Rng(7, stream), 1000));
    for (std::size_t i = 0; i < sequences.size(); ++i)
        for (std::size_t j = i + 1; j < sequences.size(); ++j)
            EXPECT_LT(countEqualPositions(sequences[i], sequences[j]), 3) << i << " vs " << j;
}

TEST(RngTest, DifferentSeedsGiveDifferentSequences) {
    for (std::uint64_t seed = 0; seed < 8; ++seed)
        EXPECT_LT(countEqualPositions(firstOutputs(Rng(seed, 0), 1000),
                                      firstOutputs(Rng(seed + 1, 0), 1000)),
                  3)
            << "seed " << seed;
}

TEST(RngTest, ForPlantIsDeterministicAndUsesPlantIndexAsStream) {
    for (std::uint64_t plant = 0; plant < 50; ++plant) {
        EXPECT_EQ(Rng::forPlant(11, plant), Rng::forPlant(11, plant));
        EXPECT_EQ(Rng::forPlant(11, plant).increment(), (plant << 1) | 1u);
    }
}

TEST(RngTest, ForPlantDiffersAcrossPlants) {
    constexpr int kPlants = 256;
    std::set<std::vector<std::uint32_t>> starts;
    std::vector<std::vector<std::uint32_t>> sequences;
    for (std::uint64_t plant = 0; plant < kPlants; ++plant) {
        sequences.push_back(firstOutputs(Rng::forPlant(2024, plant), 200));
        starts.insert(
            std::vector<std::uint32_t>(sequences.back().begin(), sequences.back().begin() + 4));
    }
    EXPECT_EQ(starts.size(), static_cast<std::size_t>(kPlants));
    for (std::size_t i = 0; i + 1 < sequences.size(); ++i)
        EXPECT_LT(countEqualPositions(sequences[i], sequences[i + 1]), 3) << "plant " << i;
}

TEST(RngTest, ForPlantDiffersAcrossScenes) {
    for (std::uint64_t plant = 0; plant < 20; ++plant) {
        EXPECT_LT(countEqualPositions(firstOutputs(Rng::forPlant(1, plant), 1000),
                                      firstOutputs(Rng::forPlant(2, plant), 1000)),
                  3);
    }
}

TEST(RngTest, ForPlantStreamsAreUncorrelated) {
    // Correlation of two independent uniform sequences has standard error 1/sqrt(n).
    const std::vector<std::array<std::uint64_t, 4>> pairs = {
        {5, 0, 5, 1}, {5, 1, 5, 2}, {5, 0, 6, 0}, {0, 0, 0, 1000}};
    for (const auto& [sceneA, plantA, sceneB, plantB] : pairs) {
        Rng a = Rng::forPlant(sceneA, plantA);
        Rng b = Rng::forPlant(sceneB, plantB);
        double sumAB = 0.0, sumA = 0.0, sumB = 0.0;
        for (int i = 0; i < kSamples; ++i) {
            const double x = a.uniform01d(), y = b.uniform01d();
            sumAB += x * y;
            sumA += x;
            sumB += y;
        }
        const double covariance = sumAB / kSamples - (sumA / kSamples) * (sumB / kSamples);
        const double correlation = covariance * 12.0;  // divided by the variance 1/12
        EXPECT_NEAR(correlation, 0.0, kSigmas / std::sqrt(double(kSamples)));
    }
}

TEST(RngTest, FromStateRestoresTheExactSequence) {
    Rng rng = advanced(Rng::forPlant(77, 3), 17);
    const Rng restored = Rng::fromState(rng.state(), rng.increment());
    EXPECT_EQ(restored, rng);
    EXPECT_EQ(firstOutputs(restored, 500), firstOutputs(rng, 500));
    // Mixed draws too, not just raw words.
    Rng x = Rng::fromState(rng.state(), rng.increment());
    for (int i = 0; i < 100; ++i) {
        EXPECT_EQ(x.normal01(), rng.normal01());
        EXPECT_EQ(x.uniformInt(-5, 5), rng.uniformInt(-5, 5));
    }
}

TEST(RngTest, FromStateRejectsEvenIncrement) {
    EXPECT_THROW(Rng::fromState(1, 2), Error);
    try {
        Rng::fromState(1, 2);
    } catch (const Error& e) {
        EXPECT_EQ(e.value(), "2");
        EXPECT_FALSE(e.validRange().empty());
    }
}

// ---- uniform floats ---------------------------------------------------------------------------

TEST(RngTest, Uniform01IsTheTop24Bits) {
    Rng rng(3, 1), twin(3, 1);
    for (int i = 0; i < 10000; ++i) {
        const float u = rng.uniform01();
        EXPECT_EQ(u, static_cast<float>(twin.nextU32() >> 8) / 16777216.0f);
        ASSERT_GE(u, 0.0f);
        ASSERT_LT(u, 1.0f);
    }
    EXPECT_EQ(rng, twin);
}

TEST(RngTest, Uniform01Statistics) {
    Rng rng(8, 0);
    expectMoments([&] { return double(rng.uniform01()); }, uniformMoments(0.0, 1.0));
}

TEST(RngTest, Uniform01dUsesTwoDrawsAnd53Bits) {
    Rng rng(4, 4);
    int finerThan32Bits = 0;
    for (int i = 0; i < 10000; ++i) {
        Rng twin = rng;
        const double u = rng.uniform01d();
        EXPECT_EQ(rng, advanced(twin, 2));
        ASSERT_GE(u, 0.0);
        ASSERT_LT(u, 1.0);
        const double scaled = u * 0x1.0p53;
        EXPECT_EQ(scaled, std::floor(scaled));  // a multiple of 2^-53
        if (u * 0x1.0p32 != std::floor(u * 0x1.0p32)) ++finerThan32Bits;
    }
    // Almost every value uses bits below 2^-32, which a single 32-bit draw cannot give.
    EXPECT_GT(finerThan32Bits, 9900);
}

TEST(RngTest, Uniform01dStatistics) {
    Rng rng(8, 1);
    expectMoments([&] { return rng.uniform01d(); }, uniformMoments(0.0, 1.0));
}

TEST(RngTest, UniformFloatRangeAndStatistics) {
    Rng rng(9, 0);
    expectMoments(
        [&] {
            const float x = rng.uniform(-2.0f, 7.0f);
            EXPECT_GE(x, -2.0f);
            EXPECT_LT(x, 7.0f);
            return double(x);
        },
        uniformMoments(-2.0, 7.0));
}

TEST(RngTest, UniformFloatExcludesUpperBound) {
    // With hi one float step above lo, half the exact results round up to hi.
    Rng rng(10, 0);
    const float lo = 1.0f, hi = std::nextafter(1.0f, 2.0f);
    for (int i = 0; i < 10000; ++i) ASSERT_EQ(rng.uniform(lo, hi), lo);
    // Extreme bounds: hi - lo overflows float but not the double arithmetic.
    const float big = std::numeric_limits<float>::max();
    for (int i = 0; i < 10000; ++i) {
        const float x = rng.uniform(-big, big);
        ASSERT_TRUE(std::isfinite(x));
        ASSERT_LT(x, big);
    }
}

TEST(RngTest, UniformFloatEqualBoundsReturnsLoWithOneDraw) {
    Rng rng(10, 1), twin(10, 1);
    EXPECT_EQ(rng.uniform(2.5f, 2.5f), 2.5f);
    twin.nextU32();
    EXPECT_EQ(rng, twin);
}

// ---- uniform integers -------------------------------------------------------------------------

TEST(RngTest, UniformIntHitsEveryValueEvenly) {
    constexpr int lo = -3, hi = 6, bins = hi - lo + 1;
    Rng rng(11, 0);
    std::array<int, bins> counts{};
    for (int i = 0; i < kSamples; ++i) {
        const int v = rng.uniformInt(lo, hi);
        ASSERT_GE(v, lo);
        ASSERT_LE(v, hi);
        ++counts[static_cast<std::size_t>(v - lo)];
    }
    double chiSquare = 0.0;
    const double expected = double(kSamples) / bins;
    for (int c : counts) {
        EXPECT_GT(c, 0);
        expectFrequency(c, kSamples, 1.0 / bins);
        chiSquare += (c - expected) * (c - expected) / expected;
    }
    // 99.9th percentile of chi-square with 9 degrees of freedom.
    EXPECT_LT(chiSquare, 27.88);
}

TEST(RngTest, UniformIntStatistics) {
    Rng rng(11, 1);
    expectMoments([&] { return double(rng.uniformInt(0, 99)); }, discreteUniformMoments(0, 100));
}

TEST(RngTest, UniformIntIsUnbiasedForAnAwkwardRange) {
    // n = 3 * 2^30 values. Reducing a 32-bit word modulo n would give the first 2^30 values
    // twice the weight of the rest (frequency 1/2 instead of 1/3).
    constexpr std::int32_t lo = std::numeric_limits<std::int32_t>::min();
    constexpr std::int32_t hi = (1 << 30) - 1;  // lo + 3 * 2^30 - 1
    constexpr std::int32_t firstThirdEnd = lo + (1 << 30);
    Rng rng(12, 0);
    int firstThird = 0;
    for (int i = 0; i < kSamples; ++i) {
        const std::int32_t v = rng.uniformInt(lo, hi);
        ASSERT_LE(v, hi);
        if (v < firstThirdEnd) ++firstThird;
    }
    expectFrequency(firstThird, kSamples, 1.0 / 3.0);
}

TEST(RngTest, UniformIntFullRangeIsLoPlusTheRawWord) {
    // Every 32-bit word is a valid offset from lo, so one draw suffices and nothing is rejected.
    constexpr auto lo = std::numeric_limits<std::int32_t>::min();
    constexpr auto hi = std::numeric_limits<std::int32_t>::max();
    Rng rng(13, 0), twin(13, 0);
    int negative = 0;
    for (int i = 0; i < 10000; ++i) {
        const std::int32_t v = rng.uniformInt(lo, hi);
        EXPECT_EQ(v, std::bit_cast<std::int32_t>(twin.nextU32() + 0x80000000u));
        if (v < 0) ++negative;
    }
    expectFrequency(negative, 10000, 0.5);
    EXPECT_EQ(rng, twin);
}

TEST(RngTest, UniformIntNearTheInt32Ends) {
    constexpr auto top = std::numeric_limits<std::int32_t>::max();
    constexpr auto bottom = std::numeric_limits<std::int32_t>::min();
    Rng rng(14, 0);
    std::set<std::int32_t> high, low;
    for (int i = 0; i < 1000; ++i) {
        high.insert(rng.uniformInt(top - 1, top));
        low.insert(rng.uniformInt(bottom, bottom + 1));
    }
    EXPECT_EQ(high, (std::set<std::int32_t>{top - 1, top}));
    EXPECT_EQ(low, (std::set<std::int32_t>{bottom, bottom + 1}));
}

TEST(RngTest, UniformIntSingleValueConsumesOneDraw) {
    Rng rng(15, 0), twin(15, 0);
    for (int i = 0; i < 100; ++i) EXPECT_EQ(rng.uniformInt(-7, -7), -7);
    EXPECT_EQ(rng, advanced(twin, 100));
}

TEST(RngTest, UniformIntSwapsReversedBounds) {
    Rng rng(16, 0), twin(16, 0);
    for (int i = 0; i < 1000; ++i) EXPECT_EQ(rng.uniformInt(6, -3), twin.uniformInt(-3, 6));
}

// ---- normal -----------------------------------------------------------------------------------

TEST(RngTest, Normal01Statistics) {
    Rng rng(17, 0);
    expectMoments([&] { return rng.normal01(); }, normalMoments(0.0, 1.0));
}

TEST(RngTest, Normal01Shape) {
    // Mass within one sigma and beyond three sigma, compared with the normal CDF.
    Rng rng(17, 1);
    int withinOne = 0, beyondThree = 0;
    for (int i = 0; i < kSamples; ++i) {
        const double z = rng.normal01();
        ASSERT_TRUE(std::isfinite(z));
        if (std::abs(z) < 1.0) ++withinOne;
        if (std::abs(z) > 3.0) ++beyondThree;
    }
    expectFrequency(withinOne, kSamples, std::erf(1.0 / std::sqrt(2.0)));
    expectFrequency(beyondThree, kSamples, std::erfc(3.0 / std::sqrt(2.0)));
}

TEST(RngTest, Normal01UsesFourDrawsAndSurvivesAZeroUniform) {
    Rng rng(18, 0), twin(18, 0);
    rng.normal01();
    EXPECT_EQ(rng, advanced(twin, 4));
    // State 0 with increment 1 outputs two zero words, so the first 53-bit uniform is 0:
    // the Box-Muller logarithm must stay finite.
    Rng zero = Rng::fromState(0, 1);
    EXPECT_EQ(Rng::fromState(0, 1).uniform01d(), 0.0);
    const double z = zero.normal01();
    EXPECT_TRUE(std::isfinite(z));
    EXPECT_EQ(z, 0.0);
}

TEST(RngTest, NormalWithMeanAndStddev) {
    Rng rng(19, 0);
    expectMoments([&] { return double(rng.normal(10.0f, 2.5f)); }, normalMoments(10.0, 2.5));
}

// ---- chance -----------------------------------------------------------------------------------

TEST(RngTest, ChanceConsumesExactlyOneDraw) {
    for (float p : {-1.0f, 0.0f, 1e-9f, 0.3f, 0.999999f, 1.0f, 2.0f, kNaN, kInf, -kInf}) {
        Rng rng(20, 0), twin(20, 0);
        for (int i = 0; i < 10; ++i) rng.chance(p);
        EXPECT_EQ(rng, advanced(twin, 10)) << "p = " << p;
    }
}

TEST(RngTest, ChanceAtTheExtremes) {
    Rng rng(21, 0);
    for (int i = 0; i < 100000; ++i) {
        ASSERT_FALSE(rng.chance(0.0f));
        ASSERT_FALSE(rng.chance(-0.5f));
        ASSERT_FALSE(rng.chance(kNaN));
        ASSERT_TRUE(rng.chance(1.0f));
        ASSERT_TRUE(rng.chance(3.0f));
    }
}

TEST(RngTest, ChanceFrequency) {
    for (float p : {0.3f, 0.01f, 0.9f}) {
        Rng rng(22, 0);
        int hits = 0;
        for (int i = 0; i < kSamples; ++i) hits += rng.chance(p) ? 1 : 0;
        expectFrequency(hits, kSamples, p);
    }
}

// ---- RandomFloat ------------------------------------------------------------------------------

TEST(RandomFloatTest, ConstantDoesNotTouchTheStream) {
    Rng rng(30, 0);
    const Rng before = rng;
    const RandomFloat pitch = 20.0f;  // implicit conversion, as in `params.pitch = 20;`
    for (int i = 0; i < 100; ++i) EXPECT_EQ(pitch.sample(rng), 20.0f);
    EXPECT_EQ(RandomFloat::constant(-3.5f).sample(rng), -3.5f);
    EXPECT_EQ(rng, before);
    EXPECT_TRUE(pitch.isConstant());
    EXPECT_EQ(pitch.kind(), RandomFloat::Kind::Constant);
    EXPECT_EQ(pitch.a(), 20.0f);
    EXPECT_EQ(pitch.b(), 0.0f);
}

TEST(RandomFloatTest, UniformStatistics) {
    const RandomFloat p = RandomFloat::uniform(10.0f, 30.0f);
    Rng rng(31, 0);
    expectMoments(
        [&] {
            const float x = p.sample(rng);
            EXPECT_GE(x, 10.0f);
            EXPECT_LE(x, 30.0f);
            return double(x);
        },
        uniformMoments(10.0, 30.0));
}

TEST(RandomFloatTest, UniformWithEqualBoundsReturnsMin) {
    const RandomFloat p = RandomFloat::uniform(4.25f, 4.25f);
    Rng rng(32, 0), twin(32, 0);
    for (int i = 0; i < 100; ++i) EXPECT_EQ(p.sample(rng), 4.25f);
    // Documented: still one draw each, like any uniform.
    EXPECT_EQ(rng, advanced(twin, 100));
}

TEST(RandomFloatTest, NormalStatistics) {
    const RandomFloat p = RandomFloat::normal(-1.5f, 5.0f);
    Rng rng(33, 0);
    expectMoments([&] { return double(p.sample(rng)); }, limitedNormalMoments(-1.5, 5.0));
}

TEST(RandomFloatTest, NormalDrawsStayWithinThreeStddev) {
    // 200k draws: about 270 on each side would fall beyond 3 stddev and take the limit.
    const RandomFloat p = RandomFloat::normal(2.0f, 0.5f);
    EXPECT_EQ(p.lowerBound(), 0.5f);
    EXPECT_EQ(p.upperBound(), 3.5f);
    Rng rng(39, 0);
    int low = 0, high = 0;
    for (int i = 0; i < kSamples; ++i) {
        const float x = p.sample(rng);
        ASSERT_GE(x, 0.5f);
        ASSERT_LE(x, 3.5f);
        low += x == 0.5f ? 1 : 0;
        high += x == 3.5f ? 1 : 0;
    }
    const double tail = 0.5 * std::erfc(3.0 / std::sqrt(2.0));
    expectFrequency(low, kSamples, tail);
    expectFrequency(high, kSamples, tail);
}

TEST(RandomFloatTest, WeibullDrawsStayBelowTheirQuantileLimit) {
    const RandomFloat p = RandomFloat::weibull(0.8f, 3.0f);
    const auto limit = float(3.0 * std::pow(std::log(1000.0), 1.0 / 0.8));
    EXPECT_FLOAT_EQ(p.upperBound(), limit);
    Rng rng(40, 0);
    int atLimit = 0;
    for (int i = 0; i < kSamples; ++i) {
        const float x = p.sample(rng);
        ASSERT_LE(x, p.upperBound());
        atLimit += x == p.upperBound() ? 1 : 0;
    }
    expectFrequency(atLimit, kSamples, 0.001);
}

TEST(RandomFloatTest, LimitsPastFloatRangeAreInfinite) {
    const float big = std::numeric_limits<float>::max();
    EXPECT_EQ(RandomFloat::normal(big, big).upperBound(), kInf);
    EXPECT_EQ(RandomFloat::normal(-big, big).lowerBound(), -kInf);
    EXPECT_EQ(RandomFloat::weibull(0.01f, 1e30f).upperBound(), kInf);
    Rng rng(41, 0);
    for (int i = 0; i < 1000; ++i)
        EXPECT_FALSE(std::isnan(RandomFloat::weibull(0.01f, 1e30f).sample(rng)));
}

TEST(RandomFloatTest, NormalWithZeroStddevReturnsTheMean) {
    const RandomFloat p = RandomFloat::normal(7.0f, 0.0f);
    Rng rng(34, 0);
    for (int i = 0; i < 100; ++i) EXPECT_EQ(p.sample(rng), 7.0f);
    EXPECT_EQ(p.lowerBound(), 7.0f);
    EXPECT_EQ(p.upperBound(), 7.0f);
}

TEST(RandomFloatTest, WeibullStatistics) {
    // Shape below, at and above 1 (heavy tail, exponential, nearly symmetric).
    const std::vector<std::array<float, 2>> cases = {
        {1.5f, 2.0f}, {1.0f, 1.0f}, {0.8f, 3.0f}, {5.0f, 0.5f}};
    for (const auto& [shape, scale] : cases) {
        SCOPED_TRACE("weibull(" + std::to_string(shape) + ", " + std::to_string(scale) + ")");
        const RandomFloat p = RandomFloat::weibull(shape, scale);
        Rng rng(35, 0);
        expectMoments(
            [&] {
                const float x = p.sample(rng);
                EXPECT_GE(x, 0.0f);
                return double(x);
            },
            limitedWeibullMoments(shape, scale));
    }
}

TEST(RandomFloatTest, WeibullMatchesItsCdf) {
    // F(x) = 1 - exp(-(x / scale)^shape), checked at the 10th, 50th and 90th percentiles.
    const float shape = 2.5f, scale = 1.7f;
    const RandomFloat p = RandomFloat::weibull(shape, scale);
    for (double q : {0.1, 0.5, 0.9}) {
        const double x = scale * std::pow(-std::log(1.0 - q), 1.0 / shape);
        Rng rng(36, 0);
        int below = 0;
        for (int i = 0; i < kSamples; ++i) below += p.sample(rng) < x ? 1 : 0;
        expectFrequency(below, kSamples, q);
    }
}

TEST(RandomFloatTest, WeibullOfAZeroUniformIsZero) {
    Rng zero = Rng::fromState(0, 1);
    EXPECT_EQ(RandomFloat::weibull(1.5f, 2.0f).sample(zero), 0.0f);
}

TEST(RandomFloatTest, EveryKindConsumesAFixedNumberOfDraws) {
    // Draws per sample: uniform 1 (24-bit float), normal 4 (two 53-bit uniforms), Weibull 2.
    const std::vector<std::pair<RandomFloat, int>> cases = {{RandomFloat::uniform(0.0f, 1.0f), 1},
                                                            {RandomFloat::normal(0.0f, 1.0f), 4},
                                                            {RandomFloat::weibull(2.0f, 1.0f), 2}};
    for (const auto& [p, draws] : cases) {
        Rng rng(37, 0), twin(37, 0);
        p.sample(rng);
        EXPECT_EQ(rng, advanced(twin, draws)) << p.describe();
    }
}

TEST(RandomFloatTest, MeanMatchesTheAnalyticValue) {
    EXPECT_EQ(RandomFloat(3.0f).mean(), 3.0f);
    EXPECT_EQ(RandomFloat::uniform(10.0f, 30.0f).mean(), 20.0f);
    EXPECT_EQ(RandomFloat::normal(-2.0f, 4.0f).mean(), -2.0f);
    // Weibull mean is scale * Gamma(1 + 1 / shape); Gamma(2) = 1 and Gamma(1.5) = sqrt(pi)/2.
    EXPECT_FLOAT_EQ(RandomFloat::weibull(1.0f, 3.0f).mean(), 3.0f);
    const auto halfRootPi = static_cast<float>(std::sqrt(std::numbers::pi) / 2.0);
    EXPECT_FLOAT_EQ(RandomFloat::weibull(2.0f, 1.0f).mean(), halfRootPi);
    // The midpoint of extreme bounds does not overflow.
    const float big = std::numeric_limits<float>::max();
    EXPECT_EQ(RandomFloat::uniform(big, big).mean(), big);
}

TEST(RandomFloatTest, Bounds) {
    EXPECT_EQ(RandomFloat(2.0f).lowerBound(), 2.0f);
    EXPECT_EQ(RandomFloat(2.0f).upperBound(), 2.0f);
    EXPECT_EQ(RandomFloat::uniform(-1.0f, 4.0f).lowerBound(), -1.0f);
    EXPECT_EQ(RandomFloat::uniform(-1.0f, 4.0f).upperBound(), 4.0f);
    EXPECT_EQ(RandomFloat::normal(0.0f, 1.0f).lowerBound(), -3.0f);
    EXPECT_EQ(RandomFloat::normal(0.0f, 1.0f).upperBound(), 3.0f);
    EXPECT_EQ(RandomFloat::weibull(1.5f, 2.0f).lowerBound(), 0.0f);
    EXPECT_FLOAT_EQ(RandomFloat::weibull(1.5f, 2.0f).upperBound(),
                    float(2.0 * std::pow(std::log(1000.0), 1.0 / 1.5)));
}

TEST(RandomFloatTest, DescribeFormats) {
    EXPECT_EQ(RandomFloat(20.0f).describe(), "20");
    EXPECT_EQ(RandomFloat(0.1f).describe(), "0.1");
    EXPECT_EQ(RandomFloat(-2.5f).describe(), "-2.5");
    EXPECT_EQ(RandomFloat::uniform(10.0f, 30.0f).describe(), "uniform(10, 30)");
    EXPECT_EQ(RandomFloat::normal(0.0f, 5.0f).describe(), "normal(0, 5)");
    EXPECT_EQ(RandomFloat::weibull(1.5f, 2.0f).describe(), "weibull(1.5, 2)");
}

TEST(RandomFloatTest, DescribeReadsBackToTheSameFloat) {
    std::vector<float> values = {0.0f,
                                 -0.0f,
                                 0.1f,
                                 1.0f / 3.0f,
                                 std::numeric_limits<float>::max(),
                                 std::numeric_limits<float>::min(),
                                 std::numeric_limits<float>::denorm_min(),
                                 -123456.789f};
    Rng rng(38, 0);
    while (values.size() < 20000) {
        const float f = std::bit_cast<float>(rng.nextU32());
        if (std::isfinite(f)) values.push_back(f);
    }
    for (float f : values) {
        const std::string text = RandomFloat(f).describe();
        float back = 0.0f;
        const auto result = std::from_chars(text.data(), text.data() + text.size(), back);
        ASSERT_EQ(result.ec, std::errc()) << text;
        ASSERT_EQ(result.ptr, text.data() + text.size()) << text;
        ASSERT_EQ(std::bit_cast<std::uint32_t>(back), std::bit_cast<std::uint32_t>(f)) << text;
    }
}

// Runs `make`, expecting a plantarch::Error with these fields.
void expectError(const std::function<void()>& make, const std::string& message,
                 const std::string& value, const std::string& validRange) {
    try {
        make();
        ADD_FAILURE() << "no error for " << value;
    } catch (const Error& e) {
        EXPECT_EQ(e.message(), message);
        EXPECT_EQ(e.value(), value);
        EXPECT_EQ(e.validRange(), validRange);
        EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos);
    }
}

TEST(RandomFloatTest, FactoriesRejectBadArguments) {
    const std::string notFinite = "arguments must be finite numbers";
    expectError([] { RandomFloat::uniform(5.0f, 1.0f); }, "min must not exceed max",
                "uniform(5, 1)", "min <= max");
    expectError([] { RandomFloat::uniform(kNaN, 1.0f); }, notFinite, "uniform(nan, 1)",
                "finite numbers");
    expectError([] { RandomFloat::uniform(0.0f, kInf); }, notFinite, "uniform(0, inf)",
                "finite numbers");
    expectError([] { RandomFloat::normal(0.0f, -1.0f); }, "stddev must not be negative",
                "normal(0, -1)", "stddev >= 0");
    expectError([] { RandomFloat::normal(-kInf, 1.0f); }, notFinite, "normal(-inf, 1)",
                "finite numbers");
    expectError([] { RandomFloat::normal(0.0f, kNaN); }, notFinite, "normal(0, nan)",
                "finite numbers");
    expectError([] { RandomFloat::weibull(0.0f, 1.0f); }, "shape must be positive", "weibull(0, 1)",
                "shape > 0");
    expectError([] { RandomFloat::weibull(-2.0f, 1.0f); }, "shape must be positive",
                "weibull(-2, 1)", "shape > 0");
    expectError([] { RandomFloat::weibull(1.5f, 0.0f); }, "scale must be positive",
                "weibull(1.5, 0)", "scale > 0");
    expectError([] { RandomFloat::weibull(kNaN, 1.0f); }, notFinite, "weibull(nan, 1)",
                "finite numbers");
    expectError([] { RandomFloat::constant(kNaN); }, "constant must be a finite number", "nan",
                "finite numbers");
    expectError([] { RandomFloat::constant(-kInf); }, "constant must be a finite number", "-inf",
                "finite numbers");
}

TEST(RandomFloatTest, ErrorReadsWellWithAParameterPath) {
    // Readers add the parameter path (and file) to the factory's error.
    try {
        RandomFloat::uniform(5.0f, 1.0f);
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_STREQ(
            e.withParameterPrefix("internode.pitch").what(),
            "internode.pitch = uniform(5, 1): min must not exceed max (valid: min <= max)");
    }
}

TEST(RandomFloatTest, ValidFactoriesKeepTheirParameters) {
    const RandomFloat w = RandomFloat::weibull(1.5f, 2.0f);
    EXPECT_EQ(w.kind(), RandomFloat::Kind::Weibull);
    EXPECT_FALSE(w.isConstant());
    EXPECT_EQ(w.a(), 1.5f);
    EXPECT_EQ(w.b(), 2.0f);
    EXPECT_EQ(w, RandomFloat::weibull(1.5f, 2.0f));
    EXPECT_NE(w, RandomFloat::weibull(1.5f, 2.5f));
    EXPECT_EQ(RandomFloat::uniform(1.0f, 2.0f).kind(), RandomFloat::Kind::Uniform);
    EXPECT_EQ(RandomFloat::normal(1.0f, 2.0f).kind(), RandomFloat::Kind::Normal);
    EXPECT_EQ(RandomFloat::constant(4.0f), RandomFloat(4.0f));
}

TEST(RandomFloatTest, SameSeedSameSamples) {
    const RandomFloat p = RandomFloat::normal(3.0f, 1.0f);
    Rng a = Rng::forPlant(9, 4), b = Rng::forPlant(9, 4);
    for (int i = 0; i < 1000; ++i) ASSERT_EQ(p.sample(a), p.sample(b));
}

// ---- RandomInt --------------------------------------------------------------------------------

TEST(RandomIntTest, ConstantDoesNotTouchTheStream) {
    Rng rng(40, 0);
    const Rng before = rng;
    const RandomInt n = 12;
    for (int i = 0; i < 100; ++i) EXPECT_EQ(n.sample(rng), 12);
    EXPECT_EQ(rng, before);
    EXPECT_TRUE(n.isConstant());
    EXPECT_EQ(n.min(), 12);
    EXPECT_EQ(n.max(), 12);
    EXPECT_EQ(n.mean(), 12.0f);
    EXPECT_EQ(n.describe(), "12");
    EXPECT_EQ(RandomInt::constant(-4).describe(), "-4");
}

TEST(RandomIntTest, UniformHitsEveryValueEvenly) {
    const RandomInt n = RandomInt::uniform(1, 4);
    Rng rng(41, 0);
    std::array<int, 4> counts{};
    for (int i = 0; i < kSamples; ++i) {
        const int v = n.sample(rng);
        ASSERT_GE(v, 1);
        ASSERT_LE(v, 4);
        ++counts[static_cast<std::size_t>(v - 1)];
    }
    double chiSquare = 0.0;
    for (int c : counts) {
        expectFrequency(c, kSamples, 0.25);
        const double expected = kSamples / 4.0;
        chiSquare += (c - expected) * (c - expected) / expected;
    }
    EXPECT_LT(chiSquare, 16.27);  // 99.9th percentile, 3 degrees of freedom
}

TEST(RandomIntTest, UniformStatistics) {
    const RandomInt n = RandomInt::uniform(-10, 10);
    Rng rng(42, 0);
    expectMoments([&] { return double(n.sample(rng)); }, discreteUniformMoments(-10, 21));
}

TEST(RandomIntTest, UniformWithEqualBoundsReturnsMin) {
    const RandomInt n = RandomInt::uniform(5, 5);
    Rng rng(43, 0);
    for (int i = 0; i < 100; ++i) EXPECT_EQ(n.sample(rng), 5);
}

TEST(RandomIntTest, DiscreteDrawsOnlyListedValuesEvenly) {
    const RandomInt n = RandomInt::discrete({2, 5, 11});
    Rng rng(44, 0);
    int twos = 0, fives = 0, elevens = 0;
    for (int i = 0; i < kSamples; ++i) {
        const int v = n.sample(rng);
        if (v == 2)
            ++twos;
        else if (v == 5)
            ++fives;
        else if (v == 11)
            ++elevens;
        else
            FAIL() << "unlisted value " << v;
    }
    for (int c : {twos, fives, elevens}) expectFrequency(c, kSamples, 1.0 / 3.0);
}

TEST(RandomIntTest, DiscreteRepeatedEntriesWeighMore) {
    const RandomInt n = RandomInt::discrete({7, 3, 3, 3});
    Rng rng(45, 0);
    int threes = 0;
    for (int i = 0; i < kSamples; ++i) threes += n.sample(rng) == 3 ? 1 : 0;
    expectFrequency(threes, kSamples, 0.75);
}

TEST(RandomIntTest, DiscreteSingleValue) {
    const RandomInt n = RandomInt::discrete({-9});
    Rng rng(46, 0);
    for (int i = 0; i < 100; ++i) EXPECT_EQ(n.sample(rng), -9);
    EXPECT_EQ(n.kind(), RandomInt::Kind::Discrete);
}

TEST(RandomIntTest, Accessors) {
    const RandomInt u = RandomInt::uniform(-3, 8);
    EXPECT_EQ(u.kind(), RandomInt::Kind::Uniform);
    EXPECT_EQ(u.min(), -3);
    EXPECT_EQ(u.max(), 8);
    EXPECT_EQ(u.mean(), 2.5f);
    EXPECT_EQ(u.describe(), "uniform(-3, 8)");

    const RandomInt d = RandomInt::discrete({5, -2, 11, 5});
    EXPECT_EQ(d.min(), -2);
    EXPECT_EQ(d.max(), 11);
    EXPECT_EQ(d.mean(), 4.75f);
    EXPECT_EQ(d.values(), (std::vector<int>{5, -2, 11, 5}));
    EXPECT_EQ(d.describe(), "discrete(5, -2, 11, 5)");

    constexpr int top = std::numeric_limits<int>::max();
    EXPECT_EQ(RandomInt::uniform(top - 1, top).mean(), float(top - 0.5));
}

TEST(RandomIntTest, FactoriesRejectBadArguments) {
    expectError([] { RandomInt::uniform(5, 1); }, "min must not exceed max", "uniform(5, 1)",
                "min <= max");
    expectError([] { RandomInt::discrete({}); }, "discrete needs at least one value", "discrete()",
                "one or more values");
}

TEST(RandomIntTest, FullRangeUniform) {
    constexpr int lo = std::numeric_limits<int>::min(), hi = std::numeric_limits<int>::max();
    const RandomInt n = RandomInt::uniform(lo, hi);
    Rng rng(47, 0);
    int negative = 0;
    for (int i = 0; i < 10000; ++i) negative += n.sample(rng) < 0 ? 1 : 0;
    expectFrequency(negative, 10000, 0.5);
}

}  // namespace
