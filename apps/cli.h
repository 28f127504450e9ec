#pragma once
// Shared pieces of the plantarch command: global options, the subcommand registry and
// terminal output helpers. Each subcommand lives in its own file and registers itself with
// PLANTARCH_REGISTER_COMMAND, so adding one never touches main.cpp.

#include <CLI/CLI.hpp>
#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "plantarch/Context.h"
#include "plantarch/Export.h"
#include "plantarch/ExportPlants.h"
#include "plantarch/PlantArchitecture.h"
#include "plantarch/Progress.h"

namespace plantarch::cli {

/// Options every subcommand sees.
struct GlobalOptions {
    int verbose = 0;          ///< -v count
    std::uint64_t seed = 42;  ///< --seed
    int threads = 0;          ///< --threads (0 = all cores)
    int imageWidth = 1024;    ///< size of PNG outputs (--image-size on build and canopy)
    int imageHeight = 768;
    int stringDigits = 4;    ///< significant digits of plant strings (--digits)
    std::size_t points = 0;  ///< --points: PLY outputs as labelled point clouds of this many points
    float meshDetail = 1.0f;  ///< --mesh-detail: factor on every organ's mesh resolution
    bool objectIDs = false;   ///< --object-ids: object IDs in .xml, object tables by meshes
    PlyColor plyColor = PlyColor::None;                   ///< --ply-color
    PlyFormat plyFormat = PlyFormat::BinaryLittleEndian;  ///< --ply-format
};

/// Parses "x,y,z" (three finite numbers) or throws an Error naming the option.
vec3 parseVec3(const std::string& text, const char* option);

/// Adds --image-size WxH (PNG output size) to a subcommand, stored in `global`.
void addImageSizeOption(CLI::App& app, GlobalOptions& global);

/// A subcommand: `setup` adds it to the app and returns the function run when it is chosen.
struct Command {
    std::string name;
    int order;  ///< position in --help
    std::function<std::function<int()>(CLI::App& app, GlobalOptions& global)> setup;
};

std::vector<Command>& commandRegistry();

struct CommandRegistrar {
    explicit CommandRegistrar(Command c) { commandRegistry().push_back(std::move(c)); }
};

#define PLANTARCH_REGISTER_COMMAND(ident, name, order, setupFn)   \
    static ::plantarch::cli::CommandRegistrar ident##_registrar { \
        { name, order, setupFn }                                  \
    }

/// Message on stderr when -v was given.
void info(const GlobalOptions& g, const std::string& message);

/// Writes `ctx` to `path`, format from the extension (.obj, .ply, .glb, .gltf, .png). Used by
/// every subcommand that produces geometry; `plants` names and places the plants in glTF
/// files. Shows the writer's progress (terminalProgress) unless `showProgress` is false.
/// Throws plantarch::Error on an unknown extension.
void writeSceneFile(const Context& ctx, const std::string& path, const GlobalOptions& g,
                    const std::vector<GltfPlant>& plants = {}, bool showProgress = true);

/// --progress: when the bar of terminalProgress() is drawn.
enum class ProgressMode {
    Auto,    ///< when stderr is a terminal, once the command has run for a second
    Always,  ///< at once, even when stderr is not a terminal
    Never,
};
void setProgressMode(ProgressMode mode);
/// The progress bar on stderr (one line, redrawn in place, wiped when its stage ends), as
/// --progress says; empty (no output at all) when it is off, so scripts and logs stay clean.
/// Never writes to stdout.
ProgressCallback terminalProgress();
/// Wipes the bar if one is on screen (before a message on stderr).
void clearProgress();

/// Checks every output's format before any work is done and creates missing directories;
/// throws plantarch::Error naming the first bad path.
/// `points` is --points: .npz outputs (point clouds) need it.
void prepareSceneOutputs(const std::vector<std::string>& paths, std::size_t points = 0);

/// A path's extension in lower case, with its dot (".obj"); empty when it has none.
std::string lowerExtension(const std::string& path);
/// Creates the missing folders of each output path; throws plantarch::Error naming the first
/// that cannot be made.
void createOutputFolders(const std::vector<std::string>& paths);

/// Whether writeSceneFile writes this extension (lower case, with its dot).
bool isSceneExtension(const std::string& ext);
/// The extensions writeSceneFile accepts, for help text and errors.
std::string sceneFileExtensions();

/// A CLI11 check of a numeric option, run on its text before conversion, so every bad value
/// gets one message: "--age = -3: not a number of days (valid: 0 to 100000)". `what` names
/// the kind of number, `whole` rejects fractions, `range` is shown as the valid range.
CLI::Validator numberCheck(const std::string& option, const std::string& what, double lo, double hi,
                           bool whole, const std::string& range);
/// numberCheck for a number of days, 0 to 100000.
CLI::Validator daysCheck(const std::string& option);

/// The plant a command builds: SPECIES (library name or species file), --age, -D name=value
/// build parameters and --no-trellis. Returns --age, for the caller to require.
CLI::Option* addPlantOptions(CLI::App& app, std::string& species, float& age,
                             std::vector<std::string>& defines, bool& noTrellis);

/// Build parameters given as -D name=value (each a finite number), by name.
std::map<std::string, float> parseDefines(const std::vector<std::string>& defines);

/// One plant's statistics as one line of JSON (species, plant, age, seed, height, leaves,
/// leaf_area, shoots, flowers, fruit, triangles), for --stats.
std::string plantStatsJSON(const PlantArchitecture& arch, const Context& ctx, unsigned plant,
                           std::uint64_t seed);

// ---- plant outputs (plant_output.cpp) ---------------------------------------------------

/// The extensions writePlantOutput accepts: the scene formats, .xml (plant structure file)
/// and .txt (plant strings, one per line).
std::string plantFileExtensions();
/// Writes `text` through a temporary file renamed into place (never half a file).
void writeWholeFile(const std::string& path, const std::string& text);

/// `path` with the plant's ID before the extension: field.glb -> field_0007.glb.
std::string separateFileName(const std::string& path, unsigned plant);
/// One file per plant for each output path (separateFileName), each in scene coordinates or,
/// with `ownOrigin`, moved so that the plant's base is at the origin; and one index,
/// <stem of the first output>_index.json, of the plants' IDs, files, positions, species, ages
/// and seed.
void writeSeparatePlantOutputs(const PlantArchitecture& arch, const std::vector<unsigned>& plants,
                               const std::vector<std::string>& paths, bool ownOrigin,
                               const GlobalOptions& g);

/// prepareSceneOutputs for commands that have plants: .xml and .txt are accepted too.
void preparePlantOutputs(const std::vector<std::string>& paths, std::size_t points = 0);
/// Writes `plants` of `arch` to `path`: a plant structure file (.xml), plant strings
/// (.txt), or the whole scene through writeSceneFile.
void writePlantOutput(const PlantArchitecture& arch, const std::vector<unsigned>& plants,
                      const std::string& path, const GlobalOptions& g);
/// Reads plants from a plant structure file (.xml; its warnings go to stderr) or a file of
/// plant strings (.txt, whose shoot types come from `species`, required then). Returns
/// the plants' IDs.
std::vector<unsigned> readPlantInput(PlantArchitecture& arch, const std::string& path,
                                     const std::string& species);
/// Adds --digits (significant digits of plant strings) to a subcommand.
void addStringDigitsOption(CLI::App& app, GlobalOptions& global);
// ---- label options (label_options.cpp) ---------------------------------------------------

/// Adds --object-ids (.xml outputs carry each organ's object IDs; each mesh output gets an
/// object table), --ply-color and --ply-format.
void addLabelOptions(CLI::App& app, GlobalOptions& global);
/// Whether an output of this path holds object IDs (.obj, .ply, .glb, .gltf, .usda, .npz),
/// and so gets an object table with --object-ids.
bool hasObjectIDs(const std::string& path);
/// The object table next to a mesh: field.obj -> field.objects.json.
std::string objectTablePath(const std::string& path);

/// A growth animation asked for with --frames START:END[:STEP] and --frame-rate
/// (animation_options.cpp).
struct AnimationArgs {
    std::string frames;
    double rate = 24.0;
};
/// Adds --frames and --frame-rate; `counted` says what the days count ("of age").
void addAnimationOptions(CLI::App& app, AnimationArgs& args, const std::string& counted);
/// The frames asked for, none without --frames; throws plantarch::Error for a bad value.
std::optional<GrowthFrames> parseFrames(const AnimationArgs& args);
/// Throws unless exactly one of --age (age >= 0) and --frames was given.
void requireAgeOrFrames(float age, bool frames);
/// The checks `build` and `canopy` make of their outputs before any work: an output unless
/// --stats, exactly one of --age and --frames, and each output's format (an animation format
/// with --frames); missing folders are made. Returns the frames asked for, if any.
std::optional<GrowthFrames> prepareGrowthOutputs(const std::vector<std::string>& outputs,
                                                 bool stats, float age,
                                                 const AnimationArgs& animation,
                                                 std::size_t points);
/// Checks that every output is an animation format (.glb, .gltf, .usda), before any work.
void prepareAnimationOutputs(const std::vector<std::string>& paths);

/// Collision avoidance options of `build` and `canopy` (collision_options.cpp).
struct CollisionArgs {
    bool soft = false;                   ///< --soft-collision
    std::string cone;                    ///< --cone half-angle,look-ahead,rays,inertia
    std::vector<std::string> obstacles;  ///< --obstacle FILE.obj (repeatable)
    std::string avoidDistance;           ///< --avoid-distance m
    bool fruitAdjustment = false;        ///< --fruit-adjustment
    std::string attractionPoints;        ///< --attraction-points FILE.csv
    std::string attractionCone;          ///< --attraction-cone half-angle,look-ahead,inertia
};
void addCollisionOptions(CLI::App& app, CollisionArgs& args);
/// Checks the options' forms and that their files open, before any work is done.
void checkCollisionOptions(const CollisionArgs& args);
/// Reads obstacles and points into `ctx` and enables what was asked for.
void applyCollisionOptions(const CollisionArgs& args, PlantArchitecture& arch, Context& ctx);

}  // namespace plantarch::cli
