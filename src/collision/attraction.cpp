// Attraction point queries (see attraction.h).

#include "collision/attraction.h"

#include <algorithm>
#include <cmath>

#include "core/math.h"

namespace plantarch::collision {

AttractionIndex::AttractionIndex(AttractionPoints points) : options_(std::move(points)) {
    cell_ = std::max(options_.lookAhead, 1e-3f);
    const std::vector<vec3>& p = options_.points;
    for (std::uint32_t i = 0; i < p.size(); ++i) {
        const Cell c = cellOf(p[i]);
        grid_[key(c.x, c.y, c.z)].push_back(i);
    }
    for (std::uint32_t i = 0; i + 1 < p.size(); ++i) {
        const float length = glm::length(p[i + 1] - p[i]);
        if (!(length > 0.0f && length <= options_.lookAhead)) continue;  // not one line
        const Cell lo = cellOf(glm::min(p[i], p[i + 1]));
        const Cell hi = cellOf(glm::max(p[i], p[i + 1]));
        for (int x = lo.x; x <= hi.x; ++x)
            for (int y = lo.y; y <= hi.y; ++y)
                for (int z = lo.z; z <= hi.z; ++z) segments_[key(x, y, z)].push_back(i);
    }
}

AttractionIndex::Cell AttractionIndex::cellOf(vec3 p) const {
    // Clamped so that any finite coordinate gives a valid int (far cells share keys anyway).
    auto index = [this](float v) { return int(std::clamp(std::floor(v / cell_), -1e9f, 1e9f)); };
    return {index(p.x), index(p.y), index(p.z)};
}

std::int64_t AttractionIndex::key(int x, int y, int z) const {
    // 21 bits per axis (cells of the look-ahead size: +-1e6 cells covers any scene).
    auto part = [](int v) { return std::int64_t(v & 0x1FFFFF); };
    return (part(x) << 42) | (part(y) << 21) | part(z);
}

bool AttractionIndex::attracts(const std::string& shootType) const {
    return options_.shootTypes.empty() ||
           std::find(options_.shootTypes.begin(), options_.shootTypes.end(), shootType) !=
               options_.shootTypes.end();
}

std::optional<vec3> AttractionIndex::nearestInCone(vec3 apex, vec3 direction,
                                                   float minDistance) const {
    const float reach = options_.lookAhead;
    const float cosHalf = std::cos(options_.halfAngle * kDeg);
    const Cell c = cellOf(apex);
    float bestD2 = reach * reach;
    std::uint32_t best = 0;
    bool found = false;
    for (int dx = -1; dx <= 1; ++dx)
        for (int dy = -1; dy <= 1; ++dy)
            for (int dz = -1; dz <= 1; ++dz) {
                auto it = grid_.find(key(c.x + dx, c.y + dy, c.z + dz));
                if (it == grid_.end()) continue;
                for (std::uint32_t i : it->second) {
                    const vec3 d = options_.points[i] - apex;
                    const float d2 = glm::dot(d, d);
                    if (d2 > bestD2 || d2 <= minDistance * minDistance) continue;
                    if (d2 == bestD2 && found && i > best) continue;
                    if (glm::dot(d, direction) < cosHalf * std::sqrt(d2)) continue;
                    bestD2 = d2;
                    best = i;
                    found = true;
                }
            }
    if (!found) return std::nullopt;
    return options_.points[best];
}

float AttractionIndex::toSegment(std::uint32_t i, vec3 p, vec3& nearest, bool& beside) const {
    const vec3 a = options_.points[i], ab = options_.points[i + 1] - a;
    const float t = glm::dot(p - a, ab) / glm::dot(ab, ab);
    beside = t >= 0.0f && t <= 1.0f;
    nearest = a + std::clamp(t, 0.0f, 1.0f) * ab;
    return glm::length(p - nearest);
}

std::optional<vec3> AttractionIndex::alongWire(const TipQuery& tip) const {
    if (segments_.empty() || !(tip.reach > 0.0f)) return std::nullopt;
    const float reach = std::min(tip.reach, options_.lookAhead);  // within the cells searched
    const float cosHalf = std::cos(options_.halfAngle * kDeg);
    const std::vector<vec3>& p = options_.points;
    const Cell c = cellOf(tip.apex);
    float bestDistance = reach;
    std::optional<vec3> best;
    std::uint32_t bestIndex = 0;
    for (int dx = -1; dx <= 1; ++dx)
        for (int dy = -1; dy <= 1; ++dy)
            for (int dz = -1; dz <= 1; ++dz) {
                auto it = segments_.find(key(c.x + dx, c.y + dy, c.z + dz));
                if (it == segments_.end()) continue;
                for (std::uint32_t i : it->second) {
                    vec3 q, unused;
                    bool beside = false, baseBeside = false;
                    const float d = toSegment(i, tip.apex, q, beside);
                    // Beyond the end of a wire nothing holds the tip.
                    if (!beside || d > bestDistance || (d == bestDistance && best && i > bestIndex))
                        continue;
                    // Along the wire, the way the tip grows.
                    vec3 along = glm::normalize(p[i + 1] - p[i]);
                    if (glm::dot(along, tip.direction) < 0.0f) along = -along;
                    // A shoot born on this wire follows it only when it grows along it.
                    if (toSegment(i, tip.shootBase, unused, baseBeside) <= reach &&
                        glm::dot(along, tip.direction) < cosHalf)
                        continue;
                    bestDistance = d;
                    bestIndex = i;
                    best = q + reach * along;
                }
            }
    return best;
}

std::optional<vec3> AttractionIndex::target(const TipQuery& tip) const {
    if (auto onWire = alongWire(tip)) return onWire;
    return nearestInCone(tip.apex, tip.direction, tip.minDistance);
}

}  // namespace plantarch::collision
