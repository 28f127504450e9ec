// Simulated terrestrial LiDAR: the scene is prepared once for ray casting (the renderer's BVH,
// with cut-out leaves' transparent texels passed through), then every scanner's rays are cast
// row by row on all threads. Each row's hits are kept in its own list and the lists are joined
// in row order, so the points come out in the same order whatever the thread count; the range
// noise of a ray is drawn from a counter-based stream keyed by the scanner and the ray's index.

#include "plantarch/Scan.h"

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "core/embree_api.h"
#include "core/embree_scene.h"
#include "core/parallel.h"
#include "core/value_text.h"
#include "plantarch/Error.h"
#include "render/render_internal.h"
#include "scene_io/export_common.h"

namespace plantarch {

namespace {

constexpr double kMaxRays = 2147483648.0;  // 2^31

struct Grid {
    std::uint64_t rows, columns;
};

// Steps of the resolution that fit a span. A float angle is taken as the decimal it was
// written as (0.1f is a little more than 0.1, which would lose the last step of 0:360).
std::uint64_t steps(double span, double resolution) {
    return std::uint64_t(std::floor(span / resolution + 1e-6));
}

double decimal(float angle) {
    return std::stod(text::formatFloat(angle));
}

Grid gridOf(const Scanner& s) {
    const double res = decimal(s.resolution);
    const std::uint64_t rows = steps(decimal(s.zenithMax) - decimal(s.zenithMin), res) + 1;
    const double span = decimal(s.azimuthMax) - decimal(s.azimuthMin);
    const bool fullTurn = span >= 360.0 - 1e-9;
    const std::uint64_t columns = steps(span, res) + (fullTurn ? 0 : 1);
    return {rows, std::max<std::uint64_t>(columns, 1)};
}

Error badOption(const std::string& option, double value, const std::string& range) {
    return Error("out of range",
                 {.parameter = option, .value = text::formatDouble(value), .validRange = range});
}

}  // namespace

void checkScanOptions(const ScanOptions& o) {
    if (o.scanners.empty() || o.scanners.size() > 65535)
        throw Error("a scan needs 1 to 65535 scanners",
                    {.parameter = "scanners", .value = std::to_string(o.scanners.size())});
    double rays = 0.0;
    for (std::size_t i = 0; i < o.scanners.size(); ++i) {
        const Scanner& s = o.scanners[i];
        const std::string at = o.scanners.size() > 1 ? " of scanner " + std::to_string(i) : "";
        for (float c : {s.origin.x, s.origin.y, s.origin.z})
            if (!std::isfinite(c)) throw badOption("origin" + at, c, "finite coordinates");
        if (!(s.resolution >= 0.001f && s.resolution <= 10.0f))
            throw badOption("resolution" + at, s.resolution, "0.001 to 10 degrees");
        if (!(s.zenithMin >= 0.0f && s.zenithMin <= 180.0f))
            throw badOption("zenith minimum" + at, s.zenithMin, "0 to 180 degrees");
        if (!(s.zenithMax >= s.zenithMin && s.zenithMax <= 180.0f))
            throw badOption("zenith maximum" + at, s.zenithMax,
                            text::formatDouble(s.zenithMin) + " to 180 degrees");
        if (!(s.azimuthMin >= -360.0f && s.azimuthMin <= 360.0f))
            throw badOption("azimuth minimum" + at, s.azimuthMin, "-360 to 360 degrees");
        if (!(s.azimuthMax >= s.azimuthMin && s.azimuthMax <= s.azimuthMin + 360.0f))
            throw badOption("azimuth maximum" + at, s.azimuthMax,
                            text::formatDouble(s.azimuthMin) + " to " +
                                text::formatDouble(double(s.azimuthMin) + 360.0) + " degrees");
        const Grid g = gridOf(s);
        rays += double(g.rows) * double(g.columns);
    }
    if (rays > kMaxRays)
        throw Error("too many rays (" + text::formatDouble(rays) + ")",
                    {.parameter = "resolution", .validRange = "at most 2147483648 rays in all"});
    if (!(o.rangeNoise >= 0.0f && o.rangeNoise <= 1.0f))
        throw badOption("range noise", o.rangeNoise, "0 to 1 m");
    if (!(o.maxRange > 0.0f && o.maxRange <= 10000.0f))
        throw badOption("maximum range", o.maxRange, "more than 0, up to 10000 m");
}

namespace {

// One row's hits.
struct Row {
    std::vector<vec3> positions, normals;
    std::vector<std::uint32_t> slots;  // object slots of the prepared scene
    std::vector<float> ranges;
};

}  // namespace

std::uint64_t scanRayCount(const Scanner& scanner) {
    const Grid g = gridOf(scanner);
    return g.rows * g.columns;
}

PointCloud scan(const Context& context, const ScanOptions& options) {
    checkScanOptions(options);
    render_detail::SceneData data;
    RenderSceneOptions sceneOptions;
    sceneOptions.smoothNormals = false;
    render_detail::buildScene(data, context, sceneOptions);
    // Labels of every object slot.
    const io::LabelReader labelsOf(context);
    std::vector<io::ObjectLabels> labels(data.objects.size());
    for (std::size_t k = 0; k < data.objects.size(); ++k) labels[k] = labelsOf(data.objects[k].id);

    PointCloud cloud;
    std::uint64_t totalRows = 0, rowsDone = 0;
    for (const Scanner& s : options.scanners) totalRows += gridOf(s).rows;
    for (std::size_t si = 0; si < options.scanners.size(); ++si) {
        const Scanner& s = options.scanners[si];
        const Grid g = gridOf(s);
        std::vector<Row> rows(g.rows);
        const double toRad = std::numbers::pi / 180.0;
        const double step = decimal(s.resolution), zenith0 = decimal(s.zenithMin),
                     azimuth0 = decimal(s.azimuthMin);
        const std::int64_t nrows = std::int64_t(g.rows);
        // Rows in bands, so progress goes out from the calling thread between parallel loops;
        // the bands do not change any point.
        const std::int64_t band = 64;
        for (std::int64_t r0 = 0; data.triangles > 0 && r0 < nrows; r0 += band) {
            const std::int64_t r1 = std::min(nrows, r0 + band);
            ParallelErrors errors;
#pragma omp parallel for schedule(dynamic, 1)
            for (std::int64_t r = r0; r < r1; ++r) {
                errors.run(r, [&] {
                    RTCIntersectContext ictx;
                    rtcInitIntersectContext(&ictx);
                    const double zenith = (zenith0 + double(r) * step) * toRad;
                    const double sz = std::sin(zenith), cz = std::cos(zenith);
                    Row& row = rows[std::size_t(r)];
                    for (std::uint64_t c = 0; c < g.columns; ++c) {
                        const double azimuth = (azimuth0 + double(c) * step) * toRad;
                        const vec3 dir(float(sz * std::cos(azimuth)), float(sz * std::sin(azimuth)),
                                       float(cz));
                        RTCRayHit rh = core::rayHit(s.origin, dir, 0.0f, options.maxRange);
                        core::embree().rtcIntersect1(data.scene, &ictx, &rh);
                        if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) continue;
                        float range = rh.ray.tfar;
                        if (options.rangeNoise > 0.0f) {
                            // Box-Muller from the ray's own stream.
                            render_detail::PixelSampler rng(
                                options.seed ^ (0x9E3779B97F4A7C15ULL * (si + 1)),
                                std::uint64_t(r) * g.columns + c);
                            const float u1 = std::max(rng.next(), 0x1p-24f), u2 = rng.next();
                            range += options.rangeNoise * std::sqrt(-2.0f * std::log(u1)) *
                                     std::cos(2.0f * std::numbers::pi_v<float> * u2);
                        }
                        vec3 n = glm::normalize(vec3(rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z));
                        if (glm::dot(n, dir) > 0.0f) n = -n;
                        const render_detail::GeometryData& geom = data.geometries[rh.hit.geomID];
                        row.positions.push_back(s.origin + range * dir);
                        row.normals.push_back(n);
                        row.slots.push_back(geom.triangleObject[rh.hit.primID]);
                        row.ranges.push_back(range);
                    }
                });
            }
            errors.rethrow();
            if (options.progress && r1 < nrows)
                options.progress("scanning",
                                 double(rowsDone + std::uint64_t(r1)) / double(totalRows));
        }
        for (const Row& row : rows) {
            for (std::size_t i = 0; i < row.positions.size(); ++i) {
                const std::uint32_t slot = row.slots[i];
                cloud.positions.push_back(row.positions[i]);
                cloud.normals.push_back(row.normals[i]);
                io::appendLabels(cloud, data.objects[slot].id, labels[slot]);
                cloud.range.push_back(row.ranges[i]);
                cloud.scanner.push_back(std::uint16_t(si));
            }
        }
        rowsDone += g.rows;
        if (options.progress) options.progress("scanning", double(rowsDone) / double(totalRows));
    }
    return cloud;
}

}  // namespace plantarch
