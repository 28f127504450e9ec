// PCG32 streams and the in-house distribution transforms behind RandomFloat and RandomInt.
//
// Everything here is written out by hand so that a (seed, stream) pair gives the same numbers
// with any compiler and standard library; only std::log, std::sqrt, std::cos and std::pow
// come from the C library.

#include "plantarch/Random.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <limits>
#include <numbers>

#include "plantarch/Error.h"

namespace plantarch {

namespace {

// The limits of a normal draw (in standard deviations) and of a Weibull draw (a quantile).
constexpr double kNormalLimit = 3.0;
constexpr double kWeibullLimit = 0.999;

// A double as a float, infinite past float's range (a plain cast there is undefined).
float toFloat(double v) {
    constexpr double kMax = std::numeric_limits<float>::max();
    if (v > kMax) return std::numeric_limits<float>::infinity();
    if (v < -kMax) return -std::numeric_limits<float>::infinity();
    return static_cast<float>(v);
}

// ---- generator constants --------------------------------------------------------------------

// The 64-bit LCG multiplier used by PCG (Knuth's MMIX multiplier).
constexpr std::uint64_t kPcgMultiplier = 6364136223846793005ULL;

// splitmix64's increment: 2^64 divided by the golden ratio, rounded to odd.
constexpr std::uint64_t kGoldenGamma = 0x9e3779b97f4a7c15ULL;

// Finalizer of splitmix64 (Steele, Lea and Flood, 2014): a bijection on 64-bit words whose
// every output bit depends on every input bit.
std::uint64_t splitmix64Mix(std::uint64_t z) {
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
}

std::uint32_t rotateRight(std::uint32_t value, unsigned amount) {
    return (value >> amount) | (value << ((32u - amount) & 31u));
}

// ---- text helpers ---------------------------------------------------------------------------

// Shortest text that reads back to exactly the same float ("0.1", "20", "1e+30", "nan").
std::string formatFloat(float value) {
    char buffer[32];
    auto result = std::to_chars(buffer, buffer + sizeof(buffer), value);
    return std::string(buffer, result.ptr);
}

std::string call(const char* name, float a, float b) {
    return std::string(name) + "(" + formatFloat(a) + ", " + formatFloat(b) + ")";
}

std::string call(const char* name, int a, int b) {
    return std::string(name) + "(" + std::to_string(a) + ", " + std::to_string(b) + ")";
}

[[noreturn]] void reject(const std::string& message, std::string value, std::string validRange) {
    ErrorContext context;
    context.value = std::move(value);
    context.validRange = std::move(validRange);
    throw Error(message, std::move(context));
}

void requireFinite(const std::string& described, float a, float b) {
    if (!std::isfinite(a) || !std::isfinite(b))
        reject("arguments must be finite numbers", described, "finite numbers");
}

}  // namespace

// ---- Rng ------------------------------------------------------------------------------------

Rng::Rng(std::uint64_t seed, std::uint64_t stream) {
    // The reference PCG seeding: an odd increment selects the stream, then the seed is added
    // between two steps so that nearby seeds start far apart.
    inc_ = (stream << 1u) | 1u;
    state_ = 0;
    nextU32();
    state_ += seed;
    nextU32();
}

Rng Rng::forPlant(std::uint64_t sceneSeed, std::uint64_t plantIndex) {
    // Seed: output number `plantIndex` of a splitmix64 generator started at mix(sceneSeed).
    // Within one scene the pre-mix inputs differ by odd multiples of kGoldenGamma, so no two
    // plants share a seed, and mixing the scene seed first keeps plant i of scene s from
    // reusing the seed of plant j of a neighbouring scene s'. Stream: the plant index, so
    // plants of one scene also differ in increment (indices are taken modulo 2^63, far more
    // plants than any scene holds).
    const std::uint64_t seed =
        splitmix64Mix(splitmix64Mix(sceneSeed) + (plantIndex + 1) * kGoldenGamma);
    return Rng(seed, plantIndex);
}

Rng Rng::fromState(std::uint64_t state, std::uint64_t increment) {
    if ((increment & 1u) == 0)
        reject("PCG increment must be odd", std::to_string(increment), "odd numbers");
    Rng rng;
    rng.state_ = state;
    rng.inc_ = increment;
    return rng;
}

std::uint32_t Rng::nextU32() {
    // XSH-RR output of the state *before* the step, as pcg32 does: xorshift the high bits
    // down, keep bits 27..58, rotate by the top 5 bits.
    const std::uint64_t old = state_;
    state_ = old * kPcgMultiplier + inc_;
    const auto xorShifted = static_cast<std::uint32_t>(((old >> 18u) ^ old) >> 27u);
    const auto rotation = static_cast<unsigned>(old >> 59u);
    return rotateRight(xorShifted, rotation);
}

float Rng::uniform01() {
    // A float has a 24-bit significand, so 24 bits fill every representable step of
    // k * 2^-24 exactly; the result is never 1.
    return static_cast<float>(nextU32() >> 8u) * 0x1.0p-24f;
}

double Rng::uniform01d() {
    // 27 high bits from the first draw and 26 from the second make one 53-bit integer.
    const std::uint64_t high = nextU32() >> 5u;
    const std::uint64_t low = nextU32() >> 6u;
    return static_cast<double>((high << 26u) | low) * 0x1.0p-53;
}

float Rng::uniform(float lo, float hi) {
    // Computed in double so hi - lo cannot overflow a float; rounding back to float can land
    // on hi itself, which the half-open interval excludes.
    const double u = static_cast<double>(uniform01());
    const auto value =
        static_cast<float>(static_cast<double>(lo) + (static_cast<double>(hi) - lo) * u);
    if (hi > lo && value >= hi) return std::nextafter(hi, lo);
    return value;
}

std::int32_t Rng::uniformInt(std::int32_t lo, std::int32_t hi) {
    if (lo > hi) std::swap(lo, hi);
    // Width minus one, computed in unsigned arithmetic so the full int32 range fits.
    const std::uint32_t span = static_cast<std::uint32_t>(hi) - static_cast<std::uint32_t>(lo);
    std::uint32_t offset;
    if (span == std::numeric_limits<std::uint32_t>::max()) {
        offset = nextU32();  // every 32-bit word is a valid answer
    } else {
        // Lemire's multiply-shift: the high word of x * n is uniform on [0, n) once the draws
        // whose low word falls below 2^32 mod n are rejected (Lemire 2019, "Fast random
        // integer generation in an interval").
        const std::uint32_t n = span + 1u;
        std::uint64_t product = static_cast<std::uint64_t>(nextU32()) * n;
        auto low = static_cast<std::uint32_t>(product);
        if (low < n) {
            const std::uint32_t threshold = (0u - n) % n;  // 2^32 mod n
            while (low < threshold) {
                product = static_cast<std::uint64_t>(nextU32()) * n;
                low = static_cast<std::uint32_t>(product);
            }
        }
        offset = static_cast<std::uint32_t>(product >> 32u);
    }
    // Modular conversion back to int32 is well defined since C++20.
    return static_cast<std::int32_t>(static_cast<std::uint32_t>(lo) + offset);
}

double Rng::normal01() {
    // Box-Muller, cosine branch only so each call is self-contained (no cached second
    // value that would make copies of an Rng diverge). 1 - u lies in (0, 1], so the
    // logarithm is finite.
    const double u1 = uniform01d();
    const double u2 = uniform01d();
    const double radius = std::sqrt(-2.0 * std::log(1.0 - u1));
    return radius * std::cos(2.0 * std::numbers::pi * u2);
}

float Rng::normal(float mean, float stddev) {
    return toFloat(static_cast<double>(mean) + static_cast<double>(stddev) * normal01());
}

bool Rng::chance(float p) {
    // The draw is taken before looking at p so that a trial with p = 0 or p = 1 leaves the
    // stream exactly where a trial with p = 0.5 would: changing one probability in a species
    // file must not shift every later random value of the plant.
    const float u = uniform01();
    if (!(p > 0.0f)) return false;  // also catches NaN
    if (p >= 1.0f) return true;
    return u < p;
}

// ---- RandomFloat ----------------------------------------------------------------------------

RandomFloat RandomFloat::constant(float value) {
    if (!std::isfinite(value))
        reject("constant must be a finite number", formatFloat(value), "finite numbers");
    return RandomFloat(value);
}

RandomFloat RandomFloat::uniform(float min, float max) {
    const std::string described = call("uniform", min, max);
    requireFinite(described, min, max);
    if (min > max) reject("min must not exceed max", described, "min <= max");
    return RandomFloat(Kind::Uniform, min, max);
}

RandomFloat RandomFloat::normal(float mean, float stddev) {
    const std::string described = call("normal", mean, stddev);
    requireFinite(described, mean, stddev);
    if (stddev < 0.0f) reject("stddev must not be negative", described, "stddev >= 0");
    return RandomFloat(Kind::Normal, mean, stddev);
}

RandomFloat RandomFloat::weibull(float shape, float scale) {
    const std::string described = call("weibull", shape, scale);
    requireFinite(described, shape, scale);
    if (!(shape > 0.0f)) reject("shape must be positive", described, "shape > 0");
    if (!(scale > 0.0f)) reject("scale must be positive", described, "scale > 0");
    return RandomFloat(Kind::Weibull, shape, scale);
}

float RandomFloat::sample(Rng& rng) const {
    switch (kind_) {
        case Kind::Constant:
            return a_;
        case Kind::Uniform:
            // Rng::uniform returns a_ exactly when a_ == b_, still consuming its one draw.
            return rng.uniform(a_, b_);
        case Kind::Normal:
            // Limited to mean +- 3 stddev (the bounds species validation checks against the
            // field's range), so a rare far tail cannot realize an impossible size.
            return std::clamp(rng.normal(a_, b_), lowerBound(), upperBound());
        case Kind::Weibull: {
            // Inversion of F(x) = 1 - exp(-(x / scale)^shape); 1 - u lies in (0, 1]. Limited
            // above to the 99.9 % quantile, the bound species validation checks.
            const double u = rng.uniform01d();
            const double e = -std::log(1.0 - u);
            const float x = toFloat(static_cast<double>(b_) * std::pow(e, 1.0 / a_));
            return std::min(x, upperBound());
        }
    }
    return a_;
}

float RandomFloat::mean() const {
    switch (kind_) {
        case Kind::Constant:
        case Kind::Normal:
            return a_;
        case Kind::Uniform:
            return static_cast<float>((static_cast<double>(a_) + b_) / 2.0);
        case Kind::Weibull:
            return toFloat(double(b_) * std::tgamma(1.0 + 1.0 / double(a_)));
    }
    return a_;
}

float RandomFloat::lowerBound() const {
    switch (kind_) {
        case Kind::Constant:
        case Kind::Uniform:
            return a_;
        case Kind::Normal:
            return toFloat(double(a_) - kNormalLimit * double(b_));
        case Kind::Weibull:
            return 0.0f;
    }
    return a_;
}

float RandomFloat::upperBound() const {
    switch (kind_) {
        case Kind::Constant:
            return a_;
        case Kind::Uniform:
            return b_;
        case Kind::Normal:
            return toFloat(double(a_) + kNormalLimit * double(b_));
        case Kind::Weibull:
            // The 99.9 % quantile, scale * (-ln 0.001)^(1 / shape) (infinite past float range).
            return toFloat(double(b_) * std::pow(-std::log(1.0 - kWeibullLimit), 1.0 / double(a_)));
    }
    return a_;
}

std::string RandomFloat::describe() const {
    switch (kind_) {
        case Kind::Constant:
            return formatFloat(a_);
        case Kind::Uniform:
            return call("uniform", a_, b_);
        case Kind::Normal:
            return call("normal", a_, b_);
        case Kind::Weibull:
            return call("weibull", a_, b_);
    }
    return formatFloat(a_);
}

// ---- RandomInt ------------------------------------------------------------------------------

RandomInt RandomInt::uniform(int min, int max) {
    if (min > max) reject("min must not exceed max", call("uniform", min, max), "min <= max");
    RandomInt result(min);
    result.kind_ = Kind::Uniform;
    result.hi_ = max;
    return result;
}

RandomInt RandomInt::discrete(std::vector<int> values) {
    if (values.empty())
        reject("discrete needs at least one value", "discrete()", "one or more values");
    // Indices are drawn with uniformInt, which covers int32.
    if (values.size() > static_cast<std::size_t>(std::numeric_limits<std::int32_t>::max()))
        reject("discrete has too many values", std::to_string(values.size()) + " values",
               "at most 2147483647 values");
    const auto [lowest, highest] = std::minmax_element(values.begin(), values.end());
    RandomInt result(*lowest);
    result.kind_ = Kind::Discrete;
    result.hi_ = *highest;
    result.values_ = std::move(values);
    return result;
}

int RandomInt::min() const {
    return lo_;
}

int RandomInt::max() const {
    return hi_;
}

int RandomInt::sample(Rng& rng) const {
    switch (kind_) {
        case Kind::Constant:
            return lo_;
        case Kind::Uniform:
            return rng.uniformInt(lo_, hi_);
        case Kind::Discrete: {
            const auto last = static_cast<std::int32_t>(values_.size() - 1);
            return values_[static_cast<std::size_t>(rng.uniformInt(0, last))];
        }
    }
    return lo_;
}

float RandomInt::mean() const {
    switch (kind_) {
        case Kind::Constant:
            return static_cast<float>(lo_);
        case Kind::Uniform:
            return static_cast<float>((static_cast<double>(lo_) + hi_) / 2.0);
        case Kind::Discrete: {
            double sum = 0.0;
            for (int v : values_) sum += v;
            return static_cast<float>(sum / static_cast<double>(values_.size()));
        }
    }
    return static_cast<float>(lo_);
}

std::string RandomInt::describe() const {
    switch (kind_) {
        case Kind::Constant:
            return std::to_string(lo_);
        case Kind::Uniform:
            return call("uniform", lo_, hi_);
        case Kind::Discrete: {
            std::string out = "discrete(";
            for (std::size_t i = 0; i < values_.size(); ++i) {
                if (i > 0) out += ", ";
                out += std::to_string(values_[i]);
            }
            return out + ")";
        }
    }
    return std::to_string(lo_);
}

}  // namespace plantarch
