#pragma once
// Angles, rotations and frames shared by every layer. Angles in parameters and state are
// degrees; the functions here take radians unless their name or argument says degrees.
//
// The arithmetic of each helper is part of what a plant's geometry is made of: the library
// plants are checked byte for byte (SpeciesChecksum), so an expression here is changed only
// together with the checksums.

#include <cmath>
#include <numbers>

#include "plantarch/Mesh.h"

namespace plantarch {

/// pi in float (the float nearest to pi). Double-precision code uses std::numbers::pi.
inline constexpr float kPi = std::numbers::pi_v<float>;
/// Radians per degree, rounded once in float: angles convert as `degrees * kDeg`.
inline constexpr float kDeg = kPi / 180.0f;

/// Degrees to radians: `degrees * kDeg`.
constexpr float radians(float degrees) {
    return degrees * kDeg;
}
/// Radians to degrees: `radians / kDeg`.
constexpr float degrees(float radians) {
    return radians / kDeg;
}
/// Degrees to radians in double precision: `(degrees * pi) / 180`.
constexpr double radians(double degrees) {
    return degrees * std::numbers::pi / 180.0;
}

/// Cosine and sine of one angle.
struct SinCos {
    float c = 1.0f, s = 0.0f;
};
/// Cosine and sine of an angle in degrees.
inline SinCos sinCosDeg(float degrees) {
    const float a = degrees * kDeg;
    return {std::cos(a), std::sin(a)};
}

/// `v` scaled to unit length, or `fallback` when `v` is shorter than 1e-6 or not finite.
inline vec3 unitOr(vec3 v, vec3 fallback) {
    const float l = glm::length(v);
    return l > 1e-6f && std::isfinite(l) ? glm::normalize(v) : fallback;
}

/// A unit vector perpendicular to `v` (any, but always the same for the same `v`).
inline vec3 anyPerpendicular(vec3 v) {
    const vec3 helper = std::abs(v.z) < 0.9f ? vec3(0, 0, 1) : vec3(1, 0, 0);
    return glm::normalize(glm::cross(helper, v));
}

/// Rotates `v` about the unit `axis` by `angle` radians (right-hand rule; Rodrigues' formula).
inline vec3 rotateAbout(vec3 v, vec3 axis, float angle) {
    const float c = std::cos(angle), s = std::sin(angle);
    return v * c + glm::cross(axis, v) * s + axis * glm::dot(axis, v) * (1.0f - c);
}

/// The unit direction at azimuth `a` about `axis`, measured from `reference` (both unit and
/// perpendicular) toward axis x reference.
inline vec3 azimuthDirection(vec3 axis, vec3 reference, SinCos a) {
    return a.c * reference + a.s * glm::cross(axis, reference);
}
/// The same with the azimuth in degrees.
inline vec3 azimuthDirection(vec3 axis, vec3 reference, float azimuthDeg) {
    return azimuthDirection(axis, reference, sinCosDeg(azimuthDeg));
}

/// The direction of an internode whose zig-zag pitch is `pitchDeg` (its angle from the previous
/// internode) on a shoot axis `guide` (unit, with its roll `reference`): half the pitch off the
/// axis, toward the internode's own petiole at `azimuthDeg`.
inline vec3 internodeLean(vec3 guide, vec3 reference, float azimuthDeg, float pitchDeg) {
    const vec3 side = azimuthDirection(guide, reference, azimuthDeg);
    const SinCos half = sinCosDeg(0.5f * pitchDeg);
    return unitOr(half.c * guide + half.s * side, guide);
}

/// An axis and the direction about it where azimuth 0 lies (unit, perpendicular): the frame a
/// shoot starts in (its guide and roll reference).
struct AxisFrame {
    vec3 axis{0.0f, 0.0f, 1.0f};
    vec3 reference{1.0f, 0.0f, 0.0f};
};

/// A frame turned from `parent` by pitch, yaw and roll (degrees), as a shoot start is turned
/// by its base rotation: yaw picks the direction about the parent axis (from its reference),
/// pitch tilts the axis that way, roll turns the new reference about the new axis.
inline AxisFrame turnedFrame(const AxisFrame& parent, float pitch, float yaw, float roll) {
    const vec3 tiltDir = azimuthDirection(parent.axis, parent.reference, yaw);
    const float p = pitch * kDeg;
    AxisFrame f;
    f.axis = unitOr(std::cos(p) * parent.axis + std::sin(p) * tiltDir, parent.axis);
    const vec3 ref = -std::sin(p) * parent.axis + std::cos(p) * tiltDir;
    f.reference =
        rotateAbout(unitOr(ref - glm::dot(ref, f.axis) * f.axis, anyPerpendicular(f.axis)), f.axis,
                    roll * kDeg);
    return f;
}

/// The frame of a lateral shoot leaving an internode of direction `axis` (unit) from the bud
/// on side `budSide` (made perpendicular to the axis here): the side is turned `yaw` degrees
/// about the axis, the new axis leaves the internode by `angle` degrees toward it, and its
/// reference (toward the parent axis) is turned `roll` degrees about the new axis.
inline AxisFrame lateralFrame(vec3 axis, vec3 budSide, float angle, float yaw, float roll) {
    vec3 side = unitOr(budSide - glm::dot(budSide, axis) * axis, anyPerpendicular(axis));
    side = rotateAbout(side, axis, yaw * kDeg);
    const float a = angle * kDeg;
    AxisFrame f;
    f.axis = unitOr(std::cos(a) * axis + std::sin(a) * side, axis);
    f.reference =
        rotateAbout(unitOr(axis - glm::dot(axis, f.axis) * f.axis, side), f.axis, roll * kDeg);
    return f;
}

}  // namespace plantarch
