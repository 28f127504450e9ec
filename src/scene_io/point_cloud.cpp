// Labelled point clouds: points drawn uniformly by area over the visible triangles, each with
// the face's normal and its object's plant, object and organ labels, written as a binary PLY
// of vertices only. Deterministic: one random stream from the seed, one pass.

#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "core/atomic_file.h"
#include "core/progress_steps.h"
#include "plantarch/Error.h"
#include "plantarch/Export.h"
#include "plantarch/OutputFormats.h"
#include "plantarch/Random.h"
#include "scene_io/export_common.h"

namespace plantarch {

std::size_t maxSamplePoints() {
    constexpr std::size_t kMost = std::size_t(1) << 31;
    const long pages = sysconf(_SC_PHYS_PAGES), pageSize = sysconf(_SC_PAGESIZE);
    if (pages <= 0 || pageSize <= 0) return kMost;
    return std::min(kMost, std::size_t(pages) / 2 * std::size_t(pageSize) / kBytesPerSamplePoint);
}

PointCloud samplePoints(const Context& context, const PointSampleOptions& options) {
    if (options.points == 0 || options.points > (std::size_t(1) << 31))
        throw Error("the number of points is out of range",
                    {.parameter = "points",
                     .value = std::to_string(options.points),
                     .validRange = "1 to 2147483648"});
    if (const std::size_t most = maxSamplePoints(); options.points > most)
        throw Error(fmt::format("{} points need about {:.1f} GB, more than half of this "
                                "machine's memory",
                                options.points,
                                double(options.points) * double(kBytesPerSamplePoint) / 1e9),
                    {.parameter = "points",
                     .value = std::to_string(options.points),
                     .validRange = fmt::format("1 to {} on this machine", most)});
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
    const io::LabelReader labelsOf(context);
    std::vector<io::ObjectLabels> labels(ids.size());
    for (std::size_t k = 0; k < ids.size(); ++k) labels[k] = labelsOf(ids[k]);
    PointCloud cloud;
    cloud.positions.resize(options.points);
    cloud.normals.resize(options.points);
    std::vector<std::uint32_t> objectOf(options.points);  // index into ids
    Rng rng(options.seed, 0x5eed);
    ProgressSteps steps(options.progress, "sampling points", double(options.points));
    for (std::size_t i = 0; i < options.points; ++i) {
        if ((i & 0xFFFF) == 0) steps.at(double(i));
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
        objectOf[i] = std::uint32_t(tri.object);
    }
    // The labels of each point's object, filled in one pass per array.
    const std::size_t n = options.points;
    cloud.plantID.resize(n);
    cloud.objectID.resize(n);
    cloud.organ.resize(n);
    cloud.leafID.resize(n);
    cloud.shootID.resize(n);
    cloud.rank.resize(n);
    cloud.age.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
        const io::ObjectLabels& l = labels[objectOf[i]];
        cloud.plantID[i] = l.plant;
        cloud.objectID[i] = ids[objectOf[i]];
        cloud.organ[i] = l.organ;
        cloud.leafID[i] = l.leaf;
        cloud.shootID[i] = l.shoot;
        cloud.rank[i] = l.rank;
        cloud.age[i] = l.age;
    }
    steps.finish();
    return cloud;
}

namespace {

// Every array holds one entry per point (range and scanner: none or all).
bool scanned(const PointCloud& cloud, const std::string& path) {
    const std::size_t n = cloud.positions.size();
    const bool scan = !cloud.range.empty() || !cloud.scanner.empty();
    if (cloud.normals.size() != n || cloud.plantID.size() != n || cloud.objectID.size() != n ||
        cloud.organ.size() != n || cloud.leafID.size() != n || cloud.shootID.size() != n ||
        cloud.rank.size() != n || cloud.age.size() != n ||
        (scan && (cloud.range.size() != n || cloud.scanner.size() != n)))
        throw Error("the point cloud's arrays differ in length", {.file = path});
    return scan;
}

}  // namespace

void writePointCloudPLY(const PointCloud& cloud, const std::string& path,
                        const ProgressCallback& progress) {
    requireOutputFormat(path, {".ply"}, "writePointCloudPLY writes a PLY point cloud");
    const bool scan = scanned(cloud, path);
    io::AtomicFile out(path);
    std::string h = "ply\nformat binary_little_endian 1.0\n";
    h += "comment plantarch point cloud: per point plant_id (-1: none), object_id, organ label, "
         "leaf_id, shoot_id, rank (-1: none), age (days; -1: unknown)";
    h += scan ? ", range (m) and scanner index\n" : "\n";
    for (std::size_t i = 0; i < kOrganLabels.size(); ++i)
        h += "comment organ_label " + std::to_string(i) + " " + std::string(kOrganLabels[i]) + "\n";
    h += "element vertex " + std::to_string(cloud.positions.size()) + "\n";
    h += "property float x\nproperty float y\nproperty float z\n";
    h += "property float nx\nproperty float ny\nproperty float nz\n";
    h += "property int plant_id\nproperty uint object_id\nproperty uchar organ\n";
    h += "property int leaf_id\nproperty int shoot_id\nproperty int rank\nproperty float age\n";
    if (scan) h += "property float range\nproperty ushort scanner\n";
    h += "end_header\n";
    out.write(h);
    const std::size_t kBytes = 6 * 4 + 4 + 4 + 1 + 16 + (scan ? 6 : 0);
    ProgressSteps steps(progress, "writing PLY", double(cloud.positions.size()));
    for (std::size_t first = 0; first < cloud.positions.size();) {
        steps.at(double(first));
        const std::size_t n =
            std::min(io::AtomicFile::kMaxReserve / kBytes, cloud.positions.size() - first);
        char* p = out.reserve(n * kBytes);
        for (std::size_t i = first; i < first + n; ++i) {
            std::memcpy(p, &cloud.positions[i], 12);
            std::memcpy(p + 12, &cloud.normals[i], 12);
            std::memcpy(p + 24, &cloud.plantID[i], 4);
            std::memcpy(p + 28, &cloud.objectID[i], 4);
            p[32] = char(cloud.organ[i]);
            std::memcpy(p + 33, &cloud.leafID[i], 4);
            std::memcpy(p + 37, &cloud.shootID[i], 4);
            std::memcpy(p + 41, &cloud.rank[i], 4);
            std::memcpy(p + 45, &cloud.age[i], 4);
            if (scan) {
                std::memcpy(p + 49, &cloud.range[i], 4);
                std::memcpy(p + 53, &cloud.scanner[i], 2);
            }
            p += kBytes;
        }
        out.advance(p);
        first += n;
    }
    out.commit();
    steps.finish();
}

namespace {

// CRC-32 (the zip polynomial) eight bytes at a time: table k holds the CRC of a byte followed
// by k zero bytes, so eight lookups fold eight bytes (little-endian words).
std::uint32_t crc32(const std::string& bytes) {
    static const auto tables = [] {
        std::array<std::array<std::uint32_t, 256>, 8> t{};
        for (std::uint32_t i = 0; i < 256; ++i) {
            std::uint32_t c = i;
            for (int k = 0; k < 8; ++k) c = (c & 1) ? 0xEDB88320u ^ (c >> 1) : c >> 1;
            t[0][i] = c;
        }
        for (std::size_t k = 1; k < 8; ++k)
            for (std::size_t i = 0; i < 256; ++i)
                t[k][i] = (t[k - 1][i] >> 8) ^ t[0][t[k - 1][i] & 0xFF];
        return t;
    }();
    std::uint32_t c = 0xFFFFFFFFu;
    const auto* p = reinterpret_cast<const unsigned char*>(bytes.data());
    std::size_t n = bytes.size();
    for (; n >= 8; n -= 8, p += 8) {
        std::uint32_t lo, hi;
        std::memcpy(&lo, p, 4);
        std::memcpy(&hi, p + 4, 4);
        lo ^= c;
        c = tables[7][lo & 0xFF] ^ tables[6][(lo >> 8) & 0xFF] ^ tables[5][(lo >> 16) & 0xFF] ^
            tables[4][lo >> 24] ^ tables[3][hi & 0xFF] ^ tables[2][(hi >> 8) & 0xFF] ^
            tables[1][(hi >> 16) & 0xFF] ^ tables[0][hi >> 24];
    }
    for (; n > 0; --n, ++p) c = tables[0][(c ^ *p) & 0xFF] ^ (c >> 8);
    return c ^ 0xFFFFFFFFu;
}

// One .npy file: NPY 1.0 header (padded to 64 bytes) and the array's bytes.
std::string npy(const std::string& descr, const std::string& shape, const void* data,
                std::size_t bytes) {
    std::string header =
        fmt::format("{{'descr': '{}', 'fortran_order': False, 'shape': {}, }}", descr, shape);
    header.append(63 - (10 + header.size()) % 64, ' ');
    header += '\n';
    std::string out = "\x93NUMPY";
    out += char(1);
    out += char(0);
    out += char(header.size() & 0xFF);
    out += char(header.size() >> 8);
    out += header;
    out.append(static_cast<const char*>(data), bytes);
    return out;
}

void put16(std::string& s, std::uint32_t v) {
    s += char(v & 0xFF);
    s += char((v >> 8) & 0xFF);
}
void put32(std::string& s, std::uint32_t v) {
    put16(s, v & 0xFFFF);
    put16(s, v >> 16);
}

}  // namespace

void writePointCloudNPZ(const PointCloud& cloud, const std::string& path,
                        const ProgressCallback& progress) {
    requireOutputFormat(path, {".npz"}, "writePointCloudNPZ writes a NumPy point cloud");
    const bool scan = scanned(cloud, path);
    const std::size_t n = cloud.positions.size();
    const std::string rows = fmt::format("({},)", n), rows3 = fmt::format("({}, 3)", n);
    std::vector<std::pair<std::string, std::string>> arrays = {
        {"positions", npy("<f4", rows3, cloud.positions.data(), n * 12)},
        {"normals", npy("<f4", rows3, cloud.normals.data(), n * 12)},
        {"plant_id", npy("<i4", rows, cloud.plantID.data(), n * 4)},
        {"object_id", npy("<u4", rows, cloud.objectID.data(), n * 4)},
        {"organ", npy("|u1", rows, cloud.organ.data(), n)},
        {"leaf_id", npy("<i4", rows, cloud.leafID.data(), n * 4)},
        {"shoot_id", npy("<i4", rows, cloud.shootID.data(), n * 4)},
        {"rank", npy("<i4", rows, cloud.rank.data(), n * 4)},
        {"age", npy("<f4", rows, cloud.age.data(), n * 4)},
    };
    std::size_t longest = 0;
    for (std::string_view name : kOrganLabels) longest = std::max(longest, name.size());
    std::string names;
    for (std::string_view name : kOrganLabels) {
        names += name;
        names.append(longest - name.size(), '\0');
    }
    arrays.push_back({"organ_labels",
                      npy(fmt::format("|S{}", longest), fmt::format("({},)", kOrganLabels.size()),
                          names.data(), names.size())});
    if (scan) {
        arrays.push_back({"range", npy("<f4", rows, cloud.range.data(), n * 4)});
        arrays.push_back({"scanner", npy("<u2", rows, cloud.scanner.data(), n * 2)});
    }
    // A zip archive of the .npy files, stored (numpy's savez writes the same), with ZIP64
    // sizes so clouds past 4 GB are fine.
    io::AtomicFile out(path);
    std::string directory;
    std::uint64_t offset = 0;
    double bytes = 0.0, done = 0.0;
    for (const auto& array : arrays) bytes += double(array.second.size());
    ProgressSteps steps(progress, "writing NPZ", bytes);
    for (const auto& [name, data] : arrays) {
        const std::string file = name + ".npy";
        const std::uint32_t crc = crc32(data);
        std::string extra;  // ZIP64: sizes and offset
        put16(extra, 1);
        put16(extra, 24);
        for (std::uint64_t v : {std::uint64_t(data.size()), std::uint64_t(data.size()), offset}) {
            put32(extra, std::uint32_t(v & 0xFFFFFFFFu));
            put32(extra, std::uint32_t(v >> 32));
        }
        std::string local;
        put32(local, 0x04034b50u);
        put16(local, 45);    // version needed: ZIP64
        put16(local, 0);     // flags
        put16(local, 0);     // stored
        put16(local, 0);     // time
        put16(local, 0x21);  // date: 1980-01-01
        put32(local, crc);
        put32(local, 0xFFFFFFFFu);
        put32(local, 0xFFFFFFFFu);
        put16(local, std::uint32_t(file.size()));
        put16(local, 20);
        local += file;
        put16(local, 1);  // ZIP64 extra: the two sizes
        put16(local, 16);
        for (int k = 0; k < 2; ++k) {
            put32(local, std::uint32_t(data.size() & 0xFFFFFFFFu));
            put32(local, std::uint32_t(std::uint64_t(data.size()) >> 32));
        }
        out.write(local);
        out.write(data);
        std::string entry;
        put32(entry, 0x02014b50u);
        put16(entry, 45);
        put16(entry, 45);
        put16(entry, 0);
        put16(entry, 0);
        put16(entry, 0);
        put16(entry, 0x21);
        put32(entry, crc);
        put32(entry, 0xFFFFFFFFu);
        put32(entry, 0xFFFFFFFFu);
        put16(entry, std::uint32_t(file.size()));
        put16(entry, std::uint32_t(extra.size()));
        put16(entry, 0);            // comment
        put16(entry, 0);            // disk
        put16(entry, 0);            // internal attributes
        put32(entry, 0);            // external attributes
        put32(entry, 0xFFFFFFFFu);  // offset: in the ZIP64 extra
        entry += file;
        entry += extra;
        directory += entry;
        offset += local.size() + data.size();
        steps.at(done += double(data.size()));
    }
    const std::uint64_t directoryAt = offset, count = arrays.size();
    std::string end;
    put32(end, 0x06064b50u);  // ZIP64 end of central directory
    put32(end, 44);
    put32(end, 0);
    put16(end, 45);
    put16(end, 45);
    put32(end, 0);
    put32(end, 0);
    for (std::uint64_t v : {count, count, std::uint64_t(directory.size()), directoryAt}) {
        put32(end, std::uint32_t(v & 0xFFFFFFFFu));
        put32(end, std::uint32_t(v >> 32));
    }
    put32(end, 0x07064b50u);  // its locator
    put32(end, 0);
    const std::uint64_t endAt = directoryAt + directory.size();
    put32(end, std::uint32_t(endAt & 0xFFFFFFFFu));
    put32(end, std::uint32_t(endAt >> 32));
    put32(end, 1);
    put32(end, 0x06054b50u);  // the classic end record, pointing at ZIP64
    put16(end, 0xFFFF);
    put16(end, 0xFFFF);
    put16(end, 0xFFFF);
    put16(end, 0xFFFF);
    put32(end, 0xFFFFFFFFu);
    put32(end, 0xFFFFFFFFu);
    put16(end, 0);
    out.write(directory);
    out.write(end);
    out.commit();
    steps.finish();
}

}  // namespace plantarch
