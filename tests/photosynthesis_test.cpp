// Leaf photosynthesis (plantarch/Photosynthesis.h) against the model's known limits and the
// behaviour of C3 leaves measured in the literature.

#include "plantarch/Photosynthesis.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "plantarch/Error.h"

using namespace plantarch;

TEST(Photosynthesis, InTheDarkALeafRespires) {
    const FarquharParameters p;
    const LeafPhotosynthesis dark = farquhar(p, 0.0, 25.0);
    EXPECT_DOUBLE_EQ(dark.gross, 0.0);
    EXPECT_DOUBLE_EQ(dark.net, -p.rd25);  // day respiration is rd25 at 25 °C
    // Respiration rises with temperature: Q10 of about 1.9 for 46.39 kJ/mol around 25 °C.
    const double q10 = farquhar(p, 0.0, 30.0).respiration / farquhar(p, 0.0, 20.0).respiration;
    EXPECT_NEAR(q10, 1.88, 0.05);
}

TEST(Photosynthesis, AtTheCompensationPointCarboxylationBalancesPhotorespiration) {
    FarquharParameters p;
    // Ci = Gamma* (42.75 µmol/mol at 25 °C): no net carboxylation at any light.
    const double ca = p.gammaStar25 / p.ciOverCa;
    EXPECT_NEAR(farquhar(p, 1500.0, 25.0, ca).gross, 0.0, 1e-9);
    EXPECT_LT(farquhar(p, 1500.0, 25.0, ca / 2).gross, 0.0);  // below it, CO2 is lost
}

TEST(Photosynthesis, LightLimitedAtLowLightRubiscoLimitedAtHigh) {
    const FarquharParameters p;
    const LeafPhotosynthesis low = farquhar(p, 50.0, 25.0);
    const LeafPhotosynthesis high = farquhar(p, 2000.0, 25.0);
    EXPECT_TRUE(low.lightLimited);
    EXPECT_FALSE(high.lightLimited);
    // The quantum yield of CO2 uptake of a C3 leaf at 25 °C and today's CO2 is 0.05-0.07
    // mol per mol of absorbed photons (Ehleringer and Björkman 1977).
    const double slope = (farquhar(p, 20.0, 25.0).gross - farquhar(p, 0.0, 25.0).gross) / 20.0;
    std::printf("quantum yield %.4f, full sun %.2f µmol m-2 s-1\n", slope, high.net);
    EXPECT_GT(slope, 0.05);
    EXPECT_LT(slope, 0.075);
    // A crop leaf in full sun fixes about 20-35 µmol m-2 s-1.
    EXPECT_GT(high.net, 20.0);
    EXPECT_LT(high.net, 35.0);
    // More light never means less photosynthesis.
    double last = -1e9;
    for (double par = 0.0; par <= 2500.0; par += 50.0) {
        const double a = farquhar(p, par, 25.0).net;
        EXPECT_GE(a, last - 1e-12) << par;
        last = a;
    }
}

TEST(Photosynthesis, MoreCO2MoreCarbonAndAWarmOptimum) {
    const FarquharParameters p;
    // Doubling CO2 raises light-saturated C3 photosynthesis by about 30-60 %.
    const double gain = farquhar(p, 1800.0, 25.0, 800.0).net / farquhar(p, 1800.0, 25.0, 400.0).net;
    EXPECT_GT(gain, 1.3);
    EXPECT_LT(gain, 1.7);
    // Light-saturated photosynthesis peaks between 25 and 35 °C and falls off on both sides.
    double best = -1e9, at = 0.0;
    for (double t = 0.0; t <= 50.0; t += 1.0) {
        const double a = farquhar(p, 1800.0, t).net;
        if (a > best) {
            best = a;
            at = t;
        }
    }
    std::printf("doubled CO2 x%.3f; optimum %.0f °C (%.2f)\n", gain, at, best);
    EXPECT_GE(at, 25.0);
    EXPECT_LE(at, 35.0);
    EXPECT_LT(farquhar(p, 1800.0, 45.0).net, 0.8 * best);
    EXPECT_LT(farquhar(p, 1800.0, 5.0).net, 0.5 * best);
}

TEST(Photosynthesis, SunlitAndShadedPartsAreAveragedByRate) {
    const FarquharParameters p;
    // Half in the sun: half the leaf at 100 + 1600, half at 100 µmol m-2 s-1.
    const LeafPhotosynthesis mixed = farquharSunlitShaded(p, 900.0, 800.0, 0.5, 25.0);
    const double expected =
        0.5 * (farquhar(p, 1700.0, 25.0).gross + farquhar(p, 100.0, 25.0).gross) - p.rd25;
    EXPECT_NEAR(mixed.net, expected, 1e-9);
    // The light's mean would overstate it: the response saturates.
    EXPECT_LT(mixed.net, farquhar(p, 900.0, 25.0).net);
    EXPECT_DOUBLE_EQ(farquharSunlitShaded(p, 300.0, 0.0, 0.0, 25.0).net,
                     farquhar(p, 300.0, 25.0).net);
    EXPECT_THROW(farquharSunlitShaded(p, 100.0, 200.0, 0.5, 25.0), Error);
    EXPECT_THROW(farquharSunlitShaded(p, 100.0, 50.0, 1.5, 25.0), Error);
}

TEST(Photosynthesis, TheLightResponseHyperbola) {
    LightResponseParameters p;
    EXPECT_DOUBLE_EQ(lightResponse(p, 0.0).net, -p.respiration);
    EXPECT_NEAR(lightResponse(p, 1e7).gross, p.pmax, 1e-3);
    EXPECT_NEAR(lightResponse(p, 1.0).gross, p.alpha, 1e-4);  // the initial slope
    p.curvature = 1.0;  // the Blackman limit: min(alpha I, Pmax)
    EXPECT_NEAR(lightResponse(p, 100.0).gross, 5.0, 1e-9);
    EXPECT_NEAR(lightResponse(p, 1000.0).gross, 25.0, 1e-9);
    p.curvature = 0.0;  // rectangular
    EXPECT_NEAR(lightResponse(p, 500.0).gross, 25.0 * 25.0 / 50.0, 1e-9);
}

TEST(Photosynthesis, ValuesOutOfRangeAreRefused) {
    FarquharParameters p;
    EXPECT_THROW(farquhar(p, -1.0, 25.0), Error);
    EXPECT_THROW(farquhar(p, NAN, 25.0), Error);
    EXPECT_THROW(farquhar(p, 100.0, 80.0), Error);
    EXPECT_THROW(farquhar(p, 100.0, 25.0, -5.0), Error);
    p.vcmax25 = 0.0;
    EXPECT_THROW(farquhar(p, 100.0, 25.0), Error);
    p = {};
    p.curvature = 1.5;
    EXPECT_THROW(farquhar(p, 100.0, 25.0), Error);
    LightResponseParameters q;
    q.alpha = 0.0;
    EXPECT_THROW(lightResponse(q, 10.0), Error);
}
