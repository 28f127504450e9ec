// plantarch fit SPECIES --target measurements.json [-o fitted.xml] [--report DIR]
// Fits chosen parameters of a species to measured plants (plantarch/Calibration.h): one line
// on stderr per improvement of the objective, a summary on stdout, the fitted species file and
// a report (DIR/report.json, drawn by scripts/plot_fit.py).

#include <fmt/format.h>

#include <cstdio>
#include <filesystem>

#include "cli.h"
#include "plantarch/Calibration.h"
#include "plantarch/Error.h"
#include "plantarch/SpeciesIO.h"

namespace plantarch::cli {

namespace {

struct FitArgs {
    std::string species;
    std::string target;
    std::string output;
    std::string report;
};

std::string valuesText(const std::vector<std::string>& paths, const std::vector<double>& values) {
    std::string out;
    for (std::size_t i = 0; i < paths.size() && i < values.size(); ++i)
        out += fmt::format("{}{} = {:.6g}", out.empty() ? "" : ", ", paths[i], values[i]);
    return out;
}

std::function<int()> setupFit(CLI::App& app, GlobalOptions& global) {
    app.description(
        "Fit parameters of a species to measured plants (statistics at ages, a point cloud or a "
        "skeleton)");
    auto a = std::make_shared<FitArgs>();
    app.add_option("species", a->species, "Library species name or species file (.xml)")
        ->required();
    app.add_option("--target", a->target,
                   "Target file (JSON): parameters with bounds, seeds, optimiser, measurements "
                   "(docs/measured-plants.md)")
        ->required();
    app.add_option("-o,--output", a->output, "The fitted species file (.xml)");
    app.add_option("--report", a->report,
                   "Folder for the report: report.json (values, residuals, every evaluation); "
                   "scripts/plot_fit.py draws it");
    return [a, &global]() {
        std::vector<std::string> outputs;
        if (!a->output.empty()) {
            std::string ext = std::filesystem::path(a->output).extension().string();
            for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
            if (ext != ".xml")
                throw Error("not a species file name",
                            {.file = a->output, .parameter = "-o", .validRange = "a .xml file"});
            outputs.push_back(a->output);
        }
        const std::string reportFile =
            a->report.empty() ? "" : (std::filesystem::path(a->report) / "report.json").string();
        if (!reportFile.empty()) outputs.push_back(reportFile);
        const FitTarget target = readFitTargetFile(a->target);
        const SpeciesModel species = loadSpecies(a->species);
        checkFitTarget(species, target);
        CommandOutputs files(outputs);
        files.requireNotAnInput(a->target, "--target");
        if (target.pointCloud) files.requireNotAnInput(target.pointCloud->path, "point_cloud");
        if (target.skeleton) files.requireNotAnInput(target.skeleton->path, "skeleton");

        std::vector<std::string> paths;
        for (const FitParameter& p : target.parameters) paths.push_back(p.path);
        FitOptions options;
        options.threads = global.threads;
        options.triangleLimit = global.maxTriangles;
        options.onImprovement = [&](const FitEvaluation& e) {
            clearProgress();
            std::fprintf(stderr, "fit: evaluation %u: objective %.6g, %s\n", e.number, e.objective,
                         valuesText(paths, e.values).c_str());
            std::fflush(stderr);
        };
        const FitResult result = fitSpecies(species, target, options);
        if (!a->output.empty()) writeSpeciesFile(result.fitted, a->output);
        if (!reportFile.empty()) writeWholeFile(reportFile, fitReportJson(result, target));
        std::printf(
            "%s",
            fmt::format(
                "{} fitted to {} over {} seed{} in {} evaluations ({}, {}): objective "
                "{:.6g} -> {:.6g}; {}{}.\n",
                species.name, target.file, target.seeds.size(), target.seeds.size() == 1 ? "" : "s",
                result.evaluations.size(), result.algorithm, result.stopReason,
                result.startObjective, result.bestObjective, valuesText(paths, result.best),
                outputs.empty() ? ""
                                : "; written to " + fmt::format("{}", fmt::join(outputs, ", ")))
                .c_str());
        files.commit();
        return 0;
    };
}

}  // namespace

PLANTARCH_REGISTER_COMMAND(fit, "fit", 75, setupFit);

}  // namespace plantarch::cli
