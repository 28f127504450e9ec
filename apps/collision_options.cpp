// Collision avoidance options shared by `build` and `canopy`: --soft-collision [--cone],
// --obstacle FILE.obj [--avoid-distance] [--fruit-adjustment], --attraction-points FILE.csv
// [--attraction-cone], --no-ground-clearance.

#include <cmath>
#include <sstream>

#include "cli.h"
#include "plantarch/Error.h"
#include "plantarch/Export.h"
#include "plantarch/PlantArchitecture.h"

namespace plantarch::cli {

namespace {

// "80,0.1,256,0.4": exactly `count` comma-separated numbers.
std::vector<double> numbers(const std::string& text, std::size_t count, const char* option,
                            const char* form) {
    const std::string expected =
        count == 1 ? "expected a number"
                   : "expected " + std::to_string(count) + " numbers separated by commas";
    std::vector<double> out;
    std::stringstream ss(text);
    for (std::string part; std::getline(ss, part, ',');) {
        std::size_t used = 0;
        double v = 0.0;
        try {
            v = std::stod(part, &used);
        } catch (const std::exception&) {
            used = 0;
        }
        while (used < part.size() && std::isspace(static_cast<unsigned char>(part[used]))) ++used;
        if (used == 0 || used != part.size() || !std::isfinite(v))
            throw Error(expected, {.parameter = option, .value = text, .validRange = form});
        out.push_back(v);
    }
    if (out.size() != count)
        throw Error(expected, {.parameter = option, .value = text, .validRange = form});
    return out;
}

}  // namespace

const char* const kNoGroundClearanceHelp =
    "Let leaves, flowers and fruit go below the plant's base (by default they are turned "
    "about their attachment to stay above it)";

void addCollisionOptions(CLI::App& app, CollisionArgs& a) {
    app.add_flag("--soft-collision", a.soft,
                 "Soft collision avoidance: shoots grow toward open space among leaves");
    app.add_option("--cone", a.cone,
                   "Soft avoidance perception cone: half-angle (deg), look-ahead (m), rays, "
                   "inertia (0-1); default 80,0.1,256,0.4");
    app.add_option("--obstacle", a.obstacles,
                   "Solid obstacle from an OBJ file, never grown into (repeatable); it is part "
                   "of the output scene");
    app.add_option("--avoid-distance", a.avoidDistance,
                   "Distance (m) at which shoots start turning away from obstacles; default 0.2");
    app.add_flag(
        "--fruit-adjustment", a.fruitAdjustment,
        "Turn fruit out of obstacles about their attachment (fruit resting on the ground)");
    app.add_option("--attraction-points", a.attractionPoints,
                   "CSV file of x,y,z points (m) that shoots grow toward (trellis wires)");
    app.add_option("--attraction-cone", a.attractionCone,
                   "Attraction perception cone: half-angle (deg), look-ahead (m), inertia "
                   "(0-1); default 80,0.1,0.4");
    app.add_flag("--no-ground-clearance", a.noGroundClearance, kNoGroundClearanceHelp);
}

void checkCollisionOptions(const CollisionArgs& a) {
    if (!a.cone.empty() && !a.soft)
        throw Error(
            "the soft avoidance cone applies only with soft avoidance",
            {.parameter = "--cone", .value = a.cone, .validRange = "with --soft-collision"});
    if (!a.cone.empty())
        numbers(a.cone, 4, "--cone", "half-angle,look-ahead,rays,inertia e.g. 80,0.1,256,0.4");
    if (!a.avoidDistance.empty())
        numbers(a.avoidDistance, 1, "--avoid-distance", "a distance in m, e.g. 0.2");
    if (!a.avoidDistance.empty() && a.obstacles.empty())
        throw Error("the avoidance distance applies only to obstacles",
                    {.parameter = "--avoid-distance",
                     .value = a.avoidDistance,
                     .validRange = "with --obstacle FILE.obj"});
    if (a.fruitAdjustment && a.obstacles.empty())
        throw Error("fruit adjustment applies only to obstacles",
                    {.parameter = "--fruit-adjustment", .validRange = "with --obstacle FILE.obj"});
    if (!a.attractionCone.empty() && a.attractionPoints.empty())
        throw Error("the attraction cone applies only with attraction points",
                    {.parameter = "--attraction-cone",
                     .value = a.attractionCone,
                     .validRange = "with --attraction-points FILE.csv"});
    if (!a.attractionCone.empty())
        numbers(a.attractionCone, 3, "--attraction-cone",
                "half-angle,look-ahead,inertia e.g. 80,0.1,0.4");
    for (const std::string& f : a.obstacles) requireInputFile(f, "obstacle file", "--obstacle");
    if (!a.attractionPoints.empty())
        requireInputFile(a.attractionPoints, "attraction point file", "--attraction-points");
}

void applyCollisionOptions(const CollisionArgs& a, PlantArchitecture& arch, Context& ctx) {
    checkCollisionOptions(a);
    if (a.noGroundClearance) arch.setGroundClearance(false);
    // Range errors of the library name its parameters; say which option set them.
    auto prefixed = [](const Error& e, const std::string& option) {
        return Error(e.message(), {.file = e.file(),
                                   .line = e.line(),
                                   .parameter = option + " (" + e.parameter() + ")",
                                   .value = e.value(),
                                   .validRange = e.validRange()});
    };
    std::vector<ObjectID> obstacles;
    for (const std::string& f : a.obstacles) {
        const std::vector<ObjectID> ids = readObstacleMesh(ctx, f);
        obstacles.insert(obstacles.end(), ids.begin(), ids.end());
    }
    if (!obstacles.empty()) {
        SolidObstacleOptions o;
        o.obstacles = obstacles;
        if (!a.avoidDistance.empty())
            o.avoidanceDistance = float(numbers(a.avoidDistance, 1, "--avoid-distance", "")[0]);
        o.fruitAdjustment = a.fruitAdjustment;
        try {
            arch.enableSolidObstacleAvoidance(o);
        } catch (const Error& e) {
            throw prefixed(e, "--avoid-distance");
        }
    }
    if (a.soft) {
        SoftCollisionOptions o;
        if (!a.cone.empty()) {
            const auto v = numbers(a.cone, 4, "--cone", "");
            if (!(v[2] >= 8 && v[2] <= 16384 && v[2] == std::floor(v[2])))
                throw Error("ray count out of range",
                            {.parameter = "--cone (ray_count)",
                             .value = a.cone,
                             .validRange = "a whole number from 8 to 16384"});
            o.cone = PerceptionCone{float(v[0]), float(v[1]), unsigned(v[2]), float(v[3])};
        }
        try {
            arch.enableSoftCollisionAvoidance(o);
        } catch (const Error& e) {
            throw prefixed(e, "--cone");
        }
    }
    if (!a.attractionPoints.empty()) {
        AttractionPoints p;
        p.points = readAttractionPointsCSV(a.attractionPoints, "--attraction-points");
        if (!a.attractionCone.empty()) {
            const auto v = numbers(a.attractionCone, 3, "--attraction-cone", "");
            p.halfAngle = float(v[0]);
            p.lookAhead = float(v[1]);
            p.inertia = float(v[2]);
        }
        try {
            arch.enableAttractionPoints(p);
        } catch (const Error& e) {
            throw prefixed(e, "--attraction-cone");
        }
    }
}

}  // namespace plantarch::cli
