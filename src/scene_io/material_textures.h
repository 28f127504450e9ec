#pragma once
// The textured look of a scene's materials (MaterialOptions, plantarch/Export.h): which
// surface each material is (from the "organ" of the objects using it), its PBR factors, and
// the procedural maps drawn for it (procedural_textures.h), shared by the glTF, USD and OBJ
// writers and the renderer.
//
// Maps are drawn once per distinct (surface, colour, outline): a leaf's outline is the union
// of the texture-space triangles of the distinct leaf meshes using the material (copies of a
// prototype share theirs), its aspect the blade's width over length measured on its first
// object. Everything is a function of the exported objects, so the same scene gives the same
// bytes.
//
// With MaterialOptions::atlas, the sets of leaves whose texture coordinates all stay in 0..1
// (bark and stem skins repeat along their tubes and keep their own images) are drawn into one
// atlas (texture_atlas.h) when two or more are: their materials' looks name the atlas's maps
// and the transform onto their rectangle. An atlas that would pass kMaxAtlasSide is not made.

#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "plantarch/Context.h"
#include "plantarch/Export.h"
#include "scene_io/procedural_textures.h"
#include "scene_io/texture_atlas.h"

namespace plantarch::io {

/// The image files a material's maps become.
enum class MapKind : std::uint8_t {
    BaseColor,  ///< RGBA (RGB where no texel is transparent)
    Normal,     ///< RGB tangent-space normals
    ORM,        ///< RGB occlusion, roughness, metallic (glTF's metallicRoughness order)
    Alpha,      ///< grey: the base colour's alpha (OBJ's map_d)
    Roughness,  ///< grey: the roughness (OBJ's map_Pr)
};
inline constexpr std::size_t kMapKinds = 5;
/// "basecolor", "normal", "orm", "alpha", "roughness".
const char* mapKindName(MapKind kind);

/// How a material is drawn.
struct MaterialLook {
    SurfaceKind kind = SurfaceKind::Other;
    SurfaceFactors factors;
    int maps = -1;          ///< index into MaterialLooks::maps(); -1: a colour (and factors) only
    bool inAtlas = false;   ///< maps is the atlas: read it through `transform`
    UVTransform transform;  ///< the material's [0,1] square onto its part of the atlas
};

/// The maps drawn for one or more materials.
struct MaterialMaps {
    std::string name;  ///< "leaf_0", "bark_1", ..., "atlas": unique in the scene
    SurfaceKind kind = SurfaceKind::Other;
    TextureMaps pixels;                      ///< kept when asked (the renderer)
    std::array<std::string, kMapKinds> png;  ///< PNG bytes of the kinds asked for
    bool hasAlpha = false;
    bool atlas = false;  ///< the atlas of several sets (pixels.height rows of pixels.size)
};

/// What to keep of the drawn maps.
struct MapRequest {
    std::vector<MapKind> png;  ///< encode these kinds as PNG
    bool flipRows = false;     ///< PNG rows from v = 0 up (glTF's convention)
    bool keepPixels = false;   ///< keep MaterialMaps::pixels
};

class MaterialLooks {
public:
    /// Flat looks: every material a colour only.
    MaterialLooks() = default;
    /// The looks of the materials the exported objects of `contexts` use (every object when
    /// includeHidden), drawn at options.textureSize (checked: checkMaterialOptions). With
    /// MaterialStyle::Flat, or `uvs` false, no maps are drawn (factors still given).
    MaterialLooks(std::span<const Context* const> contexts, const MaterialOptions& options,
                  bool includeHidden, bool uvs, const MapRequest& request);

    /// The look of a material (by value); Other with no maps for one not seen.
    const MaterialLook& look(const Material& material) const;
    const std::vector<MaterialMaps>& maps() const { return maps_; }
    bool textured() const { return textured_; }

private:
    bool textured_ = false;
    std::vector<std::pair<Material, MaterialLook>> looks_;
    std::vector<MaterialMaps> maps_;
};

/// PNG bytes of one map of `maps` (row 0 at v = 1, or v = 0 when flipRows).
std::string encodeMapPNG(const TextureMaps& maps, MapKind kind, bool flipRows);

/// The file name a writer gives a map: `<prefix><maps.name>_<kind>.png`.
std::string mapFileName(const std::string& prefix, const MaterialMaps& maps, MapKind kind);

}  // namespace plantarch::io
