#pragma once
// A point cloud of a real plant as the fit compares built plants with it (fit_cloud.cpp).

#include <embree3/rtcore.h>

#include <string>
#include <vector>

#include "plantarch/Mesh.h"

namespace plantarch::fit {

/// The points of a .ply, .xyz, .txt or .pts file (Calibration.h: readPointCloudFile).
std::vector<vec3> readCloudPoints(const std::string& path);

/// A cloud's points in an Embree scene, for nearest-point queries (thread-safe).
class CloudScene {
public:
    explicit CloudScene(std::vector<vec3> points);
    ~CloudScene();
    CloudScene(const CloudScene&) = delete;
    CloudScene& operator=(const CloudScene&) = delete;
    /// Distance from `p` to the nearest point of the cloud (m).
    float nearest(const vec3& p) const;
    const std::vector<vec3>& points() const { return points_; }

private:
    std::vector<vec3> points_;
    RTCScene scene_ = nullptr;
};

/// The symmetric mean distance (m): the mean distance from each of `cloudSample` to the
/// nearest point of the triangles of `soup` (three corners each), and from each of `surface`
/// (points drawn on those triangles) to the nearest point of `cloud`, averaged. Infinite when
/// the plant has no surface.
double symmetricMeanDistance(const CloudScene& cloud, const std::vector<vec3>& cloudSample,
                             const std::vector<vec3>& soup, const std::vector<vec3>& surface);

}  // namespace plantarch::fit
