#pragma once
// Project files: a whole scene (blocks of plants, ground, obstacles, collision avoidance,
// attraction points) as one JSON file that `plantarch project run FILE -o OUT` builds, and that
// the browser project builder (`plantarch builder`) saves and loads. builder/API.md describes
// the format field by field; docs/projects.md shows examples.
//
// Reading is strict: an unknown field (with the nearest valid name), a value of the wrong
// type or out of its range is a plantarch::Error whose one line names the file, the field
// as a JSON pointer without its leading slash ("blocks/1/count"), the value and the valid
// range, e.g.
//   trial.json: blocks/1/count = 0: out of range (valid: 1 to 1000000)
//
// Building (buildProject) is deterministic: the same project gives the same bytes on export
// whatever the thread count, and each block's plants grow as they would alone (their random
// streams are numbered from 0 within the block: PlantArchitecture::restartPlantStreams), so
// editing one block never changes the plants of another (without soft collision avoidance,
// through which plants of every block see each other).

#include <cstddef>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "plantarch/Collision.h"
#include "plantarch/Context.h"
#include "plantarch/Physiology.h"
#include "plantarch/Progress.h"

namespace plantarch {

class PlantArchitecture;

/// The version of the project format this library reads and writes ("plantarch_project").
inline constexpr int kProjectVersion = 1;

/// One block of plants of one species.
struct ProjectBlock {
    enum class Layout {
        Grid,      ///< count.x by count.y plants, spacing apart, centred on origin
        Scatter,   ///< `plants` positions drawn uniformly over `area`, centred on origin
        Single,    ///< one plant with its base at origin
        Skeleton,  ///< the plants of a measured skeleton file, moved by origin
    };
    std::string name;     ///< shown by the builder; unique within the project
    std::string species;  ///< library name ("bean") or species file ("my_bean.xml")
    Layout layout = Layout::Grid;
    vec3 origin{0.0f};                  ///< m: the block's centre (the plant's base for Single)
    glm::ivec2 count{1, 1};             ///< Grid: plants along x and y, each >= 1
    vec2 spacing{0.3f, 0.3f};           ///< Grid: m between neighbours, > 0
    vec2 area{1.0f, 1.0f};              ///< Scatter: size of the rectangle along x and y, m, >= 0
    unsigned plants = 1;                ///< Scatter: positions drawn, 1 to 10^6
    float germination = 1.0f;           ///< probability a position gets a plant, 0 to 1
    std::optional<float> age;           ///< days, 0 to 100000 (absent: the species' recommended)
    std::optional<std::uint64_t> seed;  ///< the block's seed (absent: the project's)
    /// Build parameters overriding the species' defaults (trunk_height...), checked against
    /// the species' ranges when built.
    std::map<std::string, float> parameters;
    /// Species fields changed for this block (editSpecies keys such as
    /// "shoot_types.stem.internode_length_max", values as a species file writes them).
    std::map<std::string, std::string> speciesParameters;
    bool trellis = true;  ///< the species' trellis posts and wires, if it declares one
    /// Skeleton: a skeleton file (.csv node table, .json or .mtg; plantarch/Skeleton.h),
    /// relative paths from the project's folder, rebuilt with the species' shoot types.
    std::string skeleton;
    float skeletonUnit = 1.0f;     ///< Skeleton: m per unit of its coordinates, (0, 1000]
    float skeletonSpacing = 0.0f;  ///< Skeleton: axes resampled to this m (0: every point), 0 to 10
    /// The plants bend under their load (plantarch/Bending.h): the species' mechanics
    /// enabled; false leaves the species' own `mechanics.enabled`.
    bool bend = false;
    /// The stems' elastic modulus, Pa, 1e5 to 1e12 (absent: the species').
    std::optional<float> elasticModulus;
};

/// A season of physiology (docs/physiology.md): every block is built to its age less `days`,
/// then every plant grows the last `days` days with the carbohydrate budget and/or the
/// nitrogen model, its light traced each day through the whole scene.
struct ProjectPhysiology {
    /// The models, place, clear days (start, clearness), fertilisation and light interval;
    /// its `weather` hours are read from `weatherFile` when the project is built.
    PhysiologySeason season;
    /// A weather file (CSV, relative paths from the project's folder), or "" for clear days
    /// from season.start.
    std::string weatherFile;
    unsigned days = 30;  ///< whole days, 1 to 100000; no block may be younger
};

/// A ground rectangle (a Context object with organ "ground") at z = 0.
struct ProjectGround {
    vec2 size{4.0f, 4.0f};    ///< m along x and y, > 0
    vec2 center{0.0f, 0.0f};  ///< m
};

struct Project {
    std::string name;
    std::uint64_t seed = 1;   ///< seed of every block that has none of its own
    float meshDetail = 1.0f;  ///< factor on every organ's mesh resolution, 0.1 to 4
    std::optional<ProjectGround> ground;
    bool softCollision = false;
    PerceptionCone softCone;  ///< used with softCollision
    /// OBJ files of solid obstacles (each part of the scene, organ "obstacle").
    std::vector<std::string> obstacleFiles;
    float avoidDistance = 0.2f;  ///< m, with obstacles
    bool fruitAdjustment = false;
    bool attraction = false;
    std::vector<vec3> attractionPoints;  ///< m
    std::string attractionFile;          ///< CSV of x,y,z lines (added to the points)
    PerceptionCone attractionCone;       ///< halfAngle, lookAhead, inertia (rays unused)
    std::vector<ProjectBlock> blocks;
    std::optional<ProjectPhysiology> physiology;  ///< absent: the plants grow without
    /// The folder relative paths (species files, obstacles, attraction file) are taken from:
    /// the project file's folder when read from a file. Not written.
    std::string folder = ".";
    /// The file the project was read from, named by errors ("" for "project"). Not written.
    std::string file;
};

/// Reads a project file. Throws plantarch::Error naming the file and the field.
Project readProjectFile(const std::string& path);
/// Reads a project from JSON text; `nameForErrors` stands for the file in errors and
/// `folder` is the folder relative paths are taken from.
Project readProjectString(const std::string& json, const std::string& nameForErrors,
                          const std::string& folder = ".");
/// The project as JSON text (every field written, two-space indent, a final newline);
/// reading it back gives the same project.
std::string writeProjectString(const Project& project);
/// Writes the project atomically (never half a file). Throws plantarch::Error naming the file.
void writeProjectFile(const Project& project, const std::string& path);

/// Everything buildProject checks before it builds, without building: each block's species
/// loads, its build parameters are the species' and within their ranges, every file opens
/// and reads. Throws plantarch::Error naming the file and the field ("blocks/1/species").
void checkProject(const Project& project);

/// A block's species as PlantArchitecture::loadPlantModelFromLibrary takes it: a library
/// name as written, a species file (a path with '/' or ending in ".xml") through projectPath.
std::string projectSpecies(const Project& project, const ProjectBlock& block);

/// A project path (species file, obstacle, attraction file) as the build opens it: relative
/// paths are taken from project.folder.
std::string projectPath(const Project& project, const std::string& path);

struct ProjectBuildOptions {
    /// Receives ("building", "growing", ...) progress; a callback that throws stops the
    /// build: buildProject rethrows and the Context holds nothing of the project.
    ProgressCallback progress;
    /// At most this many triangles in the Context (0: no limit); a block that would pass it
    /// throws TriangleBudgetError before it is grown.
    std::size_t maxTriangles = 0;
    /// Only some plants (a field built in tiles, plantarch/Field.h): one list per block of
    /// the indices of its plants to build, in the block's plant order (increasing; the order
    /// of projectBlockPositions); absent: every plant. Each plant built gets the ID and the
    /// random streams it gets when the whole project is built, so its geometry is the same
    /// (exactly without soft collision avoidance). A skeleton block is not built in part
    /// (an Error naming it).
    std::optional<std::vector<std::vector<unsigned>>> only;
};

/// The bases of a block's plants as buildProject places them, in the block's plant order (a
/// grid's germination and a scatter's draws with the block's seed), without building
/// anything. A skeleton block's plants stand where its file puts them: Error (build it).
/// Throws plantarch::Error naming the project file and the block's field.
std::vector<vec3> projectBlockPositions(const Project& project, std::size_t block);

/// What buildProject made, for statistics, growth and export.
struct BuiltProject {
    /// The plants of each block, in block order (IDs in the PlantArchitecture).
    std::vector<std::vector<unsigned>> blockPlants;
    std::vector<ObjectID> ground;     ///< the ground's objects
    std::vector<ObjectID> obstacles;  ///< obstacle objects, in file order
    /// With a physiology season: its daily records (growPhysiologySeason), day by day.
    std::vector<PhysiologyRecord> physiology;
    /// Every plant, block by block.
    std::vector<unsigned> plants() const;
};

/// Builds `project` into `arch` (and its Context), which must hold no plants: the ground,
/// the obstacles, collision avoidance and attraction points as the project enables them, then
/// each block in order (its species loaded, its seed set, its streams restarted, its plants
/// grown to its age in parallel). Errors name the project file and the block's field
/// ("blocks/1/parameters/trunk_height"). On an error (or a progress callback that throws) the
/// Context and `arch` are left with nothing of the project.
BuiltProject buildProject(const Project& project, PlantArchitecture& arch,
                          const ProjectBuildOptions& options = {});

/// Grows a built project on to the ages of `later`, a project equal to `built`'s but for
/// later (or equal) block ages: each block's plants are grown by the difference
/// (PlantArchitecture::advanceTime), not rebuilt. Throws plantarch::Error naming the field
/// when `later` differs otherwise or an age is earlier, or when the project has a
/// physiology season (its weather is dated: such a project is built again). Same progress and
/// cancelling as buildProject; a cancelled growth leaves the plants part grown.
void growProject(const Project& earlier, const Project& later, PlantArchitecture& arch,
                 const BuiltProject& built, const ProjectBuildOptions& options = {});
/// The checks growProject makes before it grows anything: the days each block grows by, or a
/// plantarch::Error naming the field that differs or the age that is earlier.
std::vector<double> projectGrowth(const Project& earlier, const Project& later);

/// Project statistics (the builder's panel; `plantarch project run --stats`).
struct ProjectStats {
    std::size_t plants = 0;
    std::size_t triangles = 0;  ///< every triangle of the Context (ground, obstacles too)
    std::size_t objects = 0;
    float height = 0.0f;    ///< tallest plant, m
    double leafArea = 0.0;  ///< one-sided, m^2, all plants
    std::size_t leafCount = 0;
};
ProjectStats projectStats(const PlantArchitecture& arch, const BuiltProject& built);

}  // namespace plantarch
