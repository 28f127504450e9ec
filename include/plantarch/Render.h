#pragma once
// plantarch preview renderer: ray casts a Context on Embree and writes PNG images.
//
// Two kinds of picture:
//  - Shaded: a sky (ambient hemisphere, optionally with ambient occlusion rays), a sun with
//    soft shadows (jittered shadow rays toward a sun disc), two-sided Lambert surfaces with
//    per-material colours or textures, an analytic ground plane that receives shadows,
//    stratified anti-aliasing and sRGB output.
//  - Label masks (LabelOrgan, LabelObject): one ray through each pixel centre, a flat colour
//    per organ kind or per object ID, black background, no shading, no anti-aliasing, so the
//    image is an exact segmentation mask.
//
// Output is deterministic: every pixel draws its random numbers from a stream seeded by
// (RenderOptions::seed, pixel index), so the bytes never depend on the thread count.
//
// Colours in Material::color and in the options below are display (sRGB) values in 0..1; the
// renderer converts them to linear light for shading and back to sRGB for the image. A
// material's texture (PNG, JPEG, ... read with stb_image) replaces its colour, looked up
// bilinearly with the object's UVs (v = 0 at the image's bottom row, as in OBJ); texels with
// alpha below one half are cut out (rays pass through). An object without UVs uses the
// texture's mean colour.
//
// Organ label colours (LabelOrgan), read from the object string data "organ":
//
//   organ          RGB
//   internode      230  25  75
//   petiole        245 130  48
//   leaf            60 180  75
//   peduncle       255 225  25
//   flower_closed  240  50 230
//   flower_open    145  30 180
//   fruit            0 130 200
//   ground         128 128 128
//   obstacle        70 240 240
//   (other/unset)  255 255 255
//   background       0   0   0   (also the analytic ground plane)
//
// Object label colours (LabelObject): objectLabelColor(id) is a bijection of (id + 1) onto the
// nonzero 24-bit colours, so distinct objects always get distinct colours, none is black, and
// objectIDFromLabelColor() recovers the ID from a pixel.

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "plantarch/Context.h"
#include "plantarch/Export.h"
#include "plantarch/Mesh.h"
#include "plantarch/Progress.h"

namespace plantarch {

/// An 8-bit RGB image, rows top to bottom, 3 bytes per pixel.
struct Image {
    int width = 0;
    int height = 0;
    std::vector<std::uint8_t> rgb;  ///< width * height * 3 bytes

    Image() = default;
    Image(int w, int h) : width(w), height(h), rgb(std::size_t(w) * std::size_t(h) * 3, 0) {}

    std::array<std::uint8_t, 3> pixel(int x, int y) const {
        const std::size_t i = (std::size_t(y) * std::size_t(width) + std::size_t(x)) * 3;
        return {rgb[i], rgb[i + 1], rgb[i + 2]};
    }
};

/// What a depth camera sees: per pixel (rows top to bottom) the distance from the eye along
/// the view axis to the first surface hit through the pixel's centre, in metres; 0 where the
/// ray hits nothing. The ground plane counts as a surface when RenderOptions::groundPlane.
struct DepthImage {
    int width = 0;
    int height = 0;
    std::vector<float> depth;  ///< width * height values

    float at(int x, int y) const {
        return depth[std::size_t(y) * std::size_t(width) + std::size_t(x)];
    }
};

/// A pinhole camera. With autoFrame the eye and target are computed from the scene's bounding
/// box (visible objects): the camera looks from (azimuthDeg, elevationDeg) and stands as close
/// as it can while the whole box fits in the frame with `margin` to spare on each side.
struct Camera {
    bool autoFrame = true;
    vec3 eye{0.0f};             ///< camera position (m); used when !autoFrame
    vec3 target{0.0f};          ///< point looked at (m); used when !autoFrame
    vec3 up{0.0f, 0.0f, 1.0f};  ///< image "up" direction; used when !autoFrame
    float fovDeg = 35.0f;       ///< vertical field of view, degrees (0 to 170 exclusive)

    // Auto-framing only.
    float azimuthDeg = -60.0f;   ///< direction from the target to the eye, from +x toward +y
    float elevationDeg = 22.0f;  ///< above the horizontal, degrees (-89 to 89)
    float margin = 0.07f;        ///< free border as a fraction of the half-frame (0 to 0.9)
};

enum class RenderMode {
    Shaded,       ///< lit, anti-aliased preview
    LabelOrgan,   ///< flat colour per organ kind (see the table above)
    LabelObject,  ///< flat colour per object ID (objectLabelColor)
    Flat,         ///< each object's own material colour, unlit (false-colour pictures)
};

/// What is prepared once per scene (RenderScene); the one-shot render() takes it from
/// RenderOptions::scene.
struct RenderSceneOptions {
    /// Interpolate vertex normals on smooth surfaces (tubes); corners sharper than about
    /// 40 degrees (boxes) stay flat.
    bool smoothNormals = true;
    /// A texture that cannot be read is an Error; with this set the material colour is used.
    bool ignoreMissingTextures = false;
    /// Procedural textures (MaterialOptions, plantarch/Export.h): with
    /// MaterialStyle::Textured, leaves, internodes, petioles and peduncles get the base colour
    /// (and alpha) the exporters write; normal and roughness maps are not used here.
    MaterialOptions appearance;
    /// Embree BVH build quality: Low builds about twice as fast and traces somewhat slower;
    /// High is for many renders of one scene.
    enum class BvhQuality { Low, Medium, High };
    BvhQuality bvhQuality = BvhQuality::Medium;
    /// Told how far the scene is built ("building scene", 0..1: copying the triangles, then
    /// the BVH); may be empty. Called one call at a time, possibly from the BVH builder's
    /// threads.
    ProgressCallback progress;
};

struct RenderOptions {
    int width = 1024;  ///< pixels, 1 to 16384
    int height = 768;  ///< pixels, 1 to 16384
    Camera camera;
    RenderMode mode = RenderMode::Shaded;

    /// A horizontal plane at the scene's lowest z, extended to the horizon. It is
    /// background in the label modes.
    bool groundPlane = true;
    vec3 groundColor{0.42f, 0.38f, 0.33f};  ///< sRGB albedo, neutral soil
    /// Patchy soil on the ground plane: its albedo varies by up to this fraction either way
    /// (0 to 1; 0: uniform), in smooth patches of about groundPatchSize metres (0.001 to
    /// 1000) with finer detail inside, the pattern fixed by `seed`.
    float groundVariation = 0.0f;
    float groundPatchSize = 0.1f;

    /// Direction toward the sun (normalised internally; must have z > 0 to light anything).
    vec3 sunDirection{0.54f, 0.20f, 0.82f};
    float sunAngularRadiusDeg = 1.2f;          ///< larger gives softer shadows (the real sun: 0.27)
    float sunIntensity = 2.6f;                 ///< irradiance on a surface facing the sun
    vec3 skyZenithColor{0.42f, 0.62f, 0.90f};  ///< sRGB, background straight up
    vec3 skyHorizonColor{0.83f, 0.89f, 0.95f};  ///< sRGB, background at the horizon
    float skyIntensity = 1.0f;  ///< scales the sky's light on surfaces (not the background)
    float exposure = 1.0f;      ///< linear scale before sRGB encoding
    /// Fraction of the sun's light a surface passes to its back side (thin leaves glow when
    /// lit from behind; closed surfaces shadow themselves so it does not apply to them).
    float translucency = 0.25f;

    int samplesPerPixel = 4;  ///< stratified jittered camera rays per pixel (1 to 1024)
    int shadowSamples = 1;    ///< sun rays per camera sample, toward random points on the disc
    int aoSamples = 1;        ///< sky-visibility rays per camera sample; 0 = unoccluded sky
    std::uint64_t seed = 0;   ///< picks the sample pattern; same seed, same bytes

    RenderSceneOptions scene;  ///< used by the one-shot render()
    /// Told how many image rows are done ("rendering", 0..1); may be empty.
    ProgressCallback progress;
};

/// The rays a render casts: width x height x samplesPerPixel camera rays, each with its
/// shadowSamples sun rays and aoSamples sky rays in the shaded mode (camera rays only in the
/// label modes). A depth image casts the rays of cameraRaysOnly(options).
std::uint64_t renderRayCount(const RenderOptions& options);
/// What one ray through each pixel's centre finds (RenderScene::renderSurfaces): rows top to
/// bottom, width * height entries each.
struct SurfaceImage {
    int width = 0;
    int height = 0;
    /// The object seen, as its ObjectID + 1; 0 where the ray meets nothing or the ground
    /// plane.
    std::vector<std::uint32_t> object;
    /// Distance along the view axis (m) to the surface seen, ground plane included; 0 where
    /// nothing is hit (as DepthImage).
    std::vector<float> depth;
    /// Unit world-space normal of the surface seen, turned toward the camera ((0, 0, 1) on the
    /// ground plane); (0, 0, 0) where nothing is hit. Smoothed as the shaded image is.
    std::vector<vec3> normal;
};

/// The options with no sun or sky rays: what a depth image casts.
RenderOptions cameraRaysOnly(const RenderOptions& options);
/// The most rays one render may cast (2^32): a render is refused before any work when
/// renderRayCount is larger, so that no option within its own range starts a job of hours.
inline constexpr std::uint64_t kMaxRenderRays = std::uint64_t(1) << 32;

// The organ label colour table (see the header comment): organLabelColors() and
// organLabelColor() in plantarch/Export.h, shared with the PLY writer's colours.
/// Colour of an object in LabelObject mode: a bijection of (id + 1) onto the 24-bit colours.
std::array<std::uint8_t, 3> objectLabelColor(ObjectID id);
/// Inverse of objectLabelColor; nullopt for black (background).
std::optional<ObjectID> objectIDFromLabelColor(std::array<std::uint8_t, 3> rgb);

/// The resolved camera of a render (after auto-framing).
struct CameraFrame {
    vec3 eye, target, up;
    float fovDeg;
};

/// A render's camera as vision tools take it, in OpenCV's pinhole convention (camera x right,
/// y down, z forward; pixel centres at whole coordinates; metres): a world point p is seen at
/// pixel (u, v) with (u w, v w, w) = K (worldToCamera p).
struct CameraMatrices {
    std::array<std::array<double, 3>, 3> K;              ///< intrinsics
    std::array<std::array<double, 4>, 4> worldToCamera;  ///< extrinsics (rotation, translation)
};
/// The matrices of `frame` for a width x height image, exactly the rays render() casts.
CameraMatrices cameraMatrices(const CameraFrame& frame, int width, int height);
/// The camera as JSON text: eye, target, up, vertical field of view, image size, K and
/// world_to_camera (what `plantarch render --camera-json` writes beside a picture).
std::string cameraJSON(const CameraFrame& frame, int width, int height);

/// A Context prepared for ray casting: geometry copied into an Embree BVH, materials and
/// textures loaded. It is a snapshot: later changes to the Context are not seen. Building it
/// is the costly part; render() can then be called many times (several views, label masks).
class RenderScene {
public:
    /// Throws plantarch::Error when a texture cannot be read (unless ignored).
    explicit RenderScene(const Context& context, const RenderSceneOptions& options = {});
    ~RenderScene();
    RenderScene(RenderScene&&) noexcept;
    RenderScene& operator=(RenderScene&&) noexcept;
    RenderScene(const RenderScene&) = delete;
    RenderScene& operator=(const RenderScene&) = delete;

    /// Renders with OpenMP over rows. Throws plantarch::Error on invalid options.
    Image render(const RenderOptions& options) const;
    /// The depth image of the same camera (one ray per pixel centre; mode, samples and lights
    /// do not matter). Throws plantarch::Error on invalid options.
    DepthImage renderDepth(const RenderOptions& options) const;
    /// Object, depth and normal of the first surface through each pixel's centre, in one
    /// pass (the rays of renderDepth). Throws plantarch::Error on invalid options.
    SurfaceImage renderSurfaces(const RenderOptions& options) const;
    /// Distance (m) along the unit `direction` from `origin` to the first triangle hit, as
    /// the camera's rays see them (alpha cut-outs pass rays); infinity when none is hit. The
    /// ground plane of the options is not part of the scene.
    float hitDistance(const vec3& origin, const vec3& direction) const;
    /// The camera render() would use with these options.
    CameraFrame camera(const RenderOptions& options) const;

    /// Box around the visible (not hidden) objects; empty for an empty scene.
    const AABB& bounds() const;
    std::size_t triangleCount() const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

/// One-shot: builds a RenderScene from `context` with options.scene and renders it.
Image render(const Context& context, const RenderOptions& options = {});

/// One-shot depth image: builds a RenderScene from `context` and calls renderDepth.
DepthImage renderDepth(const Context& context, const RenderOptions& options = {});

/// A one-channel 16-bit image (instance masks: a whole-number label per pixel), rows top to
/// bottom.
struct Image16 {
    int width = 0;
    int height = 0;
    std::vector<std::uint16_t> values;  ///< width * height values
};
/// Writes a 16-bit greyscale PNG, atomically. Throws plantarch::Error naming the path.
void writePNG16(const Image16& image, const std::string& path);
/// The PNG file writePNG16 would write, as bytes.
std::string encodePNG16(const Image16& image);
/// Reads a one-channel PNG (16-bit, or 8-bit scaled by 257) as 16-bit values. Throws
/// plantarch::Error naming the path.
Image16 readImage16(const std::string& path);

/// Writes float32 values as a NumPy .npy array (C order) of `shape`, whose product must be
/// values.size(), atomically, for numpy.load. Throws plantarch::Error naming the path.
void writeNPY(const std::vector<float>& values, const std::vector<std::size_t>& shape,
              const std::string& path);

/// Writes a depth image as a NumPy .npy file (float32, shape (height, width), metres; 0 where
/// nothing was hit), atomically, for numpy.load.
void writeDepthNPY(const DepthImage& depth, const std::string& path);
/// A depth image as a picture: grey from white (nearest surface) to dark grey (farthest),
/// black where nothing was hit. For looking at; the .npy holds the distances.
Image depthPicture(const DepthImage& depth);

/// Writes `image` as a PNG, atomically (temporary file in the same folder, then rename).
/// Throws plantarch::Error naming the path when it cannot be written.
void writePNG(const Image& image, const std::string& path);
/// One labelled region of an integer mask (maskRegions).
struct MaskRegion {
    std::uint32_t label = 0;
    std::size_t area = 0;       ///< pixels
    std::array<int, 4> bbox{};  ///< x, y, width, height of the smallest box holding it, pixels
    /// COCO's uncompressed run-length encoding: counts of alternating background and region
    /// pixels in column-major order, starting with background, summing to width * height.
    std::vector<std::uint32_t> rle;
};
/// The regions of a width x height mask of integer labels (rows top to bottom; 0 is
/// background), in increasing label order. Throws plantarch::Error when labels does not hold
/// width * height values.
std::vector<MaskRegion> maskRegions(const std::vector<std::uint32_t>& labels, int width,
                                    int height);

/// COCO-style instance annotations (JSON text) of an object label mask rendered from
/// `context` (RenderMode::LabelObject): one image named `imageFile`, the organ kinds as
/// categories (ids 1 to 9, as kOrganLabels), and one annotation per object seen with its
/// category, object_id, plant_id, pixel area, bounding box [x, y, width, height] and mask as
/// uncompressed RLE (column-major). Throws plantarch::Error for an empty mask.
std::string cocoAnnotations(const Context& context, const Image& objectMask,
                            const std::string& imageFile);

/// The PNG file writePNG would write, as bytes (for notebooks and web front ends).
std::string encodePNG(const Image& image);
/// Reads a PNG (or any format stb_image knows) as 8-bit RGB. Throws plantarch::Error.
Image readImage(const std::string& path);

/// Draws one line of ASCII `text` onto `image` in a plain built-in font (captions, scale-bar
/// labels), its top-left corner at pixel (x, y), each font unit `scale` pixels square (a
/// capital letter is 7 units tall and about 5 wide). Pixels outside the image are skipped;
/// characters outside printable ASCII are drawn as '?'.
void drawText(Image& image, int x, int y, std::string_view text, int scale,
              std::array<std::uint8_t, 3> color);
/// The width and height in pixels that drawText covers for `text` at `scale`.
std::array<int, 2> textSize(std::string_view text, int scale);

}  // namespace plantarch
