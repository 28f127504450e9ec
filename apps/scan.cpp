// plantarch scan INPUT --scanner x,y,z [--scanner ...] [--resolution DEG] [--zenith A:B]
//                 [--azimuth A:B] [--noise M] [--max-range M] -o scan.ply|scan.npz
// A simulated terrestrial LiDAR scan of plants (a plant structure file or plant strings) or of
// any OBJ scene: the first hit of every ray, labelled, with its range and scanner.

#include "plantarch/Scan.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>

#include "cli.h"
#include "plantarch/Error.h"
#include "plantarch/Export.h"
#include "plantarch/PlantArchitecture.h"

namespace plantarch::cli {

namespace {

struct ScanArgs {
    std::string input, species;
    std::vector<std::string> scanners, outputs;
    float resolution = 0.1f;
    std::string zenith = "30:150", azimuth = "0:360";
    float noise = 0.0f, maxRange = 100.0f;
};

// "A:B", two finite numbers.
std::pair<float, float> parseSpan(const std::string& text, const char* option) {
    const auto [a, b] =
        parseTwoNumbers(text, ':', option, "two angles in degrees joined by ':'", "e.g. 30:150");
    return {float(a), float(b)};
}

int run(const ScanArgs& a, const GlobalOptions& g) {
    ScanOptions o;
    const auto [zenithMin, zenithMax] = parseSpan(a.zenith, "--zenith");
    const auto [azimuthMin, azimuthMax] = parseSpan(a.azimuth, "--azimuth");
    for (const std::string& text : a.scanners) {
        Scanner s;
        s.origin = parseVec3(text, "--scanner");
        s.resolution = a.resolution;
        s.zenithMin = zenithMin;
        s.zenithMax = zenithMax;
        s.azimuthMin = azimuthMin;
        s.azimuthMax = azimuthMax;
        o.scanners.push_back(s);
    }
    o.rangeNoise = a.noise;
    o.maxRange = a.maxRange;
    o.seed = g.seed;
    o.progress = terminalProgress();
    for (const std::string& out : a.outputs)
        requireOutputFormat(out, kScanOutput, "a scan is written as a point cloud");
    checkScanOptions(o);  // before the input is read
    CommandOutputs outputs(a.outputs);

    Context ctx;
    std::unique_ptr<PlantArchitecture> arch;  // holds the plants while they are scanned
    if (lowerExtension(a.input) == ".obj") {
        readOBJ(ctx, a.input, {.progress = terminalProgress()});
    } else {
        arch = std::make_unique<PlantArchitecture>(&ctx);
        arch->setSeed(g.seed);
        arch->setMeshDetail(g.meshDetail);
        readPlantInput(*arch, a.input, a.species);
    }
    const PointCloud points = scan(ctx, o);
    for (const std::string& out : a.outputs) {
        if (lowerExtension(out) == ".npz")
            writePointCloudNPZ(points, out, terminalProgress());
        else
            writePointCloudPLY(points, out, terminalProgress());
    }
    outputs.commit();
    std::printf("%s", fmt::format("{} points from {} scanner(s) of {} rays each, {} triangles in "
                                  "the scene; written to {}.\n",
                                  points.positions.size(), o.scanners.size(),
                                  scanRayCount(o.scanners.front()), ctx.triangleCount(),
                                  fmt::join(a.outputs, ", "))
                          .c_str());
    return 0;
}

std::function<int()> setupScan(CLI::App& app, GlobalOptions& global) {
    app.description(
        "Simulate a terrestrial LiDAR scan: first hits of rays from each scanner, labelled");
    auto a = std::make_shared<ScanArgs>();
    app.add_option("input", a->input,
                   "Plants (.xml plant structure file, .txt plant strings) or any .obj scene")
        ->required();
    app.add_option("--scanner", a->scanners, "Scanner position x,y,z in metres (repeatable)")
        ->required();
    app.add_option("--resolution", a->resolution,
                   "Degrees between neighbouring rays, both ways (default 0.1)")
        ->check(numberCheck("--resolution", "an angle", 0.001, 10.0, false, "0.001 to 10 degrees"));
    app.add_option("--zenith", a->zenith,
                   "Zenith angles swept, MIN:MAX degrees from straight up (default 30:150)");
    app.add_option("--azimuth", a->azimuth,
                   "Azimuths swept, MIN:MAX degrees from +x toward +y (default 0:360)");
    app.add_option("--noise", a->noise, "Gaussian range noise, standard deviation in m (default 0)")
        ->check(numberCheck("--noise", "a distance", 0.0, 1.0, false, "0 to 1 m"));
    app.add_option("--max-range", a->maxRange, "Farthest hit returned, m (default 100)")
        ->check(numberCheck("--max-range", "a distance", 1e-6, 10000.0, false,
                            "more than 0, up to 10000 m"));
    app.add_option("-o,--output", a->outputs,
                   "Point cloud file(s): .ply (binary, per point labels, range, scanner) or .npz")
        ->required();
    app.add_option("--species", a->species,
                   "Species giving the shoot types of plant strings (.txt input)");
    return [a, &global] { return run(*a, global); };
}

}  // namespace

PLANTARCH_REGISTER_COMMAND(scan, "scan", 52, setupScan);

}  // namespace plantarch::cli
