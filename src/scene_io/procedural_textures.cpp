// Procedural leaf, bark and stem textures (procedural_textures.h). Every texel is a function
// of its coordinates and the inputs alone (hashed lattice noise, no random streams), so rows
// are computed in parallel with the same bytes for any thread count.

#include "scene_io/procedural_textures.h"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace plantarch::io {

namespace proctex {

constexpr float kTwoPi = 6.28318530717958647692f;

std::uint32_t mixBits(std::uint32_t h) {
    h ^= h >> 16;
    h *= 0x7feb352du;
    h ^= h >> 15;
    h *= 0x846ca68bu;
    h ^= h >> 16;
    return h;
}

// A value in [0, 1) for a lattice point.
float latticeValue(std::int32_t x, std::int32_t y, std::uint32_t seed) {
    const std::uint32_t h = mixBits(std::uint32_t(x) * 0x8da6b343u ^
                                    std::uint32_t(y) * 0xd8163841u ^ mixBits(seed + 0x9e3779b9u));
    return float(h >> 8) * (1.0f / 16777216.0f);
}

std::int32_t wrapIndex(std::int32_t i, std::int32_t period) {
    if (period <= 0) return i;
    const std::int32_t r = i % period;
    return r < 0 ? r + period : r;
}

// Smooth value noise in [0, 1); periodic over `px` x `py` lattice cells when they are > 0.
float valueNoise(float x, float y, std::int32_t px, std::int32_t py, std::uint32_t seed) {
    const float fx = std::floor(x), fy = std::floor(y);
    const auto ix = std::int32_t(fx), iy = std::int32_t(fy);
    float tx = x - fx, ty = y - fy;
    tx = tx * tx * (3.0f - 2.0f * tx);
    ty = ty * ty * (3.0f - 2.0f * ty);
    const std::int32_t x0 = wrapIndex(ix, px), x1 = wrapIndex(ix + 1, px);
    const std::int32_t y0 = wrapIndex(iy, py), y1 = wrapIndex(iy + 1, py);
    const float a = latticeValue(x0, y0, seed), b = latticeValue(x1, y0, seed);
    const float c = latticeValue(x0, y1, seed), d = latticeValue(x1, y1, seed);
    return (a + (b - a) * tx) + ((c + (d - c) * tx) - (a + (b - a) * tx)) * ty;
}

// Fractal sum of `octaves` noises, each twice the frequency (and period) of the last; 0..1.
float fbm(float x, float y, std::int32_t px, std::int32_t py, int octaves, std::uint32_t seed) {
    float sum = 0.0f, amplitude = 0.5f, norm = 0.0f;
    for (int o = 0; o < octaves; ++o) {
        sum += amplitude * valueNoise(x, y, px, py, seed + std::uint32_t(o) * 7919u);
        norm += amplitude;
        x *= 2.0f;
        y *= 2.0f;
        px *= 2;
        py *= 2;
        amplitude *= 0.5f;
    }
    return sum / norm;
}

// Distance to the nearest cell border of a Voronoi pattern (F2 - F1 over 2), in cell units.
float cellBorder(float x, float y, std::uint32_t seed) {
    const float fx = std::floor(x), fy = std::floor(y);
    float f1 = 1e9f, f2 = 1e9f;
    for (int j = -1; j <= 1; ++j)
        for (int i = -1; i <= 1; ++i) {
            const auto cx = std::int32_t(fx) + i, cy = std::int32_t(fy) + j;
            const float px = float(cx) + 0.15f + 0.7f * latticeValue(cx, cy, seed);
            const float py = float(cy) + 0.15f + 0.7f * latticeValue(cx, cy, seed ^ 0x5bd1e995u);
            const float d = std::sqrt((px - x) * (px - x) + (py - y) * (py - y));
            if (d < f1) {
                f2 = f1;
                f1 = d;
            } else if (d < f2) {
                f2 = d;
            }
        }
    return 0.5f * (f2 - f1);
}

// As cellBorder, periodic over `px` x `py` cells; `cell` receives a value in [0, 1) of the
// nearest cell (the same for every point of it).
float cellBorderPeriodic(float x, float y, std::int32_t px, std::int32_t py, std::uint32_t seed,
                         float& cell) {
    const float fx = std::floor(x), fy = std::floor(y);
    float f1 = 1e9f, f2 = 1e9f;
    for (int j = -1; j <= 1; ++j)
        for (int i = -1; i <= 1; ++i) {
            const auto cx = std::int32_t(fx) + i, cy = std::int32_t(fy) + j;
            const std::int32_t wx = wrapIndex(cx, px), wy = wrapIndex(cy, py);
            const float ox = float(cx) + 0.1f + 0.8f * latticeValue(wx, wy, seed);
            const float oy = float(cy) + 0.1f + 0.8f * latticeValue(wx, wy, seed ^ 0x5bd1e995u);
            const float d = std::sqrt((ox - x) * (ox - x) + (oy - y) * (oy - y));
            if (d < f1) {
                f2 = f1;
                f1 = d;
                cell = latticeValue(wx, wy, seed ^ 0x68e31da4u);
            } else if (d < f2) {
                f2 = d;
            }
        }
    return 0.5f * (f2 - f1);
}

float smoothStep(float edge0, float edge1, float x) {
    const float t = std::clamp((x - edge0) / (edge1 - edge0), 0.0f, 1.0f);
    return t * t * (3.0f - 2.0f * t);
}

// A vein's profile: 1 on its line, falling smoothly to 0 at distance `width`.
float veinProfile(float distance, float width) {
    return 1.0f - smoothStep(0.0f, width, distance);
}

std::uint8_t toByte(float v) {
    return std::uint8_t(std::clamp(v, 0.0f, 1.0f) * 255.0f + 0.5f);
}

// Tangent-space normals and the height field's pixel slopes: `strength` turns height per
// texel into slope. Wraps at the borders when `wrap`, else clamps.
void normalsFromHeight(const std::vector<float>& height, int n, float strength, bool wrap,
                       std::vector<std::uint8_t>& normal) {
    normal.assign(std::size_t(n) * std::size_t(n) * 3, 0);
    auto at = [&](int i, int j) {
        if (wrap) {
            i = (i + n) % n;
            j = (j + n) % n;
        } else {
            i = std::clamp(i, 0, n - 1);
            j = std::clamp(j, 0, n - 1);
        }
        return height[std::size_t(j) * std::size_t(n) + std::size_t(i)];
    };
#pragma omp parallel for schedule(static)
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            const float dhdu = 0.5f * (at(i + 1, j) - at(i - 1, j));
            const float dhdv = 0.5f * (at(i, j - 1) - at(i, j + 1));  // row 0 is v = 1
            vec3 nrm(-dhdu * strength, -dhdv * strength, 1.0f);
            nrm = glm::normalize(nrm);
            std::uint8_t* out = &normal[(std::size_t(j) * std::size_t(n) + std::size_t(i)) * 3];
            out[0] = toByte(0.5f + 0.5f * nrm.x);
            out[1] = toByte(0.5f + 0.5f * nrm.y);
            out[2] = toByte(0.5f + 0.5f * nrm.z);
        }
}

// Chamfer distance (in texels) from each texel inside the mask to the nearest texel outside
// it (or the image border); 0 outside.
std::vector<float> distanceInside(const std::vector<std::uint8_t>& mask, int n) {
    const float big = 1e9f;
    std::vector<float> d(std::size_t(n) * std::size_t(n));
    for (std::size_t k = 0; k < d.size(); ++k) d[k] = mask[k] ? big : 0.0f;
    auto get = [&](int i, int j) {
        if (i < 0 || j < 0 || i >= n || j >= n) return 0.0f;
        return d[std::size_t(j) * std::size_t(n) + std::size_t(i)];
    };
    constexpr float a = 1.0f, b = 1.41421356f;
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            float& v = d[std::size_t(j) * std::size_t(n) + std::size_t(i)];
            if (v == 0.0f) continue;
            v = std::min({v, get(i - 1, j) + a, get(i, j - 1) + a, get(i - 1, j - 1) + b,
                          get(i + 1, j - 1) + b});
        }
    for (int j = n - 1; j >= 0; --j)
        for (int i = n - 1; i >= 0; --i) {
            float& v = d[std::size_t(j) * std::size_t(n) + std::size_t(i)];
            if (v == 0.0f) continue;
            v = std::min({v, get(i + 1, j) + a, get(i, j + 1) + a, get(i + 1, j + 1) + b,
                          get(i - 1, j + 1) + b});
        }
    return d;
}

// The leaf's vein strengths at one point of leaf space (x along the midrib 0..1, y across,
// the margin near |y| = halfWidth): midrib, lateral (or parallel) veins and the fine network.
struct Veins {
    float midrib = 0.0f, lateral = 0.0f, fine = 0.0f;
};

struct VeinLayout {
    float halfWidth;
    float texel;         // a texel's size in leaf units (the larger of its two sides)
    bool parallel;       // parallel venation (narrow blades)
    int laterals;        // lateral veins a side (pinnate) or veins a half (parallel)
    float slope0, bend;  // pinnate: x = x0 + slope0 |y| + bend |y|^2
    std::uint32_t seed;
};

Veins veinsAt(const VeinLayout& L, float x, float y) {
    Veins v;
    const float ay = std::abs(y);
    const float across = std::clamp(ay / L.halfWidth, 0.0f, 1.5f);
    const float midWidth =
        std::max(L.halfWidth * (L.parallel ? 0.06f : 0.03f + 0.045f * (1.0f - x)), 1.3f * L.texel);
    v.midrib = veinProfile(ay, midWidth) * (1.0f - smoothStep(0.9f, 1.02f, x));
    if (L.parallel) {
        const float spacing = L.halfWidth / float(L.laterals);
        const float t = ay / spacing;
        const float d = std::abs(t - std::round(t)) * spacing;
        const float w = std::max(0.07f * spacing, 0.8f * L.texel);
        const float minor = std::abs(t * 4.0f - std::round(t * 4.0f)) * spacing / 4.0f;
        v.lateral = veinProfile(d, w) * (1.0f - smoothStep(0.93f, 1.0f, across));
        v.fine = 0.5f * veinProfile(minor, std::max(0.05f * spacing, 0.6f * L.texel));
        return v;
    }
    const int side = y < 0.0f ? 0 : 1;
    const float spacing = 1.0f / float(L.laterals);
    const float offset = side ? 0.38f * spacing : 0.0f;
    const float x0 = x - L.slope0 * ay - L.bend * ay * ay;
    const float t = (x0 - offset) / spacing;
    const float k = std::round(t);
    const float jitter = 0.28f * (latticeValue(std::int32_t(k), side, L.seed ^ 0x27d4eb2du) - 0.5f);
    const float origin = offset + (k + jitter) * spacing;
    if (origin > 0.03f && origin < 0.93f) {
        const float slope = L.slope0 + 2.0f * L.bend * ay;
        const float d = std::abs(t - (k + jitter)) * spacing / std::sqrt(1.0f + slope * slope);
        const float w = std::max((0.0045f + 0.004f * (1.0f - origin)) * (1.0f - 0.55f * across),
                                 0.9f * L.texel);
        v.lateral = veinProfile(d, w) * (1.0f - smoothStep(0.82f, 1.0f, across));
    }
    const float cells = 38.0f;
    const float border = cellBorder(x * cells, y * cells, L.seed ^ 0x165667b1u) / cells;
    v.fine = veinProfile(border, std::max(0.0011f, 0.6f * L.texel)) * 0.8f;
    return v;
}

}  // namespace proctex

const char* surfaceKindName(SurfaceKind kind) {
    switch (kind) {
        case SurfaceKind::Leaf:
            return "leaf";
        case SurfaceKind::Bark:
            return "bark";
        case SurfaceKind::Stem:
            return "stem";
        case SurfaceKind::Fruit:
            return "fruit";
        case SurfaceKind::Flower:
            return "flower";
        case SurfaceKind::Other:
            break;
    }
    return "other";
}

SurfaceFactors surfaceFactors(SurfaceKind kind) {
    switch (kind) {
        case SurfaceKind::Leaf:
            return {0.55f, 0.0f};
        case SurfaceKind::Bark:
            return {0.9f, 0.0f};
        case SurfaceKind::Stem:
            return {0.6f, 0.0f};
        case SurfaceKind::Fruit:
            return {0.3f, 0.0f};
        case SurfaceKind::Flower:
            return {0.55f, 0.0f};
        case SurfaceKind::Other:
            break;
    }
    return {0.8f, 0.0f};
}

std::uint64_t fnv1a(const void* data, std::size_t bytes, std::uint64_t hash) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < bytes; ++i) {
        hash ^= p[i];
        hash *= 1099511628211ull;
    }
    return hash;
}

TextureMaps leafTextureMaps(const LeafTextureInput& in) {
    using namespace proctex;
    const int n = in.size;
    const std::size_t texels = std::size_t(n) * std::size_t(n);
    const float aspect = std::clamp(in.aspect, 0.05f, 5.0f);
    const auto seed = std::uint32_t(in.seed ^ (in.seed >> 32));
    const bool masked = in.mask.size() == texels;

    VeinLayout L{};
    L.halfWidth = 0.5f * aspect;
    L.texel = std::max(1.0f, aspect) / float(n);
    L.parallel = in.parallelVeins;
    L.laterals = L.parallel ? 8 + int(mixBits(seed) % 4u) : 7 + int(mixBits(seed) % 4u);
    L.slope0 = 0.75f + 0.25f * latticeValue(1, 2, seed);
    L.bend = 0.9f / L.halfWidth;
    L.seed = seed;

    std::vector<float> inside;  // texels to the outline
    if (masked) inside = distanceInside(in.mask, n);
    const float rimTexels = std::max(1.5f, 0.018f * float(n));

    TextureMaps maps;
    maps.size = n;
    maps.baseColor.resize(texels * 4);
    maps.orm.resize(texels * 3);
    std::vector<float> height(texels);
    const vec3 base = glm::clamp(in.color, vec3(0.0f), vec3(1.0f));
    const vec3 veinColor = glm::min(base * 1.22f + vec3(0.10f, 0.11f, 0.03f), vec3(1.0f));
    const vec3 rimColor = base * vec3(0.78f, 0.80f, 0.62f) + vec3(0.05f, 0.04f, 0.0f);
    const vec3 yellowish = glm::min(base * vec3(1.12f, 1.08f, 0.72f), vec3(1.0f));

#pragma omp parallel for schedule(static)
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            const std::size_t k = std::size_t(j) * std::size_t(n) + std::size_t(i);
            const float u = (float(i) + 0.5f) / float(n);
            const float v = 1.0f - (float(j) + 0.5f) / float(n);
            const float x = u, y = (v - 0.5f) * aspect;
            const Veins veins = veinsAt(L, x, y);
            const float vein = std::max(
                {veins.midrib, (L.parallel ? 0.4f : 0.85f) * veins.lateral, 0.4f * veins.fine});

            const float mottle = fbm(x * 7.0f, y * 7.0f, 0, 0, 4, seed ^ 0x1234567u);
            const float hue = fbm(x * 3.0f + 11.0f, y * 3.0f, 0, 0, 3, seed ^ 0x89abcdeu);
            const float grain = latticeValue(i, j, seed ^ 0x2545f491u);
            vec3 c = base * (0.86f + 0.30f * mottle);
            c = glm::mix(c, yellowish, 0.45f * smoothStep(0.45f, 0.8f, hue));
            c = glm::mix(c, veinColor, 0.8f * vein);
            float rim = 0.0f;
            if (masked) rim = 1.0f - smoothStep(0.0f, rimTexels, inside[k]);
            c = glm::mix(c, rimColor, 0.45f * rim);
            c *= 0.97f + 0.06f * grain;

            std::uint8_t* rgba = &maps.baseColor[k * 4];
            rgba[0] = toByte(c.r);
            rgba[1] = toByte(c.g);
            rgba[2] = toByte(c.b);
            rgba[3] = masked && in.mask[k] == 0 ? 0 : 255;

            const float roughness = 0.46f + 0.16f * (mottle - 0.5f) + 0.12f * vein + 0.1f * rim;
            std::uint8_t* orm = &maps.orm[k * 3];
            orm[0] = toByte(1.0f - 0.25f * veins.midrib * 0.5f);
            orm[1] = toByte(roughness);
            orm[2] = 0;
            // The upper side's veins run in grooves between slightly domed areoles.
            height[k] =
                -(1.0f * veins.midrib + 0.7f * veins.lateral + 0.25f * veins.fine) + 0.25f * mottle;
        }
    if (masked)
        for (std::size_t k = 0; k < texels; ++k) maps.hasAlpha |= in.mask[k] == 0;
    normalsFromHeight(height, n, 1.6f * float(n) / 512.0f, false, maps.normal);
    return maps;
}

TextureMaps barkTextureMaps(vec3 color, std::uint64_t seed64, int n, bool stem) {
    using namespace proctex;
    const std::size_t texels = std::size_t(n) * std::size_t(n);
    const auto seed = std::uint32_t(seed64 ^ (seed64 >> 32));
    const vec3 base = glm::clamp(color, vec3(0.0f), vec3(1.0f));
    // Green stems get fine striations; brown ones fissured bark; in between, a blend.
    const float green =
        stem ? 1.0f
             : std::clamp(5.0f * (base.g - std::max(base.r, base.b)) / std::max(base.g, 1e-3f),
                          0.0f, 1.0f);
    const float luminance = 0.3f * base.r + 0.59f * base.g + 0.11f * base.b;
    const int stripes = 12 + int(mixBits(seed) % 8u);

    TextureMaps maps;
    maps.size = n;
    maps.baseColor.resize(texels * 4);
    maps.orm.resize(texels * 3);
    std::vector<float> height(texels);
#pragma omp parallel for schedule(static)
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            const std::size_t k = std::size_t(j) * std::size_t(n) + std::size_t(i);
            const float u = (float(i) + 0.5f) / float(n);
            const float v = 1.0f - (float(j) + 0.5f) / float(n);
            // Woody: plates, longer than wide, split by a network of fissures (cells of a
            // Voronoi pattern stretched along the stem), each plate its own shade, with fine
            // fibres along it and a grey cast on the lighter ones.
            const float warp = fbm(u * 4.0f, v * 4.0f, 4, 4, 3, seed ^ 0x51ed270bu);
            const float warp2 = fbm(u * 5.0f, v * 3.0f, 5, 3, 3, seed ^ 0x2f4a7c15u);
            float cell = 0.0f;
            const float border = cellBorderPeriodic(u * 11.0f + 1.1f * (warp - 0.5f),
                                                    v * 2.0f + 0.5f * (warp2 - 0.5f), 11, 2,
                                                    seed ^ 0x1b873593u, cell);
            const float plate = smoothStep(0.01f + 0.05f * warp2, 0.16f, border);
            const float rough = fbm(u * 24.0f, v * 12.0f, 24, 12, 3, seed ^ 0x6c8e9cf5u);
            const float fibre = fbm(u * 64.0f, v * 4.0f, 64, 4, 2, seed ^ 0x3c6ef372u);
            const vec3 top = base * (0.6f + 0.3f * cell + 0.45f * rough + 0.3f * fibre);
            vec3 wood = glm::mix(base * (0.3f + 0.1f * rough), top, plate);
            wood =
                glm::mix(wood, vec3(luminance * 1.1f), 0.3f * plate * smoothStep(0.6f, 0.9f, cell));
            const float woodHeight =
                0.8f * plate * (0.7f + 0.3f * cell) + 0.2f * rough + 0.1f * fibre;
            // Green: fine ridges along the stem, slightly wavy, and a faint mottle.
            const float wave = 0.25f * fbm(u * 3.0f, v * 3.0f, 3, 3, 2, seed ^ 0x7f4a7c15u);
            const float stripe = 0.5f + 0.5f * std::sin(kTwoPi * (u * float(stripes) + wave));
            const float mottle = fbm(u * 6.0f, v * 6.0f, 6, 6, 3, seed ^ 0x2c1b3c6du);
            vec3 herb = base * (0.9f + 0.14f * stripe + 0.12f * (mottle - 0.5f));
            herb = glm::mix(herb, glm::min(base * 1.25f + vec3(0.05f), vec3(1.0f)),
                            0.25f * smoothStep(0.8f, 1.0f, stripe));
            const float herbHeight = 0.35f * stripe + 0.1f * mottle;

            const vec3 c = glm::mix(wood, herb, green) *
                           (0.97f + 0.06f * latticeValue(i, j, seed ^ 0x2545f491u));
            std::uint8_t* rgba = &maps.baseColor[k * 4];
            rgba[0] = toByte(c.r);
            rgba[1] = toByte(c.g);
            rgba[2] = toByte(c.b);
            rgba[3] = 255;
            const float roughness =
                glm::mix(0.8f + 0.2f * (1.0f - plate), 0.5f + 0.1f * mottle, green);
            std::uint8_t* orm = &maps.orm[k * 3];
            orm[0] = toByte(glm::mix(0.55f + 0.45f * plate, 1.0f, green));
            orm[1] = toByte(roughness);
            orm[2] = 0;
            height[k] = glm::mix(woodHeight, herbHeight, green);
        }
    normalsFromHeight(height, n, glm::mix(3.0f, 1.2f, green) * float(n) / 512.0f, true,
                      maps.normal);
    return maps;
}

void rasterizeUVTriangles(std::span<const vec2> uvs, std::span<const std::uint32_t> indices,
                          int size, std::vector<std::uint8_t>& mask) {
    const std::size_t texels = std::size_t(size) * std::size_t(size);
    if (mask.size() != texels) mask.assign(texels, 0);
    const float n = float(size);
    for (std::size_t t = 0; t + 2 < indices.size(); t += 3) {
        if (indices[t] >= uvs.size() || indices[t + 1] >= uvs.size() ||
            indices[t + 2] >= uvs.size())
            continue;
        vec2 p[3];
        for (int c = 0; c < 3; ++c) {
            const vec2 uv = uvs[indices[t + std::size_t(c)]];
            p[c] = vec2(uv.x * n, (1.0f - uv.y) * n);  // texel units, row 0 at v = 1
            if (!std::isfinite(p[c].x) || !std::isfinite(p[c].y)) p[c] = vec2(-1e6f);
        }
        const float area =
            (p[1].x - p[0].x) * (p[2].y - p[0].y) - (p[2].x - p[0].x) * (p[1].y - p[0].y);
        const float orient = area < 0.0f ? -1.0f : 1.0f;
        const int i0 = std::max(0, int(std::floor(std::min({p[0].x, p[1].x, p[2].x}))));
        const int i1 = std::min(size - 1, int(std::floor(std::max({p[0].x, p[1].x, p[2].x}))));
        const int j0 = std::max(0, int(std::floor(std::min({p[0].y, p[1].y, p[2].y}))));
        const int j1 = std::min(size - 1, int(std::floor(std::max({p[0].y, p[1].y, p[2].y}))));
        if (i0 > i1 || j0 > j1) continue;
        // Edge functions, each grown by half a texel's reach so any texel the edge crosses
        // counts (conservative rasterization).
        float a[3], b[3], c[3];
        for (int e = 0; e < 3; ++e) {
            const vec2 q = p[e], r = p[(e + 1) % 3];
            a[e] = orient * (q.y - r.y);
            b[e] = orient * (r.x - q.x);
            c[e] = orient * (q.x * r.y - q.y * r.x) + 0.5f * (std::abs(a[e]) + std::abs(b[e]));
        }
        for (int j = j0; j <= j1; ++j)
            for (int i = i0; i <= i1; ++i) {
                const float x = float(i) + 0.5f, y = float(j) + 0.5f;
                if (a[0] * x + b[0] * y + c[0] >= 0.0f && a[1] * x + b[1] * y + c[1] >= 0.0f &&
                    a[2] * x + b[2] * y + c[2] >= 0.0f)
                    mask[std::size_t(j) * std::size_t(size) + std::size_t(i)] = 255;
            }
    }
}

}  // namespace plantarch::io
