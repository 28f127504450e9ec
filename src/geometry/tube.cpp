#include "geometry/tube.h"

#include <cmath>

#include "core/math.h"
#include "plantarch/Error.h"

namespace plantarch::geometry {

namespace {
constexpr float kEps = 1e-12f;
}  // namespace

// Rotates `v` by the smallest rotation that takes unit `from` onto unit `to`.
static vec3 transport(vec3 v, vec3 from, vec3 to) {
    const vec3 axis = glm::cross(from, to);
    const float s = glm::length(axis);
    const float c = glm::dot(from, to);
    if (s < 1e-7f) return c > 0.0f ? v : -v;
    return rotateAbout(v, axis / s, std::atan2(s, c));
}

std::vector<Ring> tubeRings(std::span<const vec3> points, std::span<const float> radii,
                            vec3 referenceNormal) {
    const std::size_t n = points.size();
    if (n < 2 || radii.size() != n)
        throw Error("a tube needs at least 2 points and one radius per point",
                    {.parameter = "tube.points", .value = std::to_string(n)});
    std::vector<vec3> segment(n - 1);
    for (std::size_t i = 0; i + 1 < n; ++i) {
        const vec3 d = points[i + 1] - points[i];
        const float len = glm::length(d);
        // A zero-length segment keeps the previous heading.
        segment[i] = len > kEps ? d / len : (i > 0 ? segment[i - 1] : vec3(0, 0, 1));
    }
    std::vector<Ring> rings(n);
    float arc = 0.0f;
    for (std::size_t i = 0; i < n; ++i) {
        vec3 t;
        if (i == 0)
            t = segment[0];
        else if (i == n - 1)
            t = segment[n - 2];
        else {
            t = segment[i - 1] + segment[i];
            t = glm::length(t) > 1e-6f ? glm::normalize(t) : segment[i];
        }
        vec3 normal;
        if (i == 0) {
            normal = referenceNormal - glm::dot(referenceNormal, t) * t;
            normal = glm::length(normal) > 1e-6f ? glm::normalize(normal) : anyPerpendicular(t);
        } else {
            normal = transport(rings[i - 1].normal, rings[i - 1].tangent, t);
            normal = glm::normalize(normal - glm::dot(normal, t) * t);
            arc += glm::length(points[i] - points[i - 1]);
        }
        rings[i] = Ring{points[i], t, normal, radii[i], arc};
    }
    return rings;
}

Mesh tubeMesh(std::span<const Ring> rings, std::size_t first, std::size_t last, unsigned sides) {
    if (sides < 3) sides = 3;
    Mesh m;
    const std::size_t count = last - first + 1;
    m.positions.reserve(count * (sides + 1));
    m.uvs.reserve(count * (sides + 1));
    const float circumference = std::max(2.0f * kPi * std::max(rings[first].radius, 1e-5f), 1e-5f);
    for (std::size_t r = first; r <= last; ++r) {
        const Ring& ring = rings[r];
        const vec3 binormal = glm::cross(ring.tangent, ring.normal);
        // sides + 1 vertices: the seam is duplicated so UVs wrap cleanly.
        for (unsigned k = 0; k <= sides; ++k) {
            const float a = 2.0f * kPi * float(k % sides) / float(sides);
            const vec3 radial = std::cos(a) * ring.normal + std::sin(a) * binormal;
            m.positions.push_back(ring.center + ring.radius * radial);
            m.uvs.push_back({float(k) / float(sides),
                             (ring.arcLength - rings[first].arcLength) / circumference});
        }
    }
    const std::uint32_t stride = sides + 1;
    for (std::uint32_t r = 0; r + 1 < count; ++r)
        for (std::uint32_t k = 0; k < sides; ++k) {
            const std::uint32_t a = r * stride + k, b = a + 1, c = a + stride, d = c + 1;
            m.indices.insert(m.indices.end(), {a, b, d, a, d, c});
        }
    return m;
}

std::vector<vec3> curvedPath(vec3 start, vec3 direction, float length, float curvature,
                             vec3 bendToward, unsigned segments) {
    std::vector<vec3> pts;
    curvedPath(start, direction, length, curvature, bendToward, segments, pts);
    return pts;
}

void curvedPath(vec3 start, vec3 direction, float length, float curvature, vec3 bendToward,
                unsigned segments, std::vector<vec3>& pts) {
    curvedPath(start, curveBasis(direction, curvature >= 0.0f ? bendToward : -bendToward), length,
               curvature, segments, pts);
}

CurveBasis curveBasis(vec3 direction, vec3 target) {
    // The path bends in the plane of d0 and the target, by a constant angle per length, until
    // it points at the target: at angle theta from d0 it runs along cos(theta) d0 + sin(theta) u.
    CurveBasis b;
    b.d0 = glm::normalize(direction);
    b.sinA = glm::length(glm::cross(b.d0, target));
    if (b.sinA < 1e-7f) return b;  // aligned or opposite: straight
    const vec3 across = target - glm::dot(target, b.d0) * b.d0;
    b.u = across / glm::length(across);
    b.limit = std::atan2(b.sinA, glm::dot(b.d0, target));
    return b;
}

void curvedPath(vec3 start, const CurveBasis& b, float length, float curvature, unsigned segments,
                std::vector<vec3>& pts) {
    if (segments == 0) segments = 1;
    pts.resize(segments + 1);
    pts[0] = start;
    const float step = length / float(segments);
    const float turn = std::abs(curvature) * step * kPi / 180.0f;  // radians per step
    vec3 p = start;
    if (b.sinA < 1e-7f || turn == 0.0f) {  // straight (aligned, opposite, or no curvature)
        for (unsigned s = 0; s < segments; ++s) {
            p += b.d0 * step;
            pts[s + 1] = p;
        }
        return;
    }
    for (unsigned s = 0; s < segments; ++s) {
        // Half a step's turn before the step and half after keeps the path symmetric in s.
        const float theta = std::min(turn * (float(s) + 0.5f), b.limit);
        p += (std::cos(theta) * b.d0 + std::sin(theta) * b.u) * step;
        pts[s + 1] = p;
    }
}

}  // namespace plantarch::geometry
