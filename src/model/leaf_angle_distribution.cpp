// Leaf angle distributions: densities, tables and draws (leaf_angle_distribution.h).
//
// The densities, with t the inclination in radians on [0, pi/2]:
//   de Wit (1965): planophile (2/pi)(1 + cos 2t), erectophile (2/pi)(1 - cos 2t), plagiophile
//     (2/pi)(1 - cos 4t), extremophile (2/pi)(1 + cos 4t), uniform 2/pi, spherical sin t;
//   Campbell's ellipsoidal (1986, 1990): 2 x^3 sin t / (L (cos^2 t + x^2 sin^2 t)^2), with the
//     exact normalising L (x + asin(e)/e for x < 1, e = sqrt(1 - x^2); x + ln((1 + e)/(1 - e))
//     / (2 e x) for x > 1, e = sqrt(1 - 1/x^2); 2 for x = 1);
//   Goel and Strebel's beta (1984): s = 2t/pi has density s^(nu-1) (1-s)^(mu-1) / B(mu, nu);
//     from a mean m and standard deviation d of s: nu = m c, mu = (1 - m) c, c = m (1 - m) / d^2
//     - 1 (Wang et al. 2007);
//   a histogram: each bin's weight spread evenly over the bin.
// Every family but the histogram is drawn by inverting a cumulative table of 9000 cells of
// 0.01 degrees (Simpson's rule in each; the beta's cells integrate its power factor exactly,
// so an exponent below 1 at an end costs no accuracy), linear within a cell.

#include "model/leaf_angle_distribution.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <numbers>

#include "core/value_text.h"
#include "plantarch/Error.h"

namespace plantarch::leaf_angles {

namespace {

constexpr double kPiD = std::numbers::pi;
constexpr double kRad = kPiD / 180.0;
constexpr int kCells = 9000;             // inclination cells of 0.01 degrees
constexpr double kCell = 90.0 / kCells;  // degrees
constexpr int kAzimuthCells = 3600;      // von Mises cells of 0.1 degrees

std::string numberText(double v) {
    return text::formatDouble(v);
}

// Campbell's normalising constant of the ellipsoidal density.
double ellipsoidalLambda(double x) {
    if (std::abs(x - 1.0) < 1e-9) return 2.0;
    if (x < 1.0) {
        const double e = std::sqrt(1.0 - x * x);
        return x + std::asin(e) / e;
    }
    const double e = std::sqrt(1.0 - 1.0 / (x * x));
    return x + std::log((1.0 + e) / (1.0 - e)) / (2.0 * e * x);
}

// The density per radian at t radians, for the families with a formula.
double densityPerRadian(const LeafAngleParameters& p, double t, double lambda) {
    using D = LeafInclinationDistribution;
    switch (p.inclination) {
        case D::Planophile:
            return 2.0 / kPiD * (1.0 + std::cos(2.0 * t));
        case D::Erectophile:
            return 2.0 / kPiD * (1.0 - std::cos(2.0 * t));
        case D::Plagiophile:
            return 2.0 / kPiD * (1.0 - std::cos(4.0 * t));
        case D::Extremophile:
            return 2.0 / kPiD * (1.0 + std::cos(4.0 * t));
        case D::Spherical:
            return std::sin(t);
        case D::Uniform:
            return 2.0 / kPiD;
        case D::Ellipsoidal: {
            const double x = p.ellipsoidal_x, c = std::cos(t), s = std::sin(t);
            const double q = c * c + x * x * s * s;
            return 2.0 * x * x * x * s / (lambda * q * q);
        }
        case D::Beta: {
            const auto [mu, nu] = betaShape(p);
            const double u = std::clamp(t / (kPiD / 2.0), 0.0, 1.0);
            const double b = std::exp(std::lgamma(mu) + std::lgamma(nu) - std::lgamma(mu + nu));
            if ((u == 0.0 && nu < 1.0) || (u == 1.0 && mu < 1.0)) return HUGE_VAL;
            return std::pow(u, nu - 1.0) * std::pow(1.0 - u, mu - 1.0) / b * (2.0 / kPiD);
        }
        default:
            return 0.0;
    }
}

// The beta's unnormalised mass on [a, b] (fractions of 90 degrees): the power factor of the
// nearer end integrated exactly, the other taken at the middle.
double betaCell(double a, double b, double mu, double nu) {
    const double m = 0.5 * (a + b);
    if (m < 0.5) return (std::pow(b, nu) - std::pow(a, nu)) / nu * std::pow(1.0 - m, mu - 1.0);
    return (std::pow(1.0 - a, mu) - std::pow(1.0 - b, mu)) / mu * std::pow(m, nu - 1.0);
}

// Inverts a cumulative table of cells of `width` starting at `start` at share u in [0, 1).
double invert(const std::vector<double>& cumul, double u, double start, double width) {
    const double want = u * cumul.back();
    auto it = std::upper_bound(cumul.begin(), cumul.end(), want);
    std::size_t i = std::size_t(std::max<std::ptrdiff_t>(1, it - cumul.begin()));
    i = std::min(i, cumul.size() - 1);
    const double lo = cumul[i - 1], hi = cumul[i];
    const double f = hi > lo ? (want - lo) / (hi - lo) : 0.5;
    return start + (double(i - 1) + std::clamp(f, 0.0, 1.0)) * width;
}

}  // namespace

Bins histogramBins(const std::map<std::string, float>& histogram, const std::string& path) {
    std::vector<std::pair<double, double>> bins;
    for (const auto& [key, weight] : histogram) {
        double edge = 0.0;
        const char* end = key.data() + key.size();
        const auto [used, ec] = std::from_chars(key.data(), end, edge);
        if (key.empty() || ec != std::errc() || used != end || !std::isfinite(edge) ||
            !(edge > 0.0 && edge <= 90.0))
            throw Error("a histogram bin's upper edge is a number of degrees",
                        {.parameter = path + "." + key,
                         .value = key,
                         .validRange = "> 0 and <= 90 (degrees)"});
        for (const auto& [other, w] : bins)
            if (other == edge)
                throw Error("a histogram edge is given twice",
                            {.parameter = path + "." + key,
                             .value = key,
                             .validRange = "each upper edge once"});
        bins.emplace_back(edge, double(weight));
    }
    std::sort(bins.begin(), bins.end());
    Bins out;
    for (const auto& [edge, weight] : bins) {
        out.upper.push_back(edge);
        out.weight.push_back(weight);
    }
    return out;
}

std::pair<double, double> betaShape(const LeafAngleParameters& p) {
    if (!(p.beta_mean > 0.0f)) return {p.beta_mu, p.beta_nu};
    const double m = double(p.beta_mean) / 90.0, d = double(p.beta_sd) / 90.0;
    const double c = d > 0.0 ? m * (1.0 - m) / (d * d) - 1.0 : 0.0;
    return {(1.0 - m) * c, m * c};
}

void check(const LeafAngleParameters& p, const std::string& path) {
    const Bins bins = histogramBins(p.histogram, path + ".histogram");
    if (p.inclination == LeafInclinationDistribution::Histogram) {
        double total = 0.0;
        for (double w : bins.weight) total += w;
        if (!(total > 0.0))
            throw Error("a histogram distribution needs bins with weight",
                        {.parameter = path + ".histogram",
                         .value = bins.upper.empty() ? "no bins" : "weights summing to 0",
                         .validRange = "at least one <bin to=\"DEGREES\">WEIGHT</bin> with "
                                       "weight above 0"});
    }
    if (p.beta_mean > 0.0f) {
        const double m = p.beta_mean, limit = std::sqrt(m * (90.0 - m));
        if (!(p.beta_sd > 0.0f && p.beta_sd < limit))
            throw Error("no beta distribution has this mean and standard deviation",
                        {.parameter = path + ".beta_sd",
                         .value = numberText(p.beta_sd),
                         .validRange = "> 0 and < sqrt(beta_mean (90 - beta_mean)) = " +
                                       numberText(std::floor(limit * 1000.0) / 1000.0)});
        const auto [mu, nu] = betaShape(p);
        for (const auto& [name, value] : {std::pair{"beta_mu", mu}, std::pair{"beta_nu", nu}})
            if (!(value >= 0.1 && value <= 100.0))
                throw Error(std::string("beta_mean and beta_sd give a ") + name +
                                " outside 0.1 to 100 (" + numberText(value) + ")",
                            {.parameter = path + ".beta_sd",
                             .value = numberText(p.beta_sd),
                             .validRange = "a beta_sd giving beta_mu and beta_nu from 0.1 to 100"});
    }
}

double inclinationDensity(const LeafAngleParameters& p, double degrees) {
    if (p.inclination == LeafInclinationDistribution::None || !(degrees >= 0.0 && degrees <= 90.0))
        return 0.0;
    if (p.inclination == LeafInclinationDistribution::Histogram) {
        const Bins bins = histogramBins(p.histogram, "leaf_angles.histogram");
        double total = 0.0;
        for (double w : bins.weight) total += w;
        double lo = 0.0;
        for (std::size_t i = 0; i < bins.upper.size(); ++i) {
            if (degrees <= bins.upper[i] && bins.upper[i] > lo)
                return bins.weight[i] / total / (bins.upper[i] - lo);
            lo = bins.upper[i];
        }
        return 0.0;
    }
    const double lambda = ellipsoidalLambda(p.ellipsoidal_x);
    return densityPerRadian(p, degrees * kRad, lambda) * kRad;
}

Sampler::Sampler(const LeafAngleParameters& p) : p_(p) {
    using D = LeafInclinationDistribution;
    if (p.inclination == D::Histogram) {
        bins_ = histogramBins(p.histogram, "leaf_angles.histogram");
        double sum = 0.0;
        cumul_.push_back(0.0);
        for (double w : bins_.weight) cumul_.push_back(sum += w);
    } else if (p.inclination != D::None) {
        cumul_.assign(kCells + 1, 0.0);
        const double lambda = ellipsoidalLambda(p.ellipsoidal_x);
        const auto [mu, nu] = betaShape(p);
        double sum = 0.0;
        for (int i = 0; i < kCells; ++i) {
            const double a = i * kCell, b = (i + 1) * kCell;
            double mass;
            if (p.inclination == D::Beta) {
                mass = betaCell(a / 90.0, b / 90.0, mu, nu);
            } else {
                const double fa = densityPerRadian(p, a * kRad, lambda),
                             fm = densityPerRadian(p, 0.5 * (a + b) * kRad, lambda),
                             fb = densityPerRadian(p, b * kRad, lambda);
                mass = (fa + 4.0 * fm + fb) / 6.0 * (kCell * kRad);
            }
            cumul_[std::size_t(i) + 1] = sum += std::max(mass, 0.0);
        }
    }
    if (p.azimuth == LeafAzimuthDistribution::VonMises && p.azimuth_concentration > 0.0f) {
        const double k = p.azimuth_concentration, w = 360.0 / kAzimuthCells;
        const auto f = [&](double deg) { return std::exp(k * (std::cos(deg * kRad) - 1.0)); };
        azimuth_.assign(kAzimuthCells + 1, 0.0);
        double sum = 0.0;
        for (int i = 0; i < kAzimuthCells; ++i) {
            const double a = -180.0 + i * w, b = a + w;
            azimuth_[std::size_t(i) + 1] = sum += (f(a) + 4.0 * f(0.5 * (a + b)) + f(b)) / 6.0 * w;
        }
    }
}

double Sampler::cdf(double degrees) const {
    if (cumul_.empty() || !(cumul_.back() > 0.0)) return 0.0;
    const double d = std::clamp(degrees, 0.0, 90.0);
    if (p_.inclination == LeafInclinationDistribution::Histogram) {
        double lo = 0.0, mass = 0.0;
        for (std::size_t i = 0; i < bins_.upper.size(); ++i) {
            const double hi = bins_.upper[i];
            if (d >= hi)
                mass += bins_.weight[i];
            else if (d > lo)
                mass += bins_.weight[i] * (d - lo) / (hi - lo);
            lo = hi;
        }
        return mass / cumul_.back();
    }
    const double x = d / kCell;
    const std::size_t i = std::min<std::size_t>(std::size_t(x), kCells - 1);
    const double f = x - double(i);
    return (cumul_[i] + f * (cumul_[i + 1] - cumul_[i])) / cumul_.back();
}

double Sampler::probability(double lo, double hi) const {
    return std::max(0.0, cdf(hi) - cdf(lo));
}

LeafAngleTarget Sampler::draw(Rng& rng) const {
    LeafAngleTarget t;
    const double u = rng.uniform01d();
    if (p_.inclination == LeafInclinationDistribution::Histogram) {
        // A bin by its weight, then evenly within it.
        const double want = u * cumul_.back();
        std::size_t i = 0;
        while (i + 1 < bins_.upper.size() && cumul_[i + 1] <= want) ++i;
        const double lo = i == 0 ? 0.0 : bins_.upper[i - 1], hi = bins_.upper[i];
        const double w = bins_.weight[i];
        const double f = w > 0.0 ? std::clamp((want - cumul_[i]) / w, 0.0, 1.0) : 0.5;
        t.inclination = float(lo + f * (hi - lo));
    } else if (!cumul_.empty()) {
        t.inclination = float(invert(cumul_, u, 0.0, kCell));
    }
    t.inclination = std::clamp(t.inclination, 0.0f, 90.0f);
    const double v = rng.uniform01d();
    double azimuth = 360.0 * v;
    if (!azimuth_.empty())
        azimuth = p_.azimuth_mean + invert(azimuth_, v, -180.0, 360.0 / kAzimuthCells);
    azimuth = std::fmod(azimuth, 360.0);
    if (azimuth < 0.0) azimuth += 360.0;
    t.azimuth = std::clamp(float(azimuth), 0.0f, 360.0f);
    return t;
}

const Sampler& sampler(const LeafAngleParameters& p) {
    thread_local std::unique_ptr<Sampler> last;
    if (!last || !(last->parameters() == p)) last = std::make_unique<Sampler>(p);
    return *last;
}

}  // namespace plantarch::leaf_angles
