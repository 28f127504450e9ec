#pragma once
// Procedural surface textures: leaf blades (venation drawn from the leaf's texture space,
// margin and colour variation, alpha from its outline), bark and green stems, as base colour,
// normal and occlusion-roughness-metallic maps. Pure functions of their inputs (a colour, a
// seed, a size, an outline mask): the same inputs give the same pixels on any thread count.
//
// Texture spaces the tessellator gives (src/geometry):
//   leaf:  u along the midrib, 0 at the base to 1 at the tip; v across, the midrib at 0.5, the
//          blade's bounding box of width leaf_aspect_ratio mapped onto 0 to 1.
//   tube:  u around the tube (0 to 1), v along it in units of its circumference (repeats).
// Images are square, row 0 at v = 1 (OBJ, USD and the renderer's convention; glTF's images
// are these flipped upside down).

#include <cstdint>
#include <span>
#include <vector>

#include "plantarch/Mesh.h"

namespace plantarch::io {

/// What a material's surface is drawn as.
enum class SurfaceKind : std::uint8_t {
    Leaf,    ///< a leaf blade: venation, margin, alpha from the outline
    Bark,    ///< an internode: fissured bark, or fine striations where the colour is green
    Stem,    ///< a petiole or peduncle: fine green striations
    Fruit,   ///< a fruit: glossy, no texture
    Flower,  ///< a flower: satin, no texture
    Other,   ///< anything else (ground, obstacles, untagged): flat, as without textures
};

/// The name of a kind ("leaf", "bark", "stem", "fruit", "flower", "other").
const char* surfaceKindName(SurfaceKind kind);

/// glTF-style material factors of a kind.
struct SurfaceFactors {
    float roughness = 0.8f;
    float metallic = 0.0f;
};
SurfaceFactors surfaceFactors(SurfaceKind kind);

/// The maps of one material, each size x size, row 0 at v = 1.
struct TextureMaps {
    int size = 0;
    int height = 0;  ///< rows when not `size` (an atlas, material_textures.h); 0: size
    int rows() const { return height > 0 ? height : size; }
    std::vector<std::uint8_t> baseColor;  ///< RGBA, sRGB colour, alpha 0 outside the outline
    std::vector<std::uint8_t> normal;     ///< RGB, tangent space (+x along u, +y along v)
    std::vector<std::uint8_t> orm;        ///< RGB: occlusion, roughness, metallic (glTF order)
    bool hasAlpha = false;                ///< some texel is transparent
};

/// What a leaf texture is drawn from.
struct LeafTextureInput {
    vec3 color{0.3f, 0.45f, 0.18f};  ///< the blade's colour, sRGB 0..1
    std::uint64_t seed = 0;
    int size = 512;
    /// Blade width over length, as the leaf's texture space stretches it (lateral veins are
    /// drawn at their true angles); 0.05 to 5.
    float aspect = 0.5f;
    /// Parallel veins along the blade (grasses) instead of a midrib with pinnate laterals.
    bool parallelVeins = false;
    /// size x size coverage of the blade (nonzero inside), row 0 at v = 1; empty: the whole
    /// square is blade (no alpha).
    std::vector<std::uint8_t> mask;
};
TextureMaps leafTextureMaps(const LeafTextureInput& input);

/// Bark (or a green stem's skin) that repeats in u and v.
TextureMaps barkTextureMaps(vec3 color, std::uint64_t seed, int size, bool stem);

/// Coverage of triangles given by their texture coordinates: `mask` (size x size, row 0 at
/// v = 1) gets 255 at every texel a triangle touches (texels crossed by an edge included, so
/// the outline never loses a texel it passes through). Triangles outside 0..1 are clipped.
void rasterizeUVTriangles(std::span<const vec2> uvs, std::span<const std::uint32_t> indices,
                          int size, std::vector<std::uint8_t>& mask);

/// 64-bit FNV-1a over bytes, continuing from `hash`.
std::uint64_t fnv1a(const void* data, std::size_t bytes,
                    std::uint64_t hash = 14695981039346656037ull);

}  // namespace plantarch::io
