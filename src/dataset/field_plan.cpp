// A field's tiles, decided from the project's layout alone: every plant's base as buildProject
// places it, its plant ID as the whole build gives it, and the tile grid over the bases.

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/value_text.h"
#include "dataset/field_internal.h"
#include "plantarch/Error.h"
#include "plantarch/NumberRange.h"

namespace plantarch {

namespace field {

std::string projectFile(const Project& p) {
    return p.file.empty() ? "project" : p.file;
}

namespace {

void checkOptions(const FieldOptions& o) {
    if (!(o.tileSize > 0.0f) || !std::isfinite(o.tileSize))
        throw Error("not a tile size", {.parameter = "tile_size",
                                        .value = text::formatFloat(o.tileSize),
                                        .validRange = "> 0 m"});
    if (!(o.halo >= 0.0f && o.halo <= 1000.0f))
        throw Error("not a halo width", {.parameter = "halo",
                                         .value = text::formatFloat(o.halo),
                                         .validRange = rangeText({0.0, 1000.0}) + " m"});
}

// Distance from p to the rectangle [lo, hi] (0 inside).
float distanceTo(const vec2& p, const vec2& lo, const vec2& hi) {
    const float dx = std::max({lo.x - p.x, 0.0f, p.x - hi.x});
    const float dy = std::max({lo.y - p.y, 0.0f, p.y - hi.y});
    return std::sqrt(dx * dx + dy * dy);
}

// Tiles along one axis over [lo, hi]: floor(extent / size) + 1, so the grid is wider than the
// bases and no base stands on its outer edges; the grid's first edge.
std::pair<double, double> axis(double lo, double hi, double size) {
    const double count = std::floor((hi - lo) / size) + 1.0;
    return {count, 0.5 * (lo + hi) - 0.5 * count * size};
}

// A whole number of tiles as written: its digits, or a double's form past 10^15.
std::string countText(double n) {
    return n < 1e15 ? std::to_string(std::uint64_t(n)) : text::formatDouble(n);
}

unsigned cell(float x, float origin, float size, unsigned count) {
    const double c = std::floor((double(x) - double(origin)) / double(size));
    return unsigned(std::clamp(c, 0.0, double(count - 1)));
}

}  // namespace

}  // namespace field

FieldPlan fieldTiles(const Project& project, const FieldOptions& options) {
    field::checkOptions(options);
    if (project.physiology)
        throw Error(
            "a field is built in tiles: its light cannot be traced through the whole "
            "scene",
            {.file = field::projectFile(project),
             .parameter = "physiology",
             .validRange = "a project without a physiology season"});
    std::vector<FieldPlant> plants;
    unsigned id = 0;  // the whole build's plant IDs: each block's plants in turn, from 0
    for (std::size_t b = 0; b < project.blocks.size(); ++b) {
        if (project.blocks[b].layout == ProjectBlock::Layout::Skeleton)
            throw Error("a field is built from layouts, not measured plants",
                        {.file = field::projectFile(project),
                         .parameter = "blocks/" + std::to_string(b) + "/layout",
                         .value = "skeleton",
                         .validRange = "grid, scatter or single"});
        const std::vector<vec3> bases = projectBlockPositions(project, b);
        for (std::size_t i = 0; i < bases.size(); ++i)
            plants.push_back({id + unsigned(i), b, unsigned(i), bases[i]});
        id += unsigned(bases.size());
    }
    if (plants.empty())
        throw Error("the field has no plants", {.file = field::projectFile(project),
                                                .parameter = "blocks",
                                                .validRange = "at least one plant"});
    vec2 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
    for (const FieldPlant& p : plants) {
        lo = glm::min(lo, vec2(p.base));
        hi = glm::max(hi, vec2(p.base));
    }
    const auto [nx, x0] = field::axis(lo.x, hi.x, options.tileSize);
    const auto [ny, y0] = field::axis(lo.y, hi.y, options.tileSize);
    if (nx * ny > double(kMaxFieldTiles))
        throw Error(
            "too many tiles",
            {.parameter = "tile_size",
             .value = text::formatFloat(options.tileSize) + " m (" + field::countText(nx) + " x " +
                      field::countText(ny) + " tiles)",
             .validRange = "a size giving at most " + std::to_string(kMaxFieldTiles) + " tiles"});
    FieldPlan plan;
    plan.tileSize = options.tileSize;
    plan.tilesX = unsigned(nx);
    plan.tilesY = unsigned(ny);
    plan.origin = vec2(float(x0), float(y0));
    plan.plants = plants.size();
    // Tiles holding a plant, row by row; each tile's plants in ID order.
    std::vector<std::size_t> cellOf(plants.size());
    std::vector<std::size_t> used;
    for (std::size_t k = 0; k < plants.size(); ++k) {
        const unsigned ix =
            field::cell(plants[k].base.x, plan.origin.x, plan.tileSize, plan.tilesX);
        const unsigned iy =
            field::cell(plants[k].base.y, plan.origin.y, plan.tileSize, plan.tilesY);
        cellOf[k] = std::size_t(iy) * plan.tilesX + ix;
        used.push_back(cellOf[k]);
    }
    std::sort(used.begin(), used.end());
    used.erase(std::unique(used.begin(), used.end()), used.end());
    for (std::size_t c : used) {
        FieldTile t;
        t.ix = unsigned(c % plan.tilesX);
        t.iy = unsigned(c / plan.tilesX);
        t.name = "tile_" + std::to_string(t.ix) + "_" + std::to_string(t.iy);
        t.min = plan.origin + plan.tileSize * vec2(float(t.ix), float(t.iy));
        t.max = t.min + vec2(plan.tileSize);
        plan.tiles.push_back(std::move(t));
    }
    for (std::size_t k = 0; k < plants.size(); ++k) {
        const auto at = std::lower_bound(used.begin(), used.end(), cellOf[k]);
        plan.tiles[std::size_t(at - used.begin())].plants.push_back(plants[k]);
    }
    if (!project.softCollision || options.halo <= 0.0f) return plan;
    // A tile's halo: the plants of the tiles within reach whose bases are within the halo of
    // its rectangle, in ID order.
    const long reach = long(std::min(1e6, std::ceil(double(options.halo) / plan.tileSize)));
    for (FieldTile& t : plan.tiles) {
        for (long y = std::max(0L, long(t.iy) - reach);
             y <= std::min(long(plan.tilesY) - 1, long(t.iy) + reach); ++y)
            for (long x = std::max(0L, long(t.ix) - reach);
                 x <= std::min(long(plan.tilesX) - 1, long(t.ix) + reach); ++x) {
                if (x == long(t.ix) && y == long(t.iy)) continue;
                const std::size_t c = std::size_t(y) * plan.tilesX + std::size_t(x);
                const auto at = std::lower_bound(used.begin(), used.end(), c);
                if (at == used.end() || *at != c) continue;
                for (const FieldPlant& p : plan.tiles[std::size_t(at - used.begin())].plants)
                    if (field::distanceTo(vec2(p.base), t.min, t.max) <= options.halo)
                        t.halo.push_back(p);
            }
        std::sort(t.halo.begin(), t.halo.end(),
                  [](const FieldPlant& a, const FieldPlant& b) { return a.id < b.id; });
    }
    return plan;
}

}  // namespace plantarch
