// The carbohydrate budget per shoot and the nitrogen per leaf (docs/physiology.md gives the
// equations and their sources).

#include "physiology/budget.h"

#include <algorithm>
#include <cmath>

#include "model/carbon_costs.h"

namespace plantarch::physiology {

namespace {

using carbon::amount;
using carbon::kCarbonMolarMass;
using carbon::kMinVolume;

double pool(const ShootCarbon& c) {
    return c.sugar + c.starch;
}

// The chain of shoots that pays for a shoot's costs: itself, then its ancestors (the base
// stem holds the seed's reserve).
void pay(PlantInstance& plant, unsigned id, double cost) {
    int at = int(id);
    while (cost > 0.0 && at >= 0) {
        Shoot& s = plant.shoots[unsigned(at)];
        if (s.carbon && !s.removed) {  // from its sugar, then its starch
            const double sugar = std::min(cost, std::max(0.0, s.carbon->sugar));
            s.carbon->sugar -= sugar;
            const double starch = std::min(cost - sugar, s.carbon->starch);
            s.carbon->starch -= starch;
            cost -= sugar + starch;
        }
        at = s.parent;
    }
    if (cost > 0.0) plant.shoots[id].carbon->sugar -= cost;  // a debt nobody could pay
}

// The subtree of `id` (itself and every shoot growing from it).
void subtree(const PlantInstance& plant, unsigned id, std::vector<unsigned>& out) {
    out.push_back(id);
    for (unsigned c : plant.shoots[id].children)
        if (!plant.shoots[c].removed) subtree(plant, c, out);
}

// Sugar flows along every parent-child link down the concentration gradient: toward the tips
// when the parent is above the transfer-up threshold, toward the base when the child is above
// the transfer-down threshold; at most to equal concentrations, and no shoot gives more than
// its sugar above its threshold (all flows from the concentrations at the phase's start, so
// the result does not depend on the order of the shoots).
void transfer(PlantInstance& plant, const std::vector<ShootMeasure>& m,
              const CarbohydrateParameters& p, double days) {
    struct Flow {
        unsigned from, to;
        double amount;
    };
    std::vector<Flow> flows;
    std::vector<double> out(plant.shoots.size(), 0.0), surplus(plant.shoots.size(), 0.0);
    auto conc = [&](unsigned id) {
        return plant.shoots[id].carbon->sugar * kCarbonMolarMass /
               (p.stem_density * std::max(m[id].woodVolume, kMinVolume));
    };
    for (Shoot& child : plant.shoots) {
        if (child.removed || !child.carbon || child.parent < 0) continue;
        const unsigned c = child.id, parent = unsigned(child.parent);
        if (!plant.shoots[parent].carbon || plant.shoots[parent].removed) continue;
        const double vp = std::max(m[parent].woodVolume, kMinVolume);
        const double vc = std::max(m[c].woodVolume, kMinVolume);
        const double gap = conc(parent) - conc(c);
        const bool up = gap > 0.0;
        const unsigned from = up ? parent : c, to = up ? c : parent;
        const double threshold = up ? p.transfer_up_threshold : p.transfer_down_threshold;
        const double k = up ? p.conductance_up : p.conductance_down;
        if (conc(from) <= threshold || gap == 0.0) continue;
        const double toEqual =
            std::abs(gap) * p.stem_density / kCarbonMolarMass * vp * vc / (vp + vc);
        const double rate =
            k * days * std::abs(gap) * p.stem_density * std::min(vp, vc) / kCarbonMolarMass;
        flows.push_back({from, to, std::min(rate, toEqual)});
        out[from] += flows.back().amount;
    }
    for (const Shoot& s : plant.shoots)
        if (!s.removed && s.carbon)
            surplus[s.id] = std::max(
                0.0, s.carbon->sugar -
                         amount(p, std::min(p.transfer_up_threshold, p.transfer_down_threshold),
                                m[s.id].woodVolume));
    for (const Flow& f : flows) {
        const double scale = out[f.from] > surplus[f.from] ? surplus[f.from] / out[f.from] : 1.0;
        const double moved = f.amount * scale;
        plant.shoots[f.from].carbon->sugar -= moved;
        plant.shoots[f.to].carbon->sugar += moved;
    }
}

bool abortable(const FloralBud& fb) {
    return fb.stage == FloralStage::FlowerClosed || fb.stage == FloralStage::FlowerOpen ||
           fb.stage == FloralStage::Fruit;
}

void kill(FloralBud& fb) {
    fb.stage = FloralStage::Removed;
    fb.state = BudState::Dead;
    fb.nextTime = -1.0;
}

// A poor shoot aborts one floral bud (its flowers or fruit) a day, the lowest first, as the
// lowest are the oldest and the furthest from the growing tip.
void abortFloral(Shoot& s, CarbonActions& actions) {
    for (unsigned k = 0; k < s.phytomers.size(); ++k)
        for (unsigned j = 0; j < s.phytomers[k].petioles.size(); ++j) {
            auto& buds = s.phytomers[k].petioles[j].floralBuds;
            for (unsigned b = 0; b < buds.size(); ++b)
                if (abortable(buds[b])) {
                    kill(buds[b]);
                    actions.aborted.push_back({s.id, k, j, b, false});
                    return;
                }
        }
    for (unsigned i = 0; i < s.terminalFloralBuds.size(); ++i)
        if (abortable(s.terminalFloralBuds[i])) {
            kill(s.terminalFloralBuds[i]);
            actions.aborted.push_back({s.id, 0, 0, i, true});
            return;
        }
}

// Phyllochron, bud break and the counters of a shoot after the day's flows.
// A shoot starves (and dies after branch_death_time days) only while it is poor and the
// leaves of it and of everything growing from it do not pay for their upkeep (`selfBalance`:
// their net input less maintenance): a poor shoot that feeds itself is in debt for growth it
// already made, which it pays back, growing more slowly meanwhile.
void regulate(PlantInstance& plant, Shoot& s, const ShootMeasure& m,
              const CarbohydrateParameters& p, double days, double selfBalance) {
    ShootCarbon& c = *s.carbon;
    const double total = pool(c);
    // Poorer than the phyllochron threshold: nodes come proportionally more slowly.
    const double r = total / amount(p, p.phyllochron_threshold, m.woodVolume);
    const double slow = 1.0 / std::clamp(r, 1.0 / double(p.max_phyllochron_factor), 1.0);
    const float phyllochron = float(double(c.phyllochron) * slow);
    if (phyllochron != s.phyllochron) {
        s.phyllochron = phyllochron;
        if (s.nextPhytomerTime >= 0.0 && !s.phytomers.empty())
            s.nextPhytomerTime = std::max(plant.age, s.phytomers.back().birth + s.phyllochron);
    }
    c.budBreakFactor =
        float(std::clamp(total / amount(p, p.bud_break_threshold, m.woodVolume), 0.0, 1.0));
    c.radialAllowance = std::max(0.0, c.sugar - amount(p, p.radial_growth_threshold, m.woodVolume));
    c.poorDays =
        total < amount(p, p.abortion_threshold, m.woodVolume) ? c.poorDays + float(days) : 0.0f;
    c.starvedDays = total < amount(p, p.pruning_threshold, m.woodVolume) && selfBalance < 0.0
                        ? c.starvedDays + float(days)
                        : 0.0f;
}

// Costs of what a shoot built since the last step: wood (with roots in proportion), leaves,
// flowers and fruit, each with its growth respiration. Returns {built, respired}.
std::pair<double, double> growthCost(const CarbohydrateParameters& p, ShootCarbon& c,
                                     const ShootMeasure& m) {
    const double wood =
        std::max(0.0, m.woodCarbon - c.woodCarbon) * (1.0 + 1.0 / double(p.shoot_root_ratio));
    const double leaves =
        std::max(0.0, m.leafArea - c.leafArea) * p.leaf_carbon_per_area / kCarbonMolarMass;
    const double fruit = std::max(0.0, m.fruitVolume - c.fruitVolume) * p.fruit_density *
                         p.fruit_carbon_fraction / kCarbonMolarMass;
    const double flowers =
        double(m.flowers > c.flowers ? m.flowers - c.flowers : 0) * p.flower_carbon;
    c.woodCarbon = m.woodCarbon;
    c.leafArea = m.leafArea;
    c.fruitVolume = m.fruitVolume;
    c.flowers = std::max(c.flowers, m.flowers);
    const double built = wood + leaves + fruit + flowers;
    return {built, built * p.growth_respiration_fraction};
}

}  // namespace

double woodCarbon(const CarbohydrateParameters& p, double volume) {
    return carbon::woodCarbon(p, volume);
}

double startCarbon(PlantInstance& plant, const std::vector<ShootMeasure>& measures) {
    const CarbohydrateParameters& p = plant.phenology.carbohydrates;
    double added = 0.0;
    for (Shoot& s : plant.shoots) {
        if (s.removed || s.carbon) continue;
        const ShootMeasure& m = measures[s.id];
        ShootCarbon c;
        c.sugar = amount(p, p.initial_concentration, m.woodVolume);
        c.woodCarbon = m.woodCarbon;
        c.leafArea = m.leafArea;
        c.fruitVolume = m.fruitVolume;
        c.flowers = m.flowers;
        c.phyllochron = s.phyllochron;
        if (s.parent < 0) c.starch = p.seed_reserve;  // the base stem
        added += c.sugar + c.starch;
        s.carbon = c;
    }
    return added;
}

CarbonActions stepCarbon(PlantInstance& plant, const std::vector<ShootMeasure>& measures,
                         double temperature, double days, PhysiologyRecord& record) {
    const CarbohydrateParameters& p = plant.phenology.carbohydrates;
    CarbonActions actions;
    // Shoots removed since the last step (pruned by hand, or by growth) take their pools.
    for (Shoot& s : plant.shoots)
        if (s.removed && s.carbon) {
            record.losses += pool(*s.carbon);
            s.carbon.reset();
        }
    // New shoots start empty, their organs unpaid: the first costs fall on their parents.
    for (Shoot& s : plant.shoots)
        if (!s.removed && !s.carbon) {
            ShootCarbon c;
            c.phyllochron = s.phyllochron;
            s.carbon = c;
        }
    const double q10 = std::pow(double(p.respiration_q10), (temperature - 20.0) / 10.0);
    const double maintenanceRate =
        (p.wood_respiration_rate + p.root_respiration_rate / p.shoot_root_ratio) * q10;
    // 1. Input, 2. maintenance; each subtree's balance of the two (children have larger IDs
    // than their parents).
    std::vector<double> balance(plant.shoots.size(), 0.0);
    for (Shoot& s : plant.shoots) {
        if (s.removed) continue;
        const ShootMeasure& m = measures[s.id];
        s.carbon->sugar += m.input;
        record.input += m.input;
        const double respired = m.woodCarbon * maintenanceRate * days;
        s.carbon->sugar -= respired;
        record.maintenance += respired;
        balance[s.id] = m.input - respired;
    }
    for (std::size_t i = plant.shoots.size(); i-- > 0;)
        if (!plant.shoots[i].removed && plant.shoots[i].parent >= 0)
            balance[std::size_t(plant.shoots[i].parent)] += balance[i];
    // 3. Growth, paid by the shoot and then its ancestors (a young shoot lives on its parent).
    for (Shoot& s : plant.shoots) {
        if (s.removed) continue;
        const auto [built, respired] = growthCost(p, *s.carbon, measures[s.id]);
        pay(plant, s.id, built + respired);
        record.growth += built;
        record.growthRespiration += respired;
    }
    // 4. Starch: a share of the sugar above the transfer threshold is stored; a poor shoot
    // draws on its starch.
    for (Shoot& s : plant.shoots) {
        if (s.removed) continue;
        ShootCarbon& c = *s.carbon;
        const double volume = measures[s.id].woodVolume;
        const double above = c.sugar - amount(p, p.transfer_up_threshold, volume);
        if (above > 0.0) {
            const double stored = above * std::min(1.0, double(p.starch_fraction) * days);
            c.sugar -= stored;
            c.starch += stored;
        }
        const double need = amount(p, p.abortion_threshold, volume) - c.sugar;
        if (need > 0.0 && c.starch > 0.0) {
            const double released = std::min(need, c.starch);
            c.starch -= released;
            c.sugar += released;
        }
    }
    // 5. Transfer along the shoot tree; what no shoot can store grows roots.
    transfer(plant, measures, p, days);
    for (Shoot& s : plant.shoots) {
        if (s.removed) continue;
        ShootCarbon& c = *s.carbon;
        const double spent = c.sugar - amount(p, p.storage_capacity, measures[s.id].woodVolume);
        if (spent <= 0.0) continue;
        c.sugar -= spent;
        const double built = spent / (1.0 + p.growth_respiration_fraction);
        record.growth += built;
        record.growthRespiration += spent - built;
        record.rootGrowth += built;
    }
    // 6-8. Phyllochron, bud break, abortion and death.
    std::vector<unsigned> dying;
    for (Shoot& s : plant.shoots) {
        if (s.removed) continue;
        const ShootMeasure& m = measures[s.id];
        regulate(plant, s, m, p, days, balance[s.id]);
        const ShootCarbon& c = *s.carbon;
        if (c.starvedDays > p.branch_death_time) {
            dying.push_back(s.id);
            continue;
        }
        if (c.poorDays > p.bud_death_time) {
            const std::size_t before = actions.aborted.size();
            abortFloral(s, actions);
            record.budsAborted += unsigned(actions.aborted.size() - before);
        }
    }
    // A dying shoot takes everything growing from it; its pools (and theirs) are lost.
    std::vector<bool> gone(plant.shoots.size(), false);
    for (unsigned id : dying) {
        if (gone[id]) continue;
        std::vector<unsigned> tree;
        subtree(plant, id, tree);
        for (unsigned t : tree) {
            if (gone[t]) continue;
            gone[t] = true;
            record.losses += pool(*plant.shoots[t].carbon);
            plant.shoots[t].carbon->sugar = 0.0;
            plant.shoots[t].carbon->starch = 0.0;
        }
        actions.prune.push_back(id);
        record.shootsPruned += unsigned(tree.size());
    }
    record.sugar = record.starch = 0.0;
    for (const Shoot& s : plant.shoots)
        if (!s.removed && s.carbon) {
            record.sugar += s.carbon->sugar;
            record.starch += s.carbon->starch;
        }
    return actions;
}

// ---- nitrogen ------------------------------------------------------------------------------

namespace {

// Leaf age as a share of the plant's leaf lifespan; with no lifespan set (a crop keeps its
// leaves until the season ends), of the oldest living leaf's age.
struct AgeScale {
    double lifespan;
    AgeScale(const PlantInstance& plant, const std::vector<LeafMeasure>& leaves) {
        lifespan = plant.phenology.max_leaf_lifespan;
        if (lifespan >= 1e5) {
            lifespan = 0.0;
            for (const LeafMeasure& l : leaves) lifespan = std::max(lifespan, double(l.leaf->age));
        }
    }
    double operator()(const LeafOrgan& l) const {
        return lifespan > 0.0 ? double(l.age) / lifespan : 0.0;
    }
};

}  // namespace

void startNitrogen(PlantInstance& plant, const std::vector<LeafMeasure>& leaves) {
    const NitrogenParameters& p = plant.phenology.nitrogen;
    PlantNitrogen n;
    n.available = p.initial_available;
    plant.nitrogen = n;
    for (const LeafMeasure& l : leaves)
        if (!l.leaf->nitrogen) l.leaf->nitrogen = LeafNitrogen{p.initial_leaf_nitrogen * l.area};
    for (const LeafMeasure& l : leaves) plant.nitrogen->leaves += l.leaf->nitrogen->content;
}

void stepNitrogen(PlantInstance& plant, const std::vector<LeafMeasure>& leaves, double fruitArea,
                  double days, PhysiologyRecord& record) {
    const NitrogenParameters& p = plant.phenology.nitrogen;
    PlantNitrogen& n = *plant.nitrogen;
    // Leaves shed or removed since the last step took their nitrogen with them.
    double before = 0.0;
    for (const LeafMeasure& l : leaves) {
        if (!l.leaf->nitrogen) l.leaf->nitrogen = LeafNitrogen{0.0};  // new leaves start empty
        before += l.leaf->nitrogen->content;
    }
    record.nitrogenShed += std::max(0.0, n.leaves - before);
    const AgeScale age(plant, leaves);
    auto content = [](const LeafMeasure& l) { return double(l.leaf->nitrogen->content); };
    auto demand = [&](const LeafMeasure& l) {
        return std::max(0.0, p.target_leaf_nitrogen * l.area - content(l));
    };
    // Uptake: each leaf toward its target at the maximum rate, shared in proportion when the
    // pool cannot meet every request.
    std::vector<double> request(leaves.size(), 0.0);
    double requested = 0.0;
    for (std::size_t i = 0; i < leaves.size(); ++i) {
        request[i] = std::min(demand(leaves[i]), p.max_accumulation_rate * leaves[i].area * days);
        requested += request[i];
    }
    const double share = requested > n.available ? n.available / requested : 1.0;
    for (std::size_t i = 0; i < leaves.size(); ++i) {
        const double got = request[i] * share;
        leaves[i].leaf->nitrogen->content += got;
        n.available = std::max(0.0, n.available - got);
        record.nitrogenUptake += got;
        n.uptake += got;
    }
    // Remobilisation: old leaves release a share of what they hold above the minimum each
    // day; young leaves with demand receive the recovered part in proportion to demand.
    double released = 0.0, youngDemand = 0.0;
    for (const LeafMeasure& l : leaves) {
        if (age(*l.leaf) < p.young_leaf_age) youngDemand += demand(l);
    }
    if (youngDemand > 0.0)
        for (const LeafMeasure& l : leaves) {
            if (age(*l.leaf) < p.old_leaf_age) continue;
            const double spare = std::max(0.0, content(l) - p.minimum_leaf_nitrogen * l.area);
            const double r = spare * std::min(1.0, double(p.remobilisation_rate) * days);
            l.leaf->nitrogen->content -= r;
            released += r;
        }
    const double recovered = std::min(released * p.remobilisation_efficiency, youngDemand);
    record.nitrogenLost += released - recovered;
    record.nitrogenRemobilised += recovered;
    if (recovered > 0.0)
        for (const LeafMeasure& l : leaves)
            if (age(*l.leaf) < p.young_leaf_age)
                l.leaf->nitrogen->content += recovered * demand(l) / youngDemand;
    // Fruit: their new surface's nitrogen from the pool, then from leaves above the minimum.
    double need = std::max(0.0, fruitArea * p.fruit_nitrogen - n.fruit);
    const double fromPool = std::min(need, n.available);
    n.available -= fromPool;
    need -= fromPool;
    double taken = fromPool;
    for (const LeafMeasure& l : leaves) {
        if (need <= 0.0) break;
        const double spare = std::max(0.0, content(l) - p.minimum_leaf_nitrogen * l.area);
        const double t = std::min(spare, need);
        l.leaf->nitrogen->content -= t;
        need -= t;
        taken += t;
    }
    n.fruit += taken;
    record.nitrogenToFruit += taken;
    double held = 0.0, area = 0.0;
    for (const LeafMeasure& l : leaves) {
        held += content(l);
        area += l.area;
    }
    n.leaves = held;
    // Stress: what the leaves hold and may still take up over what they need at the target.
    n.stress = area > 0.0
                   ? float(std::min(1.0, (held + n.available) / (p.target_leaf_nitrogen * area)))
                   : 1.0f;
    record.nitrogenAvailable = n.available;
    record.nitrogenInLeaves = held;
    record.nitrogenStress = n.stress;
}

void addNitrogen(PlantInstance& plant, double grams) {
    const NitrogenParameters& p = plant.phenology.nitrogen;
    plant.nitrogen->roots += grams * p.root_allocation;
    plant.nitrogen->available += grams * (1.0 - p.root_allocation);
}

}  // namespace plantarch::physiology
