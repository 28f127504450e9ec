// plantarch light SPECIES --age D [--count NxM --spacing AxB] [-D name=value]
//                 --location LAT,LON (--date YYYY-MM-DD [--clearness K] [--temperature MIN:MAX]
//                                     | --weather FILE)
//                 [--rays DIRECT,DIFFUSE,SCATTER] [--samples N] [--no-scattering] [--no-ground]
//                 [--series FILE.csv] [--leaves FILE.csv] [-o FILE.png|.glb|.ply|...]
// The PAR a plant or a canopy absorbs over a clear day or the intervals of a weather file,
// traced through every surface (plantarch/Light.h): an hourly series, every leaf's share, and
// a false-colour picture or mesh of it.

#include "plantarch/Light.h"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <numbers>
#include <optional>
#include <utility>

#include "cli.h"
#include "plantarch/Error.h"
#include "plantarch/Photosynthesis.h"
#include "plantarch/PlantArchitecture.h"

namespace plantarch::cli {

namespace {

constexpr const char* kLightOutputs = ".png, .obj, .ply, .glb, .gltf or .usda";

struct LightArgs {
    std::string species, count, spacing = "0.3x0.3", location, date, weather;
    std::string temperature = "15:28", rays = "4,64,32";
    unsigned samples = 0;
    float age = -1.0f, clearness = 0.75f;
    std::vector<std::string> defines, outputs;
    std::string series, leaves;
    bool noScattering = false, noGround = false, noTrellis = false;
};

// A perceptually even map from dark violet (0) through teal to yellow (1): the viridis
// colour map's hues at nine stops, interpolated linearly in sRGB.
vec3 falseColour(float t) {
    static const float stops[9][3] = {{68, 1, 84},    {71, 44, 122},  {59, 81, 139},
                                      {44, 113, 142}, {33, 144, 141}, {39, 173, 129},
                                      {92, 200, 99},  {170, 220, 50}, {253, 231, 37}};
    t = std::clamp(std::isfinite(t) ? t : 0.0f, 0.0f, 1.0f) * 8.0f;
    const int i = std::min(7, int(t));
    const float f = t - float(i);
    vec3 c;
    for (int k = 0; k < 3; ++k) c[k] = (stops[i][k] * (1 - f) + stops[i + 1][k] * f) / 255.0f;
    return c;
}

// A colour bar with its scale along the bottom of a picture.
void drawLegend(Image& image, double top, const std::string& unit) {
    const int scale = std::max(1, image.height / 300);
    const int barW = std::min(image.width / 2, 256 * scale), barH = 8 * scale;
    const int x0 = 10 * scale, y0 = image.height - barH - 22 * scale;
    for (int x = 0; x < barW; ++x) {
        const vec3 c = falseColour(float(x) / float(std::max(1, barW - 1)));
        for (int y = y0; y < y0 + barH; ++y) {
            if (y < 0 || y >= image.height || x0 + x >= image.width) continue;
            const std::size_t i =
                (std::size_t(y) * std::size_t(image.width) + std::size_t(x0 + x)) * 3;
            for (int k = 0; k < 3; ++k)
                image.rgb[i + std::size_t(k)] = std::uint8_t(c[k] * 255.0f + 0.5f);
        }
    }
    const std::array<std::uint8_t, 3> white{255, 255, 255};
    drawText(image, x0, y0 + barH + 4 * scale, "0", scale, white);
    const std::string high = fmt::format("{:.3g} {}", top, unit);
    drawText(image, x0 + barW - textSize(high, scale)[0], y0 + barH + 4 * scale, high, scale,
             white);
    drawText(image, x0, y0 - 10 * scale, "absorbed PAR", scale, white);
}

LightOptions lightOptions(const LightArgs& a, const GlobalOptions& g) {
    LightOptions o;
    const auto first = a.rays.find(','), last = a.rays.rfind(',');
    unsigned v[3] = {0, 0, 0};
    bool ok = first != std::string::npos && last != first;
    try {
        std::size_t used = 0;
        if (ok) {
            const std::string parts[3] = {a.rays.substr(0, first),
                                          a.rays.substr(first + 1, last - first - 1),
                                          a.rays.substr(last + 1)};
            for (int k = 0; k < 3 && ok; ++k) {
                const long n = std::stol(parts[k], &used);
                ok = used == parts[k].size() && n >= 1 && n <= 100000;
                v[k] = unsigned(n);
            }
        }
    } catch (const std::exception&) {
        ok = false;
    }
    if (!ok)
        throw Error("expected three ray counts joined by ','",
                    {.parameter = "--rays",
                     .value = a.rays,
                     .validRange = "DIRECT,DIFFUSE,SCATTER rays per triangle, each 1 to "
                                   "100000, e.g. 4,64,32"});
    o.directRays = v[0];
    o.diffuseRays = v[1];
    o.scatterRays = v[2];
    o.scatteringOrders = a.noScattering ? 0 : 1;
    o.samplesPerObject = a.samples;
    o.seed = g.seed;
    return o;
}

// Checks every option and output before any work; returns the outputs' paths.
std::vector<std::string> checkOutputs(const LightArgs& a, const GlobalOptions& g) {
    if (a.age < 0.0f)
        throw Error("give the plants' age",
                    {.parameter = "--age", .validRange = "0 to 100000 days"});
    if (a.date.empty() == a.weather.empty())
        throw Error(a.date.empty() ? "give the day (--date) or a weather file (--weather)"
                                   : "--date and --weather both name the light: give one",
                    {.parameter = "--date, --weather",
                     .validRange = "--date YYYY-MM-DD for a clear day, or --weather FILE.csv"});
    if (a.series.empty() && a.leaves.empty() && a.outputs.empty())
        throw Error("nothing to write: give --series, --leaves or -o",
                    {.parameter = "-o",
                     .validRange = "a .csv series, a .csv of leaves, a picture or mesh"});
    for (const std::string& out : a.outputs) {
        requireOutputFormat(out, kSceneOutput, "unknown output format");
        if (lowerExtension(out) == ".npz")
            throw Error("light writes pictures and meshes, not point clouds",
                        {.file = out, .parameter = "-o", .validRange = kLightOutputs});
    }
    if (g.pictureMode != RenderMode::Shaded)
        throw Error("light draws its pictures in false colour: not with --label",
                    {.parameter = "--label"});
    for (const auto& [path, option] : {std::pair{a.series, "--series"}, {a.leaves, "--leaves"}})
        if (!path.empty() && lowerExtension(path) != ".csv")
            throw Error("expected a .csv file", {.file = path, .parameter = option});
    std::vector<std::string> all = a.outputs;
    if (!a.series.empty()) all.push_back(a.series);
    if (!a.leaves.empty()) all.push_back(a.leaves);
    return all;
}

// The plants, and soil under them reaching out as far as they stand tall (unless
// --no-ground); returns the plants and the ground object.
std::pair<std::vector<unsigned>, std::optional<ObjectID>> buildScene(const LightArgs& a,
                                                                     const GlobalOptions& g,
                                                                     PlantArchitecture& arch,
                                                                     Context& ctx) {
    arch.setSeed(g.seed);
    arch.setTriangleLimit(g.maxTriangles);
    arch.setMeshDetail(g.meshDetail);
    arch.setProgressCallback(terminalProgress());
    arch.loadPlantModelFromLibrary(a.species);
    arch.setTrellisGeometry(!a.noTrellis);
    std::vector<unsigned> plants;
    if (!a.count.empty()) {
        const auto [nx, ny] = parsePair<int>(a.count, "--count");
        const auto [sx, sy] = parsePair<float>(a.spacing, "--spacing");
        plants = arch.buildPlantCanopyFromLibrary(vec3(0.0f), vec2(sx, sy), glm::ivec2(nx, ny),
                                                  a.age, 1.0f, parseDefines(a.defines));
    } else {
        plants.push_back(
            arch.buildPlantInstanceFromLibrary(vec3(0.0f), a.age, parseDefines(a.defines)));
    }
    arch.setProgressCallback({});
    std::optional<ObjectID> ground;
    if (!a.noGround && ctx.triangleCount() > 0) {
        const AABB box = ctx.boundingBox();
        const float reach = std::max(0.5f, box.max.z - box.min.z);
        const vec3 lo(box.min.x - reach, box.min.y - reach, std::min(0.0f, box.min.z));
        const vec3 hi(box.max.x + reach, box.max.y + reach, lo.z);
        const std::vector<vec3> p{lo, vec3(hi.x, lo.y, lo.z), hi, vec3(lo.x, hi.y, lo.z)};
        ground = ctx.addObject(p, {}, std::vector<std::uint32_t>{0, 1, 2, 0, 2, 3},
                               ctx.addMaterial(Material{vec3(0.35f, 0.3f, 0.25f), "", "soil"}));
        ctx.setObjectData(*ground, "organ", std::string("ground"));
    }
    return {plants, ground};
}

// What the intervals add up to, per triangle and over the leaves.
struct Day {
    std::string series;
    std::vector<double> area, absorbed, sunlit, assimilated;  // per triangle: m2, µmol, s, µmol
    std::vector<char> leaf;
    double seconds = 0, daylight = 0, above = 0, leafArea = 0, leafAbsorbed = 0, leafFixed = 0;
};

Day simulate(const LightModel& model, const Context& ctx, const Location& where,
             const std::vector<WeatherHour>& hours) {
    const FarquharParameters leafModel;
    const std::size_t n = model.triangleCount();
    Day d;
    d.area.assign(n, 0.0);
    d.absorbed.assign(n, 0.0);
    d.sunlit.assign(n, 0.0);
    d.assimilated.assign(n, 0.0);
    d.leaf.assign(n, 0);
    for (std::size_t i = 0; i < n; ++i) {
        d.area[i] = model.areas()[i];
        d.leaf[i] = ctx.objectDataString(model.objects()[i], "organ") == std::string("leaf");
        d.leafArea += d.leaf[i] ? d.area[i] : 0.0;
    }
    d.series =
        "time,sun_elevation,sun_azimuth,par,direct_normal,diffuse_horizontal,air_temperature,"
        "co2,leaf_absorbed,leaf_absorbed_per_area,leaf_sunlit_fraction,leaf_net_assimilation\n";
    for (std::size_t h = 0; h < hours.size(); ++h) {
        // Each row stands for the time to the next one (the last for as long as the one before).
        double dt = 3600.0;
        if (hours.size() > 1) {
            const std::size_t k = h + 1 < hours.size() ? h : h - 1;
            dt = (daysSince2000(hours[k + 1].time) - daysSince2000(hours[k].time)) * 86400.0;
        }
        const WeatherHour& w = hours[h];
        const double co2 = w.co2 >= 0.0 ? w.co2 : 420.0;
        const SkyLight sky = skyLight(where, w);
        std::optional<LightResult> r;
        if (w.par > 0.0) r = model.compute(sky);
        double leafAbs = 0.0, leafSun = 0.0, leafNet = 0.0;
        double net = 0.0;  // the last leaf triangle's, kept for its object's next ones
        for (std::size_t i = 0; i < n; ++i) {
            const double absorbed = r ? r->absorbed[i] : 0.0;
            d.absorbed[i] += absorbed * dt;
            if (r && sky.directNormal > 0.0) d.sunlit[i] += r->sunlit[i] * dt;
            if (!d.leaf[i]) continue;
            // Leaves at the air's temperature (no energy balance yet). A triangle with the light
            // of the one before in its object (every one, sampled per object) has its rate.
            const bool same = i > 0 && d.leaf[i - 1] &&
                              model.objects()[i] == model.objects()[i - 1] &&
                              (!r || (r->absorbed[i] == r->absorbed[i - 1] &&
                                      r->absorbedDirect[i] == r->absorbedDirect[i - 1] &&
                                      r->sunlit[i] == r->sunlit[i - 1]));
            if (!same)
                net = r ? farquharSunlitShaded(leafModel, absorbed, r->absorbedDirect[i],
                                               r->sunlit[i], w.airTemperature, co2)
                              .net
                        : farquhar(leafModel, 0.0, w.airTemperature, co2).net;
            d.assimilated[i] += net * dt;
            leafAbs += absorbed * d.area[i];
            leafSun += (r ? r->sunlit[i] : 0.0) * d.area[i];
            leafNet += net * d.area[i];
        }
        if (r && sky.directNormal > 0.0) d.daylight += dt;
        d.seconds += dt;
        d.above += w.par * dt;
        d.leafAbsorbed += leafAbs * dt;
        d.leafFixed += leafNet * dt;
        d.series += fmt::format(
            "{},{:.3f},{:.3f},{:.6g},{:.6g},{:.6g},{:.4g},{:.5g},{:.6g},{:.6g},{:.4f},{:.6g}\n",
            formatUTCTime(w.time), sky.sun.elevation, sky.sun.azimuth, w.par, sky.directNormal,
            sky.diffuseHorizontal, w.airTemperature, co2, leafAbs,
            d.leafArea > 0 ? leafAbs / d.leafArea : 0.0,
            d.leafArea > 0 && sky.directNormal > 0 ? leafSun / d.leafArea : 0.0, leafNet);
    }
    return d;
}

// Per object: the time-mean absorbed PAR, its total (mol m-2), the mean sunlit share while
// the sun is up and the net assimilation (mol CO2 m-2), as object data; returns the
// leaves' rows and the largest leaf total.
std::pair<std::string, double> objectTotals(Context& ctx, const LightModel& model, const Day& d) {
    struct Sum {
        ObjectID id;
        double area = 0, absorbed = 0, sunlit = 0, assimilated = 0;
    };
    std::vector<Sum> sums;
    for (std::size_t i = 0; i < model.triangleCount(); ++i) {
        const ObjectID id = model.objects()[i];
        if (sums.empty() || sums.back().id != id) sums.push_back({id});
        sums.back().area += d.area[i];
        sums.back().absorbed += d.absorbed[i] * d.area[i];
        sums.back().sunlit += d.sunlit[i] * d.area[i];
        sums.back().assimilated += d.assimilated[i] * d.area[i];
    }
    std::string rows =
        "object_id,plant_id,area,absorbed_par,absorbed_par_total,sunlit_fraction,"
        "net_assimilation_total\n";
    double top = 0.0;
    for (const Sum& s : sums) {
        const double a = s.area > 0 ? s.area : 1.0;
        const double mol = s.absorbed / a * 1e-6;
        const double sunlit = d.daylight > 0 ? s.sunlit / a / d.daylight : 0.0;
        ctx.setObjectData(s.id, "absorbed_par", float(mol * 1e6 / d.seconds));
        ctx.setObjectData(s.id, "absorbed_par_total", float(mol));
        ctx.setObjectData(s.id, "sunlit_fraction", float(sunlit));
        if (ctx.objectDataString(s.id, "organ") != std::string("leaf")) continue;
        const double fixed = s.assimilated / a * 1e-6;
        ctx.setObjectData(s.id, "net_assimilation_total", float(fixed));
        top = std::max(top, mol);
        rows += fmt::format("{},{},{:.6g},{:.6g},{:.6g},{:.4f},{:.6g}\n", s.id,
                            ctx.objectDataInt(s.id, "plantID").value_or(-1), s.area,
                            mol * 1e6 / d.seconds, mol, sunlit, fixed);
    }
    return {rows, top};
}

// The scene in false colour by each surface's absorbed PAR over the period (the leaves'
// largest total is the top of the scale), as pictures with a scale or as meshes.
void writeFalseColour(Context& ctx, const PlantArchitecture& arch,
                      const std::vector<std::string>& outputs, std::optional<ObjectID> ground,
                      double top, const GlobalOptions& g) {
    for (ObjectID id : ctx.objectIDs()) {
        const std::optional<float> mol = ctx.objectDataFloat(id, "absorbed_par_total");
        if (!mol || (ground && id == *ground)) continue;
        ctx.setObjectMaterial(
            id, ctx.addMaterial(Material{falseColour(float(top > 0 ? *mol / top : 0.0)), "", ""}));
    }
    const PlantFileOptions files = plantFileOptions(g);
    for (const std::string& out : outputs) {
        if (lowerExtension(out) != ".png") {
            writeSceneFile(ctx, out, files, exportPlants(arch));
            continue;
        }
        if (ground) ctx.setObjectHidden(*ground, true);  // framed on the plants
        RenderOptions r;
        r.width = g.imageWidth;
        r.height = g.imageHeight;
        r.camera = g.pictureCamera;
        r.mode = RenderMode::Flat;
        Image image = render(ctx, r);
        if (ground) ctx.setObjectHidden(*ground, false);
        drawLegend(image, top, "mol/m2");
        writePNG(image, out);
    }
}

int run(const LightArgs& a, const GlobalOptions& g) {
    const std::vector<std::string> all = checkOutputs(a, g);
    const auto [lat, lon] =
        parseTwoNumbers(a.location, ',', "--location", "LAT,LON in degrees", "e.g. 38.54,-121.74");
    const Location where{lat, lon};
    sunPosition(where, UTCTime{});  // checks the place before any work
    const auto [tMin, tMax] =
        parseTwoNumbers(a.temperature, ':', "--temperature", "MIN:MAX in °C", "e.g. 15:28");
    const LightOptions o = lightOptions(a, g);
    std::vector<WeatherHour> hours;
    if (!a.weather.empty()) {
        hours = readWeatherFile(a.weather);
    } else {
        const UTCTime day = parseUTCTime(a.date);
        hours = clearSkyDay(where, day.year, day.month, day.day, a.clearness, tMin, tMax);
    }
    CommandOutputs outputs(all);
    if (!a.weather.empty()) outputs.requireNotAnInput(a.weather, "--weather");

    const auto started = std::chrono::steady_clock::now();
    Context ctx;
    PlantArchitecture arch(&ctx);
    const auto [plants, ground] = buildScene(a, g, arch, ctx);
    const LightModel model(ctx, o);
    const Day d = simulate(model, ctx, where, hours);
    const auto [leafRows, top] = objectTotals(ctx, model, d);
    if (!a.series.empty()) writeWholeFile(a.series, d.series);
    if (!a.leaves.empty()) writeWholeFile(a.leaves, leafRows);
    if (!a.outputs.empty()) writeFalseColour(ctx, arch, a.outputs, ground, top, g);
    outputs.commit();
    std::printf(
        "%s",
        fmt::format("light on {} ({} plant(s), {} days) at {:.2f}, {:.2f} over {} interval(s), "
                    "{:.1f} h of sun: {:.1f} mol m-2 of PAR above, the leaves ({:.3f} m2) "
                    "absorbed {:.2f} mol ({:.1f} mol m-2 of leaf) and fixed {:.3f} mol CO2 net; "
                    "{} triangles, {} rays in {:.2f} s.\n",
                    arch.getCurrentPlantModel(), plants.size(), a.age, lat, lon, hours.size(),
                    d.daylight / 3600.0, d.above * 1e-6, d.leafArea, d.leafAbsorbed * 1e-6,
                    d.leafArea > 0 ? d.leafAbsorbed * 1e-6 / d.leafArea : 0.0, d.leafFixed * 1e-6,
                    model.triangleCount(), model.raysCast(), millisecondsSince(started) / 1000.0)
            .c_str());
    return 0;
}

std::function<int()> setupLight(CLI::App& app, GlobalOptions& global) {
    app.description(
        "The PAR a plant or canopy absorbs over a clear day or a weather file (ray traced): "
        "hourly series, per leaf, false colour");
    auto a = std::make_shared<LightArgs>();
    app.add_option("species", a->species, "Library species name or species file (.xml)")
        ->required();
    app.add_option("--age", a->age, "Plant age in days (0 to 100000)")->check(daysCheck("--age"));
    app.add_option("--count", a->count, "A grid canopy: plants along x and y, e.g. 10x10");
    app.add_option("--spacing", a->spacing, "Canopy spacing along x and y in m (default 0.3x0.3)");
    app.add_option("-D", a->defines, "Build parameter override, name=value (repeatable)");
    app.add_flag("--no-trellis", a->noTrellis, "Leave out the species' trellis");
    app.add_option("--location", a->location, "LAT,LON in degrees (north and east positive)")
        ->required();
    app.add_option("--date", a->date, "A clear day, YYYY-MM-DD (its 24 UTC hours)");
    app.add_option("--clearness", a->clearness,
                   "With --date: global radiation over that above the atmosphere (default 0.75)")
        ->check(numberCheck("--clearness", "a share", 0.0, 1.0, false, "0 to 1"));
    app.add_option("--temperature", a->temperature,
                   "With --date: the day's air temperature MIN:MAX in °C (default 15:28)");
    app.add_option("--weather", a->weather,
                   "Weather file (CSV: time, par or global_radiation, air_temperature, ...)");
    app.add_option("--rays", a->rays,
                   "Rays per triangle (per sample with --samples) DIRECT,DIFFUSE,SCATTER (default "
                   "4,64,32)");
    app.add_option("--samples", a->samples,
                   "Sample the light per object from N of its triangles (1 to 100000; default 0: "
                   "every triangle)")
        ->check(numberCheck("--samples", "triangles", 0, 100000, true, "0 to 100000"));
    app.add_flag("--no-scattering", a->noScattering,
                 "Leaves and ground absorb or lose what they do not absorb (no scattered light)");
    app.add_flag("--no-ground", a->noGround, "No soil under the plants");
    app.add_option("--series", a->series, "Hourly series (.csv): sun, sky, leaf light");
    app.add_option("--leaves", a->leaves, "Per leaf (.csv): area, absorbed PAR, sunlit share");
    app.add_option("-o,--output", a->outputs,
                   std::string("False colour of the absorbed PAR: ") + kLightOutputs);
    addImageSizeOption(app, global);
    return [a, &global] { return run(*a, global); };
}

}  // namespace

PLANTARCH_REGISTER_COMMAND(light, "light", 53, setupLight);

}  // namespace plantarch::cli
