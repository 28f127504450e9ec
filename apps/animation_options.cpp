// --frames and --frame-rate: the commands that grow plants (build, canopy, grow) write a growth
// animation instead of still files when given frames.

#include <cmath>
#include <filesystem>

#include "cli.h"
#include "plantarch/Error.h"
#include "plantarch/ExportPlants.h"

namespace plantarch::cli {

void addAnimationOptions(CLI::App& app, AnimationArgs& args, const std::string& counted) {
    app.add_option("--frames", args.frames,
                   "Write a growth animation: a frame every STEP days from START to END " +
                       counted +
                       ", e.g. 0:60:1 (STEP 1 when left out); outputs .glb, .gltf, .usda");
    app.add_option("--frame-rate", args.rate, "Frames a second of the animation (default 24)")
        ->check(numberCheck("--frame-rate", "a frame rate", 0.001, 1000.0, false, "0.001 to 1000"));
}

std::optional<GrowthFrames> parseFrames(const AnimationArgs& args) {
    if (args.frames.empty()) return std::nullopt;
    const auto bad = [&]() {
        return Error("expected START:END or START:END:STEP, in days",
                     {.parameter = "--frames", .value = args.frames, .validRange = "e.g. 0:60:1"});
    };
    std::vector<double> parts;
    std::size_t at = 0;
    while (true) {
        const std::size_t colon = args.frames.find(':', at);
        const std::string part =
            args.frames.substr(at, colon == std::string::npos ? colon : colon - at);
        std::size_t used = 0;
        double value = 0.0;
        try {
            value = std::stod(part, &used);
        } catch (const std::exception&) {
            throw bad();
        }
        if (used != part.size() || part.empty() || !std::isfinite(value)) throw bad();
        parts.push_back(value);
        if (colon == std::string::npos) break;
        at = colon + 1;
    }
    if (parts.size() != 2 && parts.size() != 3) throw bad();
    GrowthFrames frames{parts[0], parts[1], parts.size() == 3 ? parts[2] : 1.0};
    growthFrameDays(frames, "--frames");  // throws for a bad range
    return frames;
}

std::optional<GrowthFrames> prepareGrowthOutputs(const std::vector<std::string>& outputs,
                                                 bool stats, float age,
                                                 const AnimationArgs& animation,
                                                 std::size_t points) {
    if (outputs.empty() && !stats)
        throw Error("--output is required (or --stats for the statistics alone)");
    const std::optional<GrowthFrames> frames = parseFrames(animation);
    requireAgeOrFrames(age, frames.has_value());
    if (frames && outputs.empty())
        throw Error("--frames writes an animation: give -o FILE (" +
                    outputExtensions(kAnimationOutput) + ")");
    if (frames)
        checkAnimationOutputs(outputs);
    else
        checkSceneOutputs(outputs, points, true);
    return frames;
}

void requireAgeOrFrames(float age, bool frames) {
    if (frames && age >= 0.0f)
        throw Error("--age and --frames both given: --frames gives the ages of the frames");
    if (!frames && age < 0.0f)
        throw Error("--age is required (or --frames for a growth animation)");
}

void checkAnimationOutputs(const std::vector<std::string>& paths) {
    for (const std::string& out : paths)
        requireOutputFormat(out, kAnimationOutput, "--frames writes an animation");
}

}  // namespace plantarch::cli
