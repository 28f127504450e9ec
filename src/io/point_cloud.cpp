// Labelled point clouds: points drawn uniformly by area over the visible triangles, each with
// the face's normal and its object's plant, object and organ labels, written as a binary PLY
// of vertices only. Deterministic: one random stream from the seed, one pass.

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "core/atomic_file.h"
#include "io/export_common.h"
#include "plantarch/Error.h"
#include "plantarch/Export.h"
#include "plantarch/Random.h"

namespace plantarch {

namespace {

std::uint8_t organCode(const std::string& organ) {
    for (std::size_t i = 0; i < kOrganLabels.size(); ++i)
        if (organ == kOrganLabels[i]) return std::uint8_t(i);
    return organ == "trellis" ? std::uint8_t(9) : std::uint8_t(0);
}

}  // namespace

PointCloud samplePoints(const Context& context, const PointSampleOptions& options) {
    if (options.points == 0 || options.points > (std::size_t(1) << 31))
        throw Error("the number of points is out of range",
                    {.parameter = "points",
                     .value = std::to_string(options.points),
                     .validRange = "1 to 2147483648"});
    const std::vector<ObjectID> ids = io::exportedObjects(context, options.includeHidden);
    // Cumulative area over every triangle, in object then triangle order.
    struct Triangle {
        std::size_t object;
        std::uint32_t index;
    };
    std::vector<double> cumulative;
    std::vector<Triangle> triangles;
    double total = 0.0;
    for (std::size_t k = 0; k < ids.size(); ++k) {
        const ObjectView o = context.object(ids[k]);
        for (std::size_t t = 0; t < o.triangleCount(); ++t) {
            const vec3 a = o.positions[o.indices[3 * t]], b = o.positions[o.indices[3 * t + 1]],
                       c = o.positions[o.indices[3 * t + 2]];
            const double area = 0.5 * double(glm::length(glm::cross(b - a, c - a)));
            if (!(area > 0.0)) continue;
            total += area;
            cumulative.push_back(total);
            triangles.push_back({k, std::uint32_t(t)});
        }
    }
    if (triangles.empty())
        throw Error("there is no surface to sample (no visible triangle has an area)",
                    {.parameter = "points"});
    const bool hasPlant = context.objectDataType("plantID") == DataType::Int;
    std::vector<std::int32_t> plantOf(ids.size());
    std::vector<std::uint8_t> organOf(ids.size());
    for (std::size_t k = 0; k < ids.size(); ++k) {
        plantOf[k] = hasPlant ? context.objectDataInt(ids[k], "plantID").value_or(-1) : -1;
        organOf[k] = organCode(io::organOf(context, ids[k]));
    }
    PointCloud cloud;
    cloud.positions.resize(options.points);
    cloud.normals.resize(options.points);
    cloud.plantID.resize(options.points);
    cloud.objectID.resize(options.points);
    cloud.organ.resize(options.points);
    Rng rng(options.seed, 0x5eed);
    for (std::size_t i = 0; i < options.points; ++i) {
        const double u = rng.uniform01d() * total;
        const std::size_t at = std::size_t(
            std::upper_bound(cumulative.begin(), cumulative.end(), u) - cumulative.begin());
        const Triangle& tri = triangles[std::min(at, triangles.size() - 1)];
        const ObjectView o = context.object(ids[tri.object]);
        const vec3 a = o.positions[o.indices[3 * tri.index]];
        const vec3 b = o.positions[o.indices[3 * tri.index + 1]];
        const vec3 c = o.positions[o.indices[3 * tri.index + 2]];
        // Uniform over the triangle: the square-root map of two uniforms.
        const float r1 = std::sqrt(rng.uniform01()), r2 = rng.uniform01();
        cloud.positions[i] = (1.0f - r1) * a + r1 * (1.0f - r2) * b + r1 * r2 * c;
        cloud.normals[i] = glm::normalize(glm::cross(b - a, c - a));
        cloud.plantID[i] = plantOf[tri.object];
        cloud.objectID[i] = ids[tri.object];
        cloud.organ[i] = organOf[tri.object];
    }
    return cloud;
}

void writePointCloudPLY(const PointCloud& cloud, const std::string& path) {
    io::AtomicFile out(path);
    std::string h = "ply\nformat binary_little_endian 1.0\n";
    h += "comment plantarch point cloud: per point plant_id (-1: none), object_id, organ label\n";
    for (std::size_t i = 0; i < kOrganLabels.size(); ++i)
        h += "comment organ_label " + std::to_string(i) + " " + std::string(kOrganLabels[i]) + "\n";
    h += "element vertex " + std::to_string(cloud.positions.size()) + "\n";
    h += "property float x\nproperty float y\nproperty float z\n";
    h += "property float nx\nproperty float ny\nproperty float nz\n";
    h += "property int plant_id\nproperty uint object_id\nproperty uchar organ\nend_header\n";
    out.write(h);
    constexpr std::size_t kBytes = 6 * 4 + 4 + 4 + 1;
    for (std::size_t first = 0; first < cloud.positions.size();) {
        const std::size_t n =
            std::min(io::AtomicFile::kMaxReserve / kBytes, cloud.positions.size() - first);
        char* p = out.reserve(n * kBytes);
        for (std::size_t i = first; i < first + n; ++i) {
            std::memcpy(p, &cloud.positions[i], 12);
            std::memcpy(p + 12, &cloud.normals[i], 12);
            std::memcpy(p + 24, &cloud.plantID[i], 4);
            std::memcpy(p + 28, &cloud.objectID[i], 4);
            p[32] = char(cloud.organ[i]);
            p += kBytes;
        }
        out.advance(p);
        first += n;
    }
    out.commit();
}

}  // namespace plantarch
