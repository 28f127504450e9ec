// The preview renderer: camera framing, shading and the pixel loop.

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "core/embree_api.h"
#include "core/embree_scene.h"
#include "core/math.h"
#include "core/parallel.h"
#include "plantarch/Error.h"
#include "render/render_internal.h"

namespace plantarch {

using render_detail::PixelSampler;
using render_detail::SceneData;

struct RenderScene::Impl {
    SceneData data;
};

namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();

// Angles of the render options in radians, rounded as (deg * pi) / 180 (radians() of
// core/math.h multiplies by a rounded pi / 180): the renderer's images keep their bytes.
float optionRadians(float deg) {
    return deg * kPi / 180.0f;
}

// ---- option checks ---------------------------------------------------------------------

template <class T>
void checkRange(const char* name, T value, T lo, T hi, const std::string& range) {
    if (!(value >= lo && value <= hi))
        throw Error("render option out of range",
                    {.parameter = name, .value = fmt::format("{}", value), .validRange = range});
}

void checkFinite(const char* name, const vec3& v) {
    if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z))
        throw Error("render option is not a finite vector", {.parameter = name});
}

void validate(const RenderOptions& o) {
    checkRange("width", o.width, 1, 16384, "1 to 16384");
    checkRange("height", o.height, 1, 16384, "1 to 16384");
    checkRange("camera.fovDeg", o.camera.fovDeg, 0.01f, 170.0f, "0.01 to 170");
    checkRange("camera.elevationDeg", o.camera.elevationDeg, -89.0f, 89.0f, "-89 to 89");
    checkRange("camera.margin", o.camera.margin, 0.0f, 0.9f, "0 to 0.9");
    checkRange("samplesPerPixel", o.samplesPerPixel, 1, 1024, "1 to 1024");
    checkRange("shadowSamples", o.shadowSamples, 0, 256, "0 to 256");
    checkRange("aoSamples", o.aoSamples, 0, 256, "0 to 256");
    checkRange("sunAngularRadiusDeg", o.sunAngularRadiusDeg, 0.0f, 45.0f, "0 to 45");
    checkRange("exposure", o.exposure, 0.0f, 1000.0f, "0 to 1000");
    checkRange("translucency", o.translucency, 0.0f, 1.0f, "0 to 1");
    checkRange("sunIntensity", o.sunIntensity, 0.0f, 1000.0f, "0 to 1000");
    checkRange("skyIntensity", o.skyIntensity, 0.0f, 1000.0f, "0 to 1000");
    checkRange("groundVariation", o.groundVariation, 0.0f, 1.0f, "0 to 1");
    checkRange("groundPatchSize", o.groundPatchSize, 0.001f, 1000.0f, "0.001 to 1000");
    checkFinite("groundColor", o.groundColor);
    checkFinite("skyZenithColor", o.skyZenithColor);
    checkFinite("skyHorizonColor", o.skyHorizonColor);
    checkFinite("camera.eye", o.camera.eye);
    checkFinite("camera.target", o.camera.target);
    checkFinite("camera.up", o.camera.up);
    checkFinite("sunDirection", o.sunDirection);
    if (glm::length(o.sunDirection) <= 0.0f)
        throw Error("render option must not be the zero vector", {.parameter = "sunDirection"});
    if (!o.camera.autoFrame && glm::length(o.camera.target - o.camera.eye) <= 0.0f)
        throw Error("camera eye and target coincide", {.parameter = "camera.eye"});
    if (const std::uint64_t rays = renderRayCount(o); rays > kMaxRenderRays)
        throw Error(
            fmt::format("a render of {} rays ({} x {} pixels, {} samples each{}) is too "
                        "large",
                        rays, o.width, o.height, o.samplesPerPixel,
                        o.mode == RenderMode::Shaded ? ", with their sun and sky rays" : ""),
            {.parameter = "samplesPerPixel",
             .value = std::to_string(o.samplesPerPixel),
             .validRange = fmt::format("at most {} rays in all", kMaxRenderRays)});
}

}  // namespace

RenderOptions cameraRaysOnly(const RenderOptions& options) {
    RenderOptions o = options;
    o.shadowSamples = 0;
    o.aoSamples = 0;
    return o;
}

std::uint64_t renderRayCount(const RenderOptions& o) {
    const std::uint64_t camera = std::uint64_t(std::max(o.width, 0)) *
                                 std::uint64_t(std::max(o.height, 0)) *
                                 std::uint64_t(std::max(o.samplesPerPixel, 0));
    if (o.mode != RenderMode::Shaded) return camera;
    return camera * (1 + std::uint64_t(std::max(o.shadowSamples, 0)) +
                     std::uint64_t(std::max(o.aoSamples, 0)));
}

namespace {

// ---- vectors ---------------------------------------------------------------------------

/// An orthonormal basis (t, b) perpendicular to the unit vector n (Duff et al. 2017).
void orthonormalBasis(const vec3& n, vec3& t, vec3& b) {
    const float sign = std::copysign(1.0f, n.z);
    const float a = -1.0f / (sign + n.z);
    const float c = n.x * n.y * a;
    t = vec3(1.0f + sign * n.x * n.x * a, sign * c, -sign * n.x);
    b = vec3(c, sign + n.y * n.y * a, -n.y);
}

/// Uniform direction inside the cone of half-angle with cosine cosMax around the unit axis.
vec3 sampleCone(const vec3& axis, float cosMax, float u1, float u2) {
    const float cosT = 1.0f - u1 * (1.0f - cosMax);
    const float sinT = std::sqrt(std::max(0.0f, 1.0f - cosT * cosT));
    const float phi = 2.0f * kPi * u2;
    vec3 t, b;
    orthonormalBasis(axis, t, b);
    return sinT * std::cos(phi) * t + sinT * std::sin(phi) * b + cosT * axis;
}

/// Cosine-weighted direction on the hemisphere around the unit normal n.
vec3 sampleCosine(const vec3& n, float u1, float u2) {
    const float r = std::sqrt(u1);
    const float phi = 2.0f * kPi * u2;
    vec3 t, b;
    orthonormalBasis(n, t, b);
    return r * std::cos(phi) * t + r * std::sin(phi) * b + std::sqrt(std::max(0.0f, 1.0f - u1)) * n;
}

AABB framedBox(const AABB& bounds) {
    if (!bounds.empty()) return bounds;
    AABB unit;
    unit.add(vec3(-0.5f, -0.5f, 0.0f));
    unit.add(vec3(0.5f, 0.5f, 1.0f));
    return unit;
}

/// Eye and target that fit the scene in the frame. For each image axis every point's
/// projection gives a pair of linear constraints in (distance, sideways offset); solving them
/// exactly puts the nearest point on the margin on both sides of the dominant axis. The
/// points are all visible vertices (the eight box corners for an empty scene), so the plant
/// itself, not its bounding box, fills the frame.
CameraFrame autoFrame(const SceneData& data, const Camera& cam, float aspect) {
    const float az = optionRadians(cam.azimuthDeg), el = optionRadians(cam.elevationDeg);
    const vec3 toEye(std::cos(el) * std::cos(az), std::cos(el) * std::sin(az), std::sin(el));
    const vec3 forward = -toEye;
    const vec3 worldUp(0.0f, 0.0f, 1.0f);
    const vec3 right = glm::normalize(glm::cross(forward, worldUp));
    const vec3 up = glm::cross(right, forward);
    const float scale = 1.0f - cam.margin;
    const float ty = std::tan(optionRadians(cam.fovDeg) * 0.5f) * scale;
    const float tx = ty * aspect;
    const AABB box = framedBox(data.bounds);
    const vec3 c = box.center();
    // Visits every framed point (serial: a few milliseconds for millions of vertices).
    auto forEachPoint = [&](auto&& f) {
        if (data.triangles == 0) {
            for (int i = 0; i < 8; ++i)
                f(vec3((i & 1) ? box.max.x : box.min.x, (i & 2) ? box.max.y : box.min.y,
                       (i & 4) ? box.max.z : box.min.z));
            return;
        }
        for (const auto& g : data.geometries)
            for (std::size_t i = 0; i < g.vertexCount; ++i)
                f(vec3(g.positions[3 * i], g.positions[3 * i + 1], g.positions[3 * i + 2]));
    };
    float ax = -kInf, bx = -kInf, ay = -kInf, by = -kInf, zmin = kInf;
    forEachPoint([&](const vec3& point) {
        const vec3 d = point - c;
        const float x = glm::dot(d, right), y = glm::dot(d, up), z = glm::dot(d, forward);
        ax = std::max(ax, x - tx * z);
        bx = std::max(bx, -x - tx * z);
        ay = std::max(ay, y - ty * z);
        by = std::max(by, -y - ty * z);
        zmin = std::min(zmin, z);
    });
    // Need tx*d + ox >= ax and tx*d - ox >= bx (likewise y): d >= (ax + bx) / (2 tx).
    float dist = std::max((ax + bx) / (2.0f * tx), (ay + by) / (2.0f * ty));
    const float radius = 0.5f * glm::length(box.extent());
    dist = std::max(dist, -zmin + 1e-2f * std::max(radius, 1e-6f));  // eye outside the scene
    float ox = 0.5f * (ax - bx), oy = 0.5f * (ay - by);
    // The offsets above centre the tight axis exactly; on the other axis the extreme points
    // may lie at different depths, so shift the camera sideways until their images are
    // symmetric: moving by delta moves a point at depth z by -delta / z in the image.
    struct Extreme {
        float value = -kInf, depth = 1.0f;
    };
    Extreme right_, left_, top_, bottom_;
    forEachPoint([&](const vec3& point) {
        const vec3 d = point - c;
        const float z = glm::dot(d, forward) + dist;
        if (z <= 0.0f) return;
        const float x = (glm::dot(d, right) - ox) / z, y = (glm::dot(d, up) - oy) / z;
        if (x > right_.value) right_ = {x, z};
        if (-x > left_.value) left_ = {-x, z};
        if (y > top_.value) top_ = {y, z};
        if (-y > bottom_.value) bottom_ = {-y, z};
    });
    auto recentre = [](const Extreme& hi, const Extreme& lo) {
        if (!std::isfinite(hi.value) || !std::isfinite(lo.value)) return 0.0f;
        return (hi.value - lo.value) / (1.0f / hi.depth + 1.0f / lo.depth);
    };
    ox += recentre(right_, left_);
    oy += recentre(top_, bottom_);
    const vec3 target = c + ox * right + oy * up;
    return {target - dist * forward, target, worldUp, cam.fovDeg};
}

// ---- shading ---------------------------------------------------------------------------

/// Everything the per-sample code needs, resolved once per render.
struct Setup {
    const SceneData* scene;
    RTCScene rtc;
    int width, height;
    vec3 eye, forward, right, up;  ///< right and up scaled to the image plane at distance 1
    bool ground;
    float groundZ;
    float fogStart, fogEnd;  ///< horizontal distances from the scene centre (m)
    vec2 sceneCenter;
    vec3 groundAlbedo;
    vec3 sun;
    float sunCosMax, sunIntensity;
    vec3 zenith, horizon;  ///< linear background colours
    float skyIntensity, exposure, translucency;
    int spp, shadowSamples, aoSamples;
    float eps;  ///< ray offset (m)
    float aoDistance;
    vec3 groundRadiance;  ///< ground as seen by ambient rays
    float groundVariation, groundPatch;
    std::uint64_t seed;
};

vec3 skyRadiance(const Setup& s, const vec3& dir) {
    const float h = std::clamp(dir.z, 0.0f, 1.0f);
    return glm::mix(s.horizon, s.zenith, std::sqrt(h));
}

vec3 background(const Setup& s, const vec3& dir) {
    if (dir.z >= 0.0f) return skyRadiance(s, dir);
    return s.horizon * 0.85f;  // below the horizon without a ground plane
}

/// Primary-ray hit: either a triangle (geom < 2) or the ground plane.
struct Hit {
    bool found = false;
    bool isGround = false;
    float t = kInf;
    unsigned geom = RTC_INVALID_GEOMETRY_ID, prim = 0;
    float u = 0, v = 0;
    vec3 ng{0.0f};
};

Hit intersect(const Setup& s, RTCIntersectContext& ictx, const vec3& org, const vec3& dir) {
    RTCRayHit rh = core::rayHit(org, dir, 0.0f, kInf);
    if (s.scene->triangles > 0) core::embree().rtcIntersect1(s.rtc, &ictx, &rh);
    Hit hit;
    if (rh.hit.geomID != RTC_INVALID_GEOMETRY_ID) {
        hit.found = true;
        hit.t = rh.ray.tfar;
        hit.geom = rh.hit.geomID;
        hit.prim = rh.hit.primID;
        hit.u = rh.hit.u;
        hit.v = rh.hit.v;
        hit.ng = vec3(rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z);
    }
    if (s.ground && dir.z < 0.0f && org.z > s.groundZ) {
        const float t = (s.groundZ - org.z) / dir.z;
        if (t < hit.t) {
            hit.found = true;
            hit.isGround = true;
            hit.t = t;
            hit.ng = vec3(0.0f, 0.0f, 1.0f);
        }
    }
    return hit;
}

bool occluded(const Setup& s, RTCIntersectContext& ictx, const vec3& org, const vec3& dir,
              float tfar) {
    if (s.scene->triangles == 0) return false;
    RTCRay ray = core::rayHit(org, dir, 0.0f, tfar).ray;
    core::embree().rtcOccluded1(s.rtc, &ictx, &ray);
    return ray.tfar < 0.0f;  // Embree sets tfar to -inf on a hit
}

/// Surface at a triangle hit: albedo, geometric and shading normals facing the viewer.
struct Surface {
    vec3 albedo;
    vec3 ng, ns;
    const render_detail::ObjectInfo* object = nullptr;
};

Surface triangleSurface(const Setup& s, const Hit& hit, const vec3& dir) {
    const render_detail::GeometryData& g = s.scene->geometries[hit.geom];
    const render_detail::ObjectInfo& obj = s.scene->objects[g.triangleObject[hit.prim]];
    Surface surf;
    surf.object = &obj;
    const std::uint32_t* tri = g.indices + 3 * std::size_t(hit.prim);
    const float w = 1.0f - hit.u - hit.v;
    if (obj.texture >= 0) {
        const vec2 uv = w * g.uvs[tri[0]] + hit.u * g.uvs[tri[1]] + hit.v * g.uvs[tri[2]];
        surf.albedo = s.scene->textures[std::size_t(obj.texture)].color(uv);
    } else {
        surf.albedo = obj.albedo;
    }
    vec3 ng = glm::normalize(hit.ng);
    if (glm::dot(ng, dir) > 0.0f) ng = -ng;  // two-sided: face the viewer
    surf.ng = ng;
    surf.ns = ng;
    if (!g.normals.empty()) {
        // Smooth only where every corner normal is within ~40 degrees of the face, so boxes
        // and sharp creases stay flat.
        const vec3 n0 = g.normals[tri[0]], n1 = g.normals[tri[1]], n2 = g.normals[tri[2]];
        constexpr float kCosSmooth = 0.766f;
        if (std::abs(glm::dot(n0, ng)) > kCosSmooth && std::abs(glm::dot(n1, ng)) > kCosSmooth &&
            std::abs(glm::dot(n2, ng)) > kCosSmooth) {
            vec3 ns = w * n0 + hit.u * n1 + hit.v * n2;
            if (glm::dot(ns, ng) < 0.0f) ns = -ns;
            const float len = glm::length(ns);
            if (len > 0.0f) surf.ns = ns / len;
        }
    }
    return surf;
}

/// Where one camera sample is in the pixel's sample sets. Sun and sky directions come from a
/// randomly shifted rank-1 lattice (Kronecker sequence on the golden ratio) over all the
/// pixel's rays, which spreads them far more evenly than independent random numbers.
struct SampleIndex {
    int index;      ///< camera sample, 0 .. spp-1
    vec2 sunShift;  ///< per-pixel random shifts
    vec2 skyShift;
};

vec2 latticePoint(int k, int count, vec2 shift) {
    constexpr float kGolden = 0.61803398875f;
    const float u = (float(k) + 0.5f) / float(count) + shift.x;
    const float v = float(k) * kGolden + shift.y;
    return {u - std::floor(u), v - std::floor(v)};
}

/// Light leaving a surface point toward the viewer (linear RGB).
vec3 shade(const Setup& s, RTCIntersectContext& ictx, const vec3& p, const Surface& surf,
           const SampleIndex& si) {
    // Sun: soft shadows from random points on the disc; the far side of a thin surface gets
    // the translucent share.
    vec3 light(0.0f);
    if (s.sun.z > -s.sunCosMax) {
        float sun = 0.0f;
        const int n = std::max(1, s.shadowSamples);
        for (int i = 0; i < n; ++i) {
            const vec2 u = latticePoint(si.index * n + i, s.spp * n, si.sunShift);
            const vec3 l = s.sunCosMax < 1.0f ? sampleCone(s.sun, s.sunCosMax, u.x, u.y) : s.sun;
            const float cg = glm::dot(surf.ng, l);
            const float cs = glm::dot(surf.ns, l);
            float weight = cg > 0.0f ? std::max(0.0f, cs) : s.translucency * std::max(0.0f, -cs);
            if (weight <= 0.0f) continue;
            if (s.shadowSamples > 0) {
                const vec3 org = p + (cg > 0.0f ? surf.ng : -surf.ng) * s.eps;
                if (occluded(s, ictx, org, l, kInf)) weight = 0.0f;
            }
            sun += weight;
        }
        light += vec3(s.sunIntensity * sun / float(n));
    }
    // Sky: cosine-weighted rays that escape see the sky or the ground's radiance.
    if (s.aoSamples > 0) {
        vec3 sky(0.0f);
        for (int i = 0; i < s.aoSamples; ++i) {
            const vec2 u =
                latticePoint(si.index * s.aoSamples + i, s.spp * s.aoSamples, si.skyShift);
            vec3 d = sampleCosine(surf.ns, u.x, u.y);
            const float dn = glm::dot(d, surf.ng);
            if (dn < 0.0f) d -= 2.0f * dn * surf.ng;  // keep it above the true surface
            if (occluded(s, ictx, p + surf.ng * s.eps, d, s.aoDistance)) continue;
            sky += d.z >= 0.0f ? s.skyIntensity * skyRadiance(s, d) : s.groundRadiance;
        }
        light += sky / float(s.aoSamples);
    } else {
        const float up = 0.5f + 0.5f * surf.ns.z;
        light +=
            glm::mix(s.groundRadiance, s.skyIntensity * glm::mix(s.horizon, s.zenith, 0.5f), up);
    }
    return surf.albedo * light;
}

/// A value in [-1, 1] hashed from a lattice point and the seed.
float latticeValue(std::int64_t i, std::int64_t j, std::uint64_t seed) {
    std::uint64_t h = seed * 0x9E3779B97F4A7C15ull ^ std::uint64_t(i) * 0xC2B2AE3D27D4EB4Full ^
                      std::uint64_t(j) * 0x165667B19E3779F9ull;
    h ^= h >> 33;
    h *= 0xFF51AFD7ED558CCDull;
    h ^= h >> 33;
    return float(h >> 40) / float(1 << 23) - 1.0f;
}

/// Smooth value noise in [-1, 1] at p (lattice units).
float valueNoise(vec2 p, std::uint64_t seed) {
    const double fx = std::floor(double(p.x)), fy = std::floor(double(p.y));
    const auto i = std::int64_t(fx), j = std::int64_t(fy);
    const float tx = float(double(p.x) - fx), ty = float(double(p.y) - fy);
    const float sx = tx * tx * (3.0f - 2.0f * tx), sy = ty * ty * (3.0f - 2.0f * ty);
    const float a = glm::mix(latticeValue(i, j, seed), latticeValue(i + 1, j, seed), sx);
    const float b = glm::mix(latticeValue(i, j + 1, seed), latticeValue(i + 1, j + 1, seed), sx);
    return glm::mix(a, b, sy);
}

/// The ground's albedo at p: patches of groundPatch metres with detail a quarter that size.
vec3 groundAlbedo(const Setup& s, const vec3& p) {
    if (s.groundVariation <= 0.0f) return s.groundAlbedo;
    const vec2 q = vec2(p) / s.groundPatch;
    const float n = 0.7f * valueNoise(q, s.seed) + 0.3f * valueNoise(4.0f * q, s.seed + 1);
    return s.groundAlbedo * std::max(0.0f, 1.0f + s.groundVariation * n);
}

/// Radiance along one camera ray.
vec3 traceCamera(const Setup& s, RTCIntersectContext& ictx, const vec3& dir,
                 const SampleIndex& si) {
    const Hit hit = intersect(s, ictx, s.eye, dir);
    if (!hit.found) return background(s, dir);
    const vec3 p = s.eye + hit.t * dir;
    if (hit.isGround) {
        Surface surf{groundAlbedo(s, p), vec3(0, 0, 1), vec3(0, 0, 1), nullptr};
        const float dist = glm::length(vec2(p) - s.sceneCenter);
        if (dist >= s.fogEnd) return s.horizon;
        const vec3 lit = shade(s, ictx, p, surf, si);
        const float f = std::clamp((dist - s.fogStart) / (s.fogEnd - s.fogStart), 0.0f, 1.0f);
        return glm::mix(lit, s.horizon, f * f * (3.0f - 2.0f * f));
    }
    return shade(s, ictx, p, triangleSurface(s, hit, dir), si);
}

std::array<std::uint8_t, 3> labelColor(const Setup& s, const Hit& hit, RenderMode mode) {
    if (!hit.found || hit.isGround) return {0, 0, 0};
    const render_detail::GeometryData& g = s.scene->geometries[hit.geom];
    const render_detail::ObjectInfo& obj = s.scene->objects[g.triangleObject[hit.prim]];
    if (mode == RenderMode::LabelObject) return objectLabelColor(obj.id);
    if (mode == RenderMode::Flat)
        return {render_detail::linearToSrgbByte(obj.albedo.x),
                render_detail::linearToSrgbByte(obj.albedo.y),
                render_detail::linearToSrgbByte(obj.albedo.z)};
    if (obj.organ == render_detail::kOrganOther) return organLabelColor("");
    return organLabelColors()[obj.organ].rgb;
}

Setup makeSetup(const SceneData& data, const RenderOptions& o, const CameraFrame& cam) {
    const AABB box = framedBox(data.bounds);
    const float radius = std::max(0.5f * glm::length(box.extent()), 1e-3f);

    Setup s{};
    s.scene = &data;
    s.rtc = data.scene;
    s.width = o.width;
    s.height = o.height;
    s.eye = cam.eye;
    const render_detail::CameraAxes axes = render_detail::cameraAxes(cam);
    s.forward = axes.forward;
    const float tanHalf = std::tan(optionRadians(cam.fovDeg) * 0.5f);
    const float aspect = float(o.width) / float(o.height);
    s.right = glm::normalize(glm::cross(s.forward, axes.worldUp)) * tanHalf * aspect;
    s.up = glm::normalize(glm::cross(glm::normalize(s.right), s.forward)) * tanHalf;
    s.ground = o.groundPlane;
    s.groundZ = box.min.z - 1e-4f * radius;  // just below, so a ground object wins
    s.sceneCenter = vec2(box.center());
    s.fogStart = 6.0f * radius;
    s.fogEnd = 40.0f * radius;
    s.groundAlbedo = render_detail::srgbToLinear(glm::clamp(o.groundColor, vec3(0.0f), vec3(1.0f)));
    s.sun = glm::normalize(o.sunDirection);
    s.sunCosMax = std::cos(optionRadians(o.sunAngularRadiusDeg));
    s.sunIntensity = o.sunIntensity;
    s.zenith = render_detail::srgbToLinear(glm::clamp(o.skyZenithColor, vec3(0.0f), vec3(1.0f)));
    s.horizon = render_detail::srgbToLinear(glm::clamp(o.skyHorizonColor, vec3(0.0f), vec3(1.0f)));
    s.skyIntensity = o.skyIntensity;
    s.exposure = o.exposure;
    s.translucency = o.translucency;
    s.spp = o.samplesPerPixel;
    s.shadowSamples = o.shadowSamples;
    s.aoSamples = o.aoSamples;
    s.eps = 2e-5f * radius + 1e-6f * glm::length(s.eye);
    s.aoDistance = radius;
    // The ground lit by the unoccluded sun and sky, as ambient rays see it.
    s.groundRadiance = s.groundAlbedo * (s.sunIntensity * std::max(0.0f, s.sun.z) +
                                         s.skyIntensity * glm::mix(s.horizon, s.zenith, 0.6f));
    s.groundVariation = o.groundVariation;
    s.groundPatch = o.groundPatchSize;
    s.seed = o.seed;
    return s;
}

}  // namespace

// ---- RenderScene -------------------------------------------------------------------------

RenderScene::RenderScene(const Context& context, const RenderSceneOptions& options)
    : impl_(std::make_unique<Impl>()) {
    render_detail::buildScene(impl_->data, context, options);
}

RenderScene::~RenderScene() = default;
RenderScene::RenderScene(RenderScene&&) noexcept = default;
RenderScene& RenderScene::operator=(RenderScene&&) noexcept = default;

const AABB& RenderScene::bounds() const {
    return impl_->data.bounds;
}
std::size_t RenderScene::triangleCount() const {
    return impl_->data.triangles;
}

CameraFrame RenderScene::camera(const RenderOptions& o) const {
    validate(o);
    const float aspect = float(o.width) / float(o.height);
    if (o.camera.autoFrame) return autoFrame(impl_->data, o.camera, aspect);
    return {o.camera.eye, o.camera.target, o.camera.up, o.camera.fovDeg};
}

Image RenderScene::render(const RenderOptions& o) const {
    const Setup s = makeSetup(impl_->data, o, camera(o));  // camera() validates
    Image image(o.width, o.height);
    const bool label = o.mode != RenderMode::Shaded;
    const int grid = std::max(1, int(std::sqrt(float(s.spp))));
    // Rows are rendered in bands so progress is reported from the calling thread between
    // parallel loops; the bands do not change any pixel.
    const int band = std::max(1, std::min(s.height, 64));
    for (int y0 = 0; y0 < s.height; y0 += band) {
        const int y1 = std::min(s.height, y0 + band);
        ParallelErrors errors;
#pragma omp parallel for schedule(dynamic, 1)
        for (int y = y0; y < y1; ++y) {
            errors.run(y, [&] {
                RTCIntersectContext ictx;
                rtcInitIntersectContext(&ictx);
                for (int x = 0; x < s.width; ++x) {
                    const std::size_t pixel =
                        std::size_t(y) * std::size_t(s.width) + std::size_t(x);
                    std::uint8_t* out = &image.rgb[pixel * 3];
                    auto direction = [&](float px, float py) {
                        const float sx = 2.0f * px / float(s.width) - 1.0f;
                        const float sy = 1.0f - 2.0f * py / float(s.height);
                        return glm::normalize(s.forward + sx * s.right + sy * s.up);
                    };
                    if (label) {
                        const vec3 dir = direction(float(x) + 0.5f, float(y) + 0.5f);
                        const auto c = labelColor(s, intersect(s, ictx, s.eye, dir), o.mode);
                        out[0] = c[0];
                        out[1] = c[1];
                        out[2] = c[2];
                        continue;
                    }
                    PixelSampler rng(s.seed, pixel);
                    SampleIndex si{0, vec2(rng.next(), rng.next()), vec2(rng.next(), rng.next())};
                    vec3 sum(0.0f);
                    for (int i = 0; i < s.spp; ++i) {
                        // Stratified on a grid x grid pattern; samples beyond it are uniform.
                        float jx = rng.next(), jy = rng.next();
                        if (i < grid * grid) {
                            jx = (float(i % grid) + jx) / float(grid);
                            jy = (float(i / grid) + jy) / float(grid);
                        }
                        si.index = i;
                        sum += traceCamera(s, ictx, direction(float(x) + jx, float(y) + jy), si);
                    }
                    const vec3 c = sum * (s.exposure / float(s.spp));
                    out[0] = render_detail::linearToSrgbByte(c.x);
                    out[1] = render_detail::linearToSrgbByte(c.y);
                    out[2] = render_detail::linearToSrgbByte(c.z);
                }
            });
        }
        errors.rethrow();
        if (o.progress) o.progress("rendering", double(y1) / double(s.height));
    }
    return image;
}

DepthImage RenderScene::renderDepth(const RenderOptions& o) const {
    SurfaceImage surfaces = renderSurfaces(o);
    DepthImage depth;
    depth.width = surfaces.width;
    depth.height = surfaces.height;
    depth.depth = std::move(surfaces.depth);
    return depth;
}

float RenderScene::hitDistance(const vec3& origin, const vec3& direction) const {
    if (impl_->data.triangles == 0) return kInf;
    RTCIntersectContext ictx;
    rtcInitIntersectContext(&ictx);
    RTCRayHit rh = core::rayHit(origin, direction, 0.0f, kInf);
    core::embree().rtcIntersect1(impl_->data.scene, &ictx, &rh);
    return rh.hit.geomID == RTC_INVALID_GEOMETRY_ID ? kInf : rh.ray.tfar;
}

SurfaceImage RenderScene::renderSurfaces(const RenderOptions& o) const {
    const Setup s = makeSetup(impl_->data, o, camera(cameraRaysOnly(o)));
    SurfaceImage out;
    out.width = o.width;
    out.height = o.height;
    const std::size_t n = std::size_t(o.width) * std::size_t(o.height);
    out.object.assign(n, 0);
    out.depth.assign(n, 0.0f);
    out.normal.assign(n, vec3(0.0f));
    const vec3 axis = glm::normalize(s.forward);
    ParallelErrors errors;
#pragma omp parallel for schedule(dynamic, 1)
    for (int y = 0; y < s.height; ++y) {
        errors.run(y, [&] {
            RTCIntersectContext ictx;
            rtcInitIntersectContext(&ictx);
            for (int x = 0; x < s.width; ++x) {
                const float sx = 2.0f * (float(x) + 0.5f) / float(s.width) - 1.0f;
                const float sy = 1.0f - 2.0f * (float(y) + 0.5f) / float(s.height);
                const vec3 dir = glm::normalize(s.forward + sx * s.right + sy * s.up);
                const Hit hit = intersect(s, ictx, s.eye, dir);
                if (!hit.found) continue;
                const std::size_t i = std::size_t(y) * std::size_t(s.width) + std::size_t(x);
                out.depth[i] = hit.t * glm::dot(dir, axis);
                if (hit.isGround) {
                    out.normal[i] = vec3(0.0f, 0.0f, 1.0f);
                    continue;
                }
                const Surface surf = triangleSurface(s, hit, dir);
                out.object[i] = surf.object->id + 1;
                out.normal[i] = surf.ns;
            }
        });
    }
    errors.rethrow();
    return out;
}

DepthImage renderDepth(const Context& context, const RenderOptions& options) {
    validate(cameraRaysOnly(options));
    return RenderScene(context, options.scene).renderDepth(options);
}

Image render(const Context& context, const RenderOptions& options) {
    validate(options);
    return RenderScene(context, options.scene).render(options);
}

}  // namespace plantarch
