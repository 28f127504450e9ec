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

    // Rays from triangle i through the patches of `patches` (the sky's, or the whole
    // sphere's), drawn in proportion to each patch's solid angle x the cosine of its centre to
    // the triangle's normal: the light on a face is the quadrature sum over patches of
    // radiance x solid angle x cosine, with each patch's radiance sampled by rays through it
    // (jittered over the patch). Each calls sample(origin, direction, weight, onFront): the
    // radiance along it times `weight` is what it adds to that face's irradiance. The sums
    // are scaled so that a face seeing one radiance L over its whole hemisphere gets pi L.
    template <class Sample>
    void cast(std::size_t i, const std::vector<Patch>& patches, unsigned n, std::uint64_t pass,
              Sample&& sample) const {
        const vec3 nrm = normals[i];
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
        const vec3& a = soup[3 * i];
        const vec3& b = soup[3 * i + 1];
        const vec3& c = soup[3 * i + 2];
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
        const std::size_t n = normals.size();
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

    // What each triangle's scattering rays hit: they depend on the geometry alone, so they
    // are traced once and each sky's scattered light is summed over them. Kept per triangle
    // as a run of links (compressed rows): the face of the triangle hit (2 j, or 2 j + 1 for
    // its back face) and the weight, negative for light arriving on the back of the
    // receiving triangle.
    struct Link {
        std::int32_t hit;
        float weight;
    };
    mutable std::once_flag scatterOnce;
    mutable std::vector<std::uint64_t> linkStart;
    mutable std::vector<Link> links;

    void traceScatter() const {
        const std::size_t n = normals.size();
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
                         out.push_back(
                             {std::int32_t(2 * j + (jBack ? 1 : 0)), float(front ? w : -w)});
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
};

LightModel::LightModel(const Context& context, const LightOptions& options)
    : impl_(std::make_unique<Impl>()) {
    checkRays(options.directRays, "directRays", 1);
    checkRays(options.diffuseRays, "diffuseRays", 1);
    checkRays(options.scatterRays, "scatterRays", 1);
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
    // sky and a link for each scattering ray. Refused before anything is traced when it
    // would take more than half of the machine's memory.
    std::size_t triangles = 0;
    context.forEachObject(
        [&](const ObjectView& o) { triangles += o.hidden ? 0 : o.triangleCount(); });
    const double perTriangle =
        200.0 + (options.scatteringOrders > 0 ? 8.0 * options.scatterRays : 0.0);
    const long pages = sysconf(_SC_PHYS_PAGES), pageSize = sysconf(_SC_PAGESIZE);
    if (pages > 0 && pageSize > 0) {
        const double half = double(pages) * double(pageSize) / 2.0;
        if (double(triangles) * perTriangle > half)
            throw Error(
                fmt::format("lighting {} triangles with {} scattering rays each needs "
                            "about {:.1f} GB, more than half of this machine's memory",
                            triangles, options.scatterRays, double(triangles) * perTriangle / 1e9),
                {.parameter = "scatterRays",
                 .value = std::to_string(options.scatterRays),
                 .validRange = fmt::format(
                     "fewer rays or triangles: at most {:.0f} triangles with these rays",
                     half / perTriangle)});
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
    m.scene = core::triangleScene(m.soup, RTC_BUILD_QUALITY_HIGH);
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
    const std::size_t n = m.normals.size();
    if (sky.diffuseHorizontal > 0.0) std::call_once(m.skyOnce, [&] { m.traceSky(); });
    const bool sunUp = sky.sun.elevation > 0.0 && sky.directNormal > 0.0;
    const vec3 sun = sky.sun.direction();
    std::vector<double> front(n, 0.0), back(n, 0.0), direct(n, 0.0);
    LightResult r;
    r.sunlit.assign(n, 0.0f);
    ParallelErrors errors;
#pragma omp parallel for schedule(dynamic, 64)
    for (long li = 0; li < long(n); ++li)
        errors.run(li, [&] {
            const std::size_t i = std::size_t(li);
            if (sky.diffuseHorizontal > 0.0) {
                front[i] = m.skyFront[i] * sky.diffuseHorizontal;
                back[i] = m.skyBack[i] * sky.diffuseHorizontal;
            }
            if (!sunUp) return;
            const float cosine = glm::dot(m.normals[i], sun);
            const vec3 side = cosine >= 0.0f ? m.normals[i] : -m.normals[i];
            Rng rng(m.options.seed ^ 0x5DEECE66DULL, i);
            unsigned open = 0;
            const unsigned rays = m.options.directRays;
            for (unsigned k = 0; k < rays; ++k) {
                const vec3 p = trianglePoint(m.soup[3 * i], m.soup[3 * i + 1], m.soup[3 * i + 2], k,
                                             rays, rng) +
                               side * m.epsilon;
                open += m.escapes(p, sun) ? 1u : 0u;
            }
            m.rays.fetch_add(rays, std::memory_order_relaxed);
            r.sunlit[i] = float(open) / float(rays);
            const double e = sky.directNormal * std::abs(cosine) * r.sunlit[i];
            (cosine >= 0.0f ? front[i] : back[i]) += e;
            direct[i] = e;
        });
    errors.rethrow();
    std::vector<double> front2(n, 0.0), back2(n, 0.0);
    if (m.options.scatteringOrders >= 1 && n > 0) {
        std::call_once(m.scatterOnce, [&] { m.traceScatter(); });
        // Each face's radiance (2 i its front, 2 i + 1 its back): what it reflects of its own
        // light and transmits of the other face's.
        std::vector<float> radiance(2 * n);
        for (std::size_t i = 0; i < n; ++i) {
            const SurfaceOptics& o = m.optics(i);
            radiance[2 * i] = float((o.reflectance * front[i] + o.transmittance * back[i]) / kPiL);
            radiance[2 * i + 1] =
                float((o.reflectance * back[i] + o.transmittance * front[i]) / kPiL);
        }
#pragma omp parallel for schedule(static)
        for (long li = 0; li < long(n); ++li) {
            const std::size_t i = std::size_t(li);
            double f = 0.0, b = 0.0;
            for (std::uint64_t k = m.linkStart[i]; k < m.linkStart[i + 1]; ++k) {
                const Impl::Link& link = m.links[k];
                const double e = double(radiance[std::size_t(link.hit)]) * link.weight;
                if (link.weight >= 0.0f)
                    f += e;
                else
                    b -= e;
            }
            front2[i] = f;
            back2[i] = b;
        }
    }
    r.absorbed.resize(n);
    r.incident.resize(n);
    r.absorbedDirect.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
        const SurfaceOptics& o = m.optics(i);
        const double absorptance = 1.0 - o.reflectance - o.transmittance;
        const double incident = front[i] + back[i] + front2[i] + back2[i];
        r.incident[i] = float(incident);
        r.absorbed[i] = float(incident * absorptance);
        r.absorbedDirect[i] = float(std::min(direct[i] * absorptance, double(r.absorbed[i])));
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
