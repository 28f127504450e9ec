#pragma once
// Weather, the sun, and the photosynthetically active radiation (PAR) every surface of a
// scene absorbs: direct light from the sun, diffuse light from a sky divided into the 145
// patches of Tregenza (1987), and one order of scattering by leaves and the ground, all
// traced with rays through every triangle of a Context (plants, obstacles, ground).
//
// Units: PAR in micromoles of photons per square metre per second (µmol m⁻² s⁻¹), absorbed
// PAR per square metre of one-sided surface; angles in degrees; times in UTC. Directions:
// x east, y north, z up. docs/physiology.md describes the model and its sources.

#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "plantarch/Context.h"
#include "plantarch/Mesh.h"

namespace plantarch {

// ---- time, place and the sun ----------------------------------------------------------

/// A moment in Coordinated Universal Time.
struct UTCTime {
    int year = 2000;
    int month = 1;      ///< 1 to 12
    int day = 1;        ///< 1 to the month's length
    double hour = 0.0;  ///< 0 to 24 (fractional: 12.5 is 12:30)
};

/// Reads "YYYY-MM-DDTHH:MM" (or a space for the T, with optional ":SS" and a trailing "Z"; a
/// date alone is midnight). Throws plantarch::Error naming what is wrong.
UTCTime parseUTCTime(std::string_view text);
/// "YYYY-MM-DDTHH:MM:SSZ".
std::string formatUTCTime(const UTCTime& time);
/// Days since 2000-01-01T00:00Z (negative before it).
double daysSince2000(const UTCTime& time);

/// A place on the Earth, degrees: latitude north (-90 to 90), longitude east (-180 to 180).
struct Location {
    double latitude = 0.0;
    double longitude = 0.0;
};

/// Where the sun stands, as seen from a place at a moment.
struct SunPosition {
    double elevation = 90.0;  ///< above the horizon, degrees (negative: below it)
    double azimuth = 180.0;   ///< clockwise from north, degrees (90: east)
    /// Unit vector toward the sun: x east, y north, z up.
    vec3 direction() const;
};

/// The sun's position from the NOAA solar calculator's equations (after Meeus, Astronomical
/// Algorithms), for the years 1900 to 2100, without atmospheric refraction.
/// Throws plantarch::Error for a location or time out of range.
SunPosition sunPosition(const Location& where, const UTCTime& when);

/// Solar irradiance above the atmosphere on a horizontal surface, W m⁻²: the solar constant
/// 1361 W m⁻² corrected for the Earth's distance from the sun, times the sine of the sun's
/// elevation (0 when the sun is down).
double extraterrestrialHorizontal(const UTCTime& when, double elevation);

/// The diffuse share of global radiation from the hourly clearness index kt (global over
/// extraterrestrial horizontal) by the correlation of Erbs, Klein and Duffie (1982).
double erbsDiffuseFraction(double clearnessIndex);

/// PAR photons per joule of global (shortwave) radiation, µmol J⁻¹: PAR is taken as 0.5 of
/// global radiation and sunlight's PAR carries 4.57 µmol J⁻¹ (McCree 1972).
inline constexpr double kParPerGlobal = 2.285;

// ---- weather --------------------------------------------------------------------------

/// One hour of weather (or any interval: the time is its middle).
struct WeatherHour {
    UTCTime time;
    double par = 0.0;  ///< PAR on a horizontal surface above the scene, µmol m⁻² s⁻¹
    double diffuseFraction = -1.0;   ///< the diffuse share of par; negative: from the Erbs model
    double airTemperature = 20.0;    ///< °C
    double relativeHumidity = -1.0;  ///< %, negative when not given
    double vpd = -1.0;               ///< vapour pressure deficit, kPa, negative when not given
    double co2 = -1.0;               ///< ppm, negative when not given
    double wind = -1.0;              ///< m s⁻¹, negative when not given
};

/// Reads a weather file: CSV with a header line naming its columns, one row per interval.
/// Columns: `time` (UTC, as parseUTCTime reads it), `par` (µmol m⁻² s⁻¹) or
/// `global_radiation` (W m⁻², turned into PAR with kParPerGlobal), `air_temperature` (°C),
/// and optionally `diffuse_fraction` (0 to 1), `relative_humidity` (%), `vpd` (kPa), `co2`
/// (ppm), `wind_speed` (m s⁻¹). Lines starting with '#' are comments. Strict: an unknown or
/// repeated column, a missing value, a value that is not a finite number or is out of its
/// range, or times that do not increase throw plantarch::Error with the file, line and
/// column. Checked and size-limited as every input file is (InputFiles.h).
std::vector<WeatherHour> readWeatherFile(const std::string& path);

/// A cloudless day at a place, one entry per hour of the UTC day (the middle of each hour):
/// global radiation = clearness × extraterrestrial horizontal, PAR from it, the diffuse share
/// from the Erbs model; the air temperature a sine between tMin (at sunrise, 06:00 solar
/// time) and tMax (14:00 solar time). Throws plantarch::Error for values out of range.
std::vector<WeatherHour> clearSkyDay(const Location& where, int year, int month, int day,
                                     double clearness = 0.75, double tMin = 15.0,
                                     double tMax = 28.0);

/// The light of one weather interval, split for the ray tracer.
struct SkyLight {
    SunPosition sun;
    double directNormal = 0.0;       ///< PAR on a surface facing the sun, µmol m⁻² s⁻¹
    double diffuseHorizontal = 0.0;  ///< PAR from the sky on a horizontal surface
};

/// Splits an interval's PAR into direct and diffuse light with the sun's position at its
/// time: the diffuse share is the interval's own or the Erbs model's; with the sun below
/// the horizon (or under 1 degree above it) all of it is diffuse.
SkyLight skyLight(const Location& where, const WeatherHour& hour);

// ---- light on every surface -----------------------------------------------------------

/// How a kind of surface returns PAR: the shares reflected and transmitted (the rest,
/// 1 - reflectance - transmittance, is absorbed).
struct SurfaceOptics {
    float reflectance = 0.0f;
    float transmittance = 0.0f;
};

struct LightOptions {
    unsigned directRays = 4;        ///< rays per triangle toward the sun (its sunlit share)
    unsigned diffuseRays = 64;      ///< rays per triangle to the sky patches
    unsigned scatterRays = 32;      ///< rays per triangle gathering light scattered by others
    unsigned scatteringOrders = 1;  ///< 0 (absorbed at first hit) or 1
    /// Leaves: 0.85 absorbed (a typical green leaf in PAR).
    SurfaceOptics leaf{0.10f, 0.05f};
    /// Internodes, petioles and peduncles.
    SurfaceOptics stem{0.10f, 0.0f};
    /// Flowers and fruit.
    SurfaceOptics flowerAndFruit{0.20f, 0.0f};
    /// Objects labelled ground (organ "ground"), soil in PAR.
    SurfaceOptics ground{0.10f, 0.0f};
    /// Everything else: obstacles, trellises, unlabelled objects.
    SurfaceOptics other{0.10f, 0.0f};
    std::uint64_t seed = 0;  ///< the rays' jitter (same seed, same result, any thread count)
    /// 0: every triangle casts the rays above and has light of its own. N (1 to 100000):
    /// the light is sampled per object: each object casts them from N of its triangles,
    /// drawn in proportion to their area (stratified, from the seed and the object's ID),
    /// or from each of its triangles when it has N or fewer, and every triangle of the
    /// object gets the object's area-weighted mean. Photosynthesis needs no more; a leaf
    /// of a hundred triangles costs a tenth of the rays with 8.
    unsigned samplesPerObject = 0;
};

/// Light per triangle, in the model's triangle order (LightModel::primitives()); with
/// LightOptions::samplesPerObject, each triangle holds its object's mean.
struct LightResult {
    /// PAR absorbed per square metre of the triangle (one side), µmol m⁻² s⁻¹.
    std::vector<float> absorbed;
    /// The share of the triangle's sampled points that see the sun (0 with the sun down).
    std::vector<float> sunlit;
    /// PAR arriving on the triangle (both sides, before absorption), µmol m⁻² s⁻¹.
    std::vector<float> incident;
    /// The part of `absorbed` that came straight from the sun (over the whole triangle: on
    /// its sunlit share it is this over `sunlit`).
    std::vector<float> absorbedDirect;
};

/// The visible triangles of a Context as one ray-tracing scene. Build it once per geometry
/// and compute the light of many skies with it: the sky's view from each triangle is traced
/// once and kept. Const methods may run concurrently.
class LightModel {
public:
    /// Every visible object's triangles; each object's kind of surface from its "organ" data.
    /// Throws plantarch::Error for options out of range (rays 1 to 100000, samples per object
    /// 0 to 100000, scattering order 0 or 1, optical shares from 0 to 1 with reflectance +
    /// transmittance at most 1), and before any work when the model would take more than
    /// half of the machine's memory (about 200 bytes a triangle and 8 for each scattering
    /// ray).
    explicit LightModel(const Context& context, const LightOptions& options = {});
    ~LightModel();
    LightModel(const LightModel&) = delete;
    LightModel& operator=(const LightModel&) = delete;

    /// The light of one sky on every triangle. Uses the threads OpenMP gives it; the result
    /// does not depend on their number.
    LightResult compute(const SkyLight& sky) const;

    /// The Context primitive ID of each triangle, in the result's order.
    const std::vector<PrimitiveID>& primitives() const;
    /// Each triangle's object, in the result's order.
    const std::vector<ObjectID>& objects() const;
    /// Each triangle's area (m², one side) as it was when the model was built.
    const std::vector<float>& areas() const;
    /// The number of triangles lit (degenerate ones are left out).
    std::size_t triangleCount() const;
    /// The number of triangles the rays are cast from: triangleCount(), or the objects'
    /// samples with LightOptions::samplesPerObject.
    std::size_t sampleCount() const;
    /// Rays cast so far (all computations), for measuring.
    std::uint64_t raysCast() const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

/// Writes a result as object data on the objects it covers, area-weighted over each object's
/// triangles: `absorbed_par` (µmol m⁻² s⁻¹) and `sunlit_fraction` (float), replacing any
/// values there. Throws plantarch::Error for a result of another model or a Context that no
/// longer holds the model's triangles.
void writeLightData(Context& context, const LightModel& model, const LightResult& result);

}  // namespace plantarch
