// The fit: the objective (plants built over the seeds at the target's ages, their statistics
// against the measured ones), NLopt's derivative-free search over the scaled parameters, and
// the report.

#include <nlopt.h>
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>
#include <set>

#include "calibration/fit_cloud.h"
#include "core/parallel.h"
#include "core/value_text.h"
#include "plantarch/Calibration.h"
#include "plantarch/Error.h"
#include "plantarch/Export.h"
#include "plantarch/LeafAngles.h"
#include "plantarch/PlantArchitecture.h"
#include "plantarch/PlantSummary.h"
#include "plantarch/Skeleton.h"
#include "plantarch/SpeciesIO.h"

namespace plantarch {

namespace fit {

std::string canonicalPath(const SpeciesModel& species, const std::string& path);
bool wholeKind(const SpeciesModel& species, const std::string& path);
double speciesValue(const SpeciesModel& species, const std::string& path);

namespace {

// Mean current internode length of the shoots of one rank (m; 0 when none).
double meanInternode(const PlantInstance& p, unsigned rank) {
    double sum = 0.0;
    std::size_t n = 0;
    for (const Shoot& s : p.shoots) {
        if (s.removed || s.rank != rank) continue;
        for (const Phytomer& ph : s.phytomers) {
            sum += double(ph.internode.length) * double(ph.internodeFraction);
            ++n;
        }
    }
    return n ? sum / double(n) : 0.0;
}

// The simulated values of one measurement for one plant as it stands.
void measure(const PlantArchitecture& arch, unsigned plant, const PlantSummary& s,
             const FitMeasurement& m, std::vector<double>& out) {
    const PlantInstance& p = arch.plant(plant);
    switch (m.statistic) {
        case FitStatistic::Height:
            out.push_back(s.height);
            return;
        case FitStatistic::LeafArea:
            out.push_back(s.leafArea);
            return;
        case FitStatistic::Leaves:
            out.push_back(s.leaves);
            return;
        case FitStatistic::Shoots:
        case FitStatistic::Branches: {
            unsigned n = 0;
            for (std::size_t r = m.statistic == FitStatistic::Branches ? 1 : 0;
                 r < s.shootsByRank.size(); ++r)
                n += s.shootsByRank[r];
            out.push_back(n);
            return;
        }
        case FitStatistic::MainNodes:
            out.push_back(s.mainNodes);
            return;
        case FitStatistic::WidthX:
            out.push_back(s.widthX);
            return;
        case FitStatistic::WidthY:
            out.push_back(s.widthY);
            return;
        case FitStatistic::WidthLong:
            out.push_back(s.widthLong);
            return;
        case FitStatistic::WidthShort:
            out.push_back(s.widthShort);
            return;
        case FitStatistic::InternodeLength:
            out.push_back(meanInternode(p, m.rank));
            return;
        case FitStatistic::LeafInclination:
            out.push_back(plantarch::meanLeafInclination(arch, plant));
            return;
        case FitStatistic::LeafInclinationHistogram:
            for (float f : s.leafInclination) out.push_back(f);
            return;
    }
}

// The ages a plant is grown to, ascending: the measured ones and the point cloud's.
std::vector<double> sampleAges(const FitTarget& t) {
    std::set<double> ages;
    for (const FitAge& a : t.ages) ages.insert(a.age);
    if (t.pointCloud) ages.insert(t.pointCloud->age);
    if (t.skeleton) ages.insert(t.skeleton->age);
    return {ages.begin(), ages.end()};
}

// The cloud's points used: `n` picked evenly (all when it has fewer), each moved by the
// offset so that the real plant's base is at the origin.
std::vector<vec3> cloudSample(const std::vector<vec3>& points, unsigned n, const vec3& offset) {
    std::vector<vec3> out;
    const std::size_t count = std::min<std::size_t>(n, points.size());
    for (std::size_t i = 0; i < count; ++i)
        out.push_back(points[i * points.size() / count] - offset);
    return out;
}

// What one evaluation needs that is the same for every evaluation.
struct Problem {
    const SpeciesModel& species;
    const FitTarget& target;
    const FitOptions& options;
    std::vector<std::string> paths;  // canonical
    std::vector<bool> whole;
    std::vector<double> ages;
    std::unique_ptr<CloudScene> cloud;
    std::vector<vec3> cloudPoints;         // the sample, moved to the origin
    std::unique_ptr<CloudScene> skeleton;  // the measured nodes, moved to the origin

    Problem(const SpeciesModel& s, const FitTarget& t, const FitOptions& o)
        : species(s), target(t), options(o), ages(sampleAges(t)) {
        for (const FitParameter& p : t.parameters) {
            paths.push_back(canonicalPath(s, p.path));
            whole.push_back(wholeKind(s, p.path));
        }
        if (t.pointCloud) {
            std::vector<vec3> points;
            try {
                points = readCloudPoints(t.pointCloud->path);
            } catch (const Error& e) {
                // A file that does not open is named where the target names it.
                if (e.line() != 0) throw;
                throw Error(e.message(), {.file = t.file,
                                          .line = t.pointCloud->line,
                                          .parameter = "point_cloud/file",
                                          .value = t.pointCloud->file,
                                          .validRange = e.validRange()});
            }
            for (vec3& p : points) p -= t.pointCloud->offset;
            cloudPoints = cloudSample(points, t.pointCloud->points, vec3(0.0f));
            cloud = std::make_unique<CloudScene>(std::move(points));
        }
        if (t.skeleton) {
            Skeleton measured;
            try {
                measured = readSkeletonFile(t.skeleton->path);
                checkSkeleton(measured);
            } catch (const Error& e) {
                if (e.line() != 0) throw;
                throw Error(e.message(), {.file = t.file,
                                          .line = t.skeleton->line,
                                          .parameter = "skeleton/file",
                                          .value = t.skeleton->file,
                                          .validRange = e.validRange()});
            }
            std::vector<vec3> nodes;
            for (const SkeletonNode& n : measured.nodes)
                nodes.push_back(n.position - t.skeleton->offset);
            if (nodes.empty())
                throw Error("no nodes",
                            {.file = t.skeleton->path, .validRange = "a skeleton of one plant"});
            skeleton = std::make_unique<CloudScene>(std::move(nodes));
        }
    }

    // The species with `values` (own units) put in.
    SpeciesModel apply(const std::vector<double>& values) const {
        std::map<std::string, std::string> changes;
        for (std::size_t i = 0; i < paths.size(); ++i)
            changes[paths[i]] =
                whole[i] ? std::to_string(std::llround(values[i])) : text::formatDouble(values[i]);
        return editSpecies(species, changes);
    }

    // One seed's simulated values: for each age of the target in order, each measurement's
    // values in order; then the point cloud's distance.
    std::vector<double> simulate(const SpeciesModel& model, std::uint64_t seed) const {
        Context ctx;
        PlantArchitecture arch(&ctx);
        arch.setSeed(seed);
        arch.setTriangleLimit(options.triangleLimit);
        arch.setTrellisGeometry(false);
        arch.loadPlantModel(model);
        std::map<double, std::vector<double>> byAge;
        double distance = 0.0, skeletonGap = 0.0;
        unsigned plant = 0;
        double grown = 0.0;
        for (std::size_t k = 0; k < ages.size(); ++k) {
            if (k == 0)
                plant = arch.buildPlantInstanceFromLibrary(vec3(0.0f), float(ages[0]));
            else
                arch.advanceTime(plant, ages[k] - grown);
            grown = ages[k];
            const PlantSummary s = summarizePlant(arch, plant);
            std::vector<double>& values = byAge[ages[k]];
            for (const FitAge& a : target.ages)
                if (a.age == ages[k])
                    for (const FitMeasurement& m : a.measurements)
                        measure(arch, plant, s, m, values);
            if (target.pointCloud && target.pointCloud->age == ages[k])
                distance = cloudDistance(ctx, seed);
            if (target.skeleton && target.skeleton->age == ages[k])
                skeletonGap = skeletonDistance(arch, plant);
        }
        std::vector<double> out;
        for (const FitAge& a : target.ages)
            out.insert(out.end(), byAge[a.age].begin(), byAge[a.age].end());
        if (target.pointCloud) out.push_back(distance);
        if (target.skeleton) out.push_back(skeletonGap);
        return out;
    }

    // The symmetric mean distance between the measured nodes and the plant's.
    double skeletonDistance(const PlantArchitecture& arch, unsigned plant) const {
        std::vector<vec3> nodes;
        for (const SkeletonNode& n : plantSkeleton(arch, {plant}).nodes)
            nodes.push_back(n.position);
        if (nodes.empty()) return std::numeric_limits<double>::infinity();
        const CloudScene built(nodes);
        double toBuilt = 0.0, toMeasured = 0.0;
        for (const vec3& p : skeleton->points()) toBuilt += built.nearest(p);
        for (const vec3& p : nodes) toMeasured += skeleton->nearest(p);
        return 0.5 *
               (toBuilt / double(skeleton->points().size()) + toMeasured / double(nodes.size()));
    }

    double cloudDistance(const Context& ctx, std::uint64_t seed) const {
        std::vector<vec3> soup;
        ctx.forEachObject([&](const ObjectView& o) {
            if (o.hidden) return;
            for (std::uint32_t i : o.indices) soup.push_back(o.positions[i]);
        });
        if (soup.empty()) return std::numeric_limits<double>::infinity();
        const PointCloud surface =
            samplePoints(ctx, {.points = target.pointCloud->points, .seed = seed});
        return symmetricMeanDistance(*cloud, cloudPoints, soup, surface.positions);
    }

    // The simulated values averaged over the seeds (in parallel, summed in seed order).
    std::vector<double> meanOverSeeds(const std::vector<double>& values) const {
        const SpeciesModel model = apply(values);
        const long n = long(target.seeds.size());
        std::vector<std::vector<double>> perSeed = std::vector<std::vector<double>>(std::size_t(n));
        ParallelErrors errors;
        const int threads = options.threads > 0 ? options.threads : omp_get_max_threads();
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads)
        for (long i = 0; i < n; ++i)
            errors.run(i, [&] {
                perSeed[std::size_t(i)] = simulate(model, target.seeds[std::size_t(i)]);
            });
        errors.rethrow();
        std::vector<double> mean(perSeed[0].size(), 0.0);
        for (const std::vector<double>& s : perSeed)
            for (std::size_t k = 0; k < mean.size(); ++k) mean[k] += s[k];
        for (double& m : mean) m /= double(n);
        return mean;
    }

    // The objective of mean values, and the residuals when asked for.
    double objective(const std::vector<double>& mean, std::vector<FitResidual>* out) const {
        double sum = 0.0;
        std::size_t k = 0;
        for (const FitAge& a : target.ages) {
            for (const FitMeasurement& m : a.measurements) {
                for (std::size_t v = 0; v < m.values.size(); ++v, ++k) {
                    const double scale = m.sd ? *m.sd : std::fabs(m.values[v]);
                    const double r = std::sqrt(m.weight) * (mean[k] - m.values[v]) / scale;
                    sum += r * r;
                    if (!out) continue;
                    std::string name = fitStatisticName(m.statistic);
                    // (appended piece by piece: GCC 12 warns of "[" + std::to_string(...))
                    const auto index = [&name](std::size_t i) {
                        name.push_back('[');
                        name.append(std::to_string(i));
                        name.push_back(']');
                    };
                    if (m.statistic == FitStatistic::InternodeLength) index(m.rank);
                    if (m.values.size() > 1) index(v);
                    out->push_back({a.age, name, m.values[v], 0.0, mean[k], r});
                }
            }
        }
        if (target.pointCloud) {
            const double d = mean[k];
            const double r = std::sqrt(target.pointCloud->weight) * d / target.pointCloud->scale;
            sum += r * r;
            if (out)
                out->push_back({target.pointCloud->age, "point_cloud_distance", 0.0, 0.0, d, r});
        }
        if (target.skeleton) {
            const double d = mean[k + (target.pointCloud ? 1 : 0)];
            const double r = std::sqrt(target.skeleton->weight) * d / target.skeleton->scale;
            sum += r * r;
            if (out) out->push_back({target.skeleton->age, "skeleton_distance", 0.0, 0.0, d, r});
        }
        return sum;
    }
};

nlopt_algorithm algorithmOf(FitAlgorithm a) {
    switch (a) {
        case FitAlgorithm::Bobyqa:
            return NLOPT_LN_BOBYQA;
        case FitAlgorithm::Subplex:
            return NLOPT_LN_SBPLX;
        case FitAlgorithm::NelderMead:
            return NLOPT_LN_NELDERMEAD;
        case FitAlgorithm::Cobyla:
            return NLOPT_LN_COBYLA;
    }
    return NLOPT_LN_BOBYQA;
}

std::string stopText(nlopt_result r) {
    switch (r) {
        case NLOPT_SUCCESS:
            return "success";
        case NLOPT_STOPVAL_REACHED:
            return "objective reached its stop value";
        case NLOPT_FTOL_REACHED:
            return "objective tolerance reached";
        case NLOPT_XTOL_REACHED:
            return "parameter tolerance reached";
        case NLOPT_MAXEVAL_REACHED:
            return "max evaluations reached";
        case NLOPT_MAXTIME_REACHED:
            return "max time reached";
        case NLOPT_ROUNDOFF_LIMITED:
            return "roundoff limited";
        case NLOPT_FORCED_STOP:
            return "stopped";
        default:
            return std::string("NLopt: ") + nlopt_result_to_string(r);
    }
}

struct Search {
    const Problem& problem;
    std::vector<double> lower, upper;
    std::vector<FitEvaluation> evaluations;
    double best = std::numeric_limits<double>::infinity();
    std::exception_ptr error;

    std::vector<double> unscale(const double* x) const {
        std::vector<double> v(lower.size());
        for (std::size_t i = 0; i < v.size(); ++i)
            v[i] = lower[i] + std::clamp(x[i], 0.0, 1.0) * (upper[i] - lower[i]);
        return v;
    }
};

double searchObjective(unsigned n, const double* x, double*, void* data) {
    auto* s = static_cast<Search*>(data);
    (void)n;
    try {
        const std::vector<double> values = s->unscale(x);
        const double f = s->problem.objective(s->problem.meanOverSeeds(values), nullptr);
        FitEvaluation e{unsigned(s->evaluations.size() + 1), f, values};
        s->evaluations.push_back(e);
        if (f < s->best) {
            s->best = f;
            if (s->problem.options.onImprovement) s->problem.options.onImprovement(e);
        }
        // An infinite objective (a plant with no surface for the cloud) is the largest value
        // NLopt can compare.
        return std::isfinite(f) ? f : std::numeric_limits<double>::max();
    } catch (...) {
        s->error = std::current_exception();
        return std::numeric_limits<double>::max();
    }
}

}  // namespace

}  // namespace fit

double fitObjective(const SpeciesModel& species, const FitTarget& target,
                    const std::vector<double>& values, const FitOptions& options,
                    std::vector<FitResidual>* residuals) {
    checkFitTarget(species, target);
    if (values.size() != target.parameters.size())
        throw Error("one value per parameter",
                    {.parameter = "values",
                     .value = std::to_string(values.size()),
                     .validRange = std::to_string(target.parameters.size())});
    const fit::Problem problem(species, target, options);
    return problem.objective(problem.meanOverSeeds(values), residuals);
}

FitResult fitSpecies(const SpeciesModel& species, const FitTarget& target,
                     const FitOptions& options) {
    checkFitTarget(species, target);
    const fit::Problem problem(species, target, options);
    const std::size_t n = target.parameters.size();
    fit::Search search{problem, {}, {}, {}, std::numeric_limits<double>::infinity(), nullptr};
    FitResult result;
    result.algorithm = fitAlgorithmName(target.algorithm);
    std::vector<double> x(n);
    for (std::size_t i = 0; i < n; ++i) {
        const FitParameter& p = target.parameters[i];
        search.lower.push_back(p.lower);
        search.upper.push_back(p.upper);
        const double start = p.start.value_or(fit::speciesValue(species, p.path));
        result.start.push_back(start);
        result.paths.push_back(problem.paths[i]);
        x[i] = (start - p.lower) / (p.upper - p.lower);
    }
    nlopt_opt opt = nlopt_create(fit::algorithmOf(target.algorithm), unsigned(n));
    if (!opt) throw std::runtime_error("NLopt could not make its optimiser");
    struct Release {
        nlopt_opt o;
        ~Release() { nlopt_destroy(o); }
    } release{opt};
    nlopt_set_lower_bounds1(opt, 0.0);
    nlopt_set_upper_bounds1(opt, 1.0);
    // The callback stops the search through the optimiser it was given.
    struct WithOpt {
        fit::Search* search;
        nlopt_opt opt;
    } withOpt{&search, opt};
    nlopt_set_min_objective(
        opt,
        [](unsigned m, const double* xs, double* grad, void* data) -> double {
            auto* w = static_cast<WithOpt*>(data);
            if (w->search->error) return std::numeric_limits<double>::max();
            const double f = fit::searchObjective(m, xs, grad, w->search);
            if (w->search->error) nlopt_force_stop(w->opt);
            return f;
        },
        &withOpt);
    nlopt_set_maxeval(opt, int(target.maxEvaluations));
    nlopt_set_xtol_abs1(opt, target.tolerance);
    nlopt_set_initial_step1(opt, 0.1);
    double fmin = 0.0;
    const nlopt_result code = nlopt_optimize(opt, x.data(), &fmin);
    if (search.error) std::rethrow_exception(search.error);
    if (code < 0 && code != NLOPT_ROUNDOFF_LIMITED && search.evaluations.empty())
        throw std::runtime_error(std::string("NLopt failed: ") + nlopt_result_to_string(code));
    result.stopReason = fit::stopText(code);
    result.evaluations = std::move(search.evaluations);
    // The best evaluation (the first of equal ones), not NLopt's last point.
    const FitEvaluation* best = &result.evaluations.front();
    for (const FitEvaluation& e : result.evaluations)
        if (e.objective < best->objective) best = &e;
    result.best = best->values;
    result.bestObjective = best->objective;
    for (std::size_t i = 0; i < n; ++i)
        if (problem.whole[i]) result.best[i] = double(std::llround(result.best[i]));
    std::vector<FitResidual> atStart;
    result.startObjective = problem.objective(problem.meanOverSeeds(result.start), &atStart);
    problem.objective(problem.meanOverSeeds(result.best), &result.residuals);
    for (std::size_t k = 0; k < result.residuals.size() && k < atStart.size(); ++k)
        result.residuals[k].simulatedStart = atStart[k].simulated;
    result.fitted = problem.apply(result.best);
    return result;
}

std::string fitReportJson(const FitResult& r, const FitTarget& target) {
    using ojson = nlohmann::ordered_json;
    const auto num = [](double v) { return std::isfinite(v) ? ojson(v) : ojson(nullptr); };
    ojson j;
    j["plantarch_fit_report"] = 1;
    j["target"] = target.file;
    j["species"] = r.fitted.name;
    j["algorithm"] = r.algorithm;
    j["seeds"] = target.seeds;
    j["stop"] = r.stopReason;
    j["evaluations_used"] = r.evaluations.size();
    j["objective_start"] = num(r.startObjective);
    j["objective_fitted"] = num(r.bestObjective);
    ojson params = ojson::array();
    for (std::size_t i = 0; i < r.paths.size(); ++i)
        params.push_back({{"path", r.paths[i]},
                          {"lower", target.parameters[i].lower},
                          {"upper", target.parameters[i].upper},
                          {"start", r.start[i]},
                          {"fitted", r.best[i]}});
    j["parameters"] = params;
    ojson res = ojson::array();
    for (const FitResidual& x : r.residuals)
        res.push_back({{"age", x.age},
                       {"statistic", x.statistic},
                       {"measured", num(x.measured)},
                       {"simulated_start", num(x.simulatedStart)},
                       {"simulated_fitted", num(x.simulated)},
                       {"residual", num(x.residual)}});
    j["residuals"] = res;
    ojson ev = ojson::array();
    for (const FitEvaluation& e : r.evaluations) {
        ojson values = ojson::array();
        for (double v : e.values) values.push_back(v);
        ev.push_back(
            {{"evaluation", e.number}, {"objective", num(e.objective)}, {"values", values}});
    }
    j["evaluations"] = ev;
    return j.dump(1) + "\n";
}

}  // namespace plantarch
