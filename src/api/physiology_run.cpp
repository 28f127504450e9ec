// growPhysiology: light, photosynthesis and the budgets day by day (plantarch/Physiology.h),
// and the records' CSV.

#include <cmath>
#include <map>
#include <type_traits>

#include "core/atomic_file.h"
#include "core/value_text.h"
#include "model/carbon_costs.h"
#include "plant_io/plant_structure.h"
#include "plantarch/Error.h"
#include "plantarch/Photosynthesis.h"
#include "plantarch/Physiology.h"
#include "plantarch/PlantArchitecture.h"

namespace plantarch {

// ---- the records -----------------------------------------------------------------------------

namespace {

// The one list of the record's columns: name and member.
struct Column {
    const char* name;
    double (*get)(const PhysiologyRecord&);
};

constexpr Column kColumns[] = {
    {"plant", [](const PhysiologyRecord& r) { return double(r.plant); }},
    {"age", [](const PhysiologyRecord& r) { return r.age; }},
    {"days", [](const PhysiologyRecord& r) { return r.days; }},
    {"leaf_area", [](const PhysiologyRecord& r) { return r.leafArea; }},
    {"absorbed_par", [](const PhysiologyRecord& r) { return r.absorbedPar; }},
    {"temperature", [](const PhysiologyRecord& r) { return r.temperature; }},
    {"input", [](const PhysiologyRecord& r) { return r.input; }},
    {"maintenance", [](const PhysiologyRecord& r) { return r.maintenance; }},
    {"growth", [](const PhysiologyRecord& r) { return r.growth; }},
    {"growth_respiration", [](const PhysiologyRecord& r) { return r.growthRespiration; }},
    {"root_growth", [](const PhysiologyRecord& r) { return r.rootGrowth; }},
    {"losses", [](const PhysiologyRecord& r) { return r.losses; }},
    {"sugar", [](const PhysiologyRecord& r) { return r.sugar; }},
    {"starch", [](const PhysiologyRecord& r) { return r.starch; }},
    {"shoots_pruned", [](const PhysiologyRecord& r) { return double(r.shootsPruned); }},
    {"buds_aborted", [](const PhysiologyRecord& r) { return double(r.budsAborted); }},
    {"nitrogen_available", [](const PhysiologyRecord& r) { return r.nitrogenAvailable; }},
    {"nitrogen_in_leaves", [](const PhysiologyRecord& r) { return r.nitrogenInLeaves; }},
    {"nitrogen_uptake", [](const PhysiologyRecord& r) { return r.nitrogenUptake; }},
    {"nitrogen_remobilised", [](const PhysiologyRecord& r) { return r.nitrogenRemobilised; }},
    {"nitrogen_lost", [](const PhysiologyRecord& r) { return r.nitrogenLost; }},
    {"nitrogen_to_fruit", [](const PhysiologyRecord& r) { return r.nitrogenToFruit; }},
    {"nitrogen_shed", [](const PhysiologyRecord& r) { return r.nitrogenShed; }},
    {"nitrogen_stress", [](const PhysiologyRecord& r) { return r.nitrogenStress; }},
};

}  // namespace

std::vector<std::string> physiologyColumns() {
    std::vector<std::string> names;
    for (const Column& c : kColumns) names.emplace_back(c.name);
    return names;
}

std::vector<double> physiologyValues(const PhysiologyRecord& record) {
    std::vector<double> values;
    for (const Column& c : kColumns) values.push_back(c.get(record));
    return values;
}

void writePhysiologyCSV(const std::string& path, const std::vector<PhysiologyRecord>& records) {
    io::AtomicFile out(path);
    std::string line;
    for (const Column& c : kColumns) line += std::string(line.empty() ? "" : ",") + c.name;
    out.write(line + "\n");
    for (const PhysiologyRecord& r : records) {
        line.clear();
        for (const Column& c : kColumns) {
            if (!line.empty()) line += ',';
            line += text::formatDouble(c.get(r));
        }
        out.write(line + "\n");
    }
    out.commit();
}

// ---- the driver ------------------------------------------------------------------------------

namespace {

// A leaf object and what its photosynthesis depends on.
struct LeafInfo {
    unsigned plant = 0;
    FarquharParameters farquhar;
};

// Every leaf object of every plant whose budget runs, with its species' capacities scaled by
// its nitrogen (capacity in proportion to N per area over the target, at most 1).
std::map<ObjectID, LeafInfo> leafObjects(const PlantArchitecture& arch) {
    std::map<ObjectID, LeafInfo> leaves;
    const Context& ctx = arch.context();
    for (unsigned id : arch.getAllPlantIDs()) {
        if (!arch.hasCarbohydrateModel(id)) continue;
        const PlantInstance& plant = arch.plant(id);
        const LeafPhysiologyParameters& lp = plant.phenology.leaf_physiology;
        for (const Shoot& s : plant.shoots) {
            if (s.removed) continue;
            for (const Phytomer& ph : s.phytomers)
                for (const Petiole& pt : ph.petioles)
                    for (const LeafOrgan& l : pt.leaves) {
                        if (l.removed || l.objects.empty()) continue;
                        double area = 0.0;
                        for (ObjectID o : l.objects)
                            if (ctx.doesObjectExist(o)) area += ctx.objectArea(o);
                        double capacity = 1.0;
                        if (l.nitrogen && area > 0.0)
                            capacity = std::clamp(l.nitrogen->content / area /
                                                      plant.phenology.nitrogen.target_leaf_nitrogen,
                                                  0.0, 1.0);
                        LeafInfo info{id, {}};
                        info.farquhar.vcmax25 = lp.vcmax25 * capacity;
                        info.farquhar.jmax25 = lp.jmax25 * capacity;
                        info.farquhar.rd25 = lp.rd25;
                        if (info.farquhar.vcmax25 <= 0.0) info.farquhar.vcmax25 = 1e-6;
                        if (info.farquhar.jmax25 <= 0.0) info.farquhar.jmax25 = 1e-6;
                        for (ObjectID o : l.objects)
                            if (ctx.doesObjectExist(o)) leaves[o] = info;
                    }
        }
    }
    return leaves;
}

// Light per object (area-weighted over its triangles): absorbed, direct part, sunlit share.
struct ObjectLight {
    double area = 0.0, absorbed = 0.0, direct = 0.0, sunlit = 0.0;
};

std::map<ObjectID, ObjectLight> perObject(const LightModel& model, const LightResult& result,
                                          const std::map<ObjectID, LeafInfo>& leaves) {
    std::map<ObjectID, ObjectLight> out;
    const auto& objects = model.objects();
    const auto& areas = model.areas();
    for (std::size_t i = 0; i < objects.size(); ++i) {
        if (!leaves.count(objects[i])) continue;
        ObjectLight& o = out[objects[i]];
        const double a = areas[i];
        o.area += a;
        o.absorbed += a * result.absorbed[i];
        o.direct += a * result.absorbedDirect[i];
        o.sunlit += a * result.sunlit[i];
    }
    for (auto& [id, o] : out)
        if (o.area > 0.0) {
            o.absorbed /= o.area;
            o.direct /= o.area;
            o.sunlit /= o.area;
        }
    return out;
}

long dayNumber(const UTCTime& t) {
    return long(std::floor(daysSince2000(UTCTime{t.year, t.month, t.day, 0.0}) + 0.5));
}

// A leaf's light and photosynthesis over a day, for its object data.
struct LeafDay {
    double absorbed = 0.0, sunlit = 0.0, net = 0.0;  // sums over the daylight hours
    double netAll = 0.0;                             // over every hour
    unsigned daylightHours = 0, hours = 0;
};

// The day's means on each leaf object still there (`absorbed_par`, `sunlit_fraction`,
// `net_photosynthesis`: over the daylight hours, or the night's respiration on a day without
// light) and every organ's `carbohydrate_concentration`: its shoot's pool over its wood.
void writeDayData(PlantArchitecture& arch, const std::map<ObjectID, LeafDay>& days) {
    Context& ctx = arch.context();
    for (const auto& [id, d] : days) {
        if (!ctx.doesObjectExist(id) || d.hours == 0) continue;
        const double n = std::max(1u, d.daylightHours);
        ctx.setObjectData(id, "absorbed_par", float(d.absorbed / n));
        ctx.setObjectData(id, "sunlit_fraction", float(d.sunlit / n));
        ctx.setObjectData(id, "net_photosynthesis",
                          float(d.daylightHours > 0 ? d.net / n : d.netAll / d.hours));
    }
    for (unsigned plantID : arch.getAllPlantIDs()) {
        if (!arch.hasCarbohydrateModel(plantID)) continue;
        const PlantInstance& plant = arch.plant(plantID);
        const CarbohydrateParameters& p = plant.phenology.carbohydrates;
        for (const Shoot& s : plant.shoots) {
            if (s.removed || !s.carbon) continue;
            double volume = 0.0;
            for (const Phytomer& ph : s.phytomers) {
                const double r = ph.internode.radius;
                volume += M_PI * r * r * double(ph.internode.length) * ph.internodeFraction;
            }
            const float concentration =
                float((s.carbon->sugar + s.carbon->starch) / carbon::amount(p, 1.0, volume));
            auto set = [&](ObjectID o) {
                if (o != kNoObject && ctx.doesObjectExist(o))
                    ctx.setObjectData(o, "carbohydrate_concentration", concentration);
            };
            plant_io::forEachShootObjectMember(s, [&](const auto& member) {
                if constexpr (std::is_same_v<std::decay_t<decltype(member)>, ObjectID>)
                    set(member);
                else
                    for (ObjectID o : member) set(o);
            });
        }
    }
}

// One day: the hours' light and photosynthesis into the budgets' inputs, then a day of growth.
void simulateDay(PlantArchitecture& arch, const std::vector<WeatherHour>& hours,
                 const PhysiologyOptions& options) {
    const std::map<ObjectID, LeafInfo> leaves = leafObjects(arch);
    const double hoursEach = 24.0 / double(hours.size());
    bool daylight = false;
    double temperature = 0.0;
    for (const WeatherHour& h : hours) {
        daylight = daylight || h.par > 0.0;
        temperature += h.airTemperature / double(hours.size());
    }
    // The scene's leaves take the optics of the first plant with a budget.
    LightOptions optics = options.light;
    if (!leaves.empty()) {
        const LeafPhysiologyParameters& lp =
            arch.plant(leaves.begin()->second.plant).phenology.leaf_physiology;
        optics.leaf = {lp.leaf_reflectance, lp.leaf_transmittance};
    }
    std::unique_ptr<LightModel> model;
    if (daylight && !leaves.empty()) model = std::make_unique<LightModel>(arch.context(), optics);
    std::map<ObjectID, ObjectLight> light;
    std::map<ObjectID, LeafDay> day;
    double lightPar = 0.0;
    unsigned sinceLight = options.lightEvery;
    for (const WeatherHour& h : hours) {
        const double co2 = h.co2 > 0.0 ? h.co2 : options.co2;
        double scale = 0.0;
        if (h.par > 0.0 && model) {
            if (sinceLight >= options.lightEvery) {
                light = perObject(*model, model->compute(skyLight(options.location, h)), leaves);
                lightPar = h.par;
                sinceLight = 0;
            }
            ++sinceLight;
            scale = h.par / lightPar;
        }
        std::map<ObjectID, double> rates;
        std::map<unsigned, double> absorbed;
        for (const auto& [id, info] : leaves) {
            auto it = light.find(id);
            if (scale > 0.0 && it != light.end()) {
                const ObjectLight& o = it->second;
                rates[id] = farquharSunlitShaded(info.farquhar, o.absorbed * scale,
                                                 o.direct * scale, o.sunlit, h.airTemperature, co2)
                                .net;
                absorbed[info.plant] += o.absorbed * scale * o.area * hoursEach * 3600.0 * 1e-6;
            } else {
                rates[id] = farquhar(info.farquhar, 0.0, h.airTemperature, co2).net;
            }
            LeafDay& d = day[id];
            ++d.hours;
            d.netAll += rates[id];
            if (h.par > 0.0) {
                ++d.daylightHours;
                d.net += rates[id];
                if (scale > 0.0 && it != light.end()) {
                    d.absorbed += it->second.absorbed * scale;
                    d.sunlit += it->second.sunlit;
                }
            }
        }
        arch.addLeafPhotosynthesis(rates, hoursEach);
        for (const auto& [plant, mol] : absorbed) arch.addAbsorbedLight(plant, mol);
    }
    arch.setAirTemperature(std::clamp(temperature, -50.0, 60.0));
    arch.advanceTime(1.0);
    writeDayData(arch, day);
}

}  // namespace

std::vector<PhysiologyRecord> growPhysiology(PlantArchitecture& arch,
                                             const std::vector<WeatherHour>& weather,
                                             const PhysiologyOptions& options) {
    if (weather.empty()) throw Error("the weather has no hours: nothing to grow through");
    if (options.lightEvery < 1 || options.lightEvery > 24)
        throw Error("light every N hours must be from 1 to 24",
                    {.parameter = "lightEvery",
                     .value = std::to_string(options.lightEvery),
                     .validRange = "1 to 24"});
    // The hours by date, the dates consecutive.
    std::vector<std::vector<WeatherHour>> days;
    long last = 0;
    for (const WeatherHour& h : weather) {
        const long d = dayNumber(h.time);
        if (days.empty() || d != last) {
            if (!days.empty() && d != last + 1)
                throw Error("the weather skips from " + formatUTCTime(days.back().back().time) +
                            " to " + formatUTCTime(h.time) +
                            ": each date from the first to the last needs its hours");
            days.emplace_back();
            last = d;
        }
        days.back().push_back(h);
    }
    // Plants whose species switch the models on get them now.
    for (unsigned id : arch.getAllPlantIDs()) {
        const PhenologyParameters& ph = arch.plant(id).phenology;
        if (ph.carbohydrates.enabled && !arch.hasCarbohydrateModel(id))
            arch.enableCarbohydrateModel(id);
        if (ph.nitrogen.enabled && !arch.hasNitrogenModel(id)) arch.enableNitrogenModel(id);
    }
    std::vector<PhysiologyRecord> records;
    for (const auto& hours : days) {
        std::map<unsigned, std::size_t> before;
        for (unsigned id : arch.getAllPlantIDs()) before[id] = arch.getPhysiologyRecords(id).size();
        simulateDay(arch, hours, options);
        for (unsigned id : arch.getAllPlantIDs()) {  // the day's new records (none once dead)
            const auto& r = arch.getPhysiologyRecords(id);
            records.insert(records.end(), r.begin() + std::ptrdiff_t(before[id]), r.end());
        }
    }
    return records;
}

}  // namespace plantarch
