#include "plantarch/Mesh.h"

#include <cmath>
#include <string>

#include "plantarch/Error.h"

namespace plantarch {

void Mesh::append(const Mesh& other, const mat4& xf) {
    const auto base = static_cast<std::uint32_t>(positions.size());
    const bool keepUVs = (hasUVs() || positions.empty()) && other.hasUVs();
    if (!keepUVs && hasUVs()) uvs.clear();
    positions.reserve(positions.size() + other.positions.size());
    for (const vec3& p : other.positions) positions.push_back(vec3(xf * glm::vec4(p, 1.0f)));
    if (keepUVs) uvs.insert(uvs.end(), other.uvs.begin(), other.uvs.end());
    indices.reserve(indices.size() + other.indices.size());
    for (std::uint32_t i : other.indices) indices.push_back(base + i);
}

void Mesh::transform(const mat4& xf) {
    for (vec3& p : positions) p = vec3(xf * glm::vec4(p, 1.0f));
}

double Mesh::area() const {
    double total = 0.0;
    for (std::size_t t = 0; t + 2 < indices.size(); t += 3) {
        const glm::dvec3 a(positions[indices[t]]), b(positions[indices[t + 1]]),
            c(positions[indices[t + 2]]);
        total += 0.5 * glm::length(glm::cross(b - a, c - a));
    }
    return total;
}

void Mesh::validate() const {
    if (indices.size() % 3 != 0)
        throw Error("index count is not a multiple of 3",
                    {.parameter = "mesh.indices", .value = std::to_string(indices.size())});
    if (!uvs.empty() && uvs.size() != positions.size())
        throw Error("UV count must equal position count",
                    {.parameter = "mesh.uvs",
                     .value = std::to_string(uvs.size()),
                     .validRange = "0 or " + std::to_string(positions.size())});
    for (std::size_t i = 0; i < indices.size(); ++i)
        if (indices[i] >= positions.size())
            throw Error(
                "vertex index out of range",
                {.parameter = "mesh.indices[" + std::to_string(i) + "]",
                 .value = std::to_string(indices[i]),
                 .validRange = "0 to " + std::to_string(positions.size()) + " (exclusive)"});
    for (std::size_t i = 0; i < positions.size(); ++i) {
        const vec3& p = positions[i];
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
            throw Error("vertex position is not finite",
                        {.parameter = "mesh.positions[" + std::to_string(i) + "]",
                         .validRange = "finite coordinates"});
    }
}

}  // namespace plantarch
