// plantarch project run FILE -o OUT [-o OUT ...] [--separate [--plant-origin]] [--stats]
//                       [--series FILE.csv]
// plantarch project check FILE
// Builds a project file (a whole scene: blocks of plants, ground, obstacles, collision
// options; docs/projects.md) and writes it in every format asked for, as `canopy` writes a
// canopy; or checks it without building.

#include "plantarch/Project.h"

#include <fmt/format.h>

#include <cstdio>
#include <nlohmann/json.hpp>

#include "cli.h"
#include "plantarch/Error.h"
#include "plantarch/PlantArchitecture.h"

namespace plantarch::cli {

namespace {

struct ProjectArgs {
    std::string file;
    std::vector<std::string> outputs;
    bool stats = false;
    bool separate = false, plantOrigin = false;
    std::string series;  ///< --series FILE.csv
};

// The statistics of the whole project as one line of JSON (--stats).
std::string statsJSON(const Project& project, const ProjectStats& s) {
    return fmt::format(
        "{{\"project\": {}, \"plants\": {}, \"triangles\": {}, \"objects\": {}, "
        "\"height\": {:.4f}, \"leaf_area\": {:.6f}, \"leaf_count\": {}}}",
        nlohmann::json(project.name).dump(-1, ' ', false, nlohmann::json::error_handler_t::replace),
        s.plants, s.triangles, s.objects, s.height, s.leafArea, s.leafCount);
}

int runProject(const ProjectArgs& a, const GlobalOptions& global) {
    if (a.outputs.empty() && !a.stats && a.series.empty())
        throw Error(
            "no output: give -o FILE (or --stats)",
            {.parameter = "-o", .validRange = outputExtensions(kSceneOutput | kPlantOutput)});
    if (a.plantOrigin && !a.separate)
        throw Error("--plant-origin places the plants of separate files",
                    {.parameter = "--plant-origin", .validRange = "with --separate"});
    if (a.separate && a.outputs.empty())
        throw Error("--separate writes files: give -o FILE", {.parameter = "--separate"});
    checkSceneOutputs(a.outputs, global.points, true);
    checkMaterialOutputs(global, a.outputs);
    if (!a.series.empty() && !a.series.ends_with(".csv"))
        throw Error("--series writes CSV: give a .csv name",
                    {.parameter = "--series", .value = a.series, .validRange = "FILE.csv"});
    // readProjectFile checks the file (a directory, a pipe or device, its size) before it reads.
    const Project project = readProjectFile(a.file);
    checkProject(project);
    if (!a.series.empty() && !project.physiology)
        throw Error("--series writes the physiology's records: the project has no physiology",
                    {.file = a.file, .parameter = "physiology"});
    // Separate files get their names once the plants are known: their folder is checked
    // through the index's name.
    CommandOutputs outputs(a.separate
                               ? std::vector<std::string>{separatePlantIndexName(a.outputs.front())}
                               : a.outputs);
    if (!a.series.empty()) outputs.add(a.series);
    if (project.physiology && !project.physiology->weatherFile.empty())
        outputs.requireNotAnInput(projectPath(project, project.physiology->weatherFile),
                                  "physiology/weather");
    Context ctx;
    PlantArchitecture arch(&ctx);
    const BuiltProject built = buildProject(
        project, arch, {.progress = terminalProgress(), .maxTriangles = global.maxTriangles});
    const std::vector<unsigned> plants = built.plants();
    if (!a.series.empty()) writePhysiologyCSV(a.series, built.physiology);
    if (a.separate)
        writeSeparatePlantFiles(arch, plants, a.outputs, a.plantOrigin, plantFileOptions(global));
    else
        for (const std::string& out : a.outputs)
            writePlantFile(arch, plants, out, plantFileOptions(global));
    const ProjectStats s = projectStats(arch, built);
    // Statistics before the files go in place: commit() checks that they were written.
    if (a.stats) std::printf("%s\n", statsJSON(project, s).c_str());
    outputs.commit();
    if (a.stats) return 0;
    std::printf("%s",
                fmt::format("project {}: {} blocks, {} plants, {} leaves, {:.3f} m^2 leaf "
                            "area, {} triangles.\n",
                            project.name.empty() ? a.file : project.name, project.blocks.size(),
                            s.plants, s.leafCount, s.leafArea, s.triangles)
                    .c_str());
    return 0;
}

int checkProjectFile(const std::string& file) {
    const Project project = readProjectFile(file);
    checkProject(project);
    std::size_t grid = 0;
    for (const ProjectBlock& b : project.blocks)
        if (b.layout == ProjectBlock::Layout::Grid) ++grid;
    std::printf("%s", fmt::format("{}: a project of {} blocks ({} grid), fine.\n", file,
                                  project.blocks.size(), grid)
                          .c_str());
    return 0;
}

std::function<int()> setupProject(CLI::App& app, GlobalOptions& global) {
    app.description("Build a project file (blocks of plants, ground, obstacles) or check it");
    app.require_subcommand(1);
    auto a = std::make_shared<ProjectArgs>();
    CLI::App* run = app.add_subcommand(
        "run", "Build a project file and write the scene (the builder's export, from a script)");
    run->add_option("file", a->file, "Project file (.json)")->required();
    run->add_option("-o,--output", a->outputs,
                    "Output file(s): " + outputExtensions(kSceneOutput | kPlantOutput) +
                        " (none with --stats)")
        ->expected(1)
        ->allow_extra_args(false)
        ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
    run->add_flag("--stats", a->stats,
                  "Print the project's statistics as one JSON object (plants, triangles, "
                  "height, leaf area, leaf count)");
    run->add_flag("--separate", a->separate,
                  "One file per plant for each output (field.glb -> field_0007.glb ...) and one "
                  "index, field_index.json");
    run->add_flag(
        "--plant-origin", a->plantOrigin,
        "With --separate: each plant moved to its own origin (default: scene coordinates)");
    run->add_option("--series", a->series,
                    "With a physiology section: its daily records per plant (.csv)");
    addImageSizeOption(*run, global);
    addStringDigitsOption(*run, global);
    addLabelOptions(*run, global);
    CLI::App* check = app.add_subcommand(
        "check", "Check a project file: every field, its species, parameters and files");
    check->add_option("file", a->file, "Project file (.json)")->required();
    return [a, run, check, &global]() {
        if (check->parsed()) return checkProjectFile(a->file);
        (void)run;
        return runProject(*a, global);
    };
}

}  // namespace

PLANTARCH_REGISTER_COMMAND(project, "project", 35, setupProject);

}  // namespace plantarch::cli
