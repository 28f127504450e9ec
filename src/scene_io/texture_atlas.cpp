// Texture atlases (texture_atlas.h): shelf packing on aligned cells, edge-copy gutters.

#include "scene_io/texture_atlas.h"

#include <algorithm>
#include <cstring>
#include <numeric>

namespace plantarch::io {

namespace {

int roundUp(int n, int align) {
    return align > 1 ? (n + align - 1) / align * align : n;
}

struct Cell {
    int width = 0, height = 0;
};

// Shelves of at most `limit` texels: each cell's corner, and the atlas's size.
std::pair<int, int> shelves(std::span<const Cell> cells, std::span<const std::size_t> order,
                            int limit, std::vector<std::array<int, 2>>& at) {
    at.assign(cells.size(), {0, 0});
    int x = 0, y = 0, shelf = 0, width = 0;
    for (const std::size_t i : order) {
        if (x > 0 && x + cells[i].width > limit) {
            y += shelf;
            x = 0;
            shelf = 0;
        }
        at[i] = {x, y};
        x += cells[i].width;
        width = std::max(width, x);
        shelf = std::max(shelf, cells[i].height);
    }
    return {width, y + shelf};
}

}  // namespace

AtlasLayout packAtlas(std::span<const std::array<int, 2>> sizes, int gutter, int align,
                      int maxSide) {
    AtlasLayout layout;
    if (sizes.empty()) return layout;
    std::vector<Cell> cells;
    for (const auto& [w, h] : sizes) {
        if (w <= 0 || h <= 0 || w > maxSide || h > maxSide) return layout;
        cells.push_back({roundUp(w + 2 * gutter, align), roundUp(h + 2 * gutter, align)});
    }
    std::vector<std::size_t> order(cells.size());
    std::iota(order.begin(), order.end(), std::size_t{0});
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
        return cells[a].height > cells[b].height;
    });
    std::vector<int> widths;
    for (const Cell& c : cells) widths.push_back(c.width);
    std::sort(widths.begin(), widths.end(), std::greater<>());
    // Shelf widths: the j widest cells side by side, j = 1 .. all.
    std::vector<std::array<int, 2>> at, best;
    long long bestSide = 0, bestArea = 0;
    int bestWidth = 0, bestHeight = 0;
    long long limit = 0;
    for (std::size_t j = 0; j < widths.size(); ++j) {
        limit += widths[j];
        if (j > 0 && limit > maxSide) break;  // wider than any atlas allowed
        const auto [w, h] = shelves(cells, order, int(limit), at);
        const long long side = std::max(w, h), area = (long long)w * h;
        if (best.empty() || side < bestSide || (side == bestSide && area < bestArea)) {
            best = at;
            bestSide = side;
            bestArea = area;
            bestWidth = w;
            bestHeight = h;
        }
    }
    if (best.empty() || bestSide > maxSide) return layout;
    layout.width = bestWidth;
    layout.height = bestHeight;
    for (std::size_t i = 0; i < cells.size(); ++i)
        layout.rects.push_back(
            {best[i][0] + gutter, best[i][1] + gutter, sizes[i][0], sizes[i][1]});
    return layout;
}

UVTransform atlasTransform(const AtlasLayout& layout, const AtlasRect& rect) {
    const auto w = float(layout.width), h = float(layout.height);
    UVTransform t;
    t.offset = vec2(float(rect.x) / w, float(layout.height - rect.y - rect.height) / h);
    t.scale = vec2(float(rect.width) / w, float(rect.height) / h);
    return t;
}

void blitWithGutter(const std::uint8_t* tile, int channels, const AtlasRect& rect, int gutter,
                    std::uint8_t* atlas, int atlasWidth, int atlasHeight) {
    const auto ch = std::size_t(channels);
    const int x0 = std::max(0, rect.x - gutter),
              x1 = std::min(atlasWidth, rect.x + rect.width + gutter);
    const int y0 = std::max(0, rect.y - gutter),
              y1 = std::min(atlasHeight, rect.y + rect.height + gutter);
    for (int y = y0; y < y1; ++y) {
        const int ty = std::clamp(y - rect.y, 0, rect.height - 1);
        const std::uint8_t* in = tile + std::size_t(ty) * std::size_t(rect.width) * ch;
        std::uint8_t* out = atlas + std::size_t(y) * std::size_t(atlasWidth) * ch;
        for (int x = x0; x < rect.x; ++x) std::memcpy(out + std::size_t(x) * ch, in, ch);
        std::memcpy(out + std::size_t(rect.x) * ch, in, std::size_t(rect.width) * ch);
        const std::uint8_t* last = in + std::size_t(rect.width - 1) * ch;
        for (int x = rect.x + rect.width; x < x1; ++x)
            std::memcpy(out + std::size_t(x) * ch, last, ch);
    }
}

}  // namespace plantarch::io
