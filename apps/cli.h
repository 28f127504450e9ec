#pragma once
// Shared pieces of the plantarch command: global options, the subcommand registry and
// terminal output helpers. Each subcommand lives in its own file and registers itself with
// PLANTARCH_REGISTER_COMMAND, so adding one never touches main.cpp.

#include <CLI/CLI.hpp>
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "plantarch/Context.h"
#include "plantarch/Export.h"
#include "plantarch/ExportPlants.h"
#include "plantarch/OutputFiles.h"
#include "plantarch/OutputFormats.h"
#include "plantarch/Physiology.h"
#include "plantarch/PlantArchitecture.h"
#include "plantarch/PlantFiles.h"
#include "plantarch/Progress.h"
#include "plantarch/Render.h"

namespace plantarch::cli {

/// Options every subcommand sees.
struct GlobalOptions {
    int verbose = 0;          ///< -v count
    std::uint64_t seed = 42;  ///< --seed
    int threads = 0;          ///< --threads (0 = all cores)
    int imageWidth = 1024;    ///< size of PNG outputs (--image-size on build and canopy)
    int imageHeight = 768;
    /// The camera of PNG outputs: framed on the scene unless --eye fixes it (--target, --fov).
    Camera pictureCamera;
    bool pictureTarget = false;                   ///< --target given
    RenderMode pictureMode = RenderMode::Shaded;  ///< --label organ | object
    bool cameraJson = false;  ///< --camera-json: NAME.camera.json beside each PNG output
    int stringDigits = 4;     ///< significant digits of plant strings (--digits)
    std::size_t points = 0;  ///< --points: PLY outputs as labelled point clouds of this many points
    float meshDetail = 1.0f;  ///< --mesh-detail: factor on every organ's mesh resolution
    bool objectIDs = false;   ///< --object-ids: object IDs in .xml, object tables by meshes
    PlyColor plyColor = PlyColor::None;                   ///< --ply-color
    PlyFormat plyFormat = PlyFormat::BinaryLittleEndian;  ///< --ply-format
    bool skin = false;  ///< --skin: skeletons in glTF and USD outputs (skin_options.cpp)
    float wind = 0.0f;  ///< --wind DEGREES: a wind animation of skinned glTF outputs
    std::vector<GltfLevel> levels;  ///< --lod: levels of detail of glTF outputs (lod_options.cpp)
    bool meshopt = false;           ///< --meshopt: EXT_meshopt_compression of glTF outputs
    /// --materials and --texture-size: flat colours or procedural textures (material_options.cpp)
    MaterialOptions appearance;
    std::string
        textureOption;  ///< the first of --texture-size, --no-texture-atlas given ("": none)
    NodeLevel nodes = NodeLevel::Kind;           ///< --nodes (node_options.cpp)
    Instancing instancing = Instancing::Shared;  ///< --instancing
    /// --max-triangles: a job that needs more stops before it starts (or as soon as it passes
    /// it) with one line; 0 for no limit. Default: PlantArchitecture::defaultTriangleLimit().
    std::size_t maxTriangles = PlantArchitecture::defaultTriangleLimit();
};

/// Parses "x,y,z" (three finite numbers) or throws an Error naming the option.
vec3 parseVec3(const std::string& text, const char* option);
/// Parses two finite numbers joined by `separator` ("30:150", "38.5,-121.7"); throws an
/// Error naming the option: "expected `expected`", with `example` as the valid form.
std::pair<double, double> parseTwoNumbers(const std::string& text, char separator,
                                          const char* option, const std::string& expected,
                                          const std::string& example);
/// Parses "10x12" or "0.3x0.25" (two positive numbers joined by 'x', whole numbers for an
/// integral T) or throws an Error naming the option.
template <class T>
std::pair<T, T> parsePair(const std::string& text, const char* option);
/// --orbit AZIMUTH,ELEVATION (degrees; elevation -89 to 89) into an auto-framed camera's
/// view direction; throws naming the option and its form.
void parseOrbit(const std::string& text, Camera& camera);

/// The mask a --label value selects: organ or object; an Error listing them (and `more`, the
/// command's other values) for any other name.
RenderMode labelMode(const std::string& name, const std::string& more = "");
/// Adds the options of PNG outputs to a subcommand, stored in `global`: --image-size WxH,
/// --eye, --target and --fov (a fixed camera), --label organ|object (a label mask) and
/// --camera-json (the camera's matrices beside each picture, NAME.camera.json).
void addImageSizeOption(CLI::App& app, GlobalOptions& global);

/// A subcommand: `setup` adds it to the app and returns the function run when it is chosen.
struct Command {
    std::string name;
    int order;  ///< position in --help
    std::function<std::function<int()>(CLI::App& app, GlobalOptions& global)> setup;
};

std::vector<Command>& commandRegistry();

/// The command line main() was given (argv[0] first), for a command that hands it on.
void setCommandLine(int argc, char** argv);
const std::vector<std::string>& commandLine();

struct CommandRegistrar {
    explicit CommandRegistrar(Command c) { commandRegistry().push_back(std::move(c)); }
};

#define PLANTARCH_REGISTER_COMMAND(ident, name, order, setupFn)   \
    static ::plantarch::cli::CommandRegistrar ident##_registrar { \
        { name, order, setupFn }                                  \
    }

/// --shard K/N (shard_option.cpp): two whole numbers with 0 <= K < N <= maxShards; an Error
/// naming --shard and its form otherwise.
std::pair<std::size_t, std::size_t> parseShard(const std::string& text, std::size_t maxShards);

/// Message on stderr when -v was given.
void info(const GlobalOptions& g, const std::string& message);
/// Wall time since `start`, ms (what -v reports).
double millisecondsSince(std::chrono::steady_clock::time_point start);

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
/// Flushes standard output; "" when everything printed so far was written, else the line
/// "cannot write standard output: <reason>" (a full disk, a closed descriptor).
std::string standardOutputFailure();

// ---- output files (output_files.cpp) ------------------------------------------------------

/// The files one command writes. Made before any work: it creates the missing folders of each
/// path and checks that each can be written (checkOutputPath: not a directory, a folder that
/// takes new files; an .obj's .mtl not a directory), then opens an OutputSet, so that every
/// file written afterwards is held back. commit() puts them all in place together. Destroyed
/// without commit() (the command failed), it discards them: no target is created or replaced,
/// and the folders it made are removed again.
///
/// In a command (`endsProcess`, the default) commit() first flushes standard output, failing
/// like any output when that write failed, and from then on holds SIGINT and SIGTERM back
/// until the process exits: a command whose files are in place exits 0, never 130. The
/// folders it made are removed on those signals too, until commit(). The builder's server
/// passes false: it goes on serving after a commit.
class CommandOutputs {
public:
    explicit CommandOutputs(const std::vector<std::string>& paths, bool endsProcess = true);
    ~CommandOutputs();
    CommandOutputs(const CommandOutputs&) = delete;
    CommandOutputs& operator=(const CommandOutputs&) = delete;
    /// One more file, checked in the same way (an index, annotations).
    void add(const std::string& path);
    /// Throws plantarch::Error naming `input` (and `option`) when it is one of the outputs.
    void requireNotAnInput(const std::string& input, const std::string& option = "");
    void commit();

private:
    void makeFolders(const std::string& path);
    void removeMadeFolders();
    std::vector<FolderMadeForOutputs> madeFolders_;  // outermost first
    std::vector<std::filesystem::path> paths_;       // the outputs, as sameFileKey made them
    std::optional<OutputSet> set_;
    bool endsProcess_ = true;
    bool committed_ = false;
};

/// Checks each output's format (a scene format, or .xml, .txt, .csv too with `plants`) before
/// any work; `points` is --points: .npz outputs (point clouds) need it. Throws
/// plantarch::Error naming the first bad path.
void checkSceneOutputs(const std::vector<std::string>& paths, std::size_t points = 0,
                       bool plants = false);

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

/// Writes `text` as one file, whole or not at all (held back by an open OutputSet).
void writeWholeFile(const std::string& path, const std::string& text);

/// The options of plant and scene files from the command's: each writer's progress on the
/// terminal (none with `showProgress` false) and a "wrote PATH" line with -v.
PlantFileOptions plantFileOptions(const GlobalOptions& g, bool showProgress = true);

/// Throws plantarch::Error naming `path` (and `option`, if given) unless it is a file that
/// opens: "is a directory, not a <what>" or "cannot open <what>".
void requireInputFile(const std::string& path, const std::string& what,
                      const std::string& option = "");
/// Reads plants from a plant structure file (.xml; its warnings go to stderr), a file of
/// plant strings (.txt) or a measured skeleton (.mtg, .csv, .json: reconstructPlants with
/// its defaults); the last two take their shoot types from `species`, required then.
/// Returns the plants' IDs.
std::vector<unsigned> readPlantInput(PlantArchitecture& arch, const std::string& path,
                                     const std::string& species);
/// Adds --digits (significant digits of plant strings) to a subcommand.
void addStringDigitsOption(CLI::App& app, GlobalOptions& global);
// ---- label options (label_options.cpp) ---------------------------------------------------

/// Adds --object-ids (.xml outputs carry each organ's object IDs; each mesh output gets an
/// object table), --ply-color and --ply-format.
void addLabelOptions(CLI::App& app, GlobalOptions& global);
/// --skin (skin_options.cpp), added by addLabelOptions.
void addSkinOptions(CLI::App& app, GlobalOptions& global);
/// --lod and --meshopt (lod_options.cpp), added by addLabelOptions.
void addLevelOptions(CLI::App& app, GlobalOptions& global);
/// Before any work: --lod and --meshopt only with glTF mesh outputs (pictures and plant files
/// may come along), and not with --frames; throws naming the option.
void checkLevelOutputs(const GlobalOptions& global, const std::vector<std::string>& outputs,
                       bool frames);
/// --materials and --texture-size (material_options.cpp), added by addLabelOptions.
void addMaterialOptions(CLI::App& app, GlobalOptions& global);
/// Before any work: --texture-size and --no-texture-atlas only with --materials textured, and
/// --materials textured only with an output that holds materials (.obj, glTF, USD, .png).
void checkMaterialOutputs(const GlobalOptions& global, const std::vector<std::string>& outputs);
/// --nodes and --instancing (node_options.cpp), added by addLabelOptions.
void addNodeOptions(CLI::App& app, GlobalOptions& global);
/// Before any work: --skin (or --wind) neither with --frames nor with canopy --separate.
void checkSkinOutputs(const GlobalOptions& global, bool frames, bool separate = false);
/// Before any work: --nodes other than kind only with glTF and USD mesh outputs (pictures and
/// plant files may come along); with --frames only organ. Throws naming the option.
void checkNodeOutputs(const GlobalOptions& global, const std::vector<std::string>& outputs,
                      bool frames);

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
/// with --frames). Returns the frames asked for, if any.
std::optional<GrowthFrames> prepareGrowthOutputs(const std::vector<std::string>& outputs,
                                                 bool stats, float age,
                                                 const AnimationArgs& animation,
                                                 std::size_t points);
/// Checks that every output is an animation format (.glb, .gltf, .usda), before any work.
void checkAnimationOutputs(const std::vector<std::string>& paths);

/// Collision avoidance options of `build` and `canopy` (collision_options.cpp).
struct CollisionArgs {
    bool soft = false;                   ///< --soft-collision
    std::string cone;                    ///< --cone half-angle,look-ahead,rays,inertia
    std::vector<std::string> obstacles;  ///< --obstacle FILE.obj (repeatable)
    std::string avoidDistance;           ///< --avoid-distance m
    bool fruitAdjustment = false;        ///< --fruit-adjustment
    std::string attractionPoints;        ///< --attraction-points FILE.csv
    std::string attractionCone;          ///< --attraction-cone half-angle,look-ahead,inertia
    bool noGroundClearance = false;      ///< --no-ground-clearance
};
void addCollisionOptions(CLI::App& app, CollisionArgs& args);
/// Checks the options' forms and that their files open, before any work is done.
void checkCollisionOptions(const CollisionArgs& args);

/// The physiology options of build and grow (apps/physiology_options.cpp).
struct PhysiologyArgs {
    bool carbon = false;                 ///< --carbon
    bool nitrogen = false;               ///< --nitrogen
    std::string location;                ///< --location LAT,LON
    std::string start;                   ///< --start YYYY-MM-DD (clear days)
    double clearness = 0.75;             ///< --clearness
    std::string weather;                 ///< --weather FILE.csv
    std::vector<std::string> fertilise;  ///< --fertilise AGE:GRAMS (repeatable)
    unsigned lightEvery = 1;             ///< --light-every N
    std::string series;                  ///< --series FILE.csv
    float from = 10.0f;                  ///< --from D (build, canopy)
};
/// The physiology options; `withFrom` adds --from (the age the models start at).
void addPhysiologyOptions(CLI::App& app, PhysiologyArgs& args, bool withFrom);
/// The age to build the plants to: --from with --carbon/--nitrogen (checked against --age:
/// whole days, not after it, no --frames), else `age`.
float physiologyBuildAge(const PhysiologyArgs& args, float age, bool frames);
/// Whether --carbon or --nitrogen was given.
bool physiologyOn(const PhysiologyArgs& args);
/// Checks the options' forms and that they go together, before any work is done.
void checkPhysiologyOptions(const PhysiologyArgs& args);
/// Turns the asked-for models on for `plants` and grows them `days` whole days through the
/// weather (or clear days), each day's light traced; writes --series. Returns the records.
std::vector<PhysiologyRecord> growWithPhysiology(PlantArchitecture& arch,
                                                 const std::vector<unsigned>& plants,
                                                 const PhysiologyArgs& args, double days);
/// The help text of --no-ground-clearance (build, canopy, grow).
extern const char* const kNoGroundClearanceHelp;
/// Reads obstacles and points into `ctx` and enables what was asked for (ground clearance
/// turned off for the plants built afterwards with --no-ground-clearance).
void applyCollisionOptions(const CollisionArgs& args, PlantArchitecture& arch, Context& ctx);

}  // namespace plantarch::cli
