// plantarch compare SPECIES --age D [--reference FILE.png | --against SCENE] -o FILE.png
// Draws a plant in a fixed, comparable framing: a side view looking along +y and an oblique
// view from 35 degrees above, turned 45 degrees about z, both nearly orthographic and at the
// same scale, framed on the plant's bounding box, with a 10 cm scale bar in each panel, the
// ground line (side) and the ground footprint (oblique). With --reference, a picture made in
// the same framing (another system's plant, a photograph) is put above it for comparison;
// with --against, a scene file (another system's plant as OBJ, PLY or glTF, a scanned plant)
// is drawn above it in the same framing and at the same scale.

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <optional>

#include "cli.h"
#include "plantarch/Error.h"
#include "plantarch/Export.h"
#include "plantarch/PlantArchitecture.h"
#include "plantarch/Render.h"

namespace plantarch::cli {

namespace {

struct CompareArgs {
    bool noTrellis = false;
    std::string species;
    float age = -1.0f;
    std::vector<std::string> defines;
    std::string reference;
    std::string against;
    std::string output;
    int panelSize = 600;
};

constexpr float kPi = 3.14159265358979f;

// A view direction: the camera's forward, right and up unit vectors.
struct View {
    vec3 forward, right, up;
};

View sideView() {
    return {{0, 1, 0}, {1, 0, 0}, {0, 0, 1}};
}

View obliqueView() {
    const float el = 35.0f * kPi / 180.0f, az = 45.0f * kPi / 180.0f;
    const vec3 forward = glm::normalize(
        vec3(std::cos(el) * std::cos(az), std::cos(el) * std::sin(az), -std::sin(el)));
    const vec3 right = glm::normalize(glm::cross(forward, vec3(0, 0, 1)));
    return {forward, right, glm::cross(right, forward)};
}

// The corners of a box.
std::array<vec3, 8> corners(const vec3& lo, const vec3& hi) {
    std::array<vec3, 8> c;
    for (int i = 0; i < 8; ++i)
        c[i] = {(i & 1) ? hi.x : lo.x, (i & 2) ? hi.y : lo.y, (i & 4) ? hi.z : lo.z};
    return c;
}

// Extent of the box seen in a view: width along right, height along up (m).
vec2 extent(const View& v, const vec3& lo, const vec3& hi) {
    vec2 mn(1e30f), mx(-1e30f);
    for (const vec3& c : corners(lo, hi)) {
        const vec2 p(glm::dot(c, v.right), glm::dot(c, v.up));
        mn = glm::min(mn, p);
        mx = glm::max(mx, p);
    }
    return mx - mn;
}

// A panel: the camera of a view at `scale` pixels per metre, centred on the box, far away
// with a narrow field so the projection is orthographic to within 0.1 %.
struct Panel {
    View view;
    vec3 eye, centre;
    float scale;
    int size;

    Panel(const View& v, const vec3& lo, const vec3& hi, float pixelsPerMetre, int px)
        : view(v), scale(pixelsPerMetre), size(px) {
        centre = 0.5f * (lo + hi);
        const float distance = 1000.0f * std::max(glm::length(hi - lo), 0.01f);
        eye = centre - distance * v.forward;
    }
    float distance() const { return glm::length(centre - eye); }
    float fovDeg() const {
        const float halfHeight = 0.5f * float(size) / scale;
        return 2.0f * std::atan(halfHeight / distance()) * 180.0f / kPi;
    }
    // Pixel position of a world point.
    vec2 pixel(const vec3& p) const {
        const vec3 d = p - eye;
        const float depth = glm::dot(d, view.forward) / distance();
        const float x = glm::dot(d, view.right) / depth, y = glm::dot(d, view.up) / depth;
        return {0.5f * float(size) + x * scale, 0.5f * float(size) - y * scale};
    }
};

void setPixel(Image& im, int x, int y, std::array<std::uint8_t, 3> c) {
    if (x < 0 || y < 0 || x >= im.width || y >= im.height) return;
    std::memcpy(&im.rgb[(std::size_t(y) * std::size_t(im.width) + std::size_t(x)) * 3], c.data(),
                3);
}

void line(Image& im, vec2 a, vec2 b, std::array<std::uint8_t, 3> c, int thickness = 1) {
    const int steps = int(std::ceil(std::max(std::abs(b.x - a.x), std::abs(b.y - a.y)))) + 1;
    for (int i = 0; i <= steps; ++i) {
        const vec2 p = a + (b - a) * (float(i) / float(steps));
        for (int t = 0; t < thickness; ++t) setPixel(im, int(p.x), int(p.y) + t, c);
    }
}

constexpr std::array<std::uint8_t, 3> kInk{20, 20, 20};

// A 10 cm bar with end ticks at the bottom left of a panel, labelled above.
void scaleBar(Image& im, float pixelsPerMetre, int textScale) {
    const float x0 = 30.0f, y0 = float(im.height) - 25.0f, length = 0.1f * pixelsPerMetre;
    line(im, {x0, y0}, {x0 + length, y0}, kInk, 2);
    line(im, {x0, y0 - 5}, {x0, y0 + 5}, kInk);
    line(im, {x0 + length, y0 - 5}, {x0 + length, y0 + 5}, kInk);
    drawText(im, int(x0), int(y0) - 6 - 10 * textScale, "10 cm", textScale, kInk);
}

// Draws `text` at (x, y) at the largest scale up to `scale` that fits `width` pixels.
void caption(Image& im, int x, int y, const std::string& text, int scale, int width,
             std::array<std::uint8_t, 3> color) {
    while (scale > 1 && textSize(text, scale)[0] > width) --scale;
    drawText(im, x, y, text, scale, color);
}

// A white strip of `height` pixels above `image` holding one line of text.
Image withTitle(const Image& image, const std::string& title, int height) {
    Image out(image.width, image.height + height);
    std::fill(out.rgb.begin(),
              out.rgb.begin() + std::ptrdiff_t(std::size_t(image.width) * 3 * std::size_t(height)),
              std::uint8_t(255));
    std::copy(image.rgb.begin(), image.rgb.end(),
              out.rgb.begin() + std::ptrdiff_t(std::size_t(image.width) * 3 * std::size_t(height)));
    caption(out, 14, height / 2 - 10, title, 3, image.width - 28, kInk);
    return out;
}

// The four renders of the two panels, one "rendering" bar: render k (0 to 3) is its k-th
// quarter.
ProgressCallback quarter(const ProgressCallback& progress, int k) {
    if (!progress) return {};
    return [&progress, k](std::string_view stage, double f) { progress(stage, (k + f) / 4.0); };
}

// `part` 0 or 1: the panel's place in the bar.
Image renderPanel(const RenderScene& scene, const Panel& panel, const ProgressCallback& progress,
                  int part) {
    RenderOptions o;
    o.width = o.height = panel.size;
    o.camera.autoFrame = false;
    o.camera.eye = panel.eye;
    o.camera.target = panel.centre;
    o.camera.up = panel.view.up;
    o.camera.fovDeg = panel.fovDeg();
    o.groundPlane = false;
    o.skyZenithColor = o.skyHorizonColor = vec3(1.0f);
    o.samplesPerPixel = 16;
    o.progress = quarter(progress, 2 * part);
    Image image = scene.render(o);
    // White wherever no ray meets the plant (the renderer's background darkens below the
    // horizon).
    o.mode = RenderMode::LabelObject;
    o.samplesPerPixel = 1;
    o.progress = quarter(progress, 2 * part + 1);
    const Image mask = scene.render(o);
    for (std::size_t i = 0; i < mask.rgb.size(); i += 3)
        if (mask.rgb[i] == 0 && mask.rgb[i + 1] == 0 && mask.rgb[i + 2] == 0)
            image.rgb[i] = image.rgb[i + 1] = image.rgb[i + 2] = 255;
    return image;
}

// Images side by side (top aligned) or one above the other, on white, with a grey gap.
Image join(const std::vector<Image>& parts, bool across) {
    int w = 0, h = 0;
    const int gap = 2;
    for (const Image& p : parts) {
        w = across ? w + p.width + gap : std::max(w, p.width);
        h = across ? std::max(h, p.height) : h + p.height + gap;
    }
    Image out(across ? w - gap : w, across ? h : h - gap);
    std::fill(out.rgb.begin(), out.rgb.end(), std::uint8_t(190));
    int at = 0;
    for (const Image& p : parts) {
        for (int y = 0; y < p.height; ++y) {
            const int ox = across ? at : 0, oy = across ? y : at + y;
            std::memcpy(&out.rgb[(std::size_t(oy) * std::size_t(out.width) + std::size_t(ox)) * 3],
                        &p.rgb[std::size_t(y) * std::size_t(p.width) * 3],
                        std::size_t(p.width) * 3);
        }
        at += (across ? p.width : p.height) + gap;
    }
    return out;
}

// The scale (pixels per metre) at which the larger of the two views of every box fills 90 %
// of its panel.
float commonScale(const std::vector<AABB>& boxes, int size) {
    float scale = 1e30f;
    for (const AABB& box : boxes)
        for (const View& v : {sideView(), obliqueView()}) {
            const vec2 e = glm::max(extent(v, box.min, box.max), vec2(1e-3f));
            scale = std::min(scale, 0.9f * float(size) / std::max(e.x, e.y));
        }
    return scale;
}

// The two panels of one scene at `scale`, with ground, captions and scale bars, under `title`.
Image drawScene(const RenderScene& scene, float scale, int size, const std::string& title,
                const ProgressCallback& progress) {
    const AABB box = scene.bounds();
    const vec3 lo = box.min, hi = box.max;
    const Panel sidePanel(sideView(), lo, hi, scale, size),
        obliquePanel(obliqueView(), lo, hi, scale, size);
    Image left = renderPanel(scene, sidePanel, progress, 0);
    Image right = renderPanel(scene, obliquePanel, progress, 1);
    const std::array<std::uint8_t, 3> grey{128, 128, 128};
    // Ground: the line z = 0 across the side view; the footprint (plant's xy box + 10 %) at
    // z = 0 in the oblique view.
    line(left, sidePanel.pixel({lo.x - 10.0f, 0, 0}), sidePanel.pixel({hi.x + 10.0f, 0, 0}), grey);
    const vec3 pad = 0.05f * (hi - lo);
    const vec3 f0(lo.x - pad.x, lo.y - pad.y, 0), f1(hi.x + pad.x, hi.y + pad.y, 0);
    const vec3 fp[4] = {f0, {f1.x, f0.y, 0}, f1, {f0.x, f1.y, 0}};
    for (int i = 0; i < 4; ++i)
        line(right, obliquePanel.pixel(fp[i]), obliquePanel.pixel(fp[(i + 1) % 4]), grey);
    // Captions, and the bars' labels, at one scale: 2 where the longer caption fits.
    const std::string sideText = "side view (looking along +y)";
    const std::string obliqueText = "oblique (elevation 35, azimuth 45 deg)";
    const int textScale = textSize(obliqueText, 2)[0] <= size - 28 ? 2 : 1;
    const std::array<std::uint8_t, 3> grey70{70, 70, 70};
    drawText(left, 14, 12, sideText, textScale, grey70);
    drawText(right, 14, 12, obliqueText, textScale, grey70);
    scaleBar(left, scale, textScale);
    scaleBar(right, scale, textScale);
    return withTitle(join({left, right}, true), title, 44);
}

// A scene file read into `ctx` for --against: OBJ, PLY or glTF by its extension.
void readAgainst(Context& ctx, const std::string& path) {
    const std::string ext = std::filesystem::path(path).extension().string();
    if (ext == ".obj")
        readOBJ(ctx, path);
    else if (ext == ".ply")
        readPLY(ctx, path);
    else if (ext == ".glb" || ext == ".gltf")
        readGLTF(ctx, path);
    else
        throw Error(
            "not a scene file",
            {.parameter = "--against", .value = path, .validRange = ".obj, .ply, .glb or .gltf"});
    if (ctx.triangleCount() == 0)
        throw Error(
            "the scene holds no triangles",
            {.parameter = "--against", .value = path, .validRange = "a scene with triangles"});
}

int run(const CompareArgs& a, const GlobalOptions& global) {
    requireOutputFormat(a.output, kPictureOutput, "the comparison is a picture");
    Image reference;
    if (!a.reference.empty()) reference = readImage(a.reference);  // before any work
    Context againstCtx;
    if (!a.against.empty()) readAgainst(againstCtx, a.against);
    CommandOutputs outputs({a.output});
    Context ctx;
    PlantArchitecture arch(&ctx);
    arch.setSeed(global.seed);
    arch.setTriangleLimit(global.maxTriangles);
    const ProgressCallback progress = terminalProgress();
    arch.setProgressCallback(progress);
    arch.setMeshDetail(global.meshDetail);
    arch.loadPlantModelFromLibrary(a.species);
    arch.setTrellisGeometry(!a.noTrellis);
    const unsigned plant =
        arch.buildPlantInstanceFromLibrary(vec3(0.0f), a.age, parseDefines(a.defines));
    const RenderScene scene(ctx);
    std::vector<AABB> boxes = {scene.bounds()};
    std::optional<RenderScene> other;
    if (!a.against.empty()) {
        other.emplace(againstCtx);
        boxes.push_back(other->bounds());
    }
    // One scale for every panel: the larger of the two views fills 90 % of its panel.
    const float scale = commonScale(boxes, a.panelSize);
    Image ours = drawScene(
        scene, scale, a.panelSize,
        fmt::format("plantarch   {}   age {:g} d   height {:.2f} m   {} triangles   seed {}",
                    arch.getCurrentPlantModel(), a.age, arch.getPlantHeight(plant),
                    scene.triangleCount(), global.seed),
        progress);
    if (other)
        ours = join({drawScene(*other, scale, a.panelSize,
                               fmt::format("{}   height {:.2f} m   {} triangles",
                                           std::filesystem::path(a.against).filename().string(),
                                           other->bounds().max.z, other->triangleCount()),
                               progress),
                     ours},
                    false);
    writePNG(reference.width > 0 ? join({reference, ours}, false) : ours, a.output);
    outputs.commit();
    std::printf("%s",
                fmt::format("{} at {} days (seed {}): height {:.2f} m, {} triangles; "
                            "{:.0f} pixels per metre; written to {}.\n",
                            arch.getCurrentPlantModel(), a.age, global.seed,
                            arch.getPlantHeight(plant), scene.triangleCount(), scale, a.output)
                    .c_str());
    return 0;
}

std::function<int()> setupCompare(CLI::App& app, GlobalOptions& global) {
    app.description(
        "Draw a plant in a fixed framing (side and oblique views, same scale, 10 cm bar), "
        "optionally below a reference picture");
    auto a = std::make_shared<CompareArgs>();
    addPlantOptions(app, a->species, a->age, a->defines, a->noTrellis)->required();
    auto* picture = app.add_option(
        "--reference", a->reference,
        "Picture to show above (any PNG; one made in the same framing compares best)");
    app.add_option("--against", a->against,
                   "Scene to draw above in the same framing and scale (.obj, .ply, .glb, .gltf: "
                   "another system's plant, a scanned plant)")
        ->excludes(picture);
    app.add_option("--panel-size", a->panelSize, "Size of each square view in pixels")
        ->check(numberCheck("--panel-size", "a panel size", 64, 4096, true, "64 to 4096"));
    app.add_option("-o,--output", a->output, "PNG file to write")->required();
    return [a, &global]() { return run(*a, global); };
}

}  // namespace

PLANTARCH_REGISTER_COMMAND(compare, "compare", 55, setupCompare);

}  // namespace plantarch::cli
