#pragma once
// Small procedural scenes for the renderer's tests and its docs image: boxes, quads, and a
// stylised flowering plant (tube internodes, petioles, curved leaves, flowers, fruit) labelled
// with the organ names the plant model uses. Until the plant model exists this is the richest
// geometry we can show.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <glm/gtc/matrix_transform.hpp>
#include <string>

#include "core/math.h"
#include "plantarch/Context.h"

namespace plantarch::test {

/// Axis-aligned box (12 triangles, 8 shared corners).
inline Mesh boxMesh(vec3 lo, vec3 hi) {
    Mesh m;
    for (int i = 0; i < 8; ++i)
        m.positions.push_back(
            {(i & 1) ? hi.x : lo.x, (i & 2) ? hi.y : lo.y, (i & 4) ? hi.z : lo.z});
    m.indices = {0, 2, 1, 1, 2, 3, 4, 5, 6, 5, 7, 6, 0, 1, 4, 1, 5, 4,
                 2, 6, 3, 3, 6, 7, 0, 4, 2, 2, 4, 6, 1, 3, 5, 3, 7, 5};
    return m;
}

/// Quad with corners a, b, c, d (in order) and UVs (0,0) (1,0) (1,1) (0,1).
inline Mesh quadMesh(vec3 a, vec3 b, vec3 c, vec3 d) {
    Mesh m;
    m.positions = {a, b, c, d};
    m.uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    m.indices = {0, 1, 2, 0, 2, 3};
    return m;
}

/// Tapered tube from p0 to p1 (radii r0, r1), open ends, `segments` around.
inline Mesh tubeMesh(vec3 p0, vec3 p1, float r0, float r1, int segments = 10) {
    Mesh m;
    const vec3 axis = glm::normalize(p1 - p0);
    const vec3 helper = std::abs(axis.z) < 0.9f ? vec3(0, 0, 1) : vec3(1, 0, 0);
    const vec3 t = glm::normalize(glm::cross(axis, helper));
    const vec3 b = glm::cross(axis, t);
    for (int ring = 0; ring < 2; ++ring)
        for (int i = 0; i < segments; ++i) {
            const float a = 2.0f * kPi * float(i) / float(segments);
            const vec3 off = std::cos(a) * t + std::sin(a) * b;
            m.positions.push_back(ring == 0 ? p0 + r0 * off : p1 + r1 * off);
        }
    const auto n = std::uint32_t(segments);
    for (std::uint32_t i = 0; i < n; ++i) {
        const std::uint32_t j = (i + 1) % n;
        m.indices.insert(m.indices.end(), {i, j, n + j, i, n + j, n + i});
    }
    return m;
}

/// UV sphere (stacks x slices).
inline Mesh sphereMesh(vec3 c, float r, int stacks = 10, int slices = 14) {
    Mesh m;
    for (int i = 0; i <= stacks; ++i)
        for (int j = 0; j < slices; ++j) {
            const float th = kPi * float(i) / float(stacks),
                        ph = 2.0f * kPi * float(j) / float(slices);
            m.positions.push_back(c + r * vec3(std::sin(th) * std::cos(ph),
                                               std::sin(th) * std::sin(ph), std::cos(th)));
        }
    const auto s = std::uint32_t(slices);
    for (std::uint32_t i = 0; i < std::uint32_t(stacks); ++i)
        for (std::uint32_t j = 0; j < s; ++j) {
            const std::uint32_t a = i * s + j, b = i * s + (j + 1) % s, c2 = a + s, d = b + s;
            m.indices.insert(m.indices.end(), {a, c2, d, a, d, b});
        }
    return m;
}

/// A leaf blade of unit length along +x in its own frame: lens-shaped outline, folded along
/// the midrib and drooping toward the tip.
inline Mesh leafBlade(float length, float width, float droop, int nu = 12, int nv = 6) {
    Mesh m;
    for (int i = 0; i <= nu; ++i)
        for (int j = 0; j <= nv; ++j) {
            const float u = float(i) / float(nu), v = 2.0f * float(j) / float(nv) - 1.0f;
            const float half =
                0.5f * width * std::pow(std::max(0.0f, std::sin(kPi * std::pow(u, 0.8f))), 0.9f);
            const float y = v * half;
            const float z = -droop * u * u * length + 0.15f * std::abs(y);
            m.positions.push_back({u * length, y, z});
            m.uvs.push_back({u, 0.5f * (v + 1.0f)});
        }
    const auto w = std::uint32_t(nv + 1);
    for (std::uint32_t i = 0; i < std::uint32_t(nu); ++i)
        for (std::uint32_t j = 0; j < std::uint32_t(nv); ++j) {
            const std::uint32_t a = i * w + j, b = a + 1, c = a + w, d = c + 1;
            m.indices.insert(m.indices.end(), {a, c, d, a, d, b});
        }
    return m;
}

/// A flat flower: a ring of petal quads around a small centre.
inline Mesh flowerMesh(int petals, float radius) {
    Mesh m;
    for (int p = 0; p < petals; ++p) {
        const float a = 2.0f * kPi * float(p) / float(petals);
        const vec3 dir(std::cos(a), std::sin(a), 0.0f), side(-std::sin(a), std::cos(a), 0.0f);
        const auto base = std::uint32_t(m.positions.size());
        m.positions.push_back(0.15f * radius * dir);
        m.positions.push_back(0.6f * radius * dir + 0.22f * radius * side +
                              vec3(0, 0, 0.1f * radius));
        m.positions.push_back(radius * dir + vec3(0, 0, 0.25f * radius));
        m.positions.push_back(0.6f * radius * dir - 0.22f * radius * side +
                              vec3(0, 0, 0.1f * radius));
        m.indices.insert(m.indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
    }
    return m;
}

inline ObjectID addOrgan(Context& ctx, const Mesh& mesh, vec3 color, const char* organ, int plant) {
    const ObjectID id = ctx.addObject(mesh, Material{color, "", ""});
    ctx.setObjectData(id, "organ", std::string(organ));
    ctx.setObjectData(id, "plantID", std::int32_t(plant));
    return id;
}

/// A stylised flowering plant with its base at `base`: a gently leaning stem of `nodes`
/// internodes, a petiole and leaf at each node (137.5 degree phyllotaxy), flowers and fruit
/// near the top. About 3,500 triangles for 12 nodes.
inline void addDemoPlant(Context& ctx, vec3 base, int nodes, float height, int plant,
                         float phase = 0.0f) {
    const vec3 stemColor(0.36f, 0.52f, 0.20f), leafColor(0.22f, 0.50f, 0.14f);
    const float internode = height / float(nodes);
    vec3 p = base;
    for (int i = 0; i < nodes; ++i) {
        const float f = float(i) / float(nodes);
        const vec3 lean(0.08f * std::sin(1.3f * float(i) + phase), 0.06f * std::cos(float(i)),
                        1.0f);
        const vec3 q = p + internode * glm::normalize(lean);
        const float r0 = 0.012f * (1.0f - 0.6f * f),
                    r1 = 0.012f * (1.0f - 0.6f * (f + 1.0f / nodes));
        addOrgan(ctx, tubeMesh(p, q, r0, r1), stemColor, "internode", plant);
        p = q;
        if (i == 0) continue;
        const float az = phase + 2.3998f * float(i);  // golden angle
        const vec3 out(std::cos(az), std::sin(az), 0.0f);
        const float petioleLen = 0.10f * (1.0f - 0.5f * f);
        const vec3 tip = p + petioleLen * glm::normalize(out + vec3(0, 0, 0.8f));
        addOrgan(ctx, tubeMesh(p, tip, 0.004f, 0.003f, 6), stemColor, "petiole", plant);
        const float len = 0.24f * (1.0f - 0.55f * f), width = 0.45f * len;
        mat4 xf = glm::translate(mat4(1.0f), tip);
        xf = glm::rotate(xf, az, vec3(0, 0, 1));
        xf = glm::rotate(xf, -0.35f, vec3(0, 1, 0));  // pitch the blade up a little
        Mesh leaf = leafBlade(len, width, 0.35f);
        leaf.transform(xf);
        addOrgan(ctx, leaf, leafColor, "leaf", plant);
        if (i >= nodes - 4) {
            // A peduncle with an open flower, a closed bud or a fruit.
            const vec3 side(std::cos(az + 1.6f), std::sin(az + 1.6f), 0.0f);
            const vec3 end = p + 0.07f * glm::normalize(side + vec3(0, 0, 0.6f));
            addOrgan(ctx, tubeMesh(p, end, 0.003f, 0.0025f, 6), stemColor, "peduncle", plant);
            const int kind = (i + plant) % 3;
            if (kind == 0) {
                Mesh flower = flowerMesh(6, 0.035f);
                flower.transform(glm::translate(mat4(1.0f), end));
                addOrgan(ctx, flower, vec3(0.96f, 0.92f, 0.98f), "flower_open", plant);
            } else if (kind == 1) {
                addOrgan(ctx, sphereMesh(end, 0.012f, 6, 8), vec3(0.85f, 0.55f, 0.75f),
                         "flower_closed", plant);
            } else {
                addOrgan(ctx, sphereMesh(end - vec3(0, 0, 0.02f), 0.025f),
                         vec3(0.80f, 0.12f, 0.08f), "fruit", plant);
            }
        }
    }
}

/// The docs scene: three demo plants of different sizes.
inline void addDemoScene(Context& ctx) {
    addDemoPlant(ctx, {0.0f, 0.0f, 0.0f}, 12, 0.75f, 0, 0.0f);
    addDemoPlant(ctx, {0.38f, 0.22f, 0.0f}, 9, 0.50f, 1, 1.0f);
    addDemoPlant(ctx, {-0.42f, 0.02f, 0.0f}, 7, 0.38f, 2, 2.0f);
}

}  // namespace plantarch::test
