#pragma once
// One plant's statistics at a glance: size, leaves, spread, flowers and fruit, branching by
// rank and the leaf area's inclination. `plantarch build --stats` prints them, the Python
// module returns them, and the fidelity checks compare them with the reference system's.

#include <array>
#include <cstddef>
#include <vector>

namespace plantarch {

class PlantArchitecture;

struct PlantSummary {
    float height = 0.0f;    ///< top of the plant above its base (m)
    float leafArea = 0.0f;  ///< one-sided (m^2)
    unsigned leaves = 0;    ///< leaf objects (each leaflet of a compound leaf one)
    float widthX = 0.0f;    ///< width of the plant's box along x (m)
    float widthY = 0.0f;    ///< and along y (m)
    /// Along the plant's own horizontal axes: its largest extent over every whole degree of
    /// direction, and its extent square to that direction (m).
    float widthLong = 0.0f;
    float widthShort = 0.0f;
    unsigned flowers = 0;                   ///< flowers drawn (closed or open, with a size)
    unsigned fruit = 0;                     ///< fruit drawn (with a size)
    std::vector<unsigned> shootsByRank;     ///< shoots of rank 0, 1, ... (removed ones not)
    std::vector<unsigned> phytomersByRank;  ///< their phytomers
    unsigned mainNodes = 0;                 ///< phytomers of the main shoot (shoot 0)
    /// Fraction of the leaf area whose surface is inclined 0-10, 10-20, ... 80-90 degrees from
    /// horizontal (each triangle by the angle of its normal from vertical); all 0 when the
    /// plant has no leaf area.
    std::array<float, 9> leafInclination{};
    std::size_t triangles = 0;  ///< every organ's
};

/// The statistics of plant `plantID` as it stands (plantarch::Error if there is no such plant).
PlantSummary summarizePlant(const PlantArchitecture& arch, unsigned plantID);

}  // namespace plantarch
