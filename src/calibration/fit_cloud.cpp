// Point clouds of real plants for fitting: reading them (PLY vertices, XYZ text) and the
// symmetric mean distance between a cloud and a built plant's surface, with Embree's point
// queries (closest point on the plant's triangles; nearest cloud point).

#include "calibration/fit_cloud.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <limits>

#include "core/embree_scene.h"
#include "core/input_file.h"
#include "plantarch/Error.h"
#include "plantarch/Export.h"

namespace plantarch {

namespace fit {

namespace {

inline constexpr io::InputKind kXYZFile{"point cloud file", 4096 * io::kMiB};
inline constexpr std::size_t kMaxCloudPoints = std::size_t(1) << 26;

std::string lowerExtension(const std::string& path) {
    std::string e = std::filesystem::path(path).extension().string();
    std::transform(e.begin(), e.end(), e.begin(), [](unsigned char c) { return std::tolower(c); });
    return e;
}

std::vector<vec3> readXYZ(const std::string& path) {
    io::InputFile file(path, kXYZFile);
    std::vector<vec3> points;
    io::forEachLine(file, [&](std::string_view line, int number) {
        std::size_t i = 0;
        const auto skip = [&] {
            while (i < line.size() &&
                   (line[i] == ' ' || line[i] == '\t' || line[i] == ',' || line[i] == '\r'))
                ++i;
        };
        skip();
        if (i == line.size() || line[i] == '#' || line[i] == '/') return;
        float xyz[3];
        for (float& c : xyz) {
            skip();
            const char* begin = line.data() + i;
            const auto [end, ec] = std::from_chars(begin, line.data() + line.size(), c);
            if (ec != std::errc() || end == begin || !std::isfinite(c))
                throw Error(
                    "expected three numbers x y z at the start of the line",
                    {.file = path,
                     .line = number,
                     .value = std::string(line.substr(0, std::min<std::size_t>(40, line.size()))),
                     .validRange = "x y z (finite numbers, m), then anything"});
            i = std::size_t(end - line.data());
        }
        if (points.size() >= kMaxCloudPoints)
            throw Error("too many points",
                        {.file = path,
                         .line = number,
                         .validRange = "at most " + std::to_string(kMaxCloudPoints)});
        points.push_back(vec3(xyz[0], xyz[1], xyz[2]));
    });
    if (points.empty()) throw Error("no points", {.file = path, .validRange = "lines of x y z"});
    return points;
}

// Closest point on triangle (a, b, c) to p: Voronoi regions of the vertices, edges and face
// (Ericson, Real-Time Collision Detection, 5.1.5).
vec3 nearestOnTriangle(const vec3& p, const vec3& a, const vec3& b, const vec3& c) {
    const vec3 ab = b - a, ac = c - a, ap = p - a;
    const float d1 = glm::dot(ab, ap), d2 = glm::dot(ac, ap);
    if (d1 <= 0.0f && d2 <= 0.0f) return a;
    const vec3 bp = p - b;
    const float d3 = glm::dot(ab, bp), d4 = glm::dot(ac, bp);
    if (d3 >= 0.0f && d4 <= d3) return b;
    const float vc = d1 * d4 - d3 * d2;
    if (vc <= 0.0f && d1 >= 0.0f && d3 <= 0.0f) return a + ab * (d1 / (d1 - d3));
    const vec3 cp = p - c;
    const float d5 = glm::dot(ab, cp), d6 = glm::dot(ac, cp);
    if (d6 >= 0.0f && d5 <= d6) return c;
    const float vb = d5 * d2 - d1 * d6;
    if (vb <= 0.0f && d2 >= 0.0f && d6 <= 0.0f) return a + ac * (d2 / (d2 - d6));
    const float va = d3 * d6 - d5 * d4;
    if (va <= 0.0f && (d4 - d3) >= 0.0f && (d5 - d6) >= 0.0f)
        return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
    const float denom = 1.0f / (va + vb + vc);
    return a + ab * (vb * denom) + ac * (vc * denom);
}

struct TriangleQuery {
    const std::vector<vec3>* soup;
    float best;
};

bool triangleCallback(RTCPointQueryFunctionArguments* args) {
    auto* q = static_cast<TriangleQuery*>(args->userPtr);
    const vec3* t = q->soup->data() + 3 * std::size_t(args->primID);
    const vec3 p(args->query->x, args->query->y, args->query->z);
    const float d = glm::length(p - nearestOnTriangle(p, t[0], t[1], t[2]));
    if (d < q->best) {
        q->best = d;
        args->query->radius = d;
        return true;
    }
    return false;
}

struct PointQuery {
    const std::vector<vec3>* points;
    float best;
};

bool pointCallback(RTCPointQueryFunctionArguments* args) {
    auto* q = static_cast<PointQuery*>(args->userPtr);
    const vec3 p(args->query->x, args->query->y, args->query->z);
    const float d = glm::length(p - (*q->points)[args->primID]);
    if (d < q->best) {
        q->best = d;
        args->query->radius = d;
        return true;
    }
    return false;
}

RTCPointQuery queryAt(const vec3& p) {
    RTCPointQuery q{};
    q.x = p.x;
    q.y = p.y;
    q.z = p.z;
    q.time = 0.0f;
    // A radius far beyond any plant, whose square is still a finite float (Embree compares
    // squared distances; an infinite radius finds nothing).
    q.radius = 1e15f;
    return q;
}

}  // namespace

std::vector<vec3> readCloudPoints(const std::string& path) {
    const std::string ext = lowerExtension(path);
    if (ext == ".ply") {
        std::vector<vec3> points = readPLYPoints(path);
        if (points.size() > kMaxCloudPoints)
            throw Error("too many points",
                        {.file = path, .validRange = "at most " + std::to_string(kMaxCloudPoints)});
        return points;
    }
    if (ext == ".xyz" || ext == ".txt" || ext == ".pts") return readXYZ(path);
    throw Error("not a point cloud file", {.file = path,
                                           .parameter = "point_cloud/file",
                                           .value = ext.empty() ? "(no extension)" : ext,
                                           .validRange = "one of: .ply, .xyz, .txt, .pts"});
}

CloudScene::CloudScene(std::vector<vec3> points) : points_(std::move(points)) {
    // Each point as a tiny triangle at it (Embree's point queries visit the triangles whose
    // bounds reach the query; the callback measures to the point itself).
    std::vector<vec3> soup;
    soup.reserve(3 * points_.size());
    for (const vec3& p : points_) {
        soup.push_back(p);
        soup.push_back(p + vec3(1e-6f, 0.0f, 0.0f));
        soup.push_back(p + vec3(0.0f, 1e-6f, 0.0f));
    }
    scene_ = core::triangleScene(soup, RTC_BUILD_QUALITY_MEDIUM);
    core::throwOnEmbreeError("building the point cloud's scene");
}

CloudScene::~CloudScene() {
    if (scene_) core::embree().rtcReleaseScene(scene_);
}

float CloudScene::nearest(const vec3& p) const {
    RTCPointQuery q = queryAt(p);
    RTCPointQueryContext context;
    rtcInitPointQueryContext(&context);
    PointQuery data{&points_, std::numeric_limits<float>::infinity()};
    core::embree().rtcPointQuery(scene_, &q, &context, pointCallback, &data);
    return data.best;
}

double symmetricMeanDistance(const CloudScene& cloud, const std::vector<vec3>& cloudSample,
                             const std::vector<vec3>& soup, const std::vector<vec3>& surface) {
    if (soup.empty() || surface.empty()) return std::numeric_limits<double>::infinity();
    RTCScene plant = core::triangleScene(soup, RTC_BUILD_QUALITY_MEDIUM);
    double toSurface = 0.0;
    for (const vec3& p : cloudSample) {
        RTCPointQuery q = queryAt(p);
        RTCPointQueryContext context;
        rtcInitPointQueryContext(&context);
        TriangleQuery data{&soup, std::numeric_limits<float>::infinity()};
        core::embree().rtcPointQuery(plant, &q, &context, triangleCallback, &data);
        toSurface += data.best;
    }
    core::embree().rtcReleaseScene(plant);
    double toCloud = 0.0;
    for (const vec3& p : surface) toCloud += cloud.nearest(p);
    return 0.5 * (toSurface / double(cloudSample.size()) + toCloud / double(surface.size()));
}

}  // namespace fit

std::vector<vec3> readPointCloudFile(const std::string& path) {
    return fit::readCloudPoints(path);
}

}  // namespace plantarch
