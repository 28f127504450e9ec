// The hashed uniform grid of soft obstacles (see soft_grid.h).

#include "collision/soft_grid.h"

#include <algorithm>
#include <cmath>

#include "collision/collision_world.h"

namespace plantarch::collision {

namespace {

// Cell coordinates packed 21 bits each (a grid of two million cells a side, centred on 0).
constexpr std::int64_t kBias = std::int64_t(1) << 20;
constexpr std::int64_t kMask = (std::int64_t(1) << 21) - 1;

inline std::uint64_t pack(std::int64_t x, std::int64_t y, std::int64_t z) {
    return std::uint64_t((x + kBias) & kMask) | (std::uint64_t((y + kBias) & kMask) << 21) |
           (std::uint64_t((z + kBias) & kMask) << 42);
}

inline std::int64_t cellIndex(float v, float inverse) {
    const float c = std::floor(v * inverse);
    return std::int64_t(std::clamp(c, float(-kBias), float(kBias - 1)));
}

}  // namespace

void boundingSpheres(const std::vector<vec3>& soup, std::vector<glm::vec4>& spheres) {
    spheres.resize(soup.size() / 3);
    for (std::size_t t = 0; t < spheres.size(); ++t) {
        const vec3* p = soup.data() + 3 * t;
        const vec3 c = (p[0] + p[1] + p[2]) * (1.0f / 3.0f);
        const float r2 = std::max({glm::dot(p[0] - c, p[0] - c), glm::dot(p[1] - c, p[1] - c),
                                   glm::dot(p[2] - c, p[2] - c)});
        // A hair more than the farthest corner, so rounding never drops a touching triangle.
        spheres[t] = glm::vec4(c, std::sqrt(r2) * 1.0001f + 1e-7f);
    }
}

bool SoftGrid::ignored(const SoftTriangle& t, const Ignore* ignore) {
    return ignore && t.owner == ignore->plant + 1 &&
           (t.tag == ignore->organs[0] || t.tag == ignore->organs[1]);
}

void SoftGrid::cellKeys(const std::vector<glm::vec4>& spheres, float cell,
                        std::vector<std::uint64_t>& keys) {
    const float inverse = 1.0f / std::max(cell, kMinCell);
    keys.resize(spheres.size());
    for (std::size_t t = 0; t < spheres.size(); ++t)
        keys[t] = spheres[t].w > std::max(cell, kMinCell)
                      ? kLarge
                      : pack(cellIndex(spheres[t].x, inverse), cellIndex(spheres[t].y, inverse),
                             cellIndex(spheres[t].z, inverse));
}

void SoftGrid::build(const std::vector<Source>& sources, float cell) {
    cell_ = std::max(cell, kMinCell);
    inverse_ = 1.0f / cell_;
    maxRadius_ = 0.0f;
    large_.clear();
    largeSpheres_.clear();
    std::size_t total = 0;
    for (const Source& s : sources) total += s.spheres->size();
    // Buckets: a power of two, at least as many as triangles.
    int bits = 6;
    while ((std::size_t(1) << bits) < total && bits < 30) ++bits;
    shift_ = 64 - bits;
    const std::size_t buckets = std::size_t(1) << bits;
    start_.assign(buckets + 1, 0);
    // Counting sort by bucket; large triangles aside.
    for (const Source& s : sources)
        for (std::size_t t = 0; t < s.keys->size(); ++t) {
            const std::uint64_t key = (*s.keys)[t];
            if (key == kLarge) {
                large_.push_back({s.soup->data() + 3 * t, s.owner, s.tags ? (*s.tags)[t] : 0});
                largeSpheres_.push_back((*s.spheres)[t]);
                continue;
            }
            maxRadius_ = std::max(maxRadius_, (*s.spheres)[t].w);
            ++start_[bucketOf(key) + 1];
        }
    for (std::size_t b = 0; b < buckets; ++b) start_[b + 1] += start_[b];
    const std::size_t n = start_[buckets];
    small_.resize(n);
    keys_.resize(n);
    spheres_.resize(n);
    fill_.assign(start_.begin(), start_.end() - 1);
    for (const Source& s : sources)  // stable: sources' order within each bucket
        for (std::size_t t = 0; t < s.keys->size(); ++t) {
            const std::uint64_t key = (*s.keys)[t];
            if (key == kLarge) continue;
            const std::uint32_t at = fill_[bucketOf(key)]++;
            small_[at] = {s.soup->data() + 3 * t, s.owner, s.tags ? (*s.tags)[t] : 0};
            keys_[at] = key;
            spheres_[at] = (*s.spheres)[t];
        }
}

void SoftGrid::near(vec3 centre, float radius, const Ignore* ignore,
                    std::vector<const vec3*>& out, const vec3* front) const {
    const vec3 facing = front ? *front : vec3(0.0f);
    const float behind = front ? 0.0f : 1.0f;  // with no plane, nothing is behind it
    auto reaches = [&](const glm::vec4& s) {
        const vec3 d = vec3(s) - centre;
        const float r = radius + s.w;
        return glm::dot(d, d) <= r * r && glm::dot(d, facing) + s.w + behind >= 0.0f;
    };
    for (std::size_t i = 0; i < large_.size(); ++i)
        if (reaches(largeSpheres_[i]) && !ignored(large_[i], ignore)) out.push_back(large_[i].corners);
    if (small_.empty()) return;
    // Cells holding sphere centres within radius + the largest small sphere.
    const float reach = radius + maxRadius_;
    const std::int64_t x0 = cellIndex(centre.x - reach, inverse_), x1 = cellIndex(centre.x + reach, inverse_);
    const std::int64_t y0 = cellIndex(centre.y - reach, inverse_), y1 = cellIndex(centre.y + reach, inverse_);
    const std::int64_t z0 = cellIndex(centre.z - reach, inverse_), z1 = cellIndex(centre.z + reach, inverse_);
    const float reach2 = reach * reach;
    for (std::int64_t x = x0; x <= x1; ++x) {
        const float dx = std::max({0.0f, float(x) * cell_ - centre.x, centre.x - float(x + 1) * cell_});
        for (std::int64_t y = y0; y <= y1; ++y) {
            const float dy =
                std::max({0.0f, float(y) * cell_ - centre.y, centre.y - float(y + 1) * cell_});
            if (dx * dx + dy * dy > reach2) continue;
            for (std::int64_t z = z0; z <= z1; ++z) {
                const float dz =
                    std::max({0.0f, float(z) * cell_ - centre.z, centre.z - float(z + 1) * cell_});
                if (dx * dx + dy * dy + dz * dz > reach2) continue;
                const std::uint64_t key = pack(x, y, z);
                const std::size_t b = bucketOf(key);
                for (std::uint32_t i = start_[b], end = start_[b + 1]; i < end; ++i)
                    if (keys_[i] == key && reaches(spheres_[i]) && !ignored(small_[i], ignore))
                        out.push_back(small_[i].corners);
            }
        }
    }
}

}  // namespace plantarch::collision
