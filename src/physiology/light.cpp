// PAR on every triangle of a scene, by ray tracing (docs/physiology.md):
// - direct: rays from points spread over each triangle toward the sun; the share that
//   escapes is the triangle's sunlit share;
// - diffuse: the sky as the 145 patches of Tregenza (1987), each of uniform radiance (an
//   isotropic sky: radiance D / pi for a horizontal irradiance D); each triangle samples the
//   patches in proportion to their solid angle times the cosine to its normal, so the rays
//   go where the light comes from, and the share of each face's sky that is open is kept
//   (it depends on the geometry alone);
// - one order of scattering: every surface returns reflectance x the light on a face to
//   that face and transmittance x it to the other, evenly in all directions (Lambertian);
//   each triangle gathers that light over the whole sphere, sampled as for the sky.
// Each triangle's rays come from a random stream of its own (the seed and its index), so the
// result does not depend on the number of threads.
// Sampled (LightOptions::samplesPerObject): the rays are cast from a few triangles of each
// object, drawn in proportion to their area, and the light is kept per object (the object's
// faces are what the scattering rays meet). The "elements" below are then the objects; in
// the full mode each triangle is its own sample and element.

#include "plantarch/Light.h"

#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <mutex>
#include <numbers>
#include <optional>
#include <string>

#include "core/embree_scene.h"
#include "core/parallel.h"
#include "core/value_text.h"
#include "plantarch/Error.h"
#include "plantarch/Random.h"

namespace plantarch {

// Named, not anonymous: LightModel::Impl holds these types.
namespace light_internal {

constexpr double kPiL = std::numbers::pi;

enum class Surface : std::uint8_t { Leaf, Stem, FlowerFruit, Ground, Other };

Surface surfaceOf(const Context& ctx, ObjectID id) {
    const std::optional<DataValue> v = ctx.objectData(id, "organ");
    const std::string* organ = v ? std::get_if<std::string>(&*v) : nullptr;
    if (!organ) return Surface::Other;
    if (*organ == "leaf") return Surface::Leaf;
    if (*organ == "internode" || *organ == "petiole" || *organ == "peduncle") return Surface::Stem;
    if (*organ == "flower_closed" || *organ == "flower_open" || *organ == "fruit")
        return Surface::FlowerFruit;
    if (*organ == "ground") return Surface::Ground;
    return Surface::Other;
}

// One sky patch: a band of altitude [alt0, alt1] and azimuth [az0, az1], radians, of solid
// angle omega; `below` mirrors it under the horizon (for light coming from below).
struct Patch {
    double alt0, alt1, az0, az1, omega;
    bool below;
    vec3 centre;
};

vec3 patchDirection(const Patch& p, double u, double v) {
    // Uniform over the patch's solid angle: uniform in sin(altitude) and in azimuth.
    const double s = std::sin(p.alt0) + u * (std::sin(p.alt1) - std::sin(p.alt0));
    const double c = std::sqrt(std::max(0.0, 1.0 - s * s));
    const double az = p.az0 + v * (p.az1 - p.az0);
    return vec3(float(c * std::sin(az)), float(c * std::cos(az)), float(p.below ? -s : s));
}

// Tregenza's division: bands 12 degrees high from the horizon, of 30, 30, 24, 24, 18, 12 and
// 6 patches, and a cap of one patch from 84 degrees to the zenith; mirrored below with
// `withBelow`.
std::vector<Patch> tregenzaPatches(bool withBelow) {
    static const int counts[8] = {30, 30, 24, 24, 18, 12, 6, 1};
    std::vector<Patch> patches;
    for (int half = 0; half < (withBelow ? 2 : 1); ++half)
        for (int band = 0; band < 8; ++band) {
            const double alt0 = band * 12.0 * kPiL / 180.0;
            const double alt1 = band == 7 ? kPiL / 2 : (band + 1) * 12.0 * kPiL / 180.0;
            for (int j = 0; j < counts[band]; ++j) {
                Patch p;
                p.alt0 = alt0;
                p.alt1 = alt1;
                p.az0 = 2 * kPiL * j / counts[band];
                p.az1 = 2 * kPiL * (j + 1) / counts[band];
                p.omega = 2 * kPiL * (std::sin(alt1) - std::sin(alt0)) / counts[band];
                p.below = half == 1;
                p.centre = patchDirection(p, 0.5, 0.5);
                patches.push_back(p);
            }
        }
    return patches;
}

// A point spread over triangle (a, b, c): sample k of n, stratified along one barycentric
// direction.
vec3 trianglePoint(const vec3& a, const vec3& b, const vec3& c, unsigned k, unsigned n, Rng& rng) {
    const float u = (float(k) + rng.uniform01()) / float(n);
    const float v = rng.uniform01();
    const float su = std::sqrt(u);
    return (1.0f - su) * a + su * (1.0f - v) * b + su * v * c;
}

// Draws patch indices in proportion to `weights` (cumulative in `cdf`), stratified: sample k
// of n lands in [k/n, (k+1)/n) of the total.
std::size_t drawPatch(const std::vector<double>& cdf, unsigned k, unsigned n, Rng& rng) {
    const double u = (double(k) + rng.uniform01d()) / double(n) * cdf.back();
    const auto it = std::upper_bound(cdf.begin(), cdf.end(), u);
    return std::min<std::size_t>(std::size_t(it - cdf.begin()), cdf.size() - 1);
}

void checkOptics(const SurfaceOptics& o, const char* name) {
    if (!(o.reflectance >= 0.0f && o.transmittance >= 0.0f &&
          o.reflectance + o.transmittance <= 1.0f))
        throw Error(
            "optical properties out of range",
            {.parameter = std::string(name) + " reflectance, transmittance",
             .value = text::formatFloat(o.reflectance) + ", " + text::formatFloat(o.transmittance),
             .validRange = "each 0 to 1, their sum at most 1"});
}

void checkRays(unsigned n, const char* name, unsigned min) {
    if (n < min || n > 100000)
        throw Error("ray count out of range", {.parameter = name,
                                               .value = std::to_string(n),
                                               .validRange = std::to_string(min) + " to 100000"});
}

}  // namespace light_internal

using namespace light_internal;

struct LightModel::Impl {
    LightOptions options;
    std::vector<vec3> soup;  // three corners per triangle
    std::vector<vec3> normals;
    std::vector<float> areas;
    std::vector<PrimitiveID> primitives;
    std::vector<ObjectID> objects;
    std::vector<Surface> surfaces;
    RTCScene scene = nullptr;
    float epsilon = 1e-6f;
    std::vector<Patch> sky, sphere;
    mutable std::once_flag skyOnce;
    mutable std::vector<float> skyFront, skyBack;  // open sky per face, for a unit horizontal D
    mutable std::atomic<std::uint64_t> rays{0};
    // Sampled mode alone (empty otherwise): per sample its triangle and its share of its
    // object's mean; per object (element) its first sample and first triangle, each with one
    // past the last at the end; per triangle its object's index.
    bool sampled = false;
    std::vector<std::uint32_t> sampleTriangle;
    std::vector<double> sampleWeight;
    std::vector<std::uint32_t> sampleStart, triangleStart;
    std::vector<std::uint32_t> triangleObject;
    // Sampled mode: each sample's points for the sun's rays (directRays of them) and their
    // triangles. An object sampled from some of its triangles spreads its samples' points
    // over its whole area (stratified), so its sunlit share comes from that many places;
    // one with few triangles has them on each sample's triangle, as in the full mode.
    std::vector<vec3> directPoint;
    std::vector<std::uint32_t> directTriangle;

    std::size_t samples() const { return sampled ? sampleTriangle.size() : normals.size(); }
    std::size_t triangleOf(std::size_t s) const { return sampled ? sampleTriangle[s] : s; }
    std::size_t elements() const { return sampled ? triangleStart.size() - 1 : normals.size(); }
    std::size_t elementOf(std::size_t t) const { return sampled ? triangleObject[t] : t; }
    const SurfaceOptics& elementOptics(std::size_t e) const {
        return optics(sampled ? triangleStart[e] : e);
    }

    // Per-sample values as per-element ones: each object's weighted mean of its samples (the
    // values themselves in the full mode).
    template <class T>
    std::vector<T> perElement(std::vector<T> values) const {
        if (!sampled) return values;
        std::vector<T> out(elements());
        for (std::size_t e = 0; e < out.size(); ++e) {
            double sum = 0.0;
            for (std::size_t k = sampleStart[e]; k < sampleStart[e + 1]; ++k)
                sum += sampleWeight[k] * double(values[k]);
            out[e] = T(sum);
        }
        return out;
    }

    // The samples of each object: each of its triangles (weighted by area) when it has
    // `n` or fewer, else `n` drawn in proportion to area, stratified (sample k from the k-th
    // n-th of the object's area), each weighing 1 / n.
    void drawSamples(unsigned n) {
        const std::size_t count = normals.size();
        sampled = true;
        triangleObject.resize(count);
        sampleStart.assign(1, 0);
        triangleStart.assign(1, 0);
        std::vector<double> cumulative;
        for (std::size_t t0 = 0, t1 = 0; t0 < count; t0 = t1) {
            while (t1 < count && objects[t1] == objects[t0]) ++t1;
            const auto e = std::uint32_t(triangleStart.size() - 1);
            cumulative.clear();
            double total = 0.0;
            for (std::size_t t = t0; t < t1; ++t) {
                triangleObject[t] = e;
                total += areas[t];
                cumulative.push_back(total);
            }
            const unsigned rays = options.directRays;
            if (t1 - t0 <= n) {
                for (std::size_t t = t0; t < t1; ++t) {
                    Rng rng(options.seed ^ 0x5DEECE66DULL, sampleTriangle.size());
                    sampleTriangle.push_back(std::uint32_t(t));
                    sampleWeight.push_back(areas[t] / total);
                    for (unsigned k = 0; k < rays; ++k) {
                        directPoint.push_back(trianglePoint(soup[3 * t], soup[3 * t + 1],
                                                            soup[3 * t + 2], k, rays, rng));
                        directTriangle.push_back(std::uint32_t(t));
                    }
                }
            } else {
                Rng rng(options.seed ^ 0xA24BAED4963EE407ULL, objects[t0]);
                for (unsigned k = 0; k < n; ++k) {
                    const double u = (double(k) + rng.uniform01d()) / double(n) * total;
                    const auto it = std::upper_bound(cumulative.begin(), cumulative.end(), u);
                    const std::size_t j =
                        std::min<std::size_t>(std::size_t(it - cumulative.begin()), t1 - t0 - 1);
                    sampleTriangle.push_back(std::uint32_t(t0 + j));
                    sampleWeight.push_back(1.0 / double(n));
                }
                // The sun's points: n x rays strata of the object's area, sample k taking
                // strata k, k + n, ...
                for (unsigned k = 0; k < n; ++k)
                    for (unsigned r = 0; r < rays; ++r) {
                        const double u =
                            (double(r) * n + k + rng.uniform01d()) / (double(n) * rays) * total;
                        const auto it = std::upper_bound(cumulative.begin(), cumulative.end(), u);
                        const std::size_t t =
                            t0 + std::min<std::size_t>(std::size_t(it - cumulative.begin()),
                                                       t1 - t0 - 1);
                        directPoint.push_back(trianglePoint(soup[3 * t], soup[3 * t + 1],
                                                            soup[3 * t + 2], 0, 1, rng));
                        directTriangle.push_back(std::uint32_t(t));
                    }
            }
            triangleStart.push_back(std::uint32_t(t1));
            sampleStart.push_back(std::uint32_t(sampleTriangle.size()));
        }
    }

    const SurfaceOptics& optics(std::size_t i) const {
        switch (surfaces[i]) {
            case Surface::Leaf:
                return options.leaf;
            case Surface::Stem:
                return options.stem;
            case Surface::FlowerFruit:
                return options.flowerAndFruit;
            case Surface::Ground:
                return options.ground;
            case Surface::Other:
                break;
        }
        return options.other;
    }

    // Whether a ray from p along d leaves the scene without hitting anything.
    bool escapes(const vec3& p, const vec3& d) const {
        RTCIntersectContext ictx;
        rtcInitIntersectContext(&ictx);
        RTCRayHit rh = core::rayHit(p, d, 0.0f, std::numeric_limits<float>::infinity());
        core::embree().rtcOccluded1(scene, &ictx, &rh.ray);
        return rh.ray.tfar >= 0.0f;  // Embree sets tfar to -inf on a hit
    }

    // The triangle a ray from p along d hits first, or -1.
    long firstHit(const vec3& p, const vec3& d) const {
        RTCIntersectContext ictx;
        rtcInitIntersectContext(&ictx);
        RTCRayHit rh = core::rayHit(p, d, 0.0f, std::numeric_limits<float>::infinity());
        core::embree().rtcIntersect1(scene, &ictx, &rh);
        return rh.hit.geomID == RTC_INVALID_GEOMETRY_ID ? -1 : long(rh.hit.primID);
    }

    // Rays from sample i's triangle through the patches of `patches` (the sky's, or the whole
    // sphere's), drawn in proportion to each patch's solid angle x the cosine of its centre to
    // the triangle's normal: the light on a face is the quadrature sum over patches of
    // radiance x solid angle x cosine, with each patch's radiance sampled by rays through it
    // (jittered over the patch). Each calls sample(origin, direction, weight, onFront): the
    // radiance along it times `weight` is what it adds to that face's irradiance. The sums
    // are scaled so that a face seeing one radiance L over its whole hemisphere gets pi L.
    template <class Sample>
    void cast(std::size_t i, const std::vector<Patch>& patches, unsigned n, std::uint64_t pass,
              Sample&& sample) const {
        const std::size_t t = triangleOf(i);
        const vec3 nrm = normals[t];
        std::vector<double> cdf(patches.size());
        double total = 0.0;
        for (std::size_t p = 0; p < patches.size(); ++p) {
            total += patches[p].omega * std::abs(glm::dot(nrm, patches[p].centre));
            cdf[p] = total;
        }
        // Each face's whole hemisphere, over the sphere's patches, for the scale.
        double hemisphereFront = 0.0, hemisphereBack = 0.0;
        for (const Patch& q : sphere) {
            const double c = glm::dot(nrm, q.centre);
            (c >= 0.0 ? hemisphereFront : hemisphereBack) += q.omega * std::abs(c);
        }
        rays.fetch_add(n, std::memory_order_relaxed);
        if (!(total > 0.0)) return;
        Rng rng(options.seed ^ (pass * 0x9E3779B97F4A7C15ULL), i);
        const vec3& a = soup[3 * t];
        const vec3& b = soup[3 * t + 1];
        const vec3& c = soup[3 * t + 2];
        for (unsigned k = 0; k < n; ++k) {
            const std::size_t p = drawPatch(cdf, k, n, rng);
            const vec3 d = patchDirection(patches[p], rng.uniform01d(), rng.uniform01d());
            const bool onFront = glm::dot(nrm, patches[p].centre) >= 0.0f;
            const vec3 side = onFront ? nrm : -nrm;
            // Keep the ray on the face's side even where the jitter crosses its plane.
            const vec3 dir = glm::dot(d, side) > 1e-4f
                                 ? d
                                 : glm::normalize(d + side * (1e-4f - glm::dot(d, side)));
            const vec3 origin = trianglePoint(a, b, c, k, n, rng) + side * epsilon;
            const double scale = kPiL / std::max(1e-12, onFront ? hemisphereFront : hemisphereBack);
            sample(origin, dir, total / n * scale, onFront);
        }
    }

    // The open sky of each face, for an isotropic sky of unit horizontal irradiance
    // (radiance 1 / pi).
    void traceSky() const {
        const std::size_t n = samples();
        skyFront.assign(n, 0.0f);
        skyBack.assign(n, 0.0f);
        ParallelErrors errors;
#pragma omp parallel for schedule(dynamic, 64)
        for (long i = 0; i < long(n); ++i)
            errors.run(i, [&] {
                double f = 0.0, b = 0.0;
                cast(std::size_t(i), sky, options.diffuseRays, 1,
                     [&](const vec3& o, const vec3& d, double w, bool front) {
                         if (escapes(o, d)) (front ? f : b) += w / kPiL;
                     });
                skyFront[std::size_t(i)] = float(f);
                skyBack[std::size_t(i)] = float(b);
            });
        errors.rethrow();
    }

    // What each sample's scattering rays hit: they depend on the geometry alone, so they
    // are traced once and each sky's scattered light is summed over them. Kept per sample
    // as a run of links (compressed rows): the face of the element hit (2 j, or 2 j + 1 for
    // its back face) and the weight, negative for light arriving on the back of the
    // receiving sample.
    struct Link {
        std::int32_t hit;
        float weight;
    };
    mutable std::once_flag scatterOnce;
    mutable std::vector<std::uint64_t> linkStart;
    mutable std::vector<Link> links;

    void traceScatter() const {
        const std::size_t n = samples();
        std::vector<std::vector<Link>> local(n);
        ParallelErrors errors;
#pragma omp parallel for schedule(dynamic, 64)
        for (long li = 0; li < long(n); ++li)
            errors.run(li, [&] {
                std::vector<Link>& out = local[std::size_t(li)];
                cast(std::size_t(li), sphere, options.scatterRays, 2,
                     [&](const vec3& o, const vec3& d, double w, bool front) {
                         const long j = firstHit(o, d);
                         if (j < 0) return;
                         // The face of j the ray meets is the one whose normal points back.
                         const bool jBack = glm::dot(normals[std::size_t(j)], d) >= 0.0f;
                         const std::size_t e = elementOf(std::size_t(j));
                         out.push_back(
                             {std::int32_t(2 * e + (jBack ? 1 : 0)), float(front ? w : -w)});
                     });
            });
        errors.rethrow();
        linkStart.assign(n + 1, 0);
        for (std::size_t i = 0; i < n; ++i) linkStart[i + 1] = linkStart[i] + local[i].size();
        links.resize(linkStart[n]);
        for (std::size_t i = 0; i < n; ++i) {
            std::copy(local[i].begin(), local[i].end(), links.begin() + long(linkStart[i]));
            std::vector<Link>().swap(local[i]);
        }
    }

    // One sky's light on each face before scattering, what of it came straight from the
    // sun, and the sunlit share: per sample, or per element after perElement.
    struct Faces {
        std::vector<double> front, back, direct;
        std::vector<float> sunlit;
    };

    Faces firstOrder(const SkyLight& sky) const {
        const std::size_t n = samples();
        if (sky.diffuseHorizontal > 0.0) std::call_once(skyOnce, [&] { traceSky(); });
        const bool sunUp = sky.sun.elevation > 0.0 && sky.directNormal > 0.0;
        const vec3 sun = sky.sun.direction();
        Faces f{std::vector<double>(n, 0.0), std::vector<double>(n, 0.0),
                std::vector<double>(n, 0.0), std::vector<float>(n, 0.0f)};
        ParallelErrors errors;
#pragma omp parallel for schedule(dynamic, 64)
        for (long li = 0; li < long(n); ++li)
            errors.run(li, [&] {
                const std::size_t i = std::size_t(li), t = triangleOf(i);
                if (sky.diffuseHorizontal > 0.0) {
                    f.front[i] = skyFront[i] * sky.diffuseHorizontal;
                    f.back[i] = skyBack[i] * sky.diffuseHorizontal;
                }
                if (!sunUp) return;
                if (sampled) return sunOnSample(i, sun, sky.directNormal, f);
                const float cosine = glm::dot(normals[t], sun);
                const vec3 side = cosine >= 0.0f ? normals[t] : -normals[t];
                Rng rng(options.seed ^ 0x5DEECE66DULL, i);
                unsigned open = 0;
                const unsigned count = options.directRays;
                for (unsigned k = 0; k < count; ++k) {
                    const vec3 p = trianglePoint(soup[3 * t], soup[3 * t + 1], soup[3 * t + 2], k,
                                                 count, rng) +
                                   side * epsilon;
                    open += escapes(p, sun) ? 1u : 0u;
                }
                rays.fetch_add(count, std::memory_order_relaxed);
                f.sunlit[i] = float(open) / float(count);
                const double e = sky.directNormal * std::abs(cosine) * f.sunlit[i];
                (cosine >= 0.0f ? f.front[i] : f.back[i]) += e;
                f.direct[i] = e;
            });
        errors.rethrow();
        return f;
    }

    // Sampled mode: the sun on sample i from its points (directPoint), each on a triangle of
    // its own and lit on the face toward the sun.
    void sunOnSample(std::size_t i, const vec3& sun, double directNormal, Faces& f) const {
        const unsigned count = options.directRays;
        unsigned open = 0;
        double front = 0.0, back = 0.0;
        for (std::size_t k = i * count; k < (i + 1) * count; ++k) {
            const vec3& n = normals[directTriangle[k]];
            const float cosine = glm::dot(n, sun);
            if (!escapes(directPoint[k] + (cosine >= 0.0f ? n : -n) * epsilon, sun)) continue;
            ++open;
            (cosine >= 0.0f ? front : back) += directNormal * std::abs(cosine) / count;
        }
        rays.fetch_add(count, std::memory_order_relaxed);
        f.sunlit[i] = float(open) / float(count);
        f.front[i] += front;
        f.back[i] += back;
        f.direct[i] = front + back;
    }

    Faces perElement(Faces f) const {
        return {perElement(std::move(f.front)), perElement(std::move(f.back)),
                perElement(std::move(f.direct)), perElement(std::move(f.sunlit))};
    }

    // The light scattered once onto each element's faces (2 e its front, 2 e + 1 its back)
    // from the elements' first-order light.
    std::vector<double> scatter(const Faces& light) const {
        std::call_once(scatterOnce, [&] { traceScatter(); });
        const std::size_t n = elements(), ns = samples();
        // Each face's radiance: what it reflects of its own light and transmits of the other
        // face's.
        std::vector<float> radiance(2 * n);
        for (std::size_t i = 0; i < n; ++i) {
            const SurfaceOptics& o = elementOptics(i);
            radiance[2 * i] =
                float((o.reflectance * light.front[i] + o.transmittance * light.back[i]) / kPiL);
            radiance[2 * i + 1] =
                float((o.reflectance * light.back[i] + o.transmittance * light.front[i]) / kPiL);
        }
        std::vector<double> front(ns, 0.0), back(ns, 0.0);
#pragma omp parallel for schedule(static)
        for (long li = 0; li < long(ns); ++li) {
            const std::size_t i = std::size_t(li);
            double f = 0.0, b = 0.0;
            for (std::uint64_t k = linkStart[i]; k < linkStart[i + 1]; ++k) {
                const Link& link = links[k];
                const double e = double(radiance[std::size_t(link.hit)]) * link.weight;
                if (link.weight >= 0.0f)
                    f += e;
                else
                    b -= e;
            }
            front[i] = f;
            back[i] = b;
        }
        front = perElement(std::move(front));
        back = perElement(std::move(back));
        std::vector<double> out(2 * n);
        for (std::size_t i = 0; i < n; ++i) {
            out[2 * i] = front[i];
            out[2 * i + 1] = back[i];
        }
        return out;
    }
};

LightModel::LightModel(const Context& context, const LightOptions& options)
    : impl_(std::make_unique<Impl>()) {
    checkRays(options.directRays, "directRays", 1);
    checkRays(options.diffuseRays, "diffuseRays", 1);
    checkRays(options.scatterRays, "scatterRays", 1);
    if (options.samplesPerObject > 100000)
        throw Error("samples per object out of range",
                    {.parameter = "samplesPerObject",
                     .value = std::to_string(options.samplesPerObject),
                     .validRange = "0 (every triangle) to 100000"});
    if (options.scatteringOrders > 1)
        throw Error("scattering orders out of range",
                    {.parameter = "scatteringOrders",
                     .value = std::to_string(options.scatteringOrders),
                     .validRange = "0 or 1"});
    checkOptics(options.leaf, "leaf");
    checkOptics(options.stem, "stem");
    checkOptics(options.flowerAndFruit, "flowerAndFruit");
    checkOptics(options.ground, "ground");
    checkOptics(options.other, "other");
    Impl& m = *impl_;
    m.options = options;
    // What the model keeps per triangle: its corners, normal and labels, the BVH, the open
    // sky; and a link for each scattering ray of each sample (each triangle in the full
    // mode). Refused before anything is traced when it would take more than half of the
    // machine's memory.
    std::size_t triangles = 0, samples = 0;
    context.forEachObject([&](const ObjectView& o) {
        if (o.hidden) return;
        triangles += o.triangleCount();
        samples += options.samplesPerObject == 0
                       ? o.triangleCount()
                       : std::min<std::size_t>(o.triangleCount(), options.samplesPerObject);
    });
    // Per sample: the scattering rays' links, and in the sampled mode the sun's points.
    const double perSample = (options.scatteringOrders > 0 ? 8.0 * options.scatterRays : 0.0) +
                             (options.samplesPerObject > 0 ? 16.0 * options.directRays : 0.0);
    const double bytes = 200.0 * double(triangles) + perSample * double(samples);
    const long pages = sysconf(_SC_PHYS_PAGES), pageSize = sysconf(_SC_PAGESIZE);
    if (pages > 0 && pageSize > 0) {
        const double half = double(pages) * double(pageSize) / 2.0;
        if (bytes > half)
            throw Error(fmt::format("lighting {} triangles with {} scattering rays each needs "
                                    "about {:.1f} GB, more than half of this machine's memory",
                                    triangles, options.scatterRays, bytes / 1e9),
                        {.parameter = "scatterRays",
                         .value = std::to_string(options.scatterRays),
                         .validRange = fmt::format(
                             "fewer rays or triangles: at most {:.0f} triangles with these rays",
                             half / (200.0 + perSample))});
    }
    context.forEachObject([&](const ObjectView& o) {
        if (o.hidden) return;
        const Surface s = surfaceOf(context, o.id);
        for (std::size_t t = 0; t < o.triangleCount(); ++t) {
            const vec3 a = o.positions[o.indices[3 * t]];
            const vec3 b = o.positions[o.indices[3 * t + 1]];
            const vec3 c = o.positions[o.indices[3 * t + 2]];
            const vec3 cr = glm::cross(b - a, c - a);
            const float len = glm::length(cr);
            if (!(len > 0.0f)) continue;  // a degenerate triangle takes and casts no light
            m.soup.insert(m.soup.end(), {a, b, c});
            m.normals.push_back(cr / len);
            m.areas.push_back(0.5f * len);
            m.primitives.push_back(PrimitiveID(o.primitives.first + t));
            m.objects.push_back(o.id);
            m.surfaces.push_back(s);
        }
    });
    AABB box;
    for (const vec3& v : m.soup) box.add(v);
    const float extent = m.soup.empty() ? 1.0f : glm::length(box.max - box.min);
    m.epsilon = std::max(1e-7f, 1e-6f * extent);
    if (options.samplesPerObject > 0) m.drawSamples(options.samplesPerObject);
    // Sampled, the scene casts a few rays per object: the build is a large share of the cost
    // and a quicker, looser tree pays (a season of one plant and a canopy's day 10 to 25 % faster).
    m.scene = core::triangleScene(
        m.soup, options.samplesPerObject > 0 ? RTC_BUILD_QUALITY_MEDIUM : RTC_BUILD_QUALITY_HIGH);
    m.sky = tregenzaPatches(false);
    m.sphere = tregenzaPatches(true);
}

LightModel::~LightModel() {
    if (impl_ && impl_->scene) core::embree().rtcReleaseScene(impl_->scene);
}

const std::vector<PrimitiveID>& LightModel::primitives() const {
    return impl_->primitives;
}

const std::vector<ObjectID>& LightModel::objects() const {
    return impl_->objects;
}

const std::vector<float>& LightModel::areas() const {
    return impl_->areas;
}

std::size_t LightModel::triangleCount() const {
    return impl_->normals.size();
}

std::size_t LightModel::sampleCount() const {
    return impl_->samples();
}

std::uint64_t LightModel::raysCast() const {
    return impl_->rays.load();
}

LightResult LightModel::compute(const SkyLight& sky) const {
    const Impl& m = *impl_;
    if (!(std::isfinite(sky.directNormal) && sky.directNormal >= 0.0 &&
          std::isfinite(sky.diffuseHorizontal) && sky.diffuseHorizontal >= 0.0))
        throw Error("sky light out of range",
                    {.parameter = "directNormal, diffuseHorizontal",
                     .value = text::formatFloat(float(sky.directNormal)) + ", " +
                              text::formatFloat(float(sky.diffuseHorizontal)),
                     .validRange = "finite, 0 or more, µmol m-2 s-1"});
    Impl::Faces light = m.perElement(m.firstOrder(sky));
    const std::size_t n = m.elements();
    std::vector<double> scattered;  // per element: front, back
    if (m.options.scatteringOrders >= 1 && n > 0) scattered = m.scatter(light);
    LightResult r;
    r.absorbed.resize(n);
    r.incident.resize(n);
    r.absorbedDirect.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
        const SurfaceOptics& o = m.elementOptics(i);
        const double absorptance = 1.0 - o.reflectance - o.transmittance;
        double incident = light.front[i] + light.back[i];
        if (!scattered.empty()) {  // in this order: the sums of the full mode as they were
            incident += scattered[2 * i];
            incident += scattered[2 * i + 1];
        }
        r.incident[i] = float(incident);
        r.absorbed[i] = float(incident * absorptance);
        r.absorbedDirect[i] = float(std::min(light.direct[i] * absorptance, double(r.absorbed[i])));
    }
    r.sunlit = std::move(light.sunlit);
    if (m.sampled) {  // every triangle its object's
        LightResult perTriangle;
        for (auto [from, to] : {std::pair{&r.absorbed, &perTriangle.absorbed},
                                {&r.sunlit, &perTriangle.sunlit},
                                {&r.incident, &perTriangle.incident},
                                {&r.absorbedDirect, &perTriangle.absorbedDirect}}) {
            to->resize(m.normals.size());
            for (std::size_t t = 0; t < to->size(); ++t) (*to)[t] = (*from)[m.triangleObject[t]];
        }
        return perTriangle;
    }
    return r;
}

void writeLightData(Context& context, const LightModel& model, const LightResult& result) {
    const std::size_t n = model.triangleCount();
    if (result.absorbed.size() != n || result.sunlit.size() != n)
        throw Error("light result does not match the model",
                    {.parameter = "result",
                     .value = std::to_string(result.absorbed.size()) + " triangles",
                     .validRange = std::to_string(n) + " triangles, from this model"});
    const std::vector<PrimitiveID>& prims = model.primitives();
    for (PrimitiveID p : prims)
        if (!context.doesPrimitiveExist(p))
            throw Error("the Context no longer holds the light model's triangles",
                        {.parameter = "context",
                         .value = "primitive " + std::to_string(p) + " is gone",
                         .validRange = "the Context the model was built from, unchanged"});
    const std::vector<ObjectID>& objects = model.objects();
    const std::vector<float>& areas = model.areas();
    std::size_t i = 0;
    while (i < n) {
        const ObjectID id = objects[i];
        double area = 0.0, absorbed = 0.0, sunlit = 0.0;
        for (; i < n && objects[i] == id; ++i) {
            area += areas[i];
            absorbed += double(areas[i]) * result.absorbed[i];
            sunlit += double(areas[i]) * result.sunlit[i];
        }
        context.setObjectData(id, "absorbed_par", float(area > 0.0 ? absorbed / area : 0.0));
        context.setObjectData(id, "sunlit_fraction", float(area > 0.0 ? sunlit / area : 0.0));
    }
}

}  // namespace plantarch
