#pragma once
// Texture atlases: rectangles packed into one image with a gutter of their edge texels around
// each (so that filtering and mip levels down to 1/kAtlasAlign size never reach a neighbour),
// and the texture transform that maps a rectangle's own [0,1] square onto its place.
//
// Images follow procedural_textures.h: row 0 at v = 1. A transform is uv' = offset + scale * uv
// in that v-up texture space, which is also glTF's (its images are written flipped, its UVs
// unchanged), USD's and OBJ's.

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "plantarch/Mesh.h"

namespace plantarch::io {

/// Texels of edge copies around each rectangle, and the multiple its corners sit on: mip
/// level 3 (1/8 size) still has a texel of gutter and never mixes two rectangles.
inline constexpr int kAtlasGutter = 8;
inline constexpr int kAtlasAlign = 8;
/// The largest atlas side: larger ones are not made (the maps stay separate images).
inline constexpr int kMaxAtlasSide = 8192;

/// A rectangle of an atlas in texels from its top-left corner (row 0 at v = 1).
struct AtlasRect {
    int x = 0, y = 0, width = 0, height = 0;
};

/// Where packAtlas put each rectangle (inner rectangles, gutters around them).
struct AtlasLayout {
    int width = 0, height = 0;  ///< 0 x 0: nothing packed, or larger than the limit
    std::vector<AtlasRect> rects;
};

/// Packs rectangles of `sizes` (width, height; positive) in shelves, tallest first (ties in
/// input order), each in a cell of its size plus `gutter` texels a side rounded up to a
/// multiple of `align` (cells start on multiples of `align`; `gutter` should be one too). Of
/// the shelf widths that fit one to all rectangles in a row, the one with the smallest longer
/// side, then area, wins. Returns an empty layout when no rectangle is given or the atlas
/// would pass `maxSide` texels on a side. A function of its arguments alone.
AtlasLayout packAtlas(std::span<const std::array<int, 2>> sizes, int gutter = kAtlasGutter,
                      int align = kAtlasAlign, int maxSide = kMaxAtlasSide);

/// The transform of `rect` in `layout`: uv' = offset + scale * uv maps its [0,1] square onto it.
struct UVTransform {
    vec2 offset{0.0f};
    vec2 scale{1.0f};
    vec2 apply(vec2 uv) const { return offset + scale * uv; }
};
UVTransform atlasTransform(const AtlasLayout& layout, const AtlasRect& rect);

/// Copies `tile` (rect.width x rect.height texels of `channels` bytes, row 0 at the top) into
/// `atlas` (layout.width x layout.height texels of `channels`) at `rect`, and fills `gutter`
/// texels around it with copies of its nearest edge texel (corners with the corner texel).
void blitWithGutter(const std::uint8_t* tile, int channels, const AtlasRect& rect, int gutter,
                    std::uint8_t* atlas, int atlasWidth, int atlasHeight);

}  // namespace plantarch::io
