#pragma once
// Deterministic random numbers: a PCG stream per plant and immutable random parameters.
//
// The same (seed, stream) gives the same sequence with any compiler and standard library:
// the generator is PCG32 and every distribution transform is written here, not taken from
// <random> (whose distributions differ between implementations).

#include <cstdint>
#include <string>
#include <vector>

namespace plantarch {

/// A PCG32 random stream (64-bit state, 32-bit output, selectable stream).
class Rng {
public:
    /// Stream `stream` of the generator seeded with `seed`.
    explicit Rng(std::uint64_t seed = 0x853c49e6748fea9bULL, std::uint64_t stream = 0);

    /// The stream a plant owns: derived from the scene seed and the plant's index, so plants
    /// built in any order or on any thread draw the same numbers. The seed is a splitmix64
    /// mix of both numbers and the stream is the plant index, so every plant of a scene has
    /// its own seed and its own stream.
    static Rng forPlant(std::uint64_t sceneSeed, std::uint64_t plantIndex);

    std::uint32_t nextU32();
    /// Uniform in [0, 1) with 24 random bits.
    float uniform01();
    /// Uniform in [0, 1) with 53 random bits.
    double uniform01d();
    /// Uniform float in [lo, hi) (exactly lo when lo == hi). One draw.
    float uniform(float lo, float hi);
    /// Uniform integer in [lo, hi] (inclusive), unbiased, for any range up to the full int32
    /// range. Bounds given in the wrong order are swapped. At least one draw.
    std::int32_t uniformInt(std::int32_t lo, std::int32_t hi);
    /// Standard normal deviate (Box-Muller on 53-bit uniforms; one value per call).
    double normal01();
    /// Normal deviate with the given mean and standard deviation.
    float normal(float mean, float stddev);
    /// Bernoulli trial: true with probability p. p <= 0 (or NaN) is never true, p >= 1 always
    /// is; every call consumes exactly one draw so later draws do not depend on p.
    bool chance(float p);

    /// Generator state as two words (state, increment), for saving and exact restore.
    /// fromState throws plantarch::Error for an even increment (no PCG stream has one).
    std::uint64_t state() const { return state_; }
    std::uint64_t increment() const { return inc_; }
    static Rng fromState(std::uint64_t state, std::uint64_t increment);

    bool operator==(const Rng&) const = default;

private:
    std::uint64_t state_ = 0;
    std::uint64_t inc_ = 0;
};

/// A float parameter that is either a constant or a distribution. Immutable once made;
/// sample() draws from the caller's Rng and never changes the parameter.
class RandomFloat {
public:
    enum class Kind { Constant, Uniform, Normal, Weibull };

    /// A constant. Implicit so that `params.pitch = 20;` reads naturally.
    RandomFloat(float constant = 0.0f) : kind_(Kind::Constant), a_(constant) {}

    /// A checked constant: throws plantarch::Error for NaN or infinity (the implicit
    /// constructor above does not check).
    static RandomFloat constant(float value);
    /// Uniform on [min, max]; requires min <= max.
    static RandomFloat uniform(float min, float max);
    /// Normal(mean, stddev); requires stddev >= 0.
    static RandomFloat normal(float mean, float stddev);
    /// Weibull(shape k, scale lambda); requires k > 0 and lambda > 0.
    /// Every factory throws plantarch::Error for a NaN or infinite argument.
    static RandomFloat weibull(float shape, float scale);

    Kind kind() const { return kind_; }
    bool isConstant() const { return kind_ == Kind::Constant; }
    /// First parameter: the constant, min, mean or shape.
    float a() const { return a_; }
    /// Second parameter: max, stddev or scale (0 for a constant).
    float b() const { return b_; }

    /// One draw. A constant returns its value without touching the stream; every other kind
    /// consumes the same number of draws whatever its parameters (even uniform(a, a)).
    float sample(Rng& rng) const;
    /// The distribution's mean (the constant itself for a constant).
    float mean() const;
    /// Smallest and largest value a draw can take. A normal draw is limited to mean +- 3
    /// stddev and a Weibull draw to its 99.9 % quantile, scale (ln 1000)^(1 / shape) (a draw
    /// past a limit takes the limit): the bounds species validation checks against a range.
    float lowerBound() const;
    float upperBound() const;
    /// Readable form: "20", "uniform(10, 30)", "normal(0, 5)", "weibull(1.5, 2)".
    std::string describe() const;

    bool operator==(const RandomFloat&) const = default;

private:
    RandomFloat(Kind kind, float a, float b) : kind_(kind), a_(a), b_(b) {}
    Kind kind_;
    float a_ = 0.0f;
    float b_ = 0.0f;
};

/// An integer parameter: a constant, a uniform integer range, or a set of discrete values.
class RandomInt {
public:
    enum class Kind { Constant, Uniform, Discrete };

    RandomInt(int constant = 0) : kind_(Kind::Constant), lo_(constant), hi_(constant) {}

    static RandomInt constant(int value) { return RandomInt(value); }
    /// Uniform on [min, max] inclusive; requires min <= max.
    static RandomInt uniform(int min, int max);
    /// One of `values`, each equally likely; requires at least one value.
    static RandomInt discrete(std::vector<int> values);

    Kind kind() const { return kind_; }
    bool isConstant() const { return kind_ == Kind::Constant; }
    int min() const;
    int max() const;
    const std::vector<int>& values() const { return values_; }

    /// One draw. A constant does not touch the stream; uniform and discrete always do, even
    /// when they can take only one value.
    int sample(Rng& rng) const;
    float mean() const;
    /// Readable form: "3", "uniform(1, 4)", "discrete(2, 5, 11)".
    std::string describe() const;

    bool operator==(const RandomInt&) const = default;

private:
    Kind kind_;
    int lo_ = 0;
    int hi_ = 0;
    std::vector<int> values_;
};

}  // namespace plantarch
