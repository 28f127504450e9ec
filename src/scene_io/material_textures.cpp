// Materials' textured looks: surfaces classified by organ, maps drawn once per distinct
// surface (material_textures.h), and the MaterialOptions checks of plantarch/Export.h.

#include "scene_io/material_textures.h"

#include <unistd.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <optional>
#include <string_view>

#include "core/parallel.h"
#include "core/stb.h"
#include "plantarch/Error.h"
#include "scene_io/export_common.h"

namespace plantarch {

const char* materialStyleName(MaterialStyle style) {
    return style == MaterialStyle::Textured ? "textured" : "flat";
}

std::optional<MaterialStyle> materialStyleFromName(std::string_view name) {
    if (name == "flat") return MaterialStyle::Flat;
    if (name == "textured") return MaterialStyle::Textured;
    return std::nullopt;
}

void checkMaterialOptions(const MaterialOptions& options) {
    const int n = options.textureSize;
    if (n < kMinTextureSize || n > kMaxTextureSize || !std::has_single_bit(unsigned(n)))
        throw Error("texture size " + std::to_string(n) + " is not allowed",
                    {.parameter = "texture_size",
                     .value = std::to_string(n),
                     .validRange = "a power of two from " + std::to_string(kMinTextureSize) +
                                   " to " + std::to_string(kMaxTextureSize)});
}

namespace io {

namespace mattex {

// The largest outline mask drawn (texels a side); larger textures scale it up.
constexpr int kMaxMaskSize = 1024;
// Distinct leaf meshes drawn into one outline at most; a material with more gets no alpha.
constexpr std::size_t kMaxOutlineShapes = 256;

SurfaceKind surfaceOfOrgan(std::string_view organ) {
    if (organ == "leaf") return SurfaceKind::Leaf;
    if (organ == "internode") return SurfaceKind::Bark;
    if (organ == "petiole" || organ == "peduncle") return SurfaceKind::Stem;
    if (organ == "fruit") return SurfaceKind::Fruit;
    if (organ == "flower_open" || organ == "flower_closed") return SurfaceKind::Flower;
    return SurfaceKind::Other;
}

// What is known of one material while planning.
struct Planned {
    Material material;
    MaterialLook look;
    bool allUVs = true;
    std::vector<std::uint64_t> shapes;  // hashes of the distinct leaf meshes drawn
    std::vector<std::uint8_t> mask;     // their texture-space coverage
    bool maskOverflow = false;
    float aspect = -1.0f;
    bool mixed = false;   // used by organs of different surfaces (a file read without materials)
    bool unitUVs = true;  // every leaf's texture coordinates in 0..1 (an atlas can hold it)
};

// Texture coordinates within the unit square (a rounding's worth outside allowed).
bool withinUnitSquare(std::span<const vec2> uvs) {
    constexpr float lo = -1e-4f, hi = 1.0f + 1e-4f;
    for (const vec2 uv : uvs)
        if (!(uv.x >= lo && uv.x <= hi && uv.y >= lo && uv.y <= hi)) return false;
    return true;
}

// Blade width over length as the leaf's texture space stretches it: the area-weighted mean
// of |dP/dv| / |dP/du| over its triangles.
float textureAspect(const ObjectView& o) {
    double sum = 0.0, weight = 0.0;
    for (std::size_t t = 0; t + 2 < o.indices.size(); t += 3) {
        const std::uint32_t a = o.indices[t], b = o.indices[t + 1], c = o.indices[t + 2];
        const vec3 e1 = o.positions[b] - o.positions[a], e2 = o.positions[c] - o.positions[a];
        const vec2 d1 = o.uvs[b] - o.uvs[a], d2 = o.uvs[c] - o.uvs[a];
        const float det = d1.x * d2.y - d2.x * d1.y;
        if (std::abs(det) < 1e-9f) continue;
        const vec3 T = (e1 * d2.y - e2 * d1.y) / det, B = (e2 * d1.x - e1 * d2.x) / det;
        const float lt = glm::length(T), lb = glm::length(B);
        const float area = 0.5f * glm::length(glm::cross(e1, e2));
        if (!(lt > 0.0f) || !std::isfinite(lb / lt) || !(area > 0.0f)) continue;
        sum += double(area) * double(lb / lt);
        weight += double(area);
    }
    return weight > 0.0 ? float(sum / weight) : 0.5f;
}

std::vector<std::uint8_t> scaledMask(const std::vector<std::uint8_t>& mask, int from, int to) {
    if (from == to) return mask;
    std::vector<std::uint8_t> out(std::size_t(to) * std::size_t(to));
    const int f = to / from;
    for (int j = 0; j < to; ++j)
        for (int i = 0; i < to; ++i)
            out[std::size_t(j) * std::size_t(to) + std::size_t(i)] =
                mask[std::size_t(j / f) * std::size_t(from) + std::size_t(i / f)];
    return out;
}

// Grass-like blades get parallel veins: narrow (under 0.28 of their length wide) and, a tenth
// of the way up, already over half as wide as at their widest (a strap, where a narrow
// lanceolate or elliptic blade still tapers to its base). Without an outline, blades under
// 0.195 wide.
bool parallelVenation(const std::vector<std::uint8_t>& mask, int n, float aspect) {
    if (mask.empty()) return aspect < 0.195f;
    if (aspect >= 0.28f) return false;
    auto width = [&](int i) {
        int w = 0;
        for (int j = 0; j < n; ++j)
            w += mask[std::size_t(j) * std::size_t(n) + std::size_t(i)] != 0;
        return w;
    };
    int widest = 0;
    for (int i = 0; i < n; ++i) widest = std::max(widest, width(i));
    return 2 * width(n / 10) > widest;
}

// Memory a scene's textures take while they are drawn and written: one set's pixels and
// buffers (about 20 bytes a texel) and every set's PNGs (about 2.5 bytes a texel), or every
// set's pixels when they are kept (10 bytes a texel); `packed` of the sets go to an atlas of
// `atlasTexels` instead (its pixels, 10 bytes a texel, one map's copy to encode and its PNGs).
// Refused above half the machine's memory.
void checkTextureMemory(std::size_t sets, std::size_t packed, int size, bool keepPixels,
                        double atlasTexels) {
    if (sets == 0) return;
    const auto bytesAt = [&](int n) {
        const double texels = double(n) * double(n), scale = texels / double(size) / size;
        return texels * (20.0 + double(sets - packed) * (keepPixels ? 12.5 : 2.5)) +
               atlasTexels * scale * (keepPixels ? 14.0 : 17.0);
    };
    const double bytes = bytesAt(size);
    const long pages = sysconf(_SC_PHYS_PAGES), pageSize = sysconf(_SC_PAGESIZE);
    if (pages <= 0 || pageSize <= 0) return;
    const double half = 0.5 * double(pages) * double(pageSize);
    if (bytes <= half) return;
    int fits = size;
    while (fits > kMinTextureSize && bytesAt(fits) > half) fits /= 2;
    throw Error(std::to_string(sets) + " textured materials at " + std::to_string(size) +
                    " texels a side need about " + std::to_string(int(bytes / 1e9 + 0.5)) +
                    " GB, more than half of this machine's memory",
                {.parameter = "texture_size",
                 .value = std::to_string(size),
                 .validRange = "at most " + std::to_string(fits) + " on this machine"});
}

// An atlas of `layout`'s size: transparent, flat normals, no occlusion, until drawn into.
MaterialMaps emptyAtlas(const AtlasLayout& layout) {
    MaterialMaps atlas;
    atlas.name = "atlas";
    atlas.kind = SurfaceKind::Leaf;
    atlas.atlas = true;
    const std::size_t texels = std::size_t(layout.width) * std::size_t(layout.height);
    atlas.pixels.size = layout.width;
    atlas.pixels.height = layout.height;
    atlas.pixels.baseColor.assign(texels * 4, 0);
    atlas.pixels.normal.resize(texels * 3);
    atlas.pixels.orm.resize(texels * 3);
    for (std::size_t t = 0; t < texels; ++t) {
        atlas.pixels.normal[3 * t] = atlas.pixels.normal[3 * t + 1] = 128;
        atlas.pixels.normal[3 * t + 2] = 255;
        atlas.pixels.orm[3 * t] = atlas.pixels.orm[3 * t + 1] = 255;
        atlas.pixels.orm[3 * t + 2] = 0;
    }
    return atlas;
}

// The PNGs of one set (or the atlas) at once (each a function of the pixels alone); its
// pixels dropped unless kept.
void encodeMaps(MaterialMaps& maps, const MapRequest& request) {
    const auto kinds = std::ptrdiff_t(request.png.size());
    ParallelErrors errors;
#pragma omp parallel for schedule(dynamic, 1)
    for (std::ptrdiff_t k = 0; k < kinds; ++k)
        errors.run(k, [&] {
            const MapKind m = request.png[std::size_t(k)];
            maps.png[std::size_t(m)] = encodeMapPNG(maps.pixels, m, request.flipRows);
        });
    errors.rethrow();
    if (!request.keepPixels) maps.pixels = TextureMaps{};
}

std::uint64_t colorSeed(SurfaceKind kind, const Material& m) {
    std::uint64_t h = fnv1a(&kind, sizeof kind);
    h = fnv1a(&m.color, sizeof m.color, h);
    return fnv1a(m.name.data(), m.name.size(), h);
}

}  // namespace mattex

const char* mapKindName(MapKind kind) {
    switch (kind) {
        case MapKind::BaseColor:
            return "basecolor";
        case MapKind::Normal:
            return "normal";
        case MapKind::ORM:
            return "orm";
        case MapKind::Alpha:
            return "alpha";
        case MapKind::Roughness:
            break;
    }
    return "roughness";
}

std::string mapFileName(const std::string& prefix, const MaterialMaps& maps, MapKind kind) {
    return prefix + maps.name + "_" + mapKindName(kind) + ".png";
}

std::string encodeMapPNG(const TextureMaps& maps, MapKind kind, bool flipRows) {
    const int n = maps.size, rows = maps.rows();
    int channels = 3;
    const std::vector<std::uint8_t>* source = &maps.orm;
    int pick = -1;  // one channel of the source, for the grey maps
    switch (kind) {
        case MapKind::BaseColor:
            source = &maps.baseColor;
            channels = 4;
            break;
        case MapKind::Normal:
            source = &maps.normal;
            break;
        case MapKind::ORM:
            break;
        case MapKind::Alpha:
            source = &maps.baseColor;
            channels = 4;
            pick = 3;
            break;
        case MapKind::Roughness:
            pick = 1;
            break;
    }
    const bool dropAlpha = kind == MapKind::BaseColor && !maps.hasAlpha;
    const int outChannels = pick >= 0 ? 1 : dropAlpha ? 3 : channels;
    std::vector<std::uint8_t> pixels(std::size_t(n) * std::size_t(rows) * std::size_t(outChannels));
    // glTF's images start at v = 0, so flipping them turns "up" in the image from +v to -v:
    // a normal map's green (its +v component) is inverted with them.
    const bool invertGreen = flipRows && kind == MapKind::Normal;
    for (int j = 0; j < rows; ++j) {
        const int row = flipRows ? rows - 1 - j : j;
        const std::uint8_t* in = source->data() + std::size_t(row) * std::size_t(n) * channels;
        std::uint8_t* out = pixels.data() + std::size_t(j) * std::size_t(n) * outChannels;
        for (int i = 0; i < n; ++i)
            for (int c = 0; c < outChannels; ++c)
                out[std::size_t(i) * outChannels + c] =
                    in[std::size_t(i) * channels + std::size_t(pick >= 0 ? pick : c)];
        if (invertGreen)
            for (int i = 0; i < n; ++i)
                out[std::size_t(i) * 3 + 1] = 255 - out[std::size_t(i) * 3 + 1];
    }
    std::vector<std::uint8_t> png;
    if (!core::stbEncodePng(pixels.data(), n, rows, outChannels, n * outChannels, png))
        throw Error("cannot encode a " + std::string(mapKindName(kind)) + " texture as PNG");
    return std::string(png.begin(), png.end());
}

MaterialLooks::MaterialLooks(std::span<const Context* const> contexts,
                             const MaterialOptions& options, bool includeHidden, bool uvs,
                             const MapRequest& request) {
    using namespace mattex;
    checkMaterialOptions(options);
    textured_ = options.style == MaterialStyle::Textured;
    if (!textured_) return;
    const int size = options.textureSize;
    const int maskSize = std::min(size, kMaxMaskSize);
    std::vector<Planned> planned;
    for (const Context* ctx : contexts) {
        const bool organs = ctx->objectDataType("organ") == DataType::String;
        std::vector<std::int32_t> index(ctx->materialCount(), -1);
        for (const ObjectID id : exportedObjects(*ctx, includeHidden)) {
            const ObjectView o = ctx->object(id);
            const std::optional<std::string> organ =
                organs ? ctx->objectDataString(id, "organ") : std::nullopt;
            const SurfaceKind surface = surfaceOfOrgan(organ ? *organ : "");
            std::int32_t& p = index[o.material];
            if (p < 0) {
                const Material& m = ctx->material(o.material);
                const auto at = std::find_if(planned.begin(), planned.end(),
                                             [&](const Planned& q) { return q.material == m; });
                p = std::int32_t(at - planned.begin());
                if (at == planned.end()) {
                    Planned fresh{m, {}, true, {}, {}, false, -1.0f, false, true};
                    fresh.look.kind = surface;
                    fresh.look.factors = surfaceFactors(fresh.look.kind);
                    planned.push_back(std::move(fresh));
                }
            }
            Planned& q = planned[std::size_t(p)];
            if (o.uvs.empty()) q.allUVs = false;
            if (surface != q.look.kind) q.mixed = true;
            if (q.look.kind != SurfaceKind::Leaf || o.uvs.empty()) continue;
            if (q.unitUVs && !withinUnitSquare(o.uvs)) q.unitUVs = false;
            if (q.maskOverflow) continue;
            if (q.aspect < 0.0f) q.aspect = textureAspect(o);
            std::uint64_t h = fnv1a(o.uvs.data(), o.uvs.size_bytes());
            h = fnv1a(o.indices.data(), o.indices.size_bytes(), h);
            if (std::find(q.shapes.begin(), q.shapes.end(), h) != q.shapes.end()) continue;
            if (q.shapes.size() == kMaxOutlineShapes) {
                q.maskOverflow = true;
                q.mask.clear();
                continue;
            }
            q.shapes.push_back(h);
            rasterizeUVTriangles(o.uvs, o.indices, maskSize, q.mask);
        }
    }
    // One set of maps per distinct (surface, colour, outline): counted first, so that a size
    // too large for this machine is refused before any is drawn.
    std::vector<std::uint64_t> setKeys(planned.size(), 0), distinct;
    for (std::size_t i = 0; i < planned.size(); ++i) {
        Planned& q = planned[i];
        if (q.mixed) q.look = MaterialLook{};  // no one surface: a colour, as when flat
        const SurfaceKind kind = q.look.kind;
        const bool drawn =
            kind == SurfaceKind::Leaf || kind == SurfaceKind::Bark || kind == SurfaceKind::Stem;
        if (!drawn || !uvs || !q.allUVs || !q.material.texture.empty()) continue;
        const std::uint64_t seed = colorSeed(kind, q.material);
        std::uint64_t key = fnv1a(&seed, sizeof seed) | 1;  // never 0 (not drawn)
        key = fnv1a(&q.aspect, sizeof q.aspect, key) | 1;
        setKeys[i] = fnv1a(q.mask.data(), q.mask.size(), key) | 1;
        if (std::find(distinct.begin(), distinct.end(), setKeys[i]) == distinct.end())
            distinct.push_back(setKeys[i]);
    }
    // The atlas: the leaf sets whose every material keeps its coordinates in 0..1, in order.
    std::vector<std::uint64_t> packed;
    if (options.atlas) {
        for (std::size_t i = 0; i < planned.size(); ++i)
            if (setKeys[i] != 0 && planned[i].look.kind == SurfaceKind::Leaf &&
                std::find(packed.begin(), packed.end(), setKeys[i]) == packed.end())
                packed.push_back(setKeys[i]);
        for (std::size_t i = 0; i < planned.size(); ++i)
            if (setKeys[i] != 0 && !planned[i].unitUVs)
                packed.erase(std::remove(packed.begin(), packed.end(), setKeys[i]), packed.end());
    }
    AtlasLayout layout;
    if (packed.size() >= 2) {
        const std::vector<std::array<int, 2>> sizes(packed.size(), {size, size});
        layout = packAtlas(sizes);
    }
    if (layout.width == 0) packed.clear();  // none, one, or too large: separate images
    checkTextureMemory(distinct.size(), packed.size(), size, request.keepPixels,
                       double(layout.width) * double(layout.height));
    std::vector<std::pair<std::uint64_t, MaterialLook>> drawn;  // the looks of each key drawn
    int atlasMaps = -1;                                         // the atlas's index in maps_
    for (std::size_t i = 0; i < planned.size(); ++i) {
        Planned& q = planned[i];
        const SurfaceKind kind = q.look.kind;
        if (setKeys[i] == 0) {
            looks_.emplace_back(q.material, q.look);
            continue;
        }
        const std::uint64_t seed = colorSeed(kind, q.material);
        const std::uint64_t key = setKeys[i];
        const auto at =
            std::find_if(drawn.begin(), drawn.end(), [&](const auto& d) { return d.first == key; });
        if (at != drawn.end()) {
            q.look.maps = at->second.maps;
            q.look.inAtlas = at->second.inAtlas;
            q.look.transform = at->second.transform;
            looks_.emplace_back(q.material, q.look);
            continue;
        }
        MaterialMaps maps;
        maps.kind = kind;
        const int same = int(std::count_if(maps_.begin(), maps_.end(), [&](const MaterialMaps& m) {
            return m.kind == kind && !m.atlas;
        }));
        maps.name = std::string(surfaceKindName(kind)) + "_" + std::to_string(same);
        if (kind == SurfaceKind::Leaf) {
            LeafTextureInput in;
            in.color = q.material.color;
            in.seed = seed;
            in.size = size;
            in.aspect = q.aspect > 0.0f ? q.aspect : 0.5f;
            in.parallelVeins = parallelVenation(q.mask, maskSize, in.aspect);
            if (!q.mask.empty()) in.mask = scaledMask(q.mask, maskSize, size);
            maps.pixels = leafTextureMaps(in);
        } else {
            maps.pixels = barkTextureMaps(q.material.color, seed, size, kind == SurfaceKind::Stem);
        }
        maps.hasAlpha = maps.pixels.hasAlpha;
        const auto inAtlas = std::find(packed.begin(), packed.end(), key);
        if (inAtlas != packed.end()) {
            if (atlasMaps < 0) {  // the atlas takes the place of its first set
                atlasMaps = int(maps_.size());
                maps_.push_back(emptyAtlas(layout));
            }
            MaterialMaps& atlas = maps_[std::size_t(atlasMaps)];
            const AtlasRect& rect = layout.rects[std::size_t(inAtlas - packed.begin())];
            blitWithGutter(maps.pixels.baseColor.data(), 4, rect, kAtlasGutter,
                           atlas.pixels.baseColor.data(), layout.width, layout.height);
            blitWithGutter(maps.pixels.normal.data(), 3, rect, kAtlasGutter,
                           atlas.pixels.normal.data(), layout.width, layout.height);
            blitWithGutter(maps.pixels.orm.data(), 3, rect, kAtlasGutter, atlas.pixels.orm.data(),
                           layout.width, layout.height);
            atlas.hasAlpha = atlas.pixels.hasAlpha = atlas.hasAlpha || maps.hasAlpha;
            q.look.maps = atlasMaps;
            q.look.inAtlas = true;
            q.look.transform = atlasTransform(layout, rect);
        } else {
            encodeMaps(maps, request);
            q.look.maps = int(maps_.size());
            maps_.push_back(std::move(maps));
        }
        drawn.emplace_back(key, q.look);
        looks_.emplace_back(q.material, q.look);
    }
    if (atlasMaps >= 0) encodeMaps(maps_[std::size_t(atlasMaps)], request);
}

const MaterialLook& MaterialLooks::look(const Material& material) const {
    static const MaterialLook flat{};
    for (const auto& [m, look] : looks_)
        if (m == material) return look;
    return flat;
}

}  // namespace io
}  // namespace plantarch
