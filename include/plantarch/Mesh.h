#pragma once
// Small value types shared by the whole library: an indexed triangle mesh, a material,
// an axis-aligned box. Conventions: z up, metres.

#include <cstdint>
#include <glm/glm.hpp>
#include <limits>
#include <string>
#include <vector>

namespace plantarch {

using glm::mat4;
using glm::vec2;
using glm::vec3;

/// An indexed triangle mesh in its own coordinates.
struct Mesh {
    std::vector<vec3> positions;
    std::vector<vec2> uvs;               ///< empty, or exactly one per position
    std::vector<std::uint32_t> indices;  ///< three per triangle, into positions

    std::size_t triangleCount() const { return indices.size() / 3; }
    std::size_t vertexCount() const { return positions.size(); }
    bool empty() const { return indices.empty(); }
    bool hasUVs() const { return !uvs.empty(); }

    /// Appends `other` transformed by `transform` (UVs kept if both meshes have them).
    void append(const Mesh& other, const mat4& transform = mat4(1.0f));
    /// Applies `transform` to every position.
    void transform(const mat4& transform);
    /// Sum of triangle areas (m^2 when positions are in metres).
    double area() const;
    /// Throws plantarch::Error if an index is out of range, the index count is not a multiple
    /// of 3, a position is not finite or the UV count does not match.
    void validate() const;
};

/// Surface appearance of an object: an RGB colour (0..1), optionally an image texture
/// mapped with the object's UVs. Materials are compared by value and shared.
struct Material {
    vec3 color{0.5f, 0.5f, 0.5f};
    std::string texture;  ///< image file path; empty for a plain colour
    std::string name;     ///< optional name used by exporters; generated when empty

    bool operator==(const Material&) const = default;
};

/// Axis-aligned bounding box; empty() until a point is added.
struct AABB {
    vec3 min{std::numeric_limits<float>::max()};
    vec3 max{-std::numeric_limits<float>::max()};

    bool empty() const { return min.x > max.x; }
    void add(const vec3& p) {
        min = glm::min(min, p);
        max = glm::max(max, p);
    }
    void add(const AABB& b) {
        if (!b.empty()) {
            add(b.min);
            add(b.max);
        }
    }
    vec3 center() const { return 0.5f * (min + max); }
    vec3 extent() const { return empty() ? vec3(0.0f) : max - min; }
};

}  // namespace plantarch
