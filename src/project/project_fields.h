#pragma once
// The fields of a project file and their valid ranges, declared once for the reader, the
// writer and the checks of a build.

#include <algorithm>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "plantarch/Project.h"

namespace plantarch {

inline constexpr std::size_t kMaxBlocks = 1000;
inline constexpr double kMaxBlockPlants = 1000000;
inline constexpr std::size_t kMaxAttractionPoints = 1000000;
inline constexpr std::size_t kMaxProjectBytes = 16u << 20;

/// A number's valid range and how a person reads it.
struct Range {
    double lo, hi;
    std::string text;
    bool loOpen = false;  ///< lo itself excluded
    bool whole = false;   ///< whole numbers only
    bool hiOpen = false;  ///< hi itself excluded
};

inline Range anyNumber() {
    return {-1e30, 1e30, "finite numbers"};
}
inline Range ageRange() {
    return {0, 100000, "0 to 100000 days"};
}
inline Range germinationRange() {
    return {0, 1, "0 to 1"};
}
inline Range spacingRange() {
    return {0, 10000, "> 0 to 10000 m", true};
}
inline Range areaRange() {
    return {0, 10000, "0 to 10000 m"};
}
inline Range groundSizeRange() {
    return {0, 10000, "> 0 to 10000 m", true};
}
inline Range gridCountRange() {
    return {1, 1000000, "whole numbers 1 to 1000000", false, true};
}
inline Range scatterCountRange() {
    return {1, 1000000, "a whole number 1 to 1000000", false, true};
}
inline Range meshDetailRange() {
    return {0.1, 4, "0.1 to 4"};
}
inline Range distanceRange() {
    return {0, 100, "> 0 to 100 m", true};
}
inline std::vector<Range> softConeRanges() {
    return {{0, 180, "half-angle > 0 and < 180 degrees", true, false, true},
            {0, 100, "look-ahead > 0 to 100 m", true},
            {8, 16384, "rays: a whole number 8 to 16384", false, true},
            {0, 1, "inertia 0 to 1"}};
}
inline std::vector<Range> attractionConeRanges() {
    return {{0, 180, "half-angle > 0 and < 180 degrees", true, false, true},
            {0, 100, "look-ahead > 0 to 100 m", true},
            {0, 1, "inertia 0 to 1"}};
}

inline std::vector<std::string> projectFields() {
    return {"plantarch_project", "name",      "seed",       "mesh_detail", "ground",
            "soft_collision",    "obstacles", "attraction", "blocks",      "physiology"};
}

/// The fields of the physiology section, in the order they are written.
inline std::vector<std::string> physiologyFields() {
    return {"carbon",    "nitrogen",    "location", "start",    "weather",
            "clearness", "light_every", "days",     "fertilise"};
}
inline Range physiologyDaysRange() {
    return {1, 100000, "whole days 1 to 100000", false, true};
}
inline std::vector<Range> locationRanges() {
    return {{-90, 90, "latitude -90 to 90 degrees"}, {-180, 180, "longitude -180 to 180 degrees"}};
}
inline std::vector<Range> fertiliseRanges() {
    return {{0, 100000, "age 0 to 100000 days"}, {0, 1e6, "> 0 to 1000000 g N", true}};
}

inline std::vector<std::string> layoutNames() {
    return {"grid", "scatter", "single", "skeleton"};
}
/// The fields of a skeleton block's "skeleton" object, in the order they are written.
inline std::vector<std::string> skeletonFields() {
    return {"file", "unit", "spacing"};
}
inline Range skeletonUnitRange() {
    return {0, 1000, "> 0 to 1000 m per unit", true};
}
inline Range skeletonSpacingRange() {
    return {0, 10, "0 to 10 m (0: every point a node)"};
}
inline Range elasticModulusRange() {
    return {1e5, 1e12, "1e5 to 1e12 Pa, or null for the species'"};
}
inline const char* layoutName(ProjectBlock::Layout layout) {
    switch (layout) {
        case ProjectBlock::Layout::Grid:
            return "grid";
        case ProjectBlock::Layout::Scatter:
            return "scatter";
        case ProjectBlock::Layout::Single:
            return "single";
        case ProjectBlock::Layout::Skeleton:
            return "skeleton";
    }
    return "grid";
}
inline std::optional<ProjectBlock::Layout> layoutFromName(const std::string& name) {
    if (name == "grid") return ProjectBlock::Layout::Grid;
    if (name == "scatter") return ProjectBlock::Layout::Scatter;
    if (name == "single") return ProjectBlock::Layout::Single;
    if (name == "skeleton") return ProjectBlock::Layout::Skeleton;
    return std::nullopt;
}

/// The fields of a block of this layout, in the order they are written.
inline std::vector<std::string> blockFields(ProjectBlock::Layout layout) {
    switch (layout) {
        case ProjectBlock::Layout::Grid:
            return {"name",
                    "species",
                    "layout",
                    "origin",
                    "count",
                    "spacing",
                    "germination",
                    "age",
                    "seed",
                    "parameters",
                    "species_parameters",
                    "trellis",
                    "bend",
                    "elastic_modulus"};
        case ProjectBlock::Layout::Scatter:
            return {"name",
                    "species",
                    "layout",
                    "origin",
                    "count",
                    "area",
                    "germination",
                    "age",
                    "seed",
                    "parameters",
                    "species_parameters",
                    "trellis",
                    "bend",
                    "elastic_modulus"};
        case ProjectBlock::Layout::Skeleton:
            return {"name", "species", "layout", "origin",          "skeleton",
                    "age",  "seed",    "bend",   "elastic_modulus", "species_parameters"};
        case ProjectBlock::Layout::Single:
            break;
    }
    return {"name",
            "species",
            "layout",
            "origin",
            "age",
            "seed",
            "parameters",
            "trellis",
            "bend",
            "elastic_modulus",
            "species_parameters"};
}

/// Fields of other layouts, with the layouts they belong to (for the error of a field that
/// does not apply).
inline std::map<std::string, std::string> blockFieldsElsewhere(ProjectBlock::Layout layout) {
    std::map<std::string, std::string> out;
    const std::vector<std::string> own = blockFields(layout);
    for (const std::string& name : layoutNames()) {
        const ProjectBlock::Layout other = *layoutFromName(name);
        if (other == layout) continue;
        for (const std::string& f : blockFields(other))
            if (std::find(own.begin(), own.end(), f) == own.end())
                out[f] += (out[f].empty() ? "with layout " : " or ") + name;
    }
    return out;
}

}  // namespace plantarch
