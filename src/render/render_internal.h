#pragma once
// Internals of the preview renderer shared by its source files: the prepared scene, textures,
// colour conversion and the per-pixel sampler. Not installed.

#include <embree3/rtcore.h>

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "plantarch/Render.h"

namespace plantarch::render_detail {

// ---- colour ----------------------------------------------------------------------------

inline float srgbToLinear(float c) {
    return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}
inline vec3 srgbToLinear(const vec3& c) {
    return {srgbToLinear(c.x), srgbToLinear(c.y), srgbToLinear(c.z)};
}
/// Linear [0, inf) to an sRGB byte (clamped).
std::uint8_t linearToSrgbByte(float linear);
/// sRGB byte to linear, by table.
float srgbByteToLinear(std::uint8_t value);

// ---- textures --------------------------------------------------------------------------

/// An 8-bit RGBA image used as a surface texture. Lookups wrap (repeat) and filter
/// bilinearly; v = 0 is the bottom row, as in OBJ.
struct Texture {
    int width = 0;
    int height = 0;
    std::vector<std::uint8_t> rgba;
    bool hasMask = false;  ///< some texel has alpha below one half: cut-out geometry
    vec3 meanColor{0.5f};  ///< linear mean over opaque texels, for objects without UVs

    /// Linear RGB at (u, v).
    vec3 color(vec2 uv) const;
    /// Alpha (0..1) at (u, v), nearest texel.
    float alpha(vec2 uv) const;
};

/// Loads a texture file; throws plantarch::Error naming the file when it cannot be read.
Texture loadTexture(const std::string& path);
/// A texture of RGBA pixels (sRGB, row 0 at v = 1), such as a procedural map.
Texture textureOfPixels(int width, int height, std::vector<std::uint8_t> rgba);

// ---- prepared scene --------------------------------------------------------------------

inline constexpr std::uint8_t kOrganOther = 255;

/// What shading needs to know about one object.
struct ObjectInfo {
    ObjectID id = 0;
    vec3 albedo{0.5f};                 ///< linear; used when texture < 0
    std::int32_t texture = -1;         ///< index into Impl::textures, -1 for a plain colour
    std::uint8_t organ = kOrganOther;  ///< index into organLabelColors()
};

/// One Embree triangle geometry and the arrays that map its primitives back to objects.
/// Geometry 0 holds opaque objects; geometry 1 holds objects whose texture has an alpha mask
/// (an Embree filter function discards hits on transparent texels).
struct GeometryData {
    RTCGeometry geometry = nullptr;
    const float* positions = nullptr;        ///< Embree's vertex buffer (xyz per vertex)
    const std::uint32_t* indices = nullptr;  ///< Embree's index buffer
    std::size_t vertexCount = 0;
    std::vector<std::uint32_t> triangleObject;  ///< object slot (into Impl::objects)
    std::vector<vec3> normals;                  ///< per-vertex smooth normals; empty when disabled
    std::vector<vec2> uvs;  ///< per-vertex UVs; empty when no object here is textured
    const struct SceneData* scene = nullptr;
};

struct SceneData {
    RTCScene scene = nullptr;
    std::vector<ObjectInfo> objects;
    std::vector<Texture> textures;
    GeometryData geometries[2];
    AABB bounds;
    std::size_t triangles = 0;

    SceneData() = default;
    SceneData(const SceneData&) = delete;
    SceneData& operator=(const SceneData&) = delete;
    ~SceneData();
};

void buildScene(SceneData& data, const Context& context, const RenderSceneOptions& options);

/// A camera frame's view direction (unit, toward the target) and the world up its image's up
/// is made from (unit; an up parallel to the view falls back to y, then x).
struct CameraAxes {
    vec3 forward, worldUp;
};
CameraAxes cameraAxes(const CameraFrame& frame);

// ---- sampling ----------------------------------------------------------------------------

/// A small counter-based random stream: the same (seed, pixel) gives the same numbers on any
/// thread. SplitMix64 output function over a Weyl sequence.
class PixelSampler {
public:
    PixelSampler(std::uint64_t seed, std::uint64_t pixel) : state_(mix(seed ^ mix(pixel + 1))) {}
    /// Uniform in [0, 1) with 24 bits.
    float next() {
        state_ += 0x9E3779B97F4A7C15ULL;
        return float(mix(state_) >> 40) * 0x1p-24f;
    }

private:
    static std::uint64_t mix(std::uint64_t z) {
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
        return z ^ (z >> 31);
    }
    std::uint64_t state_;
};

}  // namespace plantarch::render_detail
