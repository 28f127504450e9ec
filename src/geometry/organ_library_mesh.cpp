// Mesh helpers of the organ library: quad grids with fan apexes, closed bodies, tubes along
// paths and petal-like sheets.

#include <algorithm>
#include <cmath>

#include "geometry/organ_library_internal.h"

namespace plantarch::organs {

float smooth(float a, float b, float x) {
    const float t = std::clamp((x - a) / (b - a), 0.0f, 1.0f);
    return t * t * (3.0f - 2.0f * t);
}

vec3 tint(vec3 color, float t) {
    return t >= 0.0f ? glm::mix(color, vec3(1.0f), t) : color * (1.0f + t);
}

Mesh gridMesh(const Grid& g, const std::function<vec3(unsigned i, unsigned j)>& point) {
    Mesh m;
    const unsigned colVerts = g.wrap ? g.cols : g.cols + 1;
    auto isApex = [&](unsigned i) { return (i == 0 && g.apexStart) || (i == g.rows && g.apexEnd); };
    std::vector<std::uint32_t> rowStart(g.rows + 1);
    for (unsigned i = 0; i <= g.rows; ++i) {
        rowStart[i] = std::uint32_t(m.positions.size());
        if (isApex(i)) {
            m.positions.push_back(point(i, 0));
        } else {
            for (unsigned j = 0; j < colVerts; ++j) m.positions.push_back(point(i, j));
        }
    }
    auto idx = [&](unsigned i, unsigned j) -> std::uint32_t {
        if (isApex(i)) return rowStart[i];
        return rowStart[i] + (g.wrap ? j % g.cols : j);
    };
    m.indices.reserve(std::size_t(g.rows) * g.cols * 6);
    for (unsigned i = 0; i < g.rows; ++i)
        for (unsigned j = 0; j < g.cols; ++j) {
            const std::uint32_t a = idx(i, j), b = idx(i, j + 1), c = idx(i + 1, j),
                                d = idx(i + 1, j + 1);
            if (a == b) {
                m.indices.insert(m.indices.end(), {a, d, c});
            } else if (c == d) {
                m.indices.insert(m.indices.end(), {a, b, c});
            } else {
                m.indices.insert(m.indices.end(), {a, b, d, a, d, c});
            }
        }
    return m;
}

double signedVolume(const Mesh& m) {
    double v = 0.0;
    for (std::size_t t = 0; t + 2 < m.indices.size(); t += 3) {
        const glm::dvec3 a = m.positions[m.indices[t]], b = m.positions[m.indices[t + 1]],
                         c = m.positions[m.indices[t + 2]];
        v += glm::dot(a, glm::cross(b, c));
    }
    return v / 6.0;
}

void flipWinding(Mesh& m) {
    for (std::size_t t = 0; t + 2 < m.indices.size(); t += 3)
        std::swap(m.indices[t + 1], m.indices[t + 2]);
}

Mesh closedBody(unsigned rows, unsigned sides,
                const std::function<vec3(float u, float theta)>& point) {
    rows = std::max(rows, 2u);
    sides = std::max(sides, 3u);
    Mesh m = gridMesh({rows, sides, true, true, true}, [&](unsigned i, unsigned j) {
        return point(float(i) / float(rows), 2.0f * kPi * float(j) / float(sides));
    });
    if (signedVolume(m) < 0.0) flipWinding(m);
    return m;
}

Mesh ellipsoid(vec3 centre, vec3 ax, vec3 ay, vec3 az, unsigned rows, unsigned sides) {
    return closedBody(rows, sides, [&](float u, float theta) {
        const float phi = kPi * u;
        return centre - ax * std::cos(phi) +
               (ay * std::cos(theta) + az * std::sin(theta)) * std::sin(phi);
    });
}

namespace {

// Centre, tangent and a normal per path point, the normal carried along without twist.
struct PathFrame {
    vec3 centre, tangent, normal;
};

std::vector<PathFrame> pathFrames(std::span<const vec3> path, vec3 up = vec3(0.0f)) {
    const std::size_t n = path.size();
    std::vector<PathFrame> f(n);
    for (std::size_t i = 0; i < n; ++i) {
        const vec3 back = i > 0 ? path[i] - path[i - 1] : vec3(0.0f);
        const vec3 ahead = i + 1 < n ? path[i + 1] - path[i] : vec3(0.0f);
        vec3 t = (glm::length(back) > 0 ? glm::normalize(back) : vec3(0.0f)) +
                 (glm::length(ahead) > 0 ? glm::normalize(ahead) : vec3(0.0f));
        if (glm::length(t) < 1e-6f) t = i > 0 ? f[i - 1].tangent : vec3(1, 0, 0);
        f[i].centre = path[i];
        f[i].tangent = glm::normalize(t);
    }
    const vec3 t0 = f[0].tangent;
    vec3 n0 = up - t0 * glm::dot(up, t0);
    if (glm::length(n0) < 1e-4f) {
        n0 = std::abs(t0.z) < 0.9f ? vec3(0, 0, 1) : vec3(0, 1, 0);
        n0 -= t0 * glm::dot(n0, t0);
    }
    f[0].normal = glm::normalize(n0);
    for (std::size_t i = 1; i < n; ++i) {
        vec3 nn = f[i - 1].normal - f[i].tangent * glm::dot(f[i - 1].normal, f[i].tangent);
        f[i].normal = glm::length(nn) > 1e-6f ? glm::normalize(nn) : f[i - 1].normal;
    }
    return f;
}

}  // namespace

Mesh tube(std::span<const vec3> path, std::span<const float> radii, unsigned sides) {
    sides = std::max(sides, 3u);
    const std::vector<PathFrame> frames = pathFrames(path);
    // Rows: an apex at each end (the cap centre, or the point of a zero-radius end), then
    // one ring per point of non-zero radius.
    struct Row {
        const PathFrame* frame;
        float radius;
    };
    std::vector<Row> rows;
    const std::size_t n = path.size();
    rows.push_back({&frames[0], 0.0f});
    for (std::size_t i = 0; i < n; ++i)
        if (radii[i] > 1e-7f) rows.push_back({&frames[i], radii[i]});
    rows.push_back({&frames[n - 1], 0.0f});
    Mesh m =
        gridMesh({unsigned(rows.size() - 1), sides, true, true, true}, [&](unsigned i, unsigned j) {
            const Row& r = rows[i];
            if (r.radius <= 0.0f) return r.frame->centre;
            const float a = 2.0f * kPi * float(j) / float(sides);
            const vec3 b = glm::cross(r.frame->tangent, r.frame->normal);
            return r.frame->centre + r.radius * (std::cos(a) * r.frame->normal + std::sin(a) * b);
        });
    if (signedVolume(m) < 0.0) flipWinding(m);
    return m;
}

Mesh tube(vec3 a, vec3 b, float r0, float r1, unsigned sides, unsigned segments) {
    segments = std::max(segments, 1u);
    std::vector<vec3> path;
    std::vector<float> radii;
    for (unsigned k = 0; k <= segments; ++k) {
        const float t = float(k) / float(segments);
        path.push_back(glm::mix(a, b, t));
        radii.push_back(r0 + (r1 - r0) * t);
    }
    return tube(path, radii, sides);
}

PathPoint pathAt(std::span<const vec3> path, vec3 up, float u) {
    const std::vector<PathFrame> f = pathFrames(path, up);
    std::vector<float> acc{0.0f};
    for (std::size_t i = 1; i < path.size(); ++i)
        acc.push_back(acc.back() + glm::length(path[i] - path[i - 1]));
    const float target = std::clamp(u, 0.0f, 1.0f) * acc.back();
    std::size_t k = 0;
    while (k + 2 < path.size() && acc[k + 1] < target) ++k;
    const float seg = acc[k + 1] - acc[k];
    const float t = seg > 0.0f ? std::clamp((target - acc[k]) / seg, 0.0f, 1.0f) : 0.0f;
    PathPoint p;
    p.position = glm::mix(f[k].centre, f[k + 1].centre, t);
    p.tangent = glm::normalize(glm::mix(f[k].tangent, f[k + 1].tangent, t));
    vec3 n = glm::mix(f[k].normal, f[k + 1].normal, t);
    n -= p.tangent * glm::dot(n, p.tangent);
    p.normal = glm::normalize(n);
    p.side = glm::cross(p.tangent, p.normal);
    return p;
}

Mesh sweptBody(std::span<const vec3> path, vec3 up, unsigned rows, unsigned sides,
               const std::function<vec2(float u, float theta)>& section) {
    rows = std::max(rows, 2u);
    std::vector<PathPoint> at(rows + 1);
    for (unsigned i = 0; i <= rows; ++i) at[i] = pathAt(path, up, float(i) / float(rows));
    std::size_t row = 0;
    return closedBody(rows, sides, [&](float u, float theta) {
        row = std::min<std::size_t>(std::size_t(std::lround(u * float(rows))), rows);
        const PathPoint& p = at[row];
        const vec2 s = section(u, theta);
        return p.position + s.x * p.side + s.y * p.normal;
    });
}

std::vector<vec3> arcPath(vec3 start, vec3 direction, vec3 toward, float length, float bendDeg,
                          unsigned segments) {
    segments = std::max(segments, 1u);
    const vec3 d = glm::normalize(direction);
    vec3 axis = glm::cross(d, toward);
    axis = glm::length(axis) > 1e-6f ? glm::normalize(axis) : vec3(0.0f);
    std::vector<vec3> pts{start};
    const float step = length / float(segments);
    for (unsigned k = 0; k < segments; ++k) {
        const float angle = bendDeg * kDeg * (float(k) + 0.5f) / float(segments);
        const vec3 h = glm::length(axis) > 0.0f ? rotateAbout(d, axis, angle) : d;
        pts.push_back(pts.back() + step * h);
    }
    return pts;
}

float petalHalfWidth(const PetalSpec& s, float u) {
    const float m = std::clamp(s.widest, 0.05f, 0.95f);
    const float w0 = 0.5f * std::clamp(s.claw, 0.0f, 1.0f);
    if (u <= m) {
        const float t = u / m;
        return w0 + (0.5f - w0) * std::sin(0.5f * kPi * t);
    }
    const float t = std::min((u - m) / (1.0f - m), 1.0f);
    const float rounded = std::sqrt(std::max(0.0f, 1.0f - t * t));
    return 0.5f * ((1.0f - s.tip) * rounded + s.tip * (1.0f - t));
}

Mesh petalMesh(const PetalSpec& s, vec3 origin, vec3 axis, vec3 radial, unsigned rows,
               unsigned cols) {
    rows = std::max(rows, 2u);
    cols = std::max(cols, 1u);
    // Rows crowd toward a rounded tip, where the outline turns fastest.
    std::vector<float> us(rows + 1);
    for (unsigned i = 0; i <= rows; ++i) {
        const float t = float(i) / float(rows);
        us[i] = glm::mix(std::sin(0.5f * kPi * t), t, std::clamp(s.tip, 0.0f, 1.0f));
    }
    const vec3 across = glm::normalize(glm::cross(axis, radial));
    auto heading = [&](float u) {
        const float th = (s.baseAngle + (s.tipAngle - s.baseAngle) * u) * kDeg;
        return std::pair{std::cos(th) * axis + std::sin(th) * radial,
                         std::sin(th) * axis - std::cos(th) * radial};
    };
    std::vector<vec3> centre(rows + 1);
    centre[0] = origin;
    for (unsigned i = 1; i <= rows; ++i)
        centre[i] = centre[i - 1] +
                    heading(0.5f * (us[i] + us[i - 1])).first * s.length * (us[i] - us[i - 1]);
    return gridMesh({rows, cols, false, false, true}, [&](unsigned i, unsigned j) {
        const float u = us[i];
        auto [dir, inner] = heading(u);
        vec3 side = across;
        if (s.twistDeg != 0.0f) {
            side = rotateAbout(side, dir, s.twistDeg * kDeg * u);
            inner = rotateAbout(inner, dir, s.twistDeg * kDeg * u);
        }
        const float v = i == rows ? 0.0f : -1.0f + 2.0f * float(j) / float(cols);
        const float half = s.width * petalHalfWidth(s, u);
        // Offsets toward the inner side grow with the square of the distance from the
        // midrib, relative to the widest half-width.
        const float q = v * half / (0.5f * s.width);
        const float rise = s.cupping * s.width * q * q +
                           s.wave * s.width * q * q * std::sin(2.0f * kPi * s.waves * u) +
                           s.lift * s.length;
        return centre[i] + side * (v * half) + inner * rise;
    });
}

Mesh sepalStar(int count, float x0, float r0, float length, float width, float baseAngle,
               float tipAngle, float phase, unsigned rows, unsigned cols) {
    Mesh m;
    PetalSpec s;
    s.length = length;
    s.width = width;
    s.widest = 0.3f;
    s.tip = 1.0f;
    s.claw = 0.55f;
    s.baseAngle = baseAngle;
    s.tipAngle = tipAngle;
    s.cupping = 0.08f;
    for (int k = 0; k < count; ++k) {
        const float az = phase + 2.0f * kPi * float(k) / float(count);
        s.lift = 0.002f * float(k % 2);
        m.append(petalMesh(s, vec3(x0, 0, 0) + radialDir(az) * r0, {1, 0, 0}, radialDir(az), rows,
                           cols));
    }
    return m;
}

}  // namespace plantarch::organs
