// A render's camera as vision tools take it: the axes the renderer casts rays along, and the
// pinhole matrices and JSON of plantarch/Render.h's cameraMatrices and cameraJSON.

#include <fmt/format.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <numbers>

#include "plantarch/Error.h"
#include "plantarch/Render.h"
#include "render/render_internal.h"

namespace plantarch {

namespace render_detail {

CameraAxes cameraAxes(const CameraFrame& frame) {
    CameraAxes a;
    a.forward = glm::normalize(frame.target - frame.eye);
    a.worldUp = glm::length(frame.up) > 0.0f ? glm::normalize(frame.up) : vec3(0, 0, 1);
    if (glm::length(glm::cross(a.forward, a.worldUp)) < 1e-4f)
        a.worldUp = std::abs(a.forward.y) < 0.9f ? vec3(0, 1, 0) : vec3(1, 0, 0);
    return a;
}

}  // namespace render_detail

CameraMatrices cameraMatrices(const CameraFrame& frame, int width, int height) {
    if (width < 1 || height < 1)
        throw Error("a camera needs an image of at least one pixel",
                    {.parameter = "width x height",
                     .value = fmt::format("{} x {}", width, height),
                     .validRange = "1 or more each"});
    if (!(glm::length(frame.target - frame.eye) > 0.0f))
        throw Error("the camera's eye and target are the same point",
                    {.parameter = "eye", .validRange = "an eye apart from the target"});
    const render_detail::CameraAxes axes = render_detail::cameraAxes(frame);
    const vec3 right = glm::normalize(glm::cross(axes.forward, axes.worldUp));
    const vec3 up = glm::normalize(glm::cross(right, axes.forward));
    // A pixel (u, v) of the renderer looks along forward + sx right + sy up, with
    // sx = (2 (u + 0.5) / width - 1) tan(fov / 2) width / height and
    // sy = (1 - 2 (v + 0.5) / height) tan(fov / 2): a pinhole of focal length
    // height / (2 tan(fov / 2)) pixels, centred on the image, in OpenCV's convention
    // (x right, y down, z forward; pixel centres at whole coordinates).
    const double focal =
        double(height) / (2.0 * std::tan(double(frame.fovDeg) * std::numbers::pi / 360.0));
    CameraMatrices m;
    m.K = {{{focal, 0.0, (double(width) - 1.0) / 2.0},
            {0.0, focal, (double(height) - 1.0) / 2.0},
            {0.0, 0.0, 1.0}}};
    const vec3 rows[3] = {right, -up, axes.forward};
    for (int r = 0; r < 3; ++r) {
        for (int c = 0; c < 3; ++c) m.worldToCamera[r][c] = double(rows[r][c]);
        m.worldToCamera[r][3] =
            -(double(rows[r].x) * frame.eye.x + double(rows[r].y) * frame.eye.y +
              double(rows[r].z) * frame.eye.z);
    }
    m.worldToCamera[3] = {0.0, 0.0, 0.0, 1.0};
    return m;
}

std::string cameraJSON(const CameraFrame& frame, int width, int height) {
    const CameraMatrices m = cameraMatrices(frame, width, height);
    using json = nlohmann::json;
    auto v3 = [](const vec3& v) { return json::array({v.x, v.y, v.z}); };
    json doc = {
        {"convention",
         "OpenCV pinhole: x right, y down, z forward; pixel centres at whole "
         "coordinates; metres"},
        {"width", width},
        {"height", height},
        {"eye", v3(frame.eye)},
        {"target", v3(frame.target)},
        {"up", v3(frame.up)},
        {"fov_y_deg", frame.fovDeg},
        {"K", m.K},
        {"world_to_camera", m.worldToCamera},
    };
    return doc.dump(2) + "\n";
}

}  // namespace plantarch
