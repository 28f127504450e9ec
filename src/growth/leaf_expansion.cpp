#include "growth/leaf_expansion.h"

#include <algorithm>
#include <cmath>

namespace plantarch {

double nominalReciprocal(const RandomFloat& scale) {
    const double a = scale.a(), b = scale.b();
    switch (scale.kind()) {
        case RandomFloat::Kind::Constant:
            return a > 0.0 ? 1.0 / a : 0.0;
        case RandomFloat::Kind::Uniform:
            if (!(a > 0.0)) return 0.0;
            return b > a ? std::log(b / a) / (b - a) : 1.0 / a;
        case RandomFloat::Kind::Normal:
        case RandomFloat::Kind::Weibull:
            break;
    }
    // Unbounded below or heavy near 0: the reciprocal of the mean stands in.
    const double m = scale.mean();
    return m > 0.0 ? 1.0 / m : 0.0;
}

double growthStep(const PlantInstance& plant) {
    double step = 0.0;
    for (const auto& [label, type] : plant.shootTypes) {
        const double p = type.phyllochron_min.mean();
        if (p > 0.0 && (step == 0.0 || p < step)) step = p;
    }
    return step > 0.0 ? step : 1.0;
}

float leafSizeRatio(const Phytomer& ph, double reciprocal) {
    if (ph.petioles.empty()) return 1.0f;
    // The tip leaflet (an even count has a pair at the tip, at full scale like a tip leaflet).
    const LeafOrgan* tip = nullptr;
    for (const LeafOrgan& l : ph.petioles.front().leaves)
        if (l.leafletIndex == 0 || (!tip && std::abs(l.leafletIndex) == 1)) tip = &l;
    if (!tip || !(tip->scale > 0.0f) || !(reciprocal > 0.0)) return 1.0f;
    return float(double(tip->scale) * reciprocal);
}

float leafFractionAt(float f0, float rate, double age, float ratio, double step) {
    if (f0 >= 1.0f) return 1.0f;
    const double r = ratio;
    double f;
    if (std::abs(r - 1.0) < 1e-6) {
        f = f0 + double(rate) * age;
    } else {
        // f(n+1) = r (f(n) + rate step) after n = age / step steps, in closed form.
        const double q = std::pow(r, age / step);
        f = q * f0 + double(rate) * step * r * (1.0 - q) / (1.0 - r);
    }
    return float(std::clamp(f, 0.0, 1.0));
}

}  // namespace plantarch
