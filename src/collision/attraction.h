#pragma once
// Attraction points with a uniform grid for the queries of growing tips: the nearest point in
// the perception cone, and the wire (a line of points) a tip has reached.

#include <cstdint>
#include <optional>
#include <string>
#include <unordered_map>
#include <vector>

#include "plantarch/Collision.h"

namespace plantarch::collision {

/// What a growing tip asks the attraction points.
struct TipQuery {
    vec3 apex{0.0f};                   ///< where the new internode starts, m
    vec3 direction{0.0f, 0.0f, 1.0f};  ///< the way it would grow (unit)
    vec3 shootBase{0.0f};              ///< where the tip's shoot starts, m
    float minDistance = 0;             ///< points nearer than this are passed by, m
    float reach = 0;                   ///< a wire this near is reached (one internode), m
};

/// A spatial index of AttractionPoints, derived from them (rebuilt when they change).
///
/// Points listed one after the other, at most the look-ahead distance apart, form a line (a
/// wire): a species file's <wire> is such a run, and so is any list of points given along a
/// wire. The lines let a tip that reaches a wire follow it instead of crossing it.
class AttractionIndex {
public:
    explicit AttractionIndex(AttractionPoints points);

    const AttractionPoints& options() const { return options_; }
    /// Whether shoots of this type are attracted.
    bool attracts(const std::string& shootType) const;
    /// The nearest point (ties: the lowest index) within the look-ahead distance of `apex`,
    /// within the half-angle of `direction` (unit), and farther than `minDistance`.
    std::optional<vec3> nearestInCone(vec3 apex, vec3 direction, float minDistance) const;
    /// Where a growing tip is drawn to (see docs/collision.md).
    ///  - On a wire: when a line of points passes within `reach` of the apex (at most the
    ///    look-ahead distance), the target is the point `reach` farther along that line, the
    ///    way the tip grows: the tip turns onto the wire and follows it to its end instead of
    ///    crossing it. A shoot that starts on a wire (its base within `reach` of it: a shoot
    ///    growing out of a tied cane) follows that wire only when it grows within the
    ///    half-angle of it, so shoots grow freely away from the wire they are born on.
    ///  - Otherwise: nearestInCone (points nearer than `minDistance` passed by).
    /// Ties go to the lowest index.
    std::optional<vec3> target(const TipQuery& tip) const;

private:
    struct Cell {
        int x, y, z;
    };
    Cell cellOf(vec3 p) const;
    std::int64_t key(int x, int y, int z) const;
    /// The target along the wire the tip is on, if it is on one.
    std::optional<vec3> alongWire(const TipQuery& tip) const;
    /// Distance from p to segment i, its nearest point, and whether p is beside the segment
    /// (its projection on the segment's line falls within the segment).
    float toSegment(std::uint32_t i, vec3 p, vec3& nearest, bool& beside) const;

    AttractionPoints options_;
    float cell_ = 1.0f;
    std::unordered_map<std::int64_t, std::vector<std::uint32_t>> grid_;
    /// Segments of the lines: segment i joins points i and i + 1. Each is listed in every cell
    /// its bounding box overlaps (its length is at most one cell).
    std::unordered_map<std::int64_t, std::vector<std::uint32_t>> segments_;
};

}  // namespace plantarch::collision
