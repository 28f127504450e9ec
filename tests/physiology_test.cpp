// The carbohydrate budget and the nitrogen model (plantarch/Physiology.h): the balance closes,
// light drives growth, a plant in the dark dies, nitrogen stress shrinks leaves.

#include "plantarch/Physiology.h"

#include <gtest/gtest.h>
#include <omp.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "error_of.h"
#include "plantarch/Context.h"
#include "plantarch/Error.h"
#include "plantarch/PlantArchitecture.h"

using namespace plantarch;

namespace {

// The message of the plantarch::Error `call` throws contains `text`.
#define EXPECT_THAT_ERROR(call, text)                                                    \
    EXPECT_NE(std::string(plantarch::testing::errorOf([&] { call; }).what()).find(text), \
              std::string::npos)                                                         \
        << plantarch::testing::errorOf([&] { call; }).what()

const Location kDavis{38.55, -121.74};

// `days` cloudless days from 1 June.
std::vector<WeatherHour> summer(int days, double clearness = 0.75) {
    std::vector<WeatherHour> hours;
    for (int d = 0; d < days; ++d) {
        const int month = 6 + (d >= 30 ? 1 : 0) + (d >= 61 ? 1 : 0);
        const int day = d < 30 ? d + 1 : d < 61 ? d - 29 : d - 60;
        for (const WeatherHour& h : clearSkyDay(kDavis, 2026, month, day, clearness))
            hours.push_back(h);
    }
    return hours;
}

std::vector<WeatherHour> darkness(int days) {
    std::vector<WeatherHour> hours = summer(days);
    for (WeatherHour& h : hours) h.par = 0.0;
    return hours;
}

double pools(const PlantInstance& plant) {
    double sum = 0.0;
    for (const Shoot& s : plant.shoots)
        if (!s.removed && s.carbon) sum += s.carbon->sugar + s.carbon->starch;
    return sum;
}

unsigned liveShoots(const PlantInstance& plant) {
    unsigned n = 0;
    for (const Shoot& s : plant.shoots) n += s.removed ? 0 : 1;
    return n;
}

unsigned nodes(const PlantInstance& plant) {
    unsigned n = 0;
    for (const Shoot& s : plant.shoots)
        if (!s.removed) n += unsigned(s.phytomers.size());
    return n;
}

PhysiologyOptions options() {
    PhysiologyOptions o;
    o.location = kDavis;
    o.light.directRays = 2;
    o.light.diffuseRays = 16;
    o.light.scatterRays = 8;
    o.light.scatteringOrders = 0;
    return o;
}

// The change in a plant's pools over each record equals its fluxes.
void expectBalanceCloses(const std::vector<PhysiologyRecord>& records, double start) {
    double before = start;
    for (const PhysiologyRecord& r : records) {
        const double after = r.sugar + r.starch;
        const double fluxes = r.input - r.maintenance - r.growth - r.growthRespiration - r.losses;
        EXPECT_NEAR(after - before, fluxes, 1e-9 * (1.0 + std::abs(before) + r.input))
            << "at age " << r.age;
        before = after;
    }
}

}  // namespace

TEST(Carbon, TheBalanceClosesOverASeasonInTheLight) {
    Context ctx;
    PlantArchitecture arch(&ctx);
    arch.loadPlantModelFromLibrary("bean");
    const unsigned id = arch.buildPlantInstanceFromLibrary(vec3(0.0f), 10.0f);
    arch.enableCarbohydrateModel(id);
    const double start = pools(arch.plant(id));
    EXPECT_GT(start, 0.0);
    const auto records = growPhysiology(arch, summer(40), options());
    ASSERT_EQ(records.size(), 40u);
    expectBalanceCloses(records, start);
    double input = 0.0, growth = 0.0;
    for (const auto& r : records) {
        input += r.input;
        growth += r.growth;
        EXPECT_GT(r.absorbedPar, 0.0);
    }
    EXPECT_GT(input, 0.0);
    EXPECT_GT(growth, 0.0);
    EXPECT_GT(liveShoots(arch.plant(id)), 0u);
    EXPECT_NEAR(records.back().age, 50.0, 1e-9);
    // The last day's light and carbon are on the organs (the builder colours by them). Leaves
    // that grew after the day's light have none; the rest have all three.
    std::size_t lit = 0;
    const auto leaves = arch.getPlantObjectIDs(id, OrganKind::Leaf);
    for (ObjectID o : leaves) {
        if (!ctx.hasObjectData(o, "absorbed_par")) continue;
        ++lit;
        EXPECT_GT(ctx.objectDataFloat(o, "absorbed_par").value_or(-1.0f), 0.0f);
        const float sunlit = ctx.objectDataFloat(o, "sunlit_fraction").value_or(-1.0f);
        EXPECT_TRUE(sunlit >= 0.0f && sunlit <= 1.0f) << sunlit;
        EXPECT_TRUE(std::isfinite(ctx.objectDataFloat(o, "net_photosynthesis").value_or(-1.0f)));
    }
    EXPECT_GT(lit, leaves.size() * 8 / 10) << lit << " of " << leaves.size();
    for (ObjectID o : arch.getAllPlantObjectIDs(id)) {
        ASSERT_TRUE(ctx.hasObjectData(o, "carbohydrate_concentration")) << o;
        EXPECT_GE(ctx.objectDataFloat(o, "carbohydrate_concentration").value_or(-1.0f), 0.0f);
    }
}

TEST(Carbon, APlantInTheDarkLosesShootsAndDies) {
    Context ctx;
    PlantArchitecture arch(&ctx);
    arch.loadPlantModelFromLibrary("bean");
    const unsigned id = arch.buildPlantInstanceFromLibrary(vec3(0.0f), 25.0f);
    arch.enableCarbohydrateModel(id);
    const double start = pools(arch.plant(id));
    const auto records = growPhysiology(arch, darkness(60), options());
    expectBalanceCloses(records, start);
    unsigned pruned = 0;
    double losses = 0.0;
    for (const auto& r : records) {
        pruned += r.shootsPruned;
        losses += r.losses;
        EXPECT_LE(r.input, 0.0);  // leaves only respire
    }
    EXPECT_GT(pruned, 1u);
    EXPECT_NE(losses, 0.0);
    EXPECT_EQ(liveShoots(arch.plant(id)), 0u);
    EXPECT_EQ(arch.getPlantObjectIDs(id, OrganKind::Leaf).size(), 0u);
}

TEST(Carbon, AShadedPlantFixesLessMakesFewerNodesAndAbortsMore) {
    auto grow = [](bool shaded, double& fixed, unsigned& aborted) {
        Context ctx;
        PlantArchitecture arch(&ctx);
        arch.loadPlantModelFromLibrary("bean");
        const unsigned id = arch.buildPlantInstanceFromLibrary(vec3(0.0f), 40.0f);
        arch.enableCarbohydrateModel(id);
        if (shaded) {  // a shade net 1 m up, 6 m square, that lets 10% through
            const std::vector<vec3> p{{-3, -3, 1}, {3, -3, 1}, {3, 3, 1}, {-3, 3, 1}};
            const std::vector<std::uint32_t> idx{0, 1, 2, 0, 2, 3};
            ctx.addObject(p, {}, idx);
        }
        PhysiologyOptions o = options();
        o.lightEvery = 6;
        o.light.other = {0.1f, 0.1f};
        o.light.scatteringOrders = 1;  // the light the net lets through
        o.light.diffuseRays = 8;
        o.light.scatterRays = 4;
        const auto records = growPhysiology(arch, summer(40), o);
        fixed = 0.0;
        aborted = 0;
        for (const auto& r : records) {
            fixed += r.input;
            aborted += r.budsAborted;
        }
        return nodes(arch.plant(id));
    };
    double openFixed = 0.0, shadeFixed = 0.0;
    unsigned openAborted = 0, shadeAborted = 0;
    const unsigned openNodes = grow(false, openFixed, openAborted);
    const unsigned shadeNodes = grow(true, shadeFixed, shadeAborted);
    EXPECT_LT(shadeFixed, 0.5 * openFixed);
    EXPECT_LT(shadeNodes, openNodes);
    EXPECT_GT(shadeAborted, openAborted);
    std::printf(
        "open: %.3f mol C, %u nodes, %u aborted; shaded: %.3f mol C, %u nodes, %u aborted\n",
        openFixed, openNodes, openAborted, shadeFixed, shadeNodes, shadeAborted);
}

TEST(Carbon, TheSameRecordsForAnyThreadCount) {
    auto run = [](int threads) {
        omp_set_num_threads(threads);
        Context ctx;
        PlantArchitecture arch(&ctx);
        arch.loadPlantModelFromLibrary("bean");
        const unsigned id = arch.buildPlantInstanceFromLibrary(vec3(0.0f), 12.0f);
        arch.enableCarbohydrateModel(id);
        arch.enableNitrogenModel(id);
        arch.addPlantNitrogen(id, 0.5);
        std::vector<std::vector<double>> rows;
        for (const auto& r : growPhysiology(arch, summer(5), options()))
            rows.push_back(physiologyValues(r));
        return rows;
    };
    const auto one = run(1);
    const auto two = run(2);
    omp_set_num_threads(2);
    EXPECT_EQ(one, two);
}

TEST(Carbon, MeasuredRatesThroughTheApiFeedTheBudget) {
    Context ctx;
    PlantArchitecture arch(&ctx);
    arch.loadPlantModelFromLibrary("bean");
    const unsigned id = arch.buildPlantInstanceFromLibrary(vec3(0.0f), 20.0f);
    arch.enableCarbohydrateModel(id);
    const double start = pools(arch.plant(id));
    std::map<ObjectID, double> rates;
    double area = 0.0;
    for (ObjectID o : arch.getPlantObjectIDs(id, OrganKind::Leaf)) {
        rates[o] = 10.0;
        area += ctx.objectArea(o);
    }
    arch.addLeafPhotosynthesis(rates, 12.0);
    arch.advanceTime(id, 1.0);
    const auto& records = arch.getPhysiologyRecords(id);
    ASSERT_EQ(records.size(), 1u);
    EXPECT_NEAR(records[0].input, 10.0 * area * 12.0 * 3600.0 * 1e-6, 1e-12);
    expectBalanceCloses(records, start);
    // Each object must be a leaf of a plant with a budget; nothing is added otherwise.
    std::map<ObjectID, double> bad = rates;
    bad[arch.getPlantObjectIDs(id, OrganKind::Internode).front()] = 1.0;
    EXPECT_THAT_ERROR(arch.addLeafPhotosynthesis(bad, 1.0), "is not a leaf of any plant");
    EXPECT_THAT_ERROR(arch.addLeafPhotosynthesis(rates, 25.0), "hours must be from 0 to 24");
    rates.begin()->second = std::nan("");
    EXPECT_THAT_ERROR(arch.addLeafPhotosynthesis(rates, 1.0), "must be a finite rate");
    EXPECT_THAT_ERROR(arch.setAirTemperature(99.0), "air temperature must be from -50 to 60");
    arch.advanceTime(id, 1.0);
    EXPECT_EQ(arch.getPhysiologyRecords(id).back().input, 0.0);
}

// Radial growth is paid for: a shoot well fed thickens as a plant without a budget does, a poor
// one by at least 5 % of its increase a day but less than the well-fed one.
TEST(Carbon, ThickeningTakesWhatTheShootCanPay) {
    auto baseRadius = [](int mode) {  // 0: no budget, 1: rich, 2: poor
        Context ctx;
        PlantArchitecture arch(&ctx);
        arch.setSeed(3);
        arch.loadPlantModelFromLibrary("tomato");
        const unsigned id = arch.buildPlantInstanceFromLibrary(vec3(0.0f), 15.0f);
        if (mode > 0) arch.enableCarbohydrateModel(id);
        for (int d = 0; d < 30; ++d) {
            if (mode > 0) {
                std::map<ObjectID, double> rates;
                for (ObjectID o : arch.getPlantObjectIDs(id, OrganKind::Leaf))
                    rates[o] = mode == 1 ? 25.0 : 1.5;
                arch.addLeafPhotosynthesis(rates, 14.0);
            }
            arch.advanceTime(id, 1.0);
        }
        return double(arch.plant(id).shoots.front().phytomers.front().internode.radius);
    };
    const double free = baseRadius(0), rich = baseRadius(1), poor = baseRadius(2);
    std::printf(
        "base internode radius after 30 days: %.2f mm without a budget, %.2f rich, "
        "%.2f poor\n",
        free * 1e3, rich * 1e3, poor * 1e3);
    EXPECT_NEAR(rich / free, 1.0, 0.1);
    EXPECT_LT(poor, 0.9 * rich);
    EXPECT_GT(poor, 0.0);
}

TEST(Carbon, BuildingWithTheBudgetOffIsUnchanged) {
    auto build = [](bool touchRecords) {
        Context ctx;
        PlantArchitecture arch(&ctx);
        arch.loadPlantModelFromLibrary("bean");
        const unsigned id = arch.buildPlantInstanceFromLibrary(vec3(0.0f), 10.0f);
        if (touchRecords) {
            EXPECT_TRUE(arch.getPhysiologyRecords(id).empty());
        }
        arch.advanceTime(id, 20.0);
        return arch.getPlantString(id);
    };
    EXPECT_EQ(build(false), build(true));
}

TEST(Nitrogen, WithoutNitrogenAPlantIsStressedAndMakesSmallerLeaves) {
    auto grow = [](double grams, double& stress) {
        Context ctx;
        PlantArchitecture arch(&ctx);
        arch.loadPlantModelFromLibrary("bean");
        const unsigned id = arch.buildPlantInstanceFromLibrary(vec3(0.0f), 10.0f);
        arch.enableNitrogenModel(id);
        if (grams > 0.0) arch.addPlantNitrogen(id, grams);
        arch.advanceTime(id, 25.0);
        stress = arch.getPhysiologyRecords(id).back().nitrogenStress;
        return arch.getPlantLeafArea(id);
    };
    double fedStress = 0.0, starvedStress = 0.0;
    const double fed = grow(5.0, fedStress);
    const double starved = grow(0.0, starvedStress);
    EXPECT_GT(fedStress, 0.99);
    EXPECT_LT(starvedStress, 0.6);
    EXPECT_LT(starved, 0.8 * fed);
}

TEST(Nitrogen, EveryGramIsAccountedFor) {
    Context ctx;
    PlantArchitecture arch(&ctx);
    arch.loadPlantModelFromLibrary("bean");
    const unsigned id = arch.buildPlantInstanceFromLibrary(vec3(0.0f), 20.0f);
    arch.enableNitrogenModel(id);
    auto inLeaves = [&] {
        double n = 0.0;
        for (const Shoot& s : arch.plant(id).shoots)
            for (const Phytomer& ph : s.phytomers)
                for (const Petiole& pt : ph.petioles)
                    for (const LeafOrgan& l : pt.leaves)
                        if (l.nitrogen && !l.removed) n += l.nitrogen->content;
        return n;
    };
    const double start = inLeaves();
    EXPECT_GT(start, 0.0);
    arch.addPlantNitrogen(id, 0.2);
    arch.advanceTime(id, 40.0);
    const PlantNitrogen& n = *arch.plant(id).nitrogen;
    double lost = 0.0, remobilised = 0.0;
    for (const auto& r : arch.getPhysiologyRecords(id)) {
        lost += r.nitrogenLost;
        remobilised += r.nitrogenRemobilised;
    }
    double shed = 0.0;
    for (const auto& r : arch.getPhysiologyRecords(id)) shed += r.nitrogenShed;
    EXPECT_NEAR(start + 0.2, inLeaves() + n.available + n.roots + n.fruit + lost + shed, 1e-9);
    EXPECT_NEAR(n.roots, 0.2 * 0.15, 1e-8);  // root_allocation is a float
    EXPECT_THAT_ERROR(arch.addPlantNitrogen(id, -1.0), "finite number of grams > 0");
    EXPECT_THAT_ERROR(arch.addPlantNitrogen(id, std::nan("")), "finite number of grams > 0");
}

TEST(Physiology, RecordsAsCSV) {
    const std::vector<std::string> columns = physiologyColumns();
    EXPECT_EQ(columns.front(), "plant");
    PhysiologyRecord r;
    r.input = 0.5;
    EXPECT_EQ(physiologyValues(r).size(), columns.size());
    Context ctx;
    PlantArchitecture arch(&ctx);
    EXPECT_THAT_ERROR(growPhysiology(arch, {}, {}), "the weather has no hours");
    std::vector<WeatherHour> gap = summer(3);
    gap.erase(gap.begin() + 24, gap.begin() + 48);
    EXPECT_THAT_ERROR(growPhysiology(arch, gap, {}), "the weather skips from");
}

// With ample light (every leaf at 20 umol m-2 s-1 net for 14 h a day, a sunlit leaf's clear
// summer day) an almond grown from planting to 630 days with its budget stays near the same
// almond without it: the budget runs (it aborts some flowers on poor spurs in spring) without
// starving the tree. Seeds 1-5, means of each.
TEST(Carbon, AnAlmondWithAmpleLightStaysNearTheAlmondWithoutABudget) {
    struct Stats {
        double shoots = 0, area = 0, height = 0, fruit = 0, aborted = 0;
    };
    auto grow = [](bool budget) {
        Stats sum;
        for (unsigned seed = 1; seed <= 5; ++seed) {
            Context ctx;
            PlantArchitecture arch(&ctx);
            arch.setSeed(seed);
            arch.loadPlantModelFromLibrary("almond");
            const unsigned id = arch.buildPlantInstanceFromLibrary(vec3(0.0f), budget ? 0 : 630);
            if (budget) {
                arch.enableCarbohydrateModel(id);
                const double start = pools(arch.plant(id));
                for (int d = 0; d < 630; ++d) {
                    std::map<ObjectID, double> rates;
                    for (ObjectID o : arch.getPlantObjectIDs(id, OrganKind::Leaf)) rates[o] = 20;
                    arch.addLeafPhotosynthesis(rates, 14.0);
                    arch.advanceTime(id, 1.0);
                }
                expectBalanceCloses(arch.getPhysiologyRecords(id), start);
                for (const auto& r : arch.getPhysiologyRecords(id)) sum.aborted += r.budsAborted;
            }
            sum.shoots += arch.getShootCount(id) / 5.0;
            sum.area += arch.getPlantLeafArea(id) / 5.0;
            sum.height += arch.getPlantHeight(id) / 5.0;
            sum.fruit += double(arch.getPlantObjectIDs(id, OrganKind::Fruit).size()) / 5.0;
        }
        return sum;
    };
    const Stats free = grow(false), budget = grow(true);
    std::printf(
        "without: %.1f shoots, %.2f m2, %.2f m, %.1f fruit; with: %.1f, %.2f, %.2f, "
        "%.1f (%.0f floral buds aborted)\n",
        free.shoots, free.area, free.height, free.fruit, budget.shoots, budget.area, budget.height,
        budget.fruit, budget.aborted);
    EXPECT_NEAR(budget.shoots / free.shoots, 1.0, 0.15);
    EXPECT_NEAR(budget.area / free.area, 1.0, 0.15);
    EXPECT_NEAR(budget.height / free.height, 1.0, 0.05);
    EXPECT_NEAR(budget.fruit / free.fruit, 1.0, 0.2);
    EXPECT_GT(budget.aborted, 0.0);
}

TEST(Physiology, ParametersThatCannotGoTogetherAreRefused) {
    PhenologyParameters p;
    EXPECT_NO_THROW(validate(p));
    p.leaf_physiology.leaf_reflectance = 0.6f;
    p.leaf_physiology.leaf_transmittance = 0.5f;
    EXPECT_THAT_ERROR(validate(p), "cannot reflect and transmit more");
    p = PhenologyParameters{};
    p.nitrogen.minimum_leaf_nitrogen = 2.0f;
    EXPECT_THAT_ERROR(validate(p), "minimum nitrogen exceeds its target");
    p = PhenologyParameters{};
    p.carbohydrates.stem_density = -1.0f;
    EXPECT_THAT_ERROR(validate(p), "stem_density");
    p = PhenologyParameters{};
    p.carbohydrates.respiration_q10 = std::nanf("");
    EXPECT_THAT_ERROR(validate(p), "respiration_q10");
}

// A species' `enabled` is honoured by growPhysiology; plain growth never starts a budget.
TEST(Carbon, TheSpeciesSwitchIsHonouredByGrowPhysiologyOnly) {
    Context ctx;
    PlantArchitecture arch(&ctx);
    arch.loadPlantModelFromLibrary("bean");
    const unsigned id = arch.buildPlantInstanceFromLibrary(vec3(0.0f), 15.0f);
    PhenologyParameters ph = arch.plant(id).phenology;
    ph.carbohydrates.enabled = true;
    ph.nitrogen.enabled = true;
    arch.setPlantPhenologicalThresholds(id, ph);
    arch.advanceTime(id, 2.0);
    EXPECT_FALSE(arch.hasCarbohydrateModel(id));
    EXPECT_FALSE(arch.hasNitrogenModel(id));
    EXPECT_TRUE(arch.getPhysiologyRecords(id).empty());
    const auto records = growPhysiology(arch, summer(1), options());
    EXPECT_TRUE(arch.hasCarbohydrateModel(id));
    EXPECT_TRUE(arch.hasNitrogenModel(id));
    ASSERT_EQ(records.size(), 1u);
    EXPECT_GT(records[0].input, 0.0);
}
