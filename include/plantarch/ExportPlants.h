#pragma once
// Exports that need the plants, not only their geometry: the plants as the glTF and USD
// writers describe them, and the internodes as QSM cylinders.

#include <deque>
#include <string>
#include <vector>

#include "plantarch/Export.h"
#include "plantarch/PlantArchitecture.h"

namespace plantarch {

/// Every plant of `arch`: its ID, species, base, age, and the scene's seed.
std::vector<GltfPlant> exportPlants(const PlantArchitecture& arch);

/// The skeletons of every plant of `arch` for a skinned (wind-ready) glTF or USD file
/// (GltfOptions::skeletons): a root joint at the plant's base and one joint per internode at
/// its base (its node below), parented along the shoots, a branch's first joint on the joint
/// of the parent's internode that carries it. Internode tubes blend between the joints of
/// the internodes they join on their shoot (half and half at a node, all on their own joint
/// midway and at the shoot's two ends); every other organ of a shoot is rigid on the joint of
/// its node's internode, objects of no shoot on the root.
/// The bind pose is the geometry as it stands (bent, where the plant bends under load).
/// Throws plantarch::Error for a plant of more than 65535 internodes.
std::vector<GltfSkeleton> exportSkeletons(const PlantArchitecture& arch);

/// Writes the plants' internodes as cylinders, the table a quantitative structure model
/// (QSM, as TreeQSM makes from scans of trees) holds, as CSV with a header: one row per
/// internode with its id, parent cylinder, plant, start point, unit axis, length, radius,
/// branch (shoot ID), branch order (shoot rank), position in the branch and shoot type.
/// Written atomically; throws plantarch::Error naming the file.
void writeQSM(const PlantArchitecture& arch, const std::vector<unsigned>& plants,
              const std::string& path);

/// The frames of a growth animation: one every `step` days of growth from `start` to `end`
/// (inclusive, within a millionth of a step), counted from the plants' state when recording
/// starts. At most kMaxAnimationFrames frames.
struct GrowthFrames {
    double start = 0.0;
    double end = 0.0;
    double step = 1.0;
};
inline constexpr std::size_t kMaxAnimationFrames = 10000;

/// The frame days of `frames` (start, start + step, ...); throws plantarch::Error naming
/// `parameter` for a negative or non-finite start, an end before the start, a step that is
/// not positive, or more than kMaxAnimationFrames frames.
std::vector<double> growthFrameDays(const GrowthFrames& frames,
                                    const std::string& parameter = "frames");

/// Frames of a scene recorded between steps of the caller's own (growth, pruning, harvest,
/// moving plants), written as one animation. Each frame is a copy of the Context as it stood
/// (every object), so memory grows by one scene per frame.
class GrowthRecorder {
public:
    /// Records the scene of `arch` as the next frame, at `day` (days, finite, after the last
    /// frame's). Throws plantarch::Error for another day or past kMaxAnimationFrames frames.
    void record(const PlantArchitecture& arch, double day);
    std::size_t frameCount() const { return frames_.size(); }
    /// The frames' days, in order.
    std::vector<double> days() const;
    void clear();
    /// Writes the frames into each of `paths` (.glb, .gltf or .usda) as one animation showing
    /// frame i alone at i / framesPerSecond seconds; every path is checked before any is
    /// written, each is written atomically. Throws plantarch::Error naming the file.
    void write(const std::vector<std::string>& paths, const AnimationOptions& animation = {}) const;

private:
    std::deque<Context> scenes_;  // a deque: the frames point at its elements
    std::vector<AnimationFrame> frames_;
};

/// Grows `plants` of `arch` from frame to frame and writes the scene as it stands at each
/// frame (every object of the Context) into each of `paths` as one animation: .glb or .gltf
/// (writeGLTF of frames) or .usda (writeUSDA of frames); a frame's day is its days of growth.
/// Every path is checked before any growth; each file is written atomically. The plants are
/// left grown to the last frame. Throws plantarch::Error naming the file or parameter.
void writeGrowthAnimation(PlantArchitecture& arch, const std::vector<unsigned>& plants,
                          const GrowthFrames& frames, const std::vector<std::string>& paths,
                          const AnimationOptions& animation = {});

}  // namespace plantarch
