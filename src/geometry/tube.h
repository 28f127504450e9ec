#pragma once
// Tubes for internodes, petioles and peduncles, and the curved centre lines they follow.

#include <span>
#include <vector>

#include "plantarch/Mesh.h"

namespace plantarch::geometry {

/// A circle of vertices around a centre-line point.
struct Ring {
    vec3 center;
    vec3 tangent;  ///< unit direction of the centre line here
    vec3 normal;   ///< unit, perpendicular to tangent: where the ring's first vertex lies
    float radius = 0.0f;
    float arcLength = 0.0f;  ///< distance along the centre line from its start, m
};

/// Rings through `points` (at least 2) with the given radii. Inner rings face the average of
/// the adjoining segment directions so consecutive segments join without gaps; the first
/// vertex direction is carried along by parallel transport (no twist) starting from the
/// component of `referenceNormal` perpendicular to the first segment.
std::vector<Ring> tubeRings(std::span<const vec3> points, std::span<const float> radii,
                            vec3 referenceNormal);

/// The tube between rings[first] and rings[last] (inclusive), `sides` vertices per ring.
/// UVs: u around the circumference (0..1), v = arc length / circumference at the start.
Mesh tubeMesh(std::span<const Ring> rings, std::size_t first, std::size_t last, unsigned sides);

/// A centre line of `segments` equal steps starting at `start` heading along `direction`,
/// turning by `curvature` degrees per metre toward `bendToward` (a unit vector; negative
/// curvature turns away from it). Turning stops once the heading is aligned with the target
/// direction, so a curve never overshoots. Returns segments + 1 points.
std::vector<vec3> curvedPath(vec3 start, vec3 direction, float length, float curvature,
                             vec3 bendToward, unsigned segments);
/// The same into `out` (its storage reused).
void curvedPath(vec3 start, vec3 direction, float length, float curvature, vec3 bendToward,
                unsigned segments, std::vector<vec3>& out);

/// What a curved path takes of its direction and of the direction it bends toward (the
/// bendToward of curvedPath, negated for negative curvature): the same for paths that differ
/// only in start, length and the curvature's size, so it can be kept for them.
struct CurveBasis {
    vec3 d0{0.0f, 0.0f, 1.0f};  ///< unit direction
    vec3 u{0.0f};               ///< unit, across d0 toward the target
    float sinA = 0.0f;          ///< sine of the angle between them (below 1e-7: straight)
    float limit = 0.0f;         ///< that angle: the path turns no farther
};
CurveBasis curveBasis(vec3 direction, vec3 target);
/// curvedPath on a basis from curveBasis (with the target for this curvature's sign).
void curvedPath(vec3 start, const CurveBasis& basis, float length, float curvature,
                unsigned segments, std::vector<vec3>& out);

}  // namespace plantarch::geometry
