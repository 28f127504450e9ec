// core/math.h: angle conversions, rotation about an axis and the frames shoots start in.

#include "core/math.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

using namespace plantarch;

namespace {

float angleBetween(vec3 a, vec3 b) {
    return degrees(
        std::acos(std::clamp(glm::dot(glm::normalize(a), glm::normalize(b)), -1.0f, 1.0f)));
}

void expectUnitFrame(const AxisFrame& f) {
    EXPECT_NEAR(glm::length(f.axis), 1.0f, 1e-6f);
    EXPECT_NEAR(glm::length(f.reference), 1.0f, 1e-6f);
    EXPECT_NEAR(glm::dot(f.axis, f.reference), 0.0f, 1e-6f);
}

}  // namespace

TEST(Math, PiAndDegrees) {
    EXPECT_EQ(kPi, float(std::numbers::pi));
    EXPECT_EQ(kDeg, kPi / 180.0f);
    EXPECT_EQ(radians(90.0f), 90.0f * kDeg);
    EXPECT_NEAR(degrees(radians(37.5f)), 37.5f, 1e-5f);
    EXPECT_DOUBLE_EQ(radians(180.0), std::numbers::pi);
    const SinCos a = sinCosDeg(30.0f);
    EXPECT_NEAR(a.c, std::sqrt(3.0f) / 2.0f, 1e-6f);
    EXPECT_NEAR(a.s, 0.5f, 1e-6f);
}

TEST(Math, RotationAboutAnAxisFollowsTheRightHandRule) {
    const vec3 x(1, 0, 0), y(0, 1, 0), z(0, 0, 1);
    const vec3 r = rotateAbout(x, z, radians(90.0f));
    EXPECT_NEAR(glm::length(r - y), 0.0f, 1e-6f);
    EXPECT_NEAR(glm::length(rotateAbout(z, z, 1.3f) - z), 0.0f, 1e-6f);  // the axis stays
    // Lengths and the angle to the axis are kept.
    const vec3 v(0.3f, -1.2f, 0.7f), axis = glm::normalize(vec3(1, 2, 3));
    const vec3 w = rotateAbout(v, axis, 2.1f);
    EXPECT_NEAR(glm::length(w), glm::length(v), 1e-5f);
    EXPECT_NEAR(glm::dot(w, axis), glm::dot(v, axis), 1e-5f);
}

TEST(Math, AzimuthTurnsFromTheReferenceTowardAxisCrossReference) {
    const vec3 axis(0, 0, 1), ref(1, 0, 0);
    EXPECT_NEAR(glm::length(azimuthDirection(axis, ref, 0.0f) - ref), 0.0f, 1e-6f);
    EXPECT_NEAR(glm::length(azimuthDirection(axis, ref, 90.0f) - vec3(0, 1, 0)), 0.0f, 1e-6f);
    EXPECT_NEAR(glm::length(azimuthDirection(axis, ref, 180.0f) + ref), 0.0f, 1e-6f);
}

TEST(Math, UnitOrFallsBackOnZeroAndNonFiniteVectors) {
    const vec3 fallback(0, 1, 0);
    EXPECT_NEAR(glm::length(unitOr(vec3(3, 0, 4), fallback) - vec3(0.6f, 0, 0.8f)), 0.0f, 1e-6f);
    EXPECT_EQ(unitOr(vec3(0.0f), fallback), fallback);
    EXPECT_EQ(unitOr(vec3(std::numeric_limits<float>::infinity(), 0, 0), fallback), fallback);
    EXPECT_EQ(unitOr(vec3(std::nanf(""), 0, 0), fallback), fallback);
    for (const vec3 v : {vec3(0, 0, 1), vec3(1, 0, 0), vec3(0.2f, -0.5f, 0.95f)}) {
        const vec3 p = anyPerpendicular(glm::normalize(v));
        EXPECT_NEAR(glm::length(p), 1.0f, 1e-6f);
        EXPECT_NEAR(glm::dot(p, glm::normalize(v)), 0.0f, 1e-6f);
    }
}

TEST(Math, TurnedFrameTiltsByPitchTowardYawAndRollsTheReference) {
    const AxisFrame upright;
    const AxisFrame same = turnedFrame(upright, 0.0f, 0.0f, 0.0f);
    EXPECT_EQ(same.axis, upright.axis);
    EXPECT_NEAR(glm::length(same.reference - upright.reference), 0.0f, 1e-6f);
    // Pitch 30 toward yaw 90 (the +y side of an upright frame whose reference is +x).
    const AxisFrame f = turnedFrame(upright, 30.0f, 90.0f, 0.0f);
    expectUnitFrame(f);
    EXPECT_NEAR(angleBetween(f.axis, upright.axis), 30.0f, 1e-3f);
    EXPECT_GT(f.axis.y, 0.4f);
    EXPECT_NEAR(f.axis.x, 0.0f, 1e-6f);
    // Roll turns only the reference, about the new axis.
    const AxisFrame rolled = turnedFrame(upright, 30.0f, 90.0f, 40.0f);
    expectUnitFrame(rolled);
    EXPECT_NEAR(glm::length(rolled.axis - f.axis), 0.0f, 1e-6f);
    EXPECT_NEAR(angleBetween(rolled.reference, f.reference), 40.0f, 1e-3f);
}

TEST(Math, LateralFrameLeavesTheAxisByItsAngleOnTheBudSide) {
    const vec3 axis(0, 0, 1);
    const vec3 bud = glm::normalize(vec3(1, 0, 0.3f));  // made perpendicular to the axis
    const AxisFrame f = lateralFrame(axis, bud, 35.0f, 0.0f, 0.0f);
    expectUnitFrame(f);
    EXPECT_NEAR(angleBetween(f.axis, axis), 35.0f, 1e-3f);
    EXPECT_NEAR(f.axis.y, 0.0f, 1e-6f);
    EXPECT_GT(f.axis.x, 0.0f);
    EXPECT_GT(glm::dot(f.reference, axis), 0.0f);  // the reference leans toward the parent axis
    // Yaw turns the side about the parent axis first.
    const AxisFrame yawed = lateralFrame(axis, bud, 35.0f, 90.0f, 0.0f);
    EXPECT_NEAR(angleBetween(yawed.axis, axis), 35.0f, 1e-3f);
    EXPECT_GT(yawed.axis.y, 0.5f);
    EXPECT_NEAR(yawed.axis.x, 0.0f, 1e-6f);
    // A bud side along the axis falls back to a perpendicular: still a valid frame.
    expectUnitFrame(lateralFrame(axis, axis, 35.0f, 0.0f, 0.0f));
}
