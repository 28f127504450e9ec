#pragma once
// Calibration to field data: chosen parameters of a species adjusted, within bounds, so that
// the plants built from it match measured statistics (height, leaf area, leaf count, shoots,
// widths, internode lengths by rank, leaf inclination) at one or more ages, averaged over
// several seeds, and optionally a point cloud or skeleton of one real plant. The optimiser is one
// of NLopt's derivative-free local algorithms (Subplex by default; Nelder-Mead, BOBYQA, COBYLA) on
// the parameters scaled to [0, 1] by their bounds. `plantarch fit` is the command;
// docs/measured-plants.md describes the target file (JSON) and the report.
//
//   FitTarget target = readFitTargetFile("measurements.json");
//   FitResult result = fitSpecies(loadSpecies("bean"), target);
//   writeSpeciesFile(result.fitted, "fitted.xml");

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "plantarch/Mesh.h"
#include "plantarch/Species.h"

namespace plantarch {

/// One parameter to fit: a single-number field of the species, named as editSpecies names it
/// ("shoot_types.trifoliate.internode_length_max", "phenology.max_age",
/// "build_parameters.trunk_height"; "trifoliate.internode_length_max" is read as the first).
struct FitParameter {
    std::string path;
    double lower = 0.0;
    double upper = 0.0;
    std::optional<double> start;  ///< default: the species' own value
    int line = 0;                 ///< in the target file, for errors
};

/// The statistics a measurement can name (`plantarch fit` target files use the names of
/// fitStatisticName).
enum class FitStatistic {
    Height,           ///< m, top of the plant above its base
    LeafArea,         ///< m^2, one-sided
    Leaves,           ///< leaf count (each leaflet one)
    Shoots,           ///< shoot count (every rank)
    Branches,         ///< shoots of rank 1 and above
    MainNodes,        ///< phytomers of the main shoot
    WidthX,           ///< m, the plant's box along x
    WidthY,           ///< m, along y
    WidthLong,        ///< m, largest horizontal extent
    WidthShort,       ///< m, extent square to it
    InternodeLength,  ///< m, mean current internode length of the shoots of one rank
    /// degrees, area-weighted mean leaf inclination from horizontal (meanLeafInclination,
    /// plantarch/LeafAngles.h)
    LeafInclination,
    /// fractions of leaf area in 0-10, ... 80-90 degrees (9 bins, PlantSummary's)
    LeafInclinationHistogram,
};
const char* fitStatisticName(FitStatistic s);
/// Every statistic, in the order above.
const std::vector<FitStatistic>& fitStatistics();

/// One measured statistic at one age. Its residual is (simulated - value) / sd, times
/// sqrt(weight); without an sd, relative: (simulated - value) / |value|. The histogram has 9
/// values (each bin one residual).
struct FitMeasurement {
    FitStatistic statistic = FitStatistic::Height;
    unsigned rank = 0;  ///< InternodeLength: the shoots' rank (0 the main stem)
    std::vector<double> values;
    std::optional<double> sd;
    double weight = 1.0;
    int line = 0;
};

/// What was measured at one age (days).
struct FitAge {
    double age = 0.0;
    std::vector<FitMeasurement> measurements;
    int line = 0;
};

/// A point cloud (PLY vertices or XYZ text) of one real plant at one age: the term is
/// weight * (d / scale)^2, d the symmetric mean distance (m) between points drawn on the built
/// plant's surface and the cloud (each cloud point to the nearest surface, each surface sample
/// to the nearest cloud point, the two means averaged), averaged over the seeds.
struct FitPointCloud {
    std::string file;  ///< as written in the target (relative to the target's folder)
    std::string path;  ///< resolved
    double age = 0.0;
    unsigned points = 2000;  ///< surface samples per plant, and cloud points used (evenly picked)
    double scale = 0.01;     ///< m
    double weight = 1.0;
    /// Where the real plant's base stands in the cloud's coordinates (the built plant's is
    /// the origin).
    vec3 offset{0.0f};
    int line = 0;
};

/// A measured skeleton of one real plant (plantarch/Skeleton.h: a node table .csv, .json or
/// .mtg) at one age: the term is weight * (d / scale)^2, d the symmetric mean distance (m)
/// between its nodes and the built plant's (plantSkeleton: its base and the tip of every
/// internode), each node to the nearest of the other set, the two means averaged, averaged
/// over the seeds.
struct FitSkeleton {
    std::string file;  ///< as written in the target (relative to the target's folder)
    std::string path;  ///< resolved
    double age = 0.0;
    double scale = 0.01;  ///< m
    double weight = 1.0;
    vec3 offset{0.0f};  ///< where the real plant's base stands in the skeleton's coordinates
    int line = 0;
};

/// NLopt's algorithms offered (all local and derivative-free).
enum class FitAlgorithm { Bobyqa, Subplex, NelderMead, Cobyla };
const char* fitAlgorithmName(FitAlgorithm a);

inline constexpr unsigned kMaxFitEvaluations = 10000;
inline constexpr std::size_t kMaxFitSeeds = 256;
inline constexpr std::size_t kMaxFitParameters = 32;

/// A target file as read: the parameters, seeds, optimiser settings and measurements.
struct FitTarget {
    std::string file;  ///< for messages
    std::vector<FitParameter> parameters;
    std::vector<std::uint64_t> seeds{1, 2, 3, 4};
    FitAlgorithm algorithm = FitAlgorithm::Subplex;
    unsigned maxEvaluations = 100;
    double tolerance = 1e-4;  ///< relative change of the scaled parameters that ends the fit
    std::vector<FitAge> ages;
    std::optional<FitPointCloud> pointCloud;
    std::optional<FitSkeleton> skeleton;
};

/// Reads a target file (JSON, docs/measured-plants.md) strictly: an unknown key, a value of
/// the wrong type or out of range is a plantarch::Error naming the file, the line, the key (a
/// JSON pointer without its leading '/') and the valid range. The file must be a regular file
/// (not a directory or FIFO) of at most 16 MiB.
FitTarget readFitTargetFile(const std::string& path);
/// The same from text; `nameForErrors` stands for the file; `folder` resolves the point
/// cloud's file.
FitTarget readFitTargetString(const std::string& text, const std::string& nameForErrors,
                              const std::string& folder = ".");

/// Checks the target against a species before any build: every parameter path names a
/// single-number field (a number, a whole number or a build parameter) holding a number (not
/// a distribution), its bounds within the field's valid range and its start within the bounds.
/// Throws plantarch::Error naming the target file, the parameter's line and its path.
void checkFitTarget(const SpeciesModel& species, const FitTarget& target);

/// One statistic's residual at the end of the fit.
struct FitResidual {
    double age = 0.0;
    std::string statistic;  ///< "height", "internode_length[1]", "leaf_inclination_histogram[3]"
    double measured = 0.0;
    double simulatedStart = 0.0;  ///< mean over the seeds, at the start values
    double simulated = 0.0;       ///< at the fitted values
    double residual = 0.0;        ///< normalised, at the fitted values
};

/// One evaluation of the objective.
struct FitEvaluation {
    unsigned number = 0;  ///< 1, 2, ...
    double objective = 0.0;
    std::vector<double> values;  ///< the parameters, in their own units
};

/// How fitSpecies runs.
struct FitOptions {
    int threads = 0;  ///< OpenMP threads over the seeds (0: OpenMP's default)
    /// Called after every evaluation that improves on the best so far (the first included),
    /// from the calling thread, with that evaluation.
    std::function<void(const FitEvaluation& best)> onImprovement;
    /// Triangle limit per plant (0: none), as PlantArchitecture::setTriangleLimit.
    std::size_t triangleLimit = 0;
};

struct FitResult {
    SpeciesModel fitted;  ///< the species with the fitted values
    std::vector<std::string> paths;
    std::vector<double> start;
    std::vector<double> best;
    double startObjective = 0.0;
    double bestObjective = 0.0;
    std::vector<FitEvaluation> evaluations;  ///< every evaluation, in order
    std::vector<FitResidual> residuals;      ///< per statistic and age
    std::string stopReason;                  ///< NLopt's: "max evaluations", "tolerance", ...
    std::string algorithm;
};

/// Fits the target's parameters of `species` (checkFitTarget first). Deterministic: the same
/// result for any thread count.
FitResult fitSpecies(const SpeciesModel& species, const FitTarget& target,
                     const FitOptions& options = {});

/// The objective at the given parameter values (in their own units, in the target's order),
/// and the simulated statistics (mean over the seeds) into `residuals` when given.
double fitObjective(const SpeciesModel& species, const FitTarget& target,
                    const std::vector<double>& values, const FitOptions& options = {},
                    std::vector<FitResidual>* residuals = nullptr);

/// The report of a fit as JSON text: target, species, algorithm, parameters (start, fitted,
/// bounds), objective at start and end, residuals per statistic and age, every evaluation.
std::string fitReportJson(const FitResult& result, const FitTarget& target);

/// Points of a point cloud file: PLY (its vertex element; faces, if any, ignored) or XYZ text
/// (".xyz", ".txt", ".pts": x y z first on each line, '#' comments). Throws plantarch::Error
/// naming the file and line for a bad file; at most 2^26 points.
std::vector<vec3> readPointCloudFile(const std::string& path);

}  // namespace plantarch
