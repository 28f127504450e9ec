// The plants of a PlantArchitecture as exporters describe them (plantarch/ExportPlants.h).

#include <cmath>
#include <string>

#include "core/progress_steps.h"
#include "core/value_text.h"
#include "plant_io/plant_structure.h"
#include "plantarch/Error.h"
#include "plantarch/ExportPlants.h"
#include "plantarch/OutputFormats.h"
#include "scene_io/export_common.h"

namespace plantarch {

std::vector<GltfPlant> exportPlants(const PlantArchitecture& arch) {
    std::vector<GltfPlant> plants;
    for (unsigned id : arch.getAllPlantIDs())
        plants.push_back({std::int32_t(id), arch.plant(id).name, arch.getPlantBasePosition(id),
                          arch.plant(id).age, arch.seed()});
    return plants;
}

void writeQSM(const PlantArchitecture& arch, const std::vector<unsigned>& plants,
              const std::string& path) {
    std::vector<const PlantInstance*> states;
    for (unsigned id : plants) states.push_back(&arch.plant(id));
    plant_io::writeQSM(states, path);
}

std::vector<double> growthFrameDays(const GrowthFrames& f, const std::string& parameter) {
    const auto bad = [&](const std::string& what, double value, const std::string& range) {
        return Error(
            what,
            {.parameter = parameter, .value = text::formatDouble(value), .validRange = range});
    };
    if (!std::isfinite(f.start) || f.start < 0.0 || f.start > 100000.0)
        throw bad("first frame out of range", f.start, "0 to 100000 days");
    if (!std::isfinite(f.end) || f.end < f.start || f.end > 100000.0)
        throw bad("last frame out of range", f.end,
                  text::formatDouble(f.start) + " to 100000 days");
    if (!std::isfinite(f.step) || !(f.step > 0.0))
        throw bad("frame step must be positive", f.step, "more than 0 days");
    const double count = std::floor((f.end - f.start) / f.step + 1e-6) + 1.0;
    if (count > double(kMaxAnimationFrames))
        throw bad("too many frames (" + text::formatDouble(count) + ")", f.step,
                  "a step giving at most " + std::to_string(kMaxAnimationFrames) + " frames");
    std::vector<double> days;
    for (std::size_t i = 0; i < std::size_t(count); ++i)
        days.push_back(std::min(f.end, f.start + double(i) * f.step));
    return days;
}

namespace {

// Every path an animation is written as, and the frame rate, checked before any work.
void checkAnimationPaths(const std::vector<std::string>& paths, const AnimationOptions& animation) {
    for (const std::string& path : paths)
        requireOutputFormat(path, {".glb", ".gltf", ".usda"},
                            "an animation is written as .glb, .gltf or .usda");
    io::checkFrameRate(animation, paths.empty() ? std::string() : paths.front());
}

}  // namespace

void GrowthRecorder::record(const PlantArchitecture& arch, double day) {
    if (!std::isfinite(day) || (!frames_.empty() && !(day > frames_.back().day)))
        throw Error(
            "a frame's day must be finite and after the last frame's",
            {.parameter = "day",
             .value = text::formatDouble(day),
             .validRange = frames_.empty() ? "a finite number of days"
                                           : "> " + text::formatDouble(frames_.back().day)});
    if (frames_.size() >= kMaxAnimationFrames)
        throw Error("too many animation frames",
                    {.parameter = "frames",
                     .value = std::to_string(frames_.size() + 1),
                     .validRange = "at most " + std::to_string(kMaxAnimationFrames)});
    scenes_.push_back(arch.context());
    try {
        frames_.push_back({&scenes_.back(), day, exportPlants(arch)});
    } catch (...) {
        scenes_.pop_back();
        throw;
    }
}

std::vector<double> GrowthRecorder::days() const {
    std::vector<double> out;
    for (const AnimationFrame& f : frames_) out.push_back(f.day);
    return out;
}

void GrowthRecorder::clear() {
    frames_.clear();
    scenes_.clear();
}

void GrowthRecorder::write(const std::vector<std::string>& paths,
                           const AnimationOptions& animation) const {
    checkAnimationPaths(paths, animation);
    for (const std::string& path : paths) {
        if (lowerExtension(path) == ".usda") {
            UsdOptions o;
            o.progress = animation.progress;
            o.appearance = animation.appearance;
            writeUSDA(frames_, path, o, animation);
        } else {
            GltfOptions o;
            o.progress = animation.progress;
            o.appearance = animation.appearance;
            writeGLTF(frames_, path, o, animation);
        }
    }
}

void writeGrowthAnimation(PlantArchitecture& arch, const std::vector<unsigned>& plants,
                          const GrowthFrames& frames, const std::vector<std::string>& paths,
                          const AnimationOptions& animation) {
    const std::vector<double> days = growthFrameDays(frames);
    checkAnimationPaths(paths, animation);  // before the growth, so a bad path costs nothing
    GrowthRecorder recorder;
    double grown = 0.0;
    ProgressSteps steps(animation.progress, "growing", double(days.size()));
    for (double day : days) {
        if (day > grown) arch.advanceTime(plants, day - grown);
        grown = day;
        recorder.record(arch, day);
        steps.at(double(recorder.frameCount()));
    }
    steps.finish();
    recorder.write(paths, animation);
}

}  // namespace plantarch
