// Attraction point queries (see attraction.h).

#include "collision/attraction.h"

#include <algorithm>
#include <cmath>

namespace plantarch::collision {

namespace {

constexpr float kDeg = 3.14159265358979f / 180.0f;

int cellOf(float v, float cell) { return int(std::floor(v / cell)); }

}  // namespace

AttractionIndex::AttractionIndex(AttractionPoints points) : options_(std::move(points)) {
    cell_ = std::max(options_.lookAhead, 1e-3f);
    for (std::uint32_t i = 0; i < options_.points.size(); ++i) {
        const vec3& p = options_.points[i];
        grid_[key(cellOf(p.x, cell_), cellOf(p.y, cell_), cellOf(p.z, cell_))].push_back(i);
    }
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
    const int cx = cellOf(apex.x, cell_), cy = cellOf(apex.y, cell_), cz = cellOf(apex.z, cell_);
    float bestD2 = reach * reach;
    std::uint32_t best = 0;
    bool found = false;
    for (int dx = -1; dx <= 1; ++dx)
        for (int dy = -1; dy <= 1; ++dy)
            for (int dz = -1; dz <= 1; ++dz) {
                auto it = grid_.find(key(cx + dx, cy + dy, cz + dz));
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

}  // namespace plantarch::collision
