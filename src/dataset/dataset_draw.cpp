// Drawing a sample: every random choice of sample i made from streams seeded by the spec's
// seed and i alone, in a fixed order.

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "core/value_text.h"
#include "dataset/dataset_internal.h"
#include "plantarch/Error.h"
#include "plantarch/Light.h"

namespace plantarch {

namespace dataset {

double draw(const Draw& d, Rng& rng) {
    switch (d.kind) {
        case Draw::Kind::Constant:
            return d.a;
        case Draw::Kind::Uniform:
            if (d.whole) {
                const auto lo = std::int32_t(std::clamp(d.a, -2e9, 2e9));
                const auto hi = std::int32_t(std::clamp(d.b, -2e9, 2e9));
                return double(rng.uniformInt(lo, hi));
            }
            return d.a + (d.b - d.a) * rng.uniform01d();
        case Draw::Kind::Normal: {
            // Redrawn until within the field's range; the mean is in it, so this ends.
            for (int tries = 0; tries < 64; ++tries) {
                const double v = d.a + d.b * rng.normal01();
                if (v >= d.lo && v <= d.hi) return v;
            }
            return d.a;
        }
        case Draw::Kind::Choice:
            if (d.weights.empty())
                return d.values[std::size_t(rng.uniformInt(0, std::int32_t(d.values.size()) - 1))];
            return d.values[drawIndex(d.weights, rng)];
    }
    return d.a;
}

std::size_t drawIndex(const std::vector<double>& weights, Rng& rng) {
    double sum = 0.0;
    for (double w : weights) sum += w;
    double u = rng.uniform01d() * sum;
    for (std::size_t i = 0; i < weights.size(); ++i) {
        if (u < weights[i]) return i;
        u -= weights[i];
    }
    // Rounding left u at the top: the last choice of nonzero weight.
    for (std::size_t i = weights.size(); i-- > 0;)
        if (weights[i] > 0.0) return i;
    return 0;
}

}  // namespace dataset

namespace {

using dataset::draw;

template <class T>
std::size_t pickWeighted(const std::vector<T>& items, Rng& rng) {
    std::vector<double> w;
    for (const T& t : items) w.push_back(t.weight);
    return dataset::drawIndex(w, rng);
}

// A species of the spec as a project block: its age and drawn parameters.
ProjectBlock speciesBlock(const DatasetSpecies& s, Rng& rng) {
    ProjectBlock b;
    b.species = s.species;
    b.age = float(draw(s.age, rng));
    for (const auto& [name, d] : s.buildParameters) b.parameters[name] = float(draw(d, rng));
    for (const auto& [path, d] : s.speciesParameters)
        b.speciesParameters[path] = text::formatFloat(float(draw(d, rng)));
    return b;
}

// The crop's layout on block b; returns the extent of the planted area (m, x and y).
vec2 layOut(const DatasetLayout& l, ProjectBlock& b, Rng& rng) {
    switch (l.kind) {
        case DatasetLayout::Kind::Single:
            b.layout = ProjectBlock::Layout::Single;
            return vec2(0.0f);
        case DatasetLayout::Kind::Rows: {
            b.layout = ProjectBlock::Layout::Grid;
            const int rows = int(draw(l.rows, rng)), perRow = int(draw(l.plantsPerRow, rng));
            const float rowSpacing = float(draw(l.rowSpacing, rng));
            const float plantSpacing = float(draw(l.plantSpacing, rng));
            b.count = {perRow, rows};
            b.spacing = {plantSpacing, rowSpacing};
            return {float(perRow - 1) * plantSpacing, float(rows - 1) * rowSpacing};
        }
        case DatasetLayout::Kind::Grid: {
            b.layout = ProjectBlock::Layout::Grid;
            const int n = int(draw(l.count, rng));
            const float spacing = float(draw(l.spacing, rng));
            b.count = {n, n};
            b.spacing = {spacing, spacing};
            return vec2(float(n - 1) * spacing);
        }
        case DatasetLayout::Kind::Scatter: {
            b.layout = ProjectBlock::Layout::Scatter;
            b.plants = unsigned(draw(l.plants, rng));
            const float a = float(draw(l.area, rng));
            b.area = {a, a};
            return b.area;
        }
    }
    return vec2(0.0f);
}

// A sky colour hazed toward the overcast grey by `haze` (0 to 1).
vec3 lightingColor(const vec3& zenith, const vec3& overcast, double haze) {
    return glm::mix(zenith, overcast, float(haze));
}

void drawCamera(const DatasetSpec& spec, std::size_t index, DatasetSample& s, Rng& rng) {
    const DatasetCamera& c = spec.camera;
    RenderOptions& o = s.render;
    o.width = c.width;
    o.height = c.height;
    o.samplesPerPixel = c.samplesPerPixel;
    o.camera.fovDeg = float(draw(c.fov, rng));
    switch (c.kind) {
        case DatasetCamera::Kind::Orbit:
            o.camera.autoFrame = true;
            o.camera.azimuthDeg = float(draw(c.azimuth, rng));
            o.camera.elevationDeg = float(draw(c.elevation, rng));
            o.camera.margin = float(draw(c.margin, rng));
            break;
        case DatasetCamera::Kind::Nadir:
            o.camera.autoFrame = true;
            o.camera.azimuthDeg = float(draw(c.azimuth, rng));
            o.camera.elevationDeg = 89.0f;
            o.camera.margin = float(draw(c.margin, rng));
            break;
        case DatasetCamera::Kind::Row: {
            // Beside the first row's start, looking along it (+x), pitched down; the eye's
            // x and y are set from the scene when it is built (see sampleCamera).
            o.camera.autoFrame = false;
            const float height = float(draw(c.heightAbove, rng));
            const float pitch = float(draw(c.pitch, rng)) * 3.14159265f / 180.0f;
            o.camera.eye = vec3(0.0f, 0.0f, height);
            o.camera.target = o.camera.eye + vec3(std::cos(pitch), 0.0f, -std::sin(pitch));
            break;
        }
        case DatasetCamera::Kind::Random: {
            o.camera.autoFrame = false;
            vec3 lo, hi;
            for (int k = 0; k < 3; ++k) {
                lo[k] = float(draw(c.eyeMin[std::size_t(k)], rng));
                hi[k] = float(draw(c.eyeMax[std::size_t(k)], rng));
            }
            vec3 eye;
            for (int k = 0; k < 3; ++k)
                eye[k] = std::min(lo[k], hi[k]) + std::abs(hi[k] - lo[k]) * rng.uniform01();
            o.camera.eye = eye;  // relative to the scene centre until it is built
            o.camera.target = vec3(0.0f);
            break;
        }
        case DatasetCamera::Kind::Trajectory: {
            o.camera.autoFrame = false;
            // Arc length along the path, sample i at i / (samples - 1) of it.
            std::vector<double> length{0.0};
            for (std::size_t k = 1; k < c.path.size(); ++k) {
                double d = 0.0;
                for (int a = 0; a < 3; ++a)
                    d += (c.path[k][std::size_t(a)] - c.path[k - 1][std::size_t(a)]) *
                         (c.path[k][std::size_t(a)] - c.path[k - 1][std::size_t(a)]);
                length.push_back(length.back() + std::sqrt(d));
            }
            const double f = spec.samples > 1 ? double(index) / double(spec.samples - 1) : 0.0;
            const double want = std::min(f, 1.0) * length.back();
            std::size_t k = 1;
            while (k < c.path.size() && length[k] < want) ++k;
            vec3 eye;
            if (k >= c.path.size()) {
                for (int a = 0; a < 3; ++a) eye[a] = float(c.path.back()[std::size_t(a)]);
            } else {
                const double seg = length[k] - length[k - 1];
                const double t = seg > 0.0 ? (want - length[k - 1]) / seg : 0.0;
                for (int a = 0; a < 3; ++a)
                    eye[a] = float(c.path[k - 1][std::size_t(a)] +
                                   t * (c.path[k][std::size_t(a)] - c.path[k - 1][std::size_t(a)]));
            }
            o.camera.eye = eye;
            o.camera.target = vec3(float(c.target[0]), float(c.target[1]), float(c.target[2]));
            if (glm::length(o.camera.target - eye) <= 0.0f) o.camera.target.x += 1.0f;
            break;
        }
    }
}

// Day of the year to month and day (a year of 365 days).
UTCTime dateOf(int dayOfYear, double hourUTC) {
    static const int days[12] = {31, 28, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
    UTCTime t;
    t.year = 2021;
    int d = std::clamp(dayOfYear, 1, 365);
    int m = 0;
    while (d > days[m]) d -= days[m++];
    t.month = m + 1;
    t.day = d;
    t.hour = hourUTC;
    return t;
}

void drawLighting(const DatasetSpec& spec, DatasetSample& s, Rng& rng) {
    const DatasetLighting& l = spec.lighting;
    RenderOptions& o = s.render;
    s.dayOfYear = draw(l.dayOfYear, rng);
    s.hour = draw(l.hour, rng);
    // Local mean solar time to UTC by the longitude (15 degrees an hour), kept within the day.
    double utc = s.hour - l.longitude / 15.0;
    int day = int(s.dayOfYear);
    if (utc < 0.0) {
        utc += 24.0;
        day = day > 1 ? day - 1 : 365;
    } else if (utc >= 24.0) {
        utc -= 24.0;
        day = day < 365 ? day + 1 : 1;
    }
    const SunPosition sun = sunPosition({l.latitude, l.longitude}, dateOf(day, utc));
    vec3 dir = sun.direction();
    // A sun below the horizon lights nothing: the scene is lit by the sky alone then, and
    // the direction is kept just above the horizon for the renderer's checks.
    if (dir.z < 0.02f) dir = glm::normalize(vec3(dir.x, dir.y, 0.02f));
    o.sunDirection = dir;
    const double haze = draw(l.haze, rng);
    const float sunUp = sun.elevation > 0.0 ? 1.0f : 0.0f;
    o.sunIntensity = float(draw(l.sunIntensity, rng)) * float(1.0 - 0.8 * haze) * sunUp;
    o.sunAngularRadiusDeg = float(draw(l.sunSoftness, rng));
    o.skyIntensity = float(draw(l.skyIntensity, rng));
    o.exposure = float(draw(l.exposure, rng));
    const vec3 overcast(0.78f, 0.80f, 0.83f);
    o.skyZenithColor = lightingColor(vec3(0.42f, 0.62f, 0.90f), overcast, haze);
    o.skyHorizonColor = lightingColor(vec3(0.83f, 0.89f, 0.95f), overcast, haze);
}

}  // namespace

std::string datasetSampleName(std::size_t index) {
    return fmt::format("{:06d}", index);
}

DatasetSample drawDatasetSample(const DatasetSpec& spec, std::size_t index) {
    if (index >= kMaxDatasetSamples)
        throw Error("sample index out of range",
                    {.parameter = "index",
                     .value = std::to_string(index),
                     .validRange = "0 to " + std::to_string(kMaxDatasetSamples - 1)});
    if (spec.species.empty() || spec.layouts.empty())
        throw Error("a dataset spec needs a species and a layout", {.file = spec.file});
    DatasetSample s;
    s.index = index;
    Rng seeds = Rng::forPlant(spec.seed, index);
    s.seed = (std::uint64_t(seeds.nextU32()) << 32) | seeds.nextU32();
    Rng rng(s.seed, 1);

    // The split, from a stream of its own so that changing the scene never moves a sample.
    Rng splitRng(s.seed, 2);
    double u = splitRng.uniform01d();
    s.split = spec.splits.back().first;
    for (const auto& [name, fraction] : spec.splits) {
        if (u < fraction) {
            s.split = name;
            break;
        }
        u -= fraction;
    }

    Project& p = s.project;
    p.name = spec.name + "-" + datasetSampleName(index);
    p.seed = s.seed;
    p.folder = spec.folder;
    p.file = spec.file;
    const DatasetSpecies& crop = spec.species[pickWeighted(spec.species, rng)];
    s.species = crop.species;
    ProjectBlock block = speciesBlock(crop, rng);
    block.name = "crop";
    block.seed = s.seed;
    const vec2 extent = layOut(spec.layouts[pickWeighted(spec.layouts, rng)], block, rng);
    block.germination = float(draw(spec.germination, rng));
    p.meshDetail = float(draw(spec.meshDetail, rng));
    p.softCollision = spec.softCollision;
    p.blocks.push_back(block);

    if (!spec.weeds.species.empty() && rng.chance(float(spec.weeds.probability))) {
        const DatasetSpecies& weed = spec.weeds.species[pickWeighted(spec.weeds.species, rng)];
        ProjectBlock w = speciesBlock(weed, rng);
        w.name = "weeds";
        w.layout = ProjectBlock::Layout::Scatter;
        w.plants = unsigned(draw(spec.weeds.plants, rng));
        const float margin = float(draw(spec.weeds.margin, rng));
        w.area = extent + vec2(2.0f * margin);
        w.seed = s.seed ^ 0x5EED5EED5EED5EEDull;
        p.blocks.push_back(w);
    }

    s.leafHSV = {draw(spec.leafColor.hue, rng), draw(spec.leafColor.saturation, rng),
                 draw(spec.leafColor.value, rng)};
    drawCamera(spec, index, s, rng);
    drawLighting(spec, s, rng);
    const float t = rng.uniform01();
    const DatasetGround& g = spec.ground;
    for (int k = 0; k < 3; ++k)
        s.render.groundColor[k] = float(g.colorA[std::size_t(k)] +
                                        t * (g.colorB[std::size_t(k)] - g.colorA[std::size_t(k)]));
    s.render.groundVariation = float(draw(g.variation, rng));
    s.render.groundPatchSize = float(draw(g.patchSize, rng));
    s.render.seed = s.seed;
    return s;
}

}  // namespace plantarch
