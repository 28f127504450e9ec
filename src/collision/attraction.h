#pragma once
// Attraction points with a uniform grid for "nearest point in the cone" queries.

#include <cstdint>
#include <optional>
#include <string>
#include <unordered_map>
#include <vector>

#include "plantarch/Collision.h"

namespace plantarch::collision {

class AttractionIndex {
public:
    explicit AttractionIndex(AttractionPoints points);

    const AttractionPoints& options() const { return options_; }
    /// Whether shoots of this type are attracted.
    bool attracts(const std::string& shootType) const;
    /// The nearest point (ties: the lowest index) within the look-ahead distance of `apex`,
    /// within the half-angle of `direction` (unit), and farther than `minDistance`.
    std::optional<vec3> nearestInCone(vec3 apex, vec3 direction, float minDistance) const;

private:
    std::int64_t key(int x, int y, int z) const;
    AttractionPoints options_;
    float cell_ = 1.0f;
    std::unordered_map<std::int64_t, std::vector<std::uint32_t>> grid_;
};

}  // namespace plantarch::collision
