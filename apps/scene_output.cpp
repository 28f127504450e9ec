// Writing a scene in the format its file extension names; shared by every subcommand that
// produces geometry.

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>

#include "cli.h"
#include "plantarch/Error.h"
#include "plantarch/Export.h"
#include "plantarch/Render.h"

namespace plantarch::cli {

PlantFileOptions plantFileOptions(const GlobalOptions& g, bool showProgress) {
    PlantFileOptions o;
    o.objectIDs = g.objectIDs;
    o.stringDigits = g.stringDigits;
    o.points = g.points;
    o.seed = g.seed;
    o.plyColor = g.plyColor;
    o.plyFormat = g.plyFormat;
    o.imageWidth = g.imageWidth;
    o.imageHeight = g.imageHeight;
    o.camera = g.pictureCamera;
    o.cameraTarget = g.pictureTarget;
    o.mode = g.pictureMode;
    o.cameraJson = g.cameraJson;
    o.skin = g.skin;
    o.wind = g.wind;
    o.levels = g.levels;
    o.meshoptCompression = g.meshopt;
    o.appearance = g.appearance;
    o.nodes = g.nodes;
    o.instancing = g.instancing;
    if (showProgress) o.progress = terminalProgress();
    o.onWritten = [&g](const std::string& path) { info(g, "wrote " + path); };
    return o;
}

void checkSceneOutputs(const std::vector<std::string>& paths, std::size_t points, bool plants) {
    const bool sampled = std::any_of(paths.begin(), paths.end(), [](const std::string& p) {
        const std::string ext = lowerExtension(p);
        return ext == ".ply" || ext == ".npz";
    });
    if (sampled && points > maxSamplePoints())
        throw Error(fmt::format("{} points need about {:.1f} GB, more than half of this "
                                "machine's memory",
                                points, double(points) * double(kBytesPerSamplePoint) / 1e9),
                    {.parameter = "--points",
                     .value = std::to_string(points),
                     .validRange = fmt::format("0 to {} on this machine", maxSamplePoints())});
    for (const std::string& out : paths) {
        requireOutputFormat(out, kSceneOutput | (plants ? kPlantOutput : 0u),
                            "unknown output format");
        if (lowerExtension(out) == ".npz" && points == 0)
            throw Error("an .npz output is a point cloud: give --points N",
                        {.file = out, .parameter = "--points", .validRange = "1 to 2147483648"});
    }
}

std::pair<double, double> parseTwoNumbers(const std::string& text, char separator,
                                          const char* option, const std::string& expected,
                                          const std::string& example) {
    const auto at = text.find(separator);
    try {
        if (at != std::string::npos) {
            std::size_t a = 0, b = 0;
            const double first = std::stod(text.substr(0, at), &a);
            const double second = std::stod(text.substr(at + 1), &b);
            if (a == at && b == text.size() - at - 1 && std::isfinite(first) &&
                std::isfinite(second))
                return {first, second};
        }
    } catch (const std::exception&) {
    }
    throw Error("expected " + expected,
                {.parameter = option, .value = text, .validRange = example});
}

template <class T>
std::pair<T, T> parsePair(const std::string& text, const char* option) {
    const std::string expected = "two positive numbers joined by 'x'";
    const std::string example = "e.g. 10x10 or 0.3x0.3";
    const auto [first, second] = parseTwoNumbers(text, 'x', option, expected, example);
    if (!(first > 0 && second > 0))
        throw Error("expected " + expected,
                    {.parameter = option, .value = text, .validRange = example});
    return {T(first), T(second)};
}
template std::pair<int, int> parsePair<int>(const std::string&, const char*);
template std::pair<float, float> parsePair<float>(const std::string&, const char*);

vec3 parseVec3(const std::string& text, const char* option) {
    vec3 v(0.0f);
    const char* p = text.data();
    const char* end = text.data() + text.size();
    for (int i = 0; i < 3; ++i) {
        while (p < end && *p == ' ') ++p;
        const auto [next, ec] = std::from_chars(p, end, v[i]);
        if (ec != std::errc() || !std::isfinite(v[i]))
            throw Error("not a vector",
                        {.parameter = option, .value = text, .validRange = "three numbers x,y,z"});
        p = next;
        while (p < end && *p == ' ') ++p;
        if (i < 2) {
            if (p == end || *p != ',')
                throw Error(
                    "not a vector",
                    {.parameter = option, .value = text, .validRange = "three numbers x,y,z"});
            ++p;
        }
    }
    if (p != end)
        throw Error("not a vector",
                    {.parameter = option, .value = text, .validRange = "three numbers x,y,z"});
    return v;
}

void parseOrbit(const std::string& text, Camera& camera) {
    const auto fail = [&] {
        return Error("not a view direction",
                     {.parameter = "--orbit",
                      .value = text,
                      .validRange = "AZIMUTH,ELEVATION in degrees: azimuth from +x toward +y, "
                                    "elevation -89 to 89"});
    };
    float v[2] = {0.0f, 0.0f};
    const char* p = text.data();
    const char* end = text.data() + text.size();
    for (int i = 0; i < 2; ++i) {
        while (p < end && *p == ' ') ++p;
        const auto [next, ec] = std::from_chars(p, end, v[i]);
        if (ec != std::errc() || !std::isfinite(v[i])) throw fail();
        p = next;
        while (p < end && *p == ' ') ++p;
        if (i == 0 && (p == end || *p++ != ',')) throw fail();
    }
    if (p != end || !(v[1] >= -89.0f && v[1] <= 89.0f)) throw fail();
    camera.azimuthDeg = v[0];
    camera.elevationDeg = v[1];
}

RenderMode labelMode(const std::string& name, const std::string& more) {
    // The values of --label and the masks they select.
    constexpr std::pair<const char*, RenderMode> kLabelModes[] = {
        {"organ", RenderMode::LabelOrgan}, {"object", RenderMode::LabelObject}};
    std::string valid;
    for (const auto& [label, mode] : kLabelModes) {
        if (name == label) return mode;
        valid += (valid.empty() ? "" : ", ") + std::string(label);
    }
    if (!more.empty()) valid += ", " + more;
    throw Error("unknown label mode", {.parameter = "--label", .value = name, .validRange = valid});
}

void addImageSizeOption(CLI::App& app, GlobalOptions& global) {
    app.add_option_function<std::string>(
        "--image-size",
        [&global](const std::string& text) {
            int w = 0, h = 0;
            char x = 0, extra = 0;
            if (std::sscanf(text.c_str(), "%d%c%d%c", &w, &x, &h, &extra) != 3 || x != 'x' ||
                w < 16 || h < 16 || w > 16384 || h > 16384)
                throw Error("image size is WIDTHxHEIGHT in pixels",
                            {.parameter = "--image-size",
                             .value = text,
                             .validRange = "16x16 to 16384x16384"});
            global.imageWidth = w;
            global.imageHeight = h;
        },
        "PNG output size, WIDTHxHEIGHT (default 1024x768)");
    app.add_option_function<std::string>(
        "--eye",
        [&global](const std::string& text) {
            global.pictureCamera.autoFrame = false;
            global.pictureCamera.eye = parseVec3(text, "--eye");
        },
        "Camera position x,y,z of PNG outputs in metres (default: framed on the scene); one "
        "framing for every age");
    app.add_option_function<std::string>(
           "--orbit",
           [&global](const std::string& text) { parseOrbit(text, global.pictureCamera); },
           "PNG outputs seen from AZIMUTH,ELEVATION degrees (default -60,22), framed on the "
           "scene")
        ->excludes("--eye");
    app.add_option_function<std::string>(
           "--target",
           [&global](const std::string& text) {
               global.pictureCamera.target = parseVec3(text, "--target");
               global.pictureTarget = true;
           },
           "Point the PNG camera looks at, x,y,z (default: the scene's centre; needs --eye)")
        ->needs("--eye");
    app.add_option_function<float>(
           "--fov", [&global](float fov) { global.pictureCamera.fovDeg = fov; },
           "Vertical field of view of PNG outputs in degrees (default 35)")
        ->check(numberCheck("--fov", "a field of view", 0.01, 170.0, false, "0.01 to 170 degrees"));
    app.add_option_function<std::string>(
        "--label", [&global](const std::string& text) { global.pictureMode = labelMode(text); },
        "PNG outputs as label masks: organ (a colour per organ kind) or object (a colour per "
        "object)");
    app.add_flag("--camera-json", global.cameraJson,
                 "Beside each PNG output, NAME.camera.json: eye, target, up, field of view, "
                 "intrinsics K and extrinsics world_to_camera (OpenCV's pinhole convention)");
}

}  // namespace plantarch::cli
