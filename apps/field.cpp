// plantarch field PROJECT.json --out DIR --tile-size M [--halo M] [--shard K/N] [--resume]
//                [--index-only]
// Builds a project as tiles (plantarch/Field.h): one labelled GLB and one CSV of plants per
// tile, then the index (tileset.json, 3D Tiles 1.1, and plants.csv). A shard builds its share
// of the tiles and no index; a run without --shard, or with --index-only, writes the index.

#include "plantarch/Field.h"

#include <fmt/format.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>

#include "cli.h"
#include "plantarch/Error.h"
#include "plantarch/Project.h"

namespace plantarch::cli {

namespace {

struct FieldArgs {
    std::string project;
    std::string out;
    float tileSize = 0.0f;
    float halo = 1.0f;
    std::string shard;  ///< "K/N"
    bool resume = false;
    bool indexOnly = false;
};

// The library's name for an option given on the command line.
[[noreturn]] void rethrowFieldOption() {
    try {
        throw;
    } catch (const Error& e) {
        const std::string p = e.parameter();
        if (p != "tile_size" && p != "halo") throw;
        throw Error(e.message(), {.parameter = p == "halo" ? "--halo" : "--tile-size",
                                  .value = e.value(),
                                  .validRange = e.validRange()});
    }
}

// --out is a folder, or can be made: its nearest existing parent is a folder this process
// may write in. Nothing is made before any work.
void requireFieldFolder(const std::string& out) {
    const auto bad = [&](const std::string& why, const std::string& path) {
        return Error(
            why, {.file = path, .parameter = "--out", .validRange = "a folder (made if missing)"});
    };
    if (out.empty()) throw bad("no output folder", out);
    std::error_code ec;
    const std::filesystem::path given = std::filesystem::absolute(out, ec);
    for (std::filesystem::path p = given;; p = p.parent_path()) {
        const auto status = std::filesystem::status(p, ec);
        if (std::filesystem::exists(status)) {
            if (!std::filesystem::is_directory(status))
                throw bad("not a folder", p == given ? out : p.string());
            if (::access(p.c_str(), W_OK | X_OK) != 0)
                throw bad("cannot write in the folder", p.string());
            return;
        }
        if (!p.has_parent_path() || p.parent_path() == p) throw bad("no such folder", out);
    }
}

int runField(const FieldArgs& a, const GlobalOptions& global) {
    if (a.indexOnly && (!a.shard.empty() || a.resume))
        throw Error("--index-only builds no tile",
                    {.parameter = "--index-only", .validRange = "without --shard and --resume"});
    std::size_t shard = 0, shards = 1;
    if (!a.shard.empty()) std::tie(shard, shards) = parseShard(a.shard, kMaxFieldTiles);
    requireFieldFolder(a.out);
    const Project project = readProjectFile(a.project);
    FieldOptions options;
    options.tileSize = a.tileSize;
    options.halo = a.halo;
    options.maxTriangles = global.maxTriangles;
    FieldPlan plan;
    try {
        plan = fieldTiles(project, options);
    } catch (const Error&) {
        rethrowFieldOption();
    }
    if (!a.indexOnly) checkProject(project);
    const std::filesystem::path dir(a.out);
    std::size_t built = 0, skipped = 0;
    if (!a.indexOnly) {
        const ProgressCallback bar = terminalProgress();
        for (std::size_t i = shard; i < plan.tiles.size(); i += shards) {
            const FieldTile& t = plan.tiles[i];
            if (a.resume && std::filesystem::is_regular_file(dir / (t.name + ".glb"))) {
                ++skipped;
                continue;
            }
            if (bar) {
                const std::string prefix =
                    fmt::format("{} ({} of {}): ", t.name, i + 1, plan.tiles.size());
                options.progress = [bar, prefix](std::string_view stage, double fraction) {
                    bar(prefix + std::string(stage), fraction);
                };
            }
            buildFieldTile(project, options, i, a.out);
            info(global, "wrote " + (dir / (t.name + ".glb")).string());
            ++built;
        }
    }
    const bool index = a.shard.empty();
    if (index) writeFieldIndex(project, options, a.out);
    std::printf("%s", fmt::format("field {}: {} tiles of {} m, {} plants; {} tiles built{}{}.\n",
                                  project.name.empty() ? a.project : project.name,
                                  plan.tiles.size(), a.tileSize, plan.plants, built,
                                  skipped ? fmt::format(", {} already there", skipped) : "",
                                  index ? ", index written to " + (dir / "tileset.json").string() +
                                              " and " + (dir / "plants.csv").string()
                                        : fmt::format(" (shard {}/{}: no index)", shard, shards))
                          .c_str());
    return 0;
}

std::function<int()> setupField(CLI::App& app, GlobalOptions& global) {
    app.description(
        "Build a project as tiles: a labelled GLB per tile, a 3D Tiles index and a table of "
        "plants (fields larger than memory; docs/datasets.md)");
    auto a = std::make_shared<FieldArgs>();
    app.add_option("project", a->project, "Project file (.json)")->required();
    app.add_option("--out", a->out, "Output folder (made if missing)")->required();
    app.add_option("--tile-size", a->tileSize, "Edge of a square tile, m")
        ->required()
        ->check(
            numberCheck("--tile-size", "a tile size", 1e-30, 1e6, false, "> 0 and <= 1000000 m"));
    app.add_option("--halo", a->halo,
                   "With soft collision avoidance: neighbours within this many m of a tile are "
                   "grown with it (not written); default 1")
        ->check(numberCheck("--halo", "a halo width", 0.0, 1000.0, false, "0 to 1000 m"));
    app.add_option("--shard", a->shard,
                   "Build tiles i with i % N == K only (K/N, e.g. "
                   "$SLURM_ARRAY_TASK_ID/$SLURM_ARRAY_TASK_COUNT); no index");
    app.add_flag("--resume", a->resume, "Skip the tiles whose GLB is there already");
    app.add_flag("--index-only", a->indexOnly,
                 "Build no tile: write the index from the tiles in the folder");
    return [a, &global]() { return runField(*a, global); };
}

}  // namespace

PLANTARCH_REGISTER_COMMAND(field, "field", 38, setupField);

}  // namespace plantarch::cli
