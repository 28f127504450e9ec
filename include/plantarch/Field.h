#pragma once
// Fields larger than one machine's memory (docs/datasets.md, "Fields larger than memory"): a
// project (plantarch/Project.h) built as square tiles of its plants' bases, each tile on its
// own (any process, any machine), written as its own labelled GLB, then indexed as a 3D Tiles
// tileset (tileset.json, version 1.1, GLB content) with a table of every plant (plants.csv).
//
// A plant belongs to the tile its base stands in and is written whole there, leaves across the
// border included. It is the same plant whichever tile or worker builds it: it gets the plant
// ID and random streams it gets when the whole project is built (ProjectBuildOptions::only).
// Without soft collision avoidance a tile's plants are exactly the whole field's; with it a
// tile also grows its halo (the plants of other tiles within FieldOptions::halo of its border)
// so that its plants steer round their neighbours, and the tiles equal the whole field only
// approximately (a halo plant's own neighbours beyond the halo are missing).
//
// Files in the output folder, each written atomically (whole or not at all):
//   tile_IX_IY.csv  the tile's rows of plants.csv (written first)
//   tile_IX_IY.glb  the tile's plants, labelled (writeGLTF); present means the tile is done
//   tileset.json    the index: a root with one child per tile (box, geometric error, GLB)
//   plants.csv      every plant: the header fieldPlantsHeader() then the tiles' rows in order

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "plantarch/Context.h"
#include "plantarch/Mesh.h"
#include "plantarch/Progress.h"
#include "plantarch/Project.h"

namespace plantarch {

/// How a field is cut into tiles.
struct FieldOptions {
    /// Edge of a square tile, m: above 0, finite, at most kMaxFieldTiles tiles in all.
    float tileSize = 0.0f;
    /// With soft collision avoidance: the plants within this distance (m, 0 to 1000) of a
    /// tile's rectangle are grown with the tile (not written) so its plants see them. Without
    /// avoidance plants do not see each other and no halo is grown.
    float halo = 1.0f;
    /// At most this many triangles in a tile's scene (0: no limit), halo included.
    std::size_t maxTriangles = 0;
    /// Receives a tile's build progress ("block NAME (1 of 2): building", ...); may be empty.
    ProgressCallback progress;
};

/// The most tiles a field is cut into.
inline constexpr std::size_t kMaxFieldTiles = 1000000;

/// One plant of a field, as placed from the project's layout (nothing built).
struct FieldPlant {
    unsigned id = 0;        ///< its plant ID when the whole project is built
    std::size_t block = 0;  ///< its block
    unsigned index = 0;     ///< its place in the block's plant order (= its stream number)
    vec3 base{0.0f};        ///< m
};

/// One tile: the plants whose bases stand in its rectangle [min, max).
struct FieldTile {
    unsigned ix = 0, iy = 0;  ///< column along x and row along y of the tile grid
    std::string name;         ///< "tile_IX_IY": its files are NAME.glb and NAME.csv
    vec2 min{0.0f}, max{0.0f};
    std::vector<FieldPlant> plants;  ///< its own, in plant ID order
    std::vector<FieldPlant> halo;    ///< neighbours grown with it (soft avoidance only)
};

/// A field's tiles: a grid of tilesX x tilesY tiles of tileSize centred on the box of the
/// plants' bases (floor(extent / tileSize) + 1 tiles along each axis), of which only those
/// holding a plant are listed, row by row (iy, then ix).
struct FieldPlan {
    float tileSize = 0.0f;
    unsigned tilesX = 0, tilesY = 0;
    vec2 origin{0.0f};  ///< corner (min x, min y) of tile 0_0
    std::vector<FieldTile> tiles;
    std::size_t plants = 0;  ///< in all tiles
};

/// The tiles of `project` with each tile's plants, decided from the layout alone: bases as
/// buildProject places them (projectBlockPositions: germination and scatter draws included).
/// Throws plantarch::Error for a tile size or halo out of range, too many tiles, a project
/// with a physiology season or a skeleton block (tiles are built from layouts), or no plants.
FieldPlan fieldTiles(const Project& project, const FieldOptions& options);

/// One row of plants.csv.
struct FieldPlantRow {
    unsigned id = 0;
    std::string block;          ///< the block's name
    std::string species;        ///< the plant's species (its name)
    std::string tile;           ///< the tile's name
    vec3 base{0.0f};            ///< m
    float age = 0.0f;           ///< days
    std::uint64_t seed = 0;     ///< the block's seed
    unsigned stream = 0;        ///< the plant's random stream within its block
    std::size_t triangles = 0;  ///< its organs and trellis
    float height = 0.0f;        ///< m, getPlantHeight
    double leafArea = 0.0;      ///< m^2, one-sided
    AABB bounds;                ///< of its geometry (organs and trellis), m
};

/// The header line of plants.csv and of each tile's CSV (without its newline).
std::string fieldPlantsHeader();

/// Builds tile `tile` of fieldTiles(project, options) (its plants and halo, ground and
/// obstacles left out of the file) and writes `outDir`/NAME.csv, then `outDir`/NAME.glb, each
/// atomically; `outDir` is made if missing. Returns the tile's rows. Throws plantarch::Error
/// for a tile index out of range or an output folder that is not one (a file).
std::vector<FieldPlantRow> buildFieldTile(const Project& project, const FieldOptions& options,
                                          std::size_t tile, const std::string& outDir);

/// Writes `outDir`/tileset.json and `outDir`/plants.csv (atomically) from the tiles' files
/// there. Throws plantarch::Error naming the first tile whose GLB or CSV is missing or whose
/// CSV does not hold the tile's plants (the index is then not written).
void writeFieldIndex(const Project& project, const FieldOptions& options,
                     const std::string& outDir);

}  // namespace plantarch
