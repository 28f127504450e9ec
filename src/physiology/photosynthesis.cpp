// Leaf photosynthesis: the Farquhar–von Caemmerer–Berry C3 model and a light-response
// hyperbola (plantarch/Photosynthesis.h).

#include "plantarch/Photosynthesis.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/value_text.h"
#include "plantarch/Error.h"

namespace plantarch {

namespace {

constexpr double kGas = 8.314e-3;  // kJ mol-1 K-1
constexpr double kRef = 298.15;    // 25 °C in K

void require(bool ok, const char* parameter, double value, const char* valid) {
    if (!ok)
        throw Error("out of range", {.parameter = parameter,
                                     .value = text::formatFloat(float(value)),
                                     .validRange = valid});
}

// Arrhenius factor of a rate with activation energy e (kJ mol-1) at tk kelvin, 1 at 25 °C.
double arrhenius(double e, double tk) {
    return std::exp(e * (tk - kRef) / (kRef * kGas * tk));
}

// The smaller root of theta x^2 - (a + b) x + a b = 0 (a non-rectangular hyperbola of a and
// b; the rectangular limit a b / (a + b) for theta 0).
double hyperbola(double a, double b, double theta) {
    if (a <= 0.0 || b <= 0.0) return 0.0;
    if (theta < 1e-9) return a * b / (a + b);
    const double s = a + b;
    return (s - std::sqrt(std::max(0.0, s * s - 4.0 * theta * a * b))) / (2.0 * theta);
}

}  // namespace

LeafPhotosynthesis farquhar(const FarquharParameters& p, double absorbedPar, double leafTemperature,
                            double co2) {
    require(std::isfinite(absorbedPar) && absorbedPar >= 0.0, "absorbed PAR", absorbedPar,
            "0 or more µmol m-2 s-1");
    require(leafTemperature >= -50.0 && leafTemperature <= 70.0, "leaf temperature",
            leafTemperature, "-50 to 70 °C");
    require(co2 >= 0.0 && co2 <= 100000.0, "co2", co2, "0 to 100000 µmol mol-1");
    for (const auto& [value, name] : {std::pair{p.vcmax25, "vcmax25"},
                                      {p.jmax25, "jmax25"},
                                      {p.kc25, "kc25"},
                                      {p.ko25, "ko25"},
                                      {p.gammaStar25, "gammaStar25"},
                                      {p.quantumYield, "quantumYield"},
                                      {p.ciOverCa, "ciOverCa"}})
        require(std::isfinite(value) && value > 0.0, name, value, "more than 0");
    require(p.rd25 >= 0.0 && std::isfinite(p.rd25), "rd25", p.rd25, "0 or more");
    require(p.curvature >= 0.0 && p.curvature <= 1.0, "curvature", p.curvature, "0 to 1");
    const double tk = leafTemperature + 273.15;
    const double kc = p.kc25 * arrhenius(p.kcEnergy, tk);
    const double ko = p.ko25 * arrhenius(p.koEnergy, tk);
    const double gammaStar = p.gammaStar25 * arrhenius(p.gammaEnergy, tk);
    const double vcmax = p.vcmax25 * arrhenius(p.vcmaxEnergy, tk);
    const double rd = p.rd25 * arrhenius(p.rdEnergy, tk);
    // Jmax rises with temperature and falls as the enzymes deactivate, 1 at 25 °C.
    const auto deactivation = [&](double t) {
        return 1.0 + std::exp((t * p.jmaxEntropy - p.jmaxDeactivation) / (kGas * t));
    };
    const double jmax =
        p.jmax25 * arrhenius(p.jmaxEnergy, tk) * deactivation(kRef) / deactivation(tk);
    const double ci = p.ciOverCa * co2;
    const double rubisco = vcmax * (ci - gammaStar) / (ci + kc * (1.0 + p.oxygen / ko));
    const double j = hyperbola(p.quantumYield * absorbedPar, jmax, p.curvature);
    const double electron = j * (ci - gammaStar) / (4.0 * ci + 8.0 * gammaStar);
    LeafPhotosynthesis out;
    out.lightLimited = electron < rubisco;
    out.gross = std::min(rubisco, electron);
    out.respiration = rd;
    out.net = out.gross - rd;
    return out;
}

LeafPhotosynthesis farquharSunlitShaded(const FarquharParameters& p, double absorbed,
                                        double absorbedDirect, double sunlitFraction,
                                        double leafTemperature, double co2) {
    require(sunlitFraction >= 0.0 && sunlitFraction <= 1.0, "sunlit fraction", sunlitFraction,
            "0 to 1");
    require(std::isfinite(absorbedDirect) && absorbedDirect >= 0.0 && absorbedDirect <= absorbed,
            "absorbed direct PAR", absorbedDirect, "0 to the absorbed PAR");
    const double shaded = absorbed - absorbedDirect;
    const LeafPhotosynthesis dark = farquhar(p, shaded, leafTemperature, co2);
    if (!(sunlitFraction > 0.0) || absorbedDirect <= 0.0) return dark;
    const LeafPhotosynthesis lit =
        farquhar(p, shaded + absorbedDirect / sunlitFraction, leafTemperature, co2);
    LeafPhotosynthesis out;
    out.gross = sunlitFraction * lit.gross + (1.0 - sunlitFraction) * dark.gross;
    out.respiration = lit.respiration;
    out.net = out.gross - out.respiration;
    out.lightLimited = lit.lightLimited;
    return out;
}

LeafPhotosynthesis lightResponse(const LightResponseParameters& p, double absorbedPar) {
    require(std::isfinite(absorbedPar) && absorbedPar >= 0.0, "absorbed PAR", absorbedPar,
            "0 or more µmol m-2 s-1");
    require(p.alpha > 0.0 && p.alpha <= 1.0, "alpha", p.alpha, "more than 0, at most 1");
    require(std::isfinite(p.pmax) && p.pmax > 0.0, "pmax", p.pmax, "more than 0");
    require(p.curvature >= 0.0 && p.curvature <= 1.0, "curvature", p.curvature, "0 to 1");
    require(std::isfinite(p.respiration) && p.respiration >= 0.0, "respiration", p.respiration,
            "0 or more");
    LeafPhotosynthesis out;
    out.gross = hyperbola(p.alpha * absorbedPar, p.pmax, p.curvature);
    out.respiration = p.respiration;
    out.net = out.gross - p.respiration;
    out.lightLimited = p.alpha * absorbedPar < p.pmax;
    return out;
}

}  // namespace plantarch
