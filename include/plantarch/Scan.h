#pragma once
// Simulated terrestrial LiDAR scans: rays cast from scanner positions on a grid of zenith and
// azimuth angles, the first hit of each kept with its labels, range and scanner, so occlusion
// looks as it does in a real scan. Deterministic: the same scene and options give the same
// points, in the same order, whatever the thread count.

#include <cstdint>
#include <vector>

#include "plantarch/Context.h"
#include "plantarch/Export.h"
#include "plantarch/Progress.h"

namespace plantarch {

/// One scanner position and the angles its rays sweep, in degrees.
struct Scanner {
    vec3 origin{0.0f, 0.0f, 1.5f};  ///< m
    /// Zenith angles of the rays, from straight up (0) to straight down (180), inclusive.
    float zenithMin = 30.0f, zenithMax = 150.0f;
    /// Azimuths from +x toward +y; a full turn (360) casts the start angle once.
    float azimuthMin = 0.0f, azimuthMax = 360.0f;
    /// Angle between neighbouring rays, both ways (0.001 to 10).
    float resolution = 0.1f;
};

struct ScanOptions {
    std::vector<Scanner> scanners;
    /// Standard deviation of Gaussian noise added to each range, m (0 to 1; 0: exact).
    float rangeNoise = 0.0f;
    /// Hits farther than this from the scanner are not returned, m (more than 0, up to 10000).
    float maxRange = 100.0f;
    std::uint64_t seed = 0;  ///< picks the noise
    /// Told how far the scan is ("scanning", 0..1); may be empty.
    ProgressCallback progress;
};

/// Throws what scan() throws for these options (no scanner, an angle, resolution, noise or
/// range out of range, too many rays), without casting a ray.
void checkScanOptions(const ScanOptions& options);

/// How many rays a scanner casts (rows of zenith angles times columns of azimuths).
std::uint64_t scanRayCount(const Scanner& scanner);

/// Casts every scanner's rays into the visible (not hidden) objects of `context` and returns the
/// first hits, scanner by scanner, row by row (zenith), column by column (azimuth): position (with
/// the range noise applied along the ray), the hit triangle's normal turned toward the
/// scanner, plant, object and organ labels, range and scanner index. Throws plantarch::Error
/// naming the option for no scanner (or more than 65535), an angle, resolution, noise or range out
/// of range, or more than 2^31 rays in all.
PointCloud scan(const Context& context, const ScanOptions& options);

}  // namespace plantarch
