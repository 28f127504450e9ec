#pragma once
// Shared pieces of the plantarch command: global options, the subcommand registry and
// terminal output helpers. Each subcommand lives in its own file and registers itself with
// PLANTARCH_REGISTER_COMMAND, so adding one never touches main.cpp.

#include <functional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "plantarch/Context.h"
#include "plantarch/Progress.h"

namespace plantarch {
class PlantArchitecture;
}

namespace plantarch::cli {

/// Options every subcommand sees.
struct GlobalOptions {
    int verbose = 0;             ///< -v count
    std::uint64_t seed = 42;     ///< --seed
    int threads = 0;             ///< --threads (0 = all cores)
    int imageWidth = 1024;       ///< size of PNG outputs (--image-size on build and canopy)
    int imageHeight = 768;
};

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

#define PLANTARCH_REGISTER_COMMAND(ident, name, order, setupFn) \
    static ::plantarch::cli::CommandRegistrar ident##_registrar{{name, order, setupFn}}

/// Message on stderr when -v was given.
void info(const GlobalOptions& g, const std::string& message);

/// Writes `ctx` to `path`, format from the extension (.obj, .ply, .png). Used by every
/// subcommand that produces geometry. Throws plantarch::Error on an unknown extension.
void writeSceneFile(const Context& ctx, const std::string& path, const GlobalOptions& g);

/// A progress bar on stderr for work that takes over a second; empty (no output at all)
/// when stderr is not a terminal, so scripts and logs stay clean.
ProgressCallback terminalProgress();

/// Checks every output's format before any work is done and creates missing directories;
/// throws plantarch::Error naming the first bad path.
void prepareSceneOutputs(const std::vector<std::string>& paths);

/// The extensions writeSceneFile accepts, for help text and errors.
std::string sceneFileExtensions();

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
