// Growth over time, driven by events at exact plant ages.
//
// Everything that changes the plant's topology or draws random numbers is an event with a
// time stored on the organ it concerns (a shoot's next phytomer, a bud's break time, a
// flower's next stage, a season boundary, a leaf's fall, a whole-day callback). advanceTime
// processes the events due before the target age in time order (ties broken by a fixed key),
// so splitting a period into any number of calls visits the same events in the same order
// and draws the same random numbers. Elongation, fruit growth and ages are closed-form
// functions of age, evaluated at the end of each call.

#include "growth/growth.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <queue>
#include <tuple>

#include "core/math.h"
#include "core/value_text.h"
#include "geometry/tessellate.h"
#include "growth/bending.h"
#include "growth/leaf_expansion.h"
#include "model/carbon_costs.h"
#include "model/node_rules.h"
#include "plantarch/Error.h"

namespace plantarch {

namespace {

// The least share of its full increase a shoot's internodes thicken by at a girth update,
// however poor the shoot (docs/physiology.md).
constexpr double kRadialMinimum = 0.05;

enum EventKind : int {
    kDormancyBreak = 0,
    kSenescence = 1,
    kDaily = 2,
    kLeafFall = 3,
    kFloral = 4,
    kBudBreak = 5,
    kPhytomer = 6,
    kEpicormic = 7,
};

struct Event {
    double time;
    int kind;
    unsigned shoot = 0, node = 0, petiole = 0, index = 0;
    bool terminal = false;

    auto key() const { return std::tie(time, kind, shoot, node, petiole, index, terminal); }
    bool operator>(const Event& o) const { return key() > o.key(); }
};

// Probability that an axillary bud at node `k` of a shoot with `n` nodes breaks. Buds sorted
// after a winter (`afterWinter`) lie on a finished shoot: a positive decay rate makes the
// probability highest at its tip (dropping by the rate per node below it), a negative one
// highest at its base. On a shoot that grows on without a winter, a positive decay gives the
// shoot's first bud the maximum (it forms at the tip of a one-node shoot) and every later bud,
// formed as the shoot grows on, the minimum; a negative decay gives the minimum everywhere.
// Never below the minimum; with no decay the minimum applies all along the shoot.
float budBreakProbability(const ShootParameters& t, Rng& rng, int k, int n, bool afterWinter) {
    const float pmin = t.vegetative_bud_break_probability_min.sample(rng);
    const float pmax = t.vegetative_bud_break_probability_max.sample(rng);
    const float decay = t.vegetative_bud_break_probability_decay_rate.sample(rng);
    if (decay > 0.0f && !afterWinter) return k == 0 ? std::max(pmin, pmax) : pmin;
    if (decay > 0.0f) return std::max(pmin, pmax - decay * float(n - 1 - k));
    if (decay < 0.0f && afterWinter) return std::max(pmin, pmax + decay * float(k));
    return pmin;
}

// Full internode length of a child shoot of type `childType` growing from node `k` of a
// parent with `n` nodes, from the child type's own lengths: basitonic (decay < 0) is longest
// at the parent's base, acrotonic (decay > 0) at its tip.
float childInternodeLength(const ShootParameters& childType, Rng& rng, int k, int n) {
    const float lmax = childType.internode_length_max.sample(rng);
    const float lmin = childType.internode_length_min.sample(rng);
    const float decay = childType.internode_length_decay_rate.sample(rng);
    if (decay < 0.0f) return std::max(lmin, lmax + decay * float(k));
    if (decay > 0.0f) return std::max(lmin, lmax - decay * float(n - 1 - k));
    return lmax;
}

std::string chooseChildType(const ShootParameters& parentType, const std::string& parentLabel,
                            Rng& rng) {
    if (parentType.child_shoot_types.empty()) return parentLabel;
    const float u = rng.uniform01();
    float acc = 0.0f;
    std::string last;
    for (const auto& [label, p] : parentType.child_shoot_types) {
        acc += p;
        last = label;
        if (u < acc) return label;
    }
    return last;  // rounding: the sum may fall a hair short of 1
}

struct Grower {
    const GrowthContext& growth;
    PlantInstance& plant;
    std::priority_queue<Event, std::vector<Event>, std::greater<Event>> queue;

    // Shoot types by label; the plant's map is not modified during one call, so the
    // references stay valid.
    std::map<std::string, const ShootParameters*, std::less<>> types;
    const ShootParameters& typeOf(const std::string& label) {
        auto it = types.find(label);
        if (it == types.end())
            it = types.emplace(label, &growth.store.shootTypeFor(plant, label)).first;
        return *it->second;
    }
    std::vector<double> girthTotals, girthNodes;  // reused by updateGirth
    std::vector<float> girthTargets;
    // Called at most once a day of growth with the fraction of the call's days done (before
    // that day's first event); may be null.
    const std::function<void(double)>* onDay = nullptr;
    bool growingSeason() const {
        return plant.stage == PhenologyStage::Vegetative ||
               plant.stage == PhenologyStage::Reproductive;
    }

    // ---- scheduling --------------------------------------------------------------------

    // Days from a floral bud's start to its first stage: closed flowers after
    // time_to_flower_initiation, or open ones after time_to_flower_opening when initiation is
    // off, or fruit after time_to_fruit_set when both are off; negative: it never flowers.
    double firstFloralDelay() const {
        const PhenologyParameters& ph = plant.phenology;
        if (ph.time_to_flower_initiation >= 0.0f) return ph.time_to_flower_initiation;
        if (ph.time_to_flower_opening >= 0.0f) return ph.time_to_flower_opening;
        if (ph.time_to_fruit_set >= 0.0f) return ph.time_to_fruit_set;
        return -1.0;
    }

    // When a floral bud whose clock starts at `start` reaches its first stage. Each bud keeps
    // its own clock, as a vegetative bud does: it starts when the bud is made in a growing
    // season, or when dormancy breaks for a bud made or kept through a winter (or one that
    // needs a winter). Before the plant's first dormancy break no clock runs.
    double floweringTime(double start) const {
        const double delay = firstFloralDelay();
        if (plant.dormancyBreakTime < 0.0 || delay < 0.0) return -1.0;
        return std::max(start, plant.dormancyBreakTime) + delay;
    }

    // Events after the end of the current run are not queued: the run would stop before
    // them, and their times stay stored on the plant, from which the next run queues them
    // (plants grown in many short steps would otherwise queue every pending event each step).
    double horizon = std::numeric_limits<double>::infinity();
    void push(double time, int kind, unsigned shoot, unsigned node = 0, unsigned petiole = 0,
              unsigned index = 0, bool terminal = false) {
        if (time >= 0.0 && time <= horizon)
            queue.push(Event{time, kind, shoot, node, petiole, index, terminal});
    }

    // Puts every pending time stored on the plant into the queue.
    void enqueueAll(double now) {
        push(plant.nextDormancyBreak, kDormancyBreak, 0);
        push(plant.senescenceTime, kSenescence, 0);
        if (usesCallbacks()) push(std::floor(now) + 1.0, kDaily, 0);
        if (sprouts()) push(std::floor(now) + 1.0, kEpicormic, 0);
        for (Shoot& s : plant.shoots)
            if (!s.removed) enqueueShoot(s);
    }

    void enqueueShoot(Shoot& s) {
        push(s.nextPhytomerTime, kPhytomer, s.id);
        for (unsigned k = 0; k < s.phytomers.size(); ++k) enqueuePhytomer(s, k);
        for (unsigned i = 0; i < s.terminalFloralBuds.size(); ++i)
            push(s.terminalFloralBuds[i].nextTime, kFloral, s.id, 0, 0, i, true);
    }

    void enqueuePhytomer(Shoot& s, unsigned k) {
        Phytomer& ph = s.phytomers[k];
        const float lifespan = plant.phenology.max_leaf_lifespan;
        for (unsigned j = 0; j < ph.petioles.size(); ++j) {
            Petiole& pt = ph.petioles[j];
            for (unsigned b = 0; b < pt.vegetativeBuds.size(); ++b)
                if (pt.vegetativeBuds[b].state == BudState::Dormant)
                    push(pt.vegetativeBuds[b].breakTime, kBudBreak, s.id, k, j, b);
            for (unsigned b = 0; b < pt.floralBuds.size(); ++b)
                push(pt.floralBuds[b].nextTime, kFloral, s.id, k, j, b);
            if (lifespan < 1e6f)
                for (unsigned l = 0; l < pt.leaves.size(); ++l)
                    if (!pt.leaves[l].removed)
                        push(pt.leaves[l].birth + lifespan, kLeafFall, s.id, k, j, l);
        }
    }

    bool usesCallbacks() {
        for (const auto& [label, t] : plant.shootTypes)
            if (!t.phytomer_parameters.phytomer_callback_function.empty()) return true;
        return rules::hasDailyRules(plant.shootTypes);
    }

    // When an axillary vegetative bud of `ph` breaks: vegetative_bud_break_time after it was
    // made, or now if that time passed while the plant was dormant (a bud that needed a winter,
    // one made in winter, or one still waiting when the last season ended). So last season's
    // buds break as the season begins, on the shoot as it stood through the winter.
    double budBreakTime(const ShootParameters& t, const Phytomer& ph, double now) {
        return std::max(now, ph.birth + t.vegetative_bud_break_time.sample(plant.rng));
    }

    // Sets the stored times of a phytomer's buds (new phytomers and new seasons).
    void scheduleBuds(Shoot& s, Phytomer& ph) {
        const ShootParameters& t = typeOf(s.type);
        const double flowering = floweringTime(plant.age);
        for (Petiole& pt : ph.petioles) {
            for (VegetativeBud& b : pt.vegetativeBuds)
                if (b.state == BudState::Dormant && b.breakTime < 0.0 && growingSeason() &&
                    !t.growth_requires_dormancy)
                    b.breakTime = budBreakTime(t, ph, plant.age);
            for (FloralBud& fb : pt.floralBuds)
                if (fb.stage == FloralStage::Bud && waiting(fb) && fb.nextTime < 0.0 &&
                    flowering >= 0.0 && !t.flowers_require_dormancy)
                    fb.nextTime = flowering;
        }
    }

    // A floral bud still to flower: dormant, or made active (forced) by a rule function.
    static bool waiting(const FloralBud& fb) {
        return fb.state == BudState::Dormant || fb.state == BudState::Active;
    }

    // A determinate shoot that turns reproductive makes no more shoots: its axillary
    // vegetative buds still waiting die (its apex stops with `flowering`, see canGrow).
    static void endVegetativeGrowth(Shoot& s) {
        for (Phytomer& ph : s.phytomers)
            for (Petiole& pt : ph.petioles)
                for (VegetativeBud& b : pt.vegetativeBuds)
                    if (b.state == BudState::Dormant) b.state = BudState::Dead;
    }

    bool canGrow(const Shoot& s, const ShootParameters& t) const {
        return s.apicalBud.state == BudState::Active && int(s.phytomers.size()) < s.maxNodes &&
               s.nodesThisSeason < s.maxNodesPerSeason &&
               !(t.determinate_shoot_growth && s.flowering);
    }

    // ---- events ------------------------------------------------------------------------

    void onPhytomer(Shoot& s, double now) {
        s.nextPhytomerTime = -1.0;
        const ShootParameters& t = typeOf(s.type);
        if (!growingSeason()) return;  // resumes when dormancy breaks
        if (!canGrow(s, t)) {
            stopShoot(s, t);
            return;
        }
        const PhytomerParameters& pp = t.phytomer_parameters;
        const float radius = pp.internode.radius_initial.sample(plant.rng);
        createPhytomer(growth, plant, s, pp, radius, s.internodeLengthMax, 0.01f, 0.01f, nullptr);
        s.nodesThisSeason++;
        scheduleBuds(s, s.phytomers.back());
        enqueuePhytomer(s, unsigned(s.phytomers.size() - 1));
        if (canGrow(s, t)) {
            s.nextPhytomerTime = now + s.phyllochron;
            push(s.nextPhytomerTime, kPhytomer, s.id);
        } else {
            stopShoot(s, t);
        }
    }

    // A shoot that stops growing this season sets its terminal floral buds.
    void stopShoot(Shoot& s, const ShootParameters& t) {
        const int n = t.max_terminal_floral_buds.sample(plant.rng);
        if (s.terminalFloralBuds.empty() && n > 0 && !s.phytomers.empty()) {
            s.terminalFloralBuds.resize(std::size_t(n));
            const double flowering = floweringTime(plant.age);
            for (unsigned i = 0; i < s.terminalFloralBuds.size(); ++i) {
                FloralBud& fb = s.terminalFloralBuds[i];
                fb.terminal = true;
                fb.terminalAzimuth = 360.0f * float(i) / float(s.terminalFloralBuds.size());
                if (!t.flowers_require_dormancy && flowering >= 0.0) {
                    fb.nextTime = flowering;
                    push(fb.nextTime, kFloral, s.id, 0, 0, i, true);
                }
            }
        }
    }

    void onBudBreak(const Event& e) {
        Shoot& s = plant.shoots[e.shoot];
        VegetativeBud& bud = s.phytomers[e.node].petioles[e.petiole].vegetativeBuds[e.index];
        bud.breakTime = -1.0;
        if (bud.state != BudState::Dormant) return;
        if (!growingSeason()) return;  // rescheduled when dormancy breaks
        const ShootParameters& t = typeOf(s.type);
        const int n = int(s.phytomers.size());
        // Buds that need a winter were sorted when dormancy broke; the others are sorted now,
        // by their place below the growing tip.
        // A shoot short of carbohydrates breaks fewer buds (docs/physiology.md).
        const float carbon = s.carbon ? s.carbon->budBreakFactor : 1.0f;
        if (!t.growth_requires_dormancy &&
            !plant.rng.chance(carbon * budBreakProbability(t, plant.rng, int(e.node), n, false))) {
            bud.state = BudState::Dead;
            return;
        }
        const std::string childType = chooseChildType(t, s.type, plant.rng);
        const ShootParameters& ct = typeOf(childType);
        ShootSpec spec;
        spec.phytomers = 1;
        spec.shootType = childType;
        spec.size.internodeRadius =
            std::max(ct.phytomer_parameters.internode.radius_initial.sample(plant.rng), 1e-6f);
        spec.size.internodeLengthMax = childInternodeLength(ct, plant.rng, int(e.node), n);
        spec.size.internodeLengthScale = 0.01f;
        spec.size.leafScale = 0.01f;
        const unsigned id =
            createShoot(growth, plant, spec, StartMode::Bud, int(e.shoot), e.node, e.petiole);
        enqueueShoot(plant.shoots[id]);
    }

    FloralBud& floralBud(const Event& e) {
        Shoot& s = plant.shoots[e.shoot];
        return e.terminal ? s.terminalFloralBuds[e.index]
                          : s.phytomers[e.node].petioles[e.petiole].floralBuds[e.index];
    }

    void onFloral(const Event& e, double now) {
        Shoot& s = plant.shoots[e.shoot];
        FloralBud& fb = floralBud(e);
        fb.nextTime = -1.0;
        const ShootParameters& t = typeOf(s.type);
        const PhenologyParameters& ph = plant.phenology;
        const PhytomerParameters& pp =
            !fb.parametersLabel.empty() ? typeOf(fb.parametersLabel).phytomer_parameters
            : e.terminal                ? t.phytomer_parameters
                         : typeOf(s.phytomers[e.node].parametersLabel).phytomer_parameters;
        auto next = [&](float delay) { return delay >= 0.0f ? now + delay : -1.0; };
        switch (fb.stage) {
            case FloralStage::Bud: {
                if (!waiting(fb) || !growingSeason()) return;
                // A determinate shoot turns reproductive as its first floral bud comes due,
                // whether or not that bud flowers: it grows no more, and its waiting vegetative
                // buds die.
                if (t.determinate_shoot_growth && !s.flowering) {
                    endVegetativeGrowth(s);
                    s.flowering = true;
                }
                const bool forced = fb.state == BudState::Active;
                if (!forced &&
                    !plant.rng.chance(t.flower_bud_break_probability.sample(plant.rng))) {
                    fb.state = BudState::Dead;
                    fb.stage = FloralStage::Removed;
                    return;
                }
                // A bud made ready again by a rule function may still hold the objects of its
                // previous inflorescence when no geometry update ran in between.
                for (FlowerOrgan& fl : fb.flowers) removeObjects(fl.objects);
                realizeInflorescence(plant, fb, pp);
                if (growth.steering)
                    growth.steering->steerPeduncle(plant, s, e.node, e.petiole, e.index, e.terminal,
                                                   fb);
                fb.state = BudState::Broken;
                s.flowering = true;
                if (plant.stage == PhenologyStage::Vegetative)
                    plant.stage = PhenologyStage::Reproductive;
                if (ph.time_to_flower_initiation < 0.0f && ph.time_to_flower_opening < 0.0f) {
                    setFruit(fb, t, now);  // no flower stages: the bud sets fruit directly
                } else if (ph.time_to_flower_initiation >= 0.0f) {
                    fb.stage = FloralStage::FlowerClosed;
                    fb.nextTime = next(ph.time_to_flower_opening >= 0.0f ? ph.time_to_flower_opening
                                                                         : ph.time_to_fruit_set);
                    if (ph.time_to_flower_opening < 0.0f && fb.nextTime >= 0.0)
                        fb.state = BudState::Active;
                } else {
                    fb.stage = FloralStage::FlowerOpen;
                    fb.nextTime = next(ph.time_to_fruit_set);
                }
                break;
            }
            case FloralStage::FlowerClosed:
                if (fb.state == BudState::Active) {  // opening disabled: straight to fruit
                    setFruit(fb, t, now);
                } else {
                    fb.stage = FloralStage::FlowerOpen;
                    fb.nextTime = next(ph.time_to_fruit_set);
                }
                break;
            case FloralStage::FlowerOpen:
                setFruit(fb, t, now);
                break;
            default:
                return;
        }
        fb.stageTime = now;
        push(fb.nextTime, kFloral, e.shoot, e.node, e.petiole, e.index, e.terminal);
    }

    void setFruit(FloralBud& fb, const ShootParameters& t, double now) {
        const float p = t.fruit_set_probability.sample(plant.rng);
        std::vector<FlowerOrgan> set;
        for (FlowerOrgan& fl : fb.flowers) {
            if (plant.rng.chance(p))
                set.push_back(fl);
            else
                removeObjects(fl.objects);
        }
        fb.flowers = std::move(set);
        fb.stage = fb.flowers.empty() ? FloralStage::Removed : FloralStage::Fruit;
        fb.fruitAge = 0.0f;
        fb.fruitGrowth = 0.0f;
        fb.stageTime = now;
    }

    std::vector<ObjectID> pendingDeletes;
    void removeObjects(std::vector<ObjectID>& ids) {
        pendingDeletes.insert(pendingDeletes.end(), ids.begin(), ids.end());
        ids.clear();
    }

    void onDormancyBreak(double now) {
        // A plant built dormant spent its first winter as built: each built shoot whose
        // flowers need a winter and whose apex lives set its terminal floral buds then, as a
        // shoot does at the end of every later season (onSenescence).
        if (plant.season == 0)
            for (Shoot& s : plant.shoots) {
                const ShootParameters& t = typeOf(s.type);
                if (!s.removed && t.flowers_require_dormancy && s.apicalBud.state != BudState::Dead)
                    stopShoot(s, t);
            }
        plant.nextDormancyBreak = -1.0;
        plant.stage = PhenologyStage::Vegetative;
        plant.dormancyBreakTime = now;
        plant.season++;
        const float senesce = plant.phenology.time_to_senescence;
        plant.senescenceTime = senesce >= 0.0f ? now + senesce : -1.0;
        push(plant.senescenceTime, kSenescence, 0);
        const double flowering = floweringTime(now);
        // A dormant floral bud still waiting flowers this season, its clock starting now.
        auto awaken = [&](FloralBud& fb, unsigned shoot, unsigned node, unsigned petiole,
                          unsigned index, bool terminal) {
            if (fb.stage == FloralStage::Bud && waiting(fb) && fb.nextTime < 0.0 &&
                flowering >= 0.0) {
                fb.nextTime = flowering;
                push(fb.nextTime, kFloral, shoot, node, petiole, index, terminal);
            }
        };
        for (Shoot& s : plant.shoots) {
            if (s.removed) continue;
            const ShootParameters& t = typeOf(s.type);
            s.nodesThisSeason = 0;
            if (s.apicalBud.state == BudState::Dormant) s.apicalBud.state = BudState::Active;
            if (s.nextPhytomerTime < 0.0 && canGrow(s, t)) {
                s.nextPhytomerTime = now + s.phyllochron;
                push(s.nextPhytomerTime, kPhytomer, s.id);
            }
            for (unsigned k = 0; k < s.phytomers.size(); ++k)
                for (unsigned j = 0; j < s.phytomers[k].petioles.size(); ++j) {
                    Petiole& pt = s.phytomers[k].petioles[j];
                    for (unsigned b = 0; b < pt.vegetativeBuds.size(); ++b) {
                        VegetativeBud& bud = pt.vegetativeBuds[b];
                        if (bud.state == BudState::Dormant && bud.breakTime < 0.0) {
                            // Buds that need a winter are sorted as the season begins, by
                            // their place on the shoot as it stands now.
                            const float carbon = s.carbon ? s.carbon->budBreakFactor : 1.0f;
                            if (t.growth_requires_dormancy &&
                                !plant.rng.chance(
                                    carbon * budBreakProbability(t, plant.rng, int(k),
                                                                 int(s.phytomers.size()), true))) {
                                bud.state = BudState::Dead;
                                continue;
                            }
                            bud.breakTime = budBreakTime(t, s.phytomers[k], now);
                            push(bud.breakTime, kBudBreak, s.id, k, j, b);
                        }
                    }
                    for (unsigned b = 0; b < pt.floralBuds.size(); ++b)
                        awaken(pt.floralBuds[b], s.id, k, j, b, false);
                }
            for (unsigned i = 0; i < s.terminalFloralBuds.size(); ++i)
                awaken(s.terminalFloralBuds[i], s.id, 0, 0, i, true);
        }
    }

    // The season ends: leaves fall unless evergreen, flowers and fruit are shed, growth
    // stops until the next dormancy break.
    void onSenescence(double now) {
        plant.senescenceTime = -1.0;
        updateGirth();  // girth keeps the peak it reached with the leaves still on
        for (Shoot& s : plant.shoots) {
            if (s.removed) continue;
            const ShootParameters& t = typeOf(s.type);
            if (s.apicalBud.state == BudState::Active) stopShoot(s, t);
            if (s.apicalBud.state == BudState::Active) s.apicalBud.state = BudState::Dormant;
            s.nextPhytomerTime = -1.0;
            auto shed = [&](FloralBud& fb) {
                if (fb.stage == FloralStage::FlowerClosed || fb.stage == FloralStage::FlowerOpen ||
                    fb.stage == FloralStage::Fruit) {
                    fb.stage = FloralStage::Removed;
                    fb.state = BudState::Dead;
                    fb.nextTime = -1.0;
                }
            };
            for (Phytomer& ph : s.phytomers)
                for (Petiole& pt : ph.petioles) {
                    if (!plant.phenology.evergreen)
                        for (LeafOrgan& l : pt.leaves) l.removed = true;
                    for (FloralBud& fb : pt.floralBuds) shed(fb);
                    for (VegetativeBud& b : pt.vegetativeBuds)
                        if (b.state == BudState::Dormant) b.breakTime = -1.0;
                }
            for (FloralBud& fb : s.terminalFloralBuds) shed(fb);
        }
        plant.stage = PhenologyStage::Dormant;
        const float winter = plant.phenology.time_to_dormancy_break;
        plant.nextDormancyBreak = winter >= 0.0f ? now + winter : -1.0;
        push(plant.nextDormancyBreak, kDormancyBreak, 0);
    }

    // Callbacks see the plant as it stands on this day: run() brings elongation up to date
    // before this event, and node positions are computed per shoot when first needed.
    void onDaily(double now) {
        std::vector<vec3> positions;
        for (Shoot& s : plant.shoots) {
            if (s.removed) continue;
            positions.clear();
            auto nodeBases = [&]() -> const std::vector<vec3>& {
                if (positions.empty()) positions = shootNodePositions(plant, s.id);
                return positions;
            };
            for (unsigned k = 0; k < s.phytomers.size(); ++k) {
                const PhytomerParameters& pp =
                    typeOf(s.phytomers[k].parametersLabel).phytomer_parameters;
                if (!pp.node_rules.empty())
                    rules::applyDaily(plant, s, k, pp, now, [&] { return nodeBases()[k]; });
                const std::string& name = pp.phytomer_callback_function;
                if (name.empty()) continue;
                const PhytomerCallbackFunction& fn = growth.functions.callback(name, s.type);
                PhytomerCallbackContext c{plant, s, s.phytomers[k], k, now, nodeBases()[k]};
                fn(c);
            }
        }
        push(now + 1.0, kDaily, 0);
    }

    // ---- water sprouts --------------------------------------------------------------------

    bool sprouts() const { return plant.epicormic && plant.epicormic->probability > 0.0f; }

    // Once a day in a growing season, each shoot there was at the day's start draws a point
    // along its phytomers and grows a water sprout there with probability rate x its length x
    // the vertical part of that internode's axis (two draws per shoot, whatever the outcome).
    void onEpicormic(double now) {
        if (!sprouts()) return;
        push(now + 1.0, kEpicormic, 0);
        if (!growingSeason()) return;
        const EpicormicShoots sprout = *plant.epicormic;
        const std::size_t shoots = plant.shoots.size();
        for (std::size_t i = 0; i < shoots; ++i) {
            const Shoot& s = plant.shoots[i];
            if (s.removed || s.phytomers.empty()) continue;
            double length = 0.0;
            for (const Phytomer& ph : s.phytomers)
                length += double(ph.internode.length) * ph.internodeFraction;
            const float u = plant.rng.uniform01();
            const float draw = plant.rng.uniform01();
            const unsigned node = epicormicNode(s, u);
            const double chance = double(sprout.probability) * length *
                                  std::abs(double(s.phytomers[node].internode.direction.z));
            if (!(double(draw) < chance)) continue;
            const ShootParameters& ct = typeOf(sprout.shootType);
            ShootSpec spec;
            spec.phytomers = 1;
            spec.shootType = sprout.shootType;
            spec.size.internodeRadius =
                std::max(ct.phytomer_parameters.internode.radius_initial.sample(plant.rng), 1e-6f);
            spec.size.internodeLengthMax = ct.internode_length_max.sample(plant.rng);
            spec.size.internodeLengthScale = 0.01f;
            spec.size.leafScale = 0.01f;
            const unsigned id =
                createShoot(growth, plant, spec, StartMode::Epicormic, int(i), node, 0);
            enqueueShoot(plant.shoots[id]);
        }
    }

    // ---- continuous state --------------------------------------------------------------

    void updateContinuous(double now) {
        const double step = growthStep(plant);
        const std::string* label = nullptr;  // the phytomer type whose `reciprocal` is held
        double reciprocal = 0.0;
        for (Shoot& s : plant.shoots) {
            if (s.removed) continue;
            const float rate = s.elongationRate;
            for (Phytomer& ph : s.phytomers) {
                const double age = std::max(0.0, now - ph.birth);
                ph.age = float(age);
                ph.internodeFraction = float(std::min(1.0, ph.internodeFraction0 + rate * age));
                if (ph.leafFraction0 >= 1.0f) {
                    ph.leafFraction = 1.0f;
                } else {
                    // One type's nominal size serves its run of phytomers (usually the shoot).
                    if (!label || *label != ph.parametersLabel) {
                        label = &ph.parametersLabel;
                        reciprocal = nominalReciprocal(
                            typeOf(*label).phytomer_parameters.leaf.prototype_scale);
                    }
                    ph.leafFraction = leafFractionAt(ph.leafFraction0, rate, age,
                                                     leafSizeRatio(ph, reciprocal), step);
                }
                for (Petiole& pt : ph.petioles) {
                    for (LeafOrgan& l : pt.leaves) l.age = float(std::max(0.0, now - l.birth));
                    for (FloralBud& fb : pt.floralBuds) updateFruit(fb, now);
                }
            }
            for (FloralBud& fb : s.terminalFloralBuds) updateFruit(fb, now);
        }
    }

    void updateFruit(FloralBud& fb, double now) {
        if (fb.stage != FloralStage::Fruit) return;
        const float maturity = plant.phenology.time_to_fruit_maturity;
        fb.fruitAge = float(now - fb.stageTime);
        fb.fruitGrowth = maturity > 0.0f ? std::min(1.0f, fb.fruitAge / maturity) : 1.0f;
    }

    // The prototype areas of one shoot's leaves (PrototypeCache::leafPrototypeArea) from the
    // cache's table of its prototype: girth is updated at every growth step, and a shoot's
    // leaves share a few prototypes (a prototype per leaf, unique_prototypes = 0, goes to the
    // memo).
    class ShootAreas {
    public:
        using Table = PrototypeCache::LeafAreaTable;
        ShootAreas(PrototypeCache& prototypes, const LeafParameters& lp)
            : prototypes_(prototypes),
              lp_(lp),
              variants_(lp.prototype.unique_prototypes),
              table_(variants_ > 0 && variants_ <= Table::kVariants
                         ? &prototypes.leafAreaTable(&lp.prototype)
                         : nullptr) {}
        double operator()(const LeafOrgan& l) {
            if (!table_ || l.leafletIndex < -Table::kLeaflets || l.leafletIndex > Table::kLeaflets)
                return prototypes_.leafPrototypeArea(lp_, l);
            const std::size_t slot =
                std::size_t(l.leafletIndex + Table::kLeaflets) * Table::kVariants +
                l.variant % variants_;
            if (!table_->set[slot]) {
                table_->area[slot] = prototypes_.leafPrototypeArea(lp_, l);
                table_->set[slot] = true;
            }
            return table_->area[slot];
        }

    private:
        PrototypeCache& prototypes_;
        const LeafParameters& lp_;
        const unsigned variants_;
        Table* table_;
    };

    // Each internode of `s` toward its target radius. A shoot with a carbohydrate budget
    // thickens as far as its radial allowance pays (the cross-sections' share of the full
    // increase, at least radialMinimum, the allowance spent); others reach the targets.
    void thicken(Shoot& s, const std::vector<float>& target) {
        double share = 1.0;
        if (s.carbon) {
            const CarbohydrateParameters& p = plant.phenology.carbohydrates;
            double volume = 0.0;  // m³ of the full increase
            for (std::size_t k = 0; k < target.size(); ++k) {
                const Phytomer& ph = s.phytomers[k];
                const double r0 = ph.internode.radius, r1 = target[k];
                volume += kPi * (r1 * r1 - r0 * r0) * double(ph.internode.length) *
                          double(ph.internodeFraction);
            }
            const double cost = carbon::woodCost(p, carbon::woodCarbon(p, volume));
            if (cost > 0.0) {
                share = std::clamp(s.carbon->radialAllowance / cost, kRadialMinimum, 1.0);
                s.carbon->radialAllowance = std::max(0.0, s.carbon->radialAllowance - share * cost);
            }
        }
        for (std::size_t k = 0; k < target.size(); ++k) {
            Internode& in = s.phytomers[k].internode;
            const double r0 = in.radius, r1 = target[k];
            in.radius =
                std::max({in.radius, float(std::sqrt(r0 * r0 + share * (r1 * r1 - r0 * r0))),
                          std::min(s.phytomers[k].radiusInitial, target[k])});
        }
    }

    // Internode cross-section = girth_area_factor (cm^2 per m^2) x leaf area downstream;
    // radii never shrink and never fall below their initial value.
    void updateGirth() {
        std::vector<double>& shootTotal = girthTotals;
        shootTotal.assign(plant.shoots.size(), 0.0);
        for (std::size_t i = plant.shoots.size(); i-- > 0;) {
            Shoot& s = plant.shoots[i];
            if (s.removed) continue;
            std::vector<double>& atNode = girthNodes;
            atNode.assign(s.phytomers.size(), 0.0);
            const LeafParameters& lp = typeOf(s.type).phytomer_parameters.leaf;
            ShootAreas areas(growth.prototypes, lp);
            for (std::size_t k = 0; k < s.phytomers.size(); ++k) {
                Phytomer& ph = s.phytomers[k];
                for (Petiole& pt : ph.petioles)
                    for (LeafOrgan& l : pt.leaves)
                        if (!l.removed) {
                            const double size = double(l.scale) * ph.leafFraction;
                            atNode[k] += areas(l) * size * size;
                        }
            }
            for (unsigned c : s.children) {
                const Shoot& child = plant.shoots[c];
                if (!child.removed && child.parentNode >= 0 &&
                    std::size_t(child.parentNode) < atNode.size())
                    atNode[std::size_t(child.parentNode)] += shootTotal[c];
            }
            double downstream = 0.0;
            std::vector<float>& target = girthTargets;
            target.assign(s.phytomers.size(), 0.0f);
            for (std::size_t k = s.phytomers.size(); k-- > 0;) {
                downstream += atNode[k];
                const Phytomer& ph = s.phytomers[k];
                target[k] = ph.internode.radius;
                if (s.girthAreaFactor > 0.0f && !ph.measured) {  // a measured radius stays
                    const double area = double(s.girthAreaFactor) * downstream * 1e-4;  // m^2
                    target[k] = std::max(
                        {ph.internode.radius, float(std::sqrt(area / kPi)), ph.radiusInitial});
                }
            }
            thicken(s, target);
            shootTotal[i] = downstream;
        }
    }

    void run(double target) {
        const double maxAge = plant.phenology.max_age;
        if (plant.age > maxAge) {  // frozen as it stood at max_age: only its age goes on
            plant.age = target;
            plant.stage = PhenologyStage::Senescent;
            return;
        }
        const double stop = std::min(target, std::max(plant.age, maxAge));
        const double start = plant.age;
        double nextReport = std::floor(start) + 1.0;
        horizon = stop;
        enqueueAll(plant.age);
        while (!queue.empty() && queue.top().time <= stop) {
            const Event e = queue.top();
            queue.pop();
            if (!valid(e)) continue;
            if (e.time >= nextReport && onDay && *onDay) {  // at most once a day
                (*onDay)((e.time - start) / (stop - start));
                nextReport = std::floor(e.time) + 1.0;
            }
            plant.age = e.time;
            if (e.kind == kLeafFall || e.kind == kSenescence || e.kind == kDaily)
                updateContinuous(e.time);
            switch (e.kind) {
                case kDormancyBreak:
                    onDormancyBreak(e.time);
                    break;
                case kSenescence:
                    onSenescence(e.time);
                    break;
                case kDaily:
                    onDaily(e.time);
                    break;
                case kEpicormic:
                    onEpicormic(e.time);
                    budget.grew(*this);
                    break;
                case kPhytomer:
                    onPhytomer(plant.shoots[e.shoot], e.time);
                    budget.grew(*this);
                    break;
                case kBudBreak:
                    onBudBreak(e);
                    budget.grew(*this);
                    break;
                case kFloral:
                    onFloral(e, e.time);
                    break;
                case kLeafFall: {
                    updateGirth();
                    LeafOrgan& l =
                        plant.shoots[e.shoot].phytomers[e.node].petioles[e.petiole].leaves[e.index];
                    l.removed = true;
                    break;
                }
            }
        }
        plant.age = std::max(plant.age, stop);
        updateContinuous(plant.age);
        updateGirth();
        budget.check(*this);
        plant.age = target;
        if (target > plant.phenology.max_age) plant.stage = PhenologyStage::Senescent;
    }

    // ---- the triangle limit --------------------------------------------------------------

    // The fewest triangles the plant's organs need once drawn: each internode's tube side
    // (two triangles a side) and two per leaf. It never exceeds what tessellation makes, so
    // a plant within the limit is never stopped; a runaway plant stops here, long before
    // its geometry is made. Also counts the phytomers (for TriangleBudget's schedule).
    std::size_t leastTriangles(std::size_t& phytomers) {
        std::size_t n = 0;
        phytomers = 0;
        for (const Shoot& s : plant.shoots) {
            if (s.removed) continue;
            const unsigned sides =
                detailed(typeOf(s.type).phytomer_parameters.internode.radial_subdivisions,
                         growth.store.meshDetail, 3);
            phytomers += s.phytomers.size();
            for (const Phytomer& ph : s.phytomers) {
                n += 2 * std::size_t(sides);
                for (const Petiole& pt : ph.petioles)
                    for (const LeafOrgan& l : pt.leaves) n += l.removed ? 0 : 2;
            }
        }
        return n;
    }

    // Checks leastTriangles against the store's limit after every so many new phytomers and
    // shoots (a quarter of the plant's phytomers, at least 256): linear time overall.
    struct TriangleBudget {
        std::size_t sinceCheck = 0, checkEvery = 256;
        void grew(Grower& g) {
            if (g.growth.store.triangleLimit != 0 && ++sinceCheck >= checkEvery) check(g);
        }
        void check(Grower& g) {
            const std::size_t limit = g.growth.store.triangleLimit;
            if (limit == 0) return;
            sinceCheck = 0;
            std::size_t phytomers = 0;
            const std::size_t least = g.leastTriangles(phytomers);
            checkEvery = std::max<std::size_t>(256, phytomers / 4);
            if (least > limit)
                throw TriangleBudgetError("plant " + std::to_string(g.plant.id) + " grown to " +
                                              text::formatFloat(float(g.plant.age)) + " days",
                                          least, limit,
                                          "at least: 2 per internode side and 2 per leaf of its " +
                                              std::to_string(phytomers) + " phytomers");
        }
    } budget;

    // An event is current only if the time stored on its organ still says so (organs may
    // have been pruned, removed or rescheduled since it was queued).
    bool valid(const Event& e) {
        switch (e.kind) {
            case kDormancyBreak:
                return plant.nextDormancyBreak == e.time;
            case kSenescence:
                return plant.senescenceTime == e.time;
            case kDaily:
            case kEpicormic:
                return true;
            default:
                break;
        }
        if (e.shoot >= plant.shoots.size() || plant.shoots[e.shoot].removed) return false;
        Shoot& s = plant.shoots[e.shoot];
        if (e.kind == kPhytomer) return s.nextPhytomerTime == e.time;
        if (e.terminal)
            return e.index < s.terminalFloralBuds.size() &&
                   s.terminalFloralBuds[e.index].nextTime == e.time;
        if (e.node >= s.phytomers.size() || e.petiole >= s.phytomers[e.node].petioles.size())
            return false;
        Petiole& pt = s.phytomers[e.node].petioles[e.petiole];
        switch (e.kind) {
            case kBudBreak:
                return e.index < pt.vegetativeBuds.size() &&
                       pt.vegetativeBuds[e.index].breakTime == e.time;
            case kFloral:
                return e.index < pt.floralBuds.size() && pt.floralBuds[e.index].nextTime == e.time;
            case kLeafFall:
                return e.index < pt.leaves.size() && !pt.leaves[e.index].removed &&
                       pt.leaves[e.index].birth + plant.phenology.max_leaf_lifespan == e.time;
        }
        return false;
    }
};

}  // namespace

void realizeInflorescence(PlantInstance& p, FloralBud& fb, const PhytomerParameters& pp) {
    fb.peduncleLength = pp.peduncle.length.sample(p.rng);
    fb.peduncleRadius = pp.peduncle.radius.sample(p.rng);
    fb.pedunclePitch = pp.peduncle.pitch.sample(p.rng);
    fb.peduncleRoll = pp.peduncle.roll.sample(p.rng);
    fb.peduncleCurvature = pp.peduncle.curvature.sample(p.rng);
    fb.peduncleAzimuth = 0.0f;  // on its petiole's side until steered
    const InflorescenceParameters& inf = pp.inflorescence;
    const int count = std::max(1, inf.flowers_per_peduncle.sample(p.rng));
    const float offset = inf.flower_offset.sample(p.rng);
    const bool opposite = inf.flower_arrangement == FlowerArrangement::Opposite;
    fb.flowers.clear();
    for (int i = 0; i < count; ++i) {
        FlowerOrgan fl;
        // Alternate: one flower per position, sides alternating. Opposite: pairs per position.
        const int step = opposite ? i / 2 : i;
        fl.position = std::max(0.0f, 1.0f - float(step) * offset);
        fl.azimuth = (i % 2 ? 180.0f : 0.0f) + (opposite ? 90.0f : 0.0f);
        fl.pitch = inf.pitch.sample(p.rng);
        fl.roll = inf.roll.sample(p.rng);
        fl.flowerScale = inf.flower_prototype_scale.sample(p.rng);
        fl.fruitScale = inf.fruit_prototype_scale.sample(p.rng);
        fl.gravityFactor = inf.fruit_gravity_factor_fraction.sample(p.rng);
        fl.variant = inf.unique_prototypes > 1 ? p.rng.nextU32() % inf.unique_prototypes : 0;
        fb.flowers.push_back(fl);
    }
}

void scheduleNewShoot(const GrowthContext& growth, PlantInstance& plant, Shoot& shoot) {
    Grower grower{growth, plant, {}, {}, {}, {}};
    const ShootParameters& t = grower.typeOf(shoot.type);
    if (shoot.nextPhytomerTime < 0.0 && grower.growingSeason() && grower.canGrow(shoot, t))
        shoot.nextPhytomerTime = plant.age + shoot.phyllochron;
    for (Phytomer& ph : shoot.phytomers) grower.scheduleBuds(shoot, ph);
}

unsigned epicormicNode(const Shoot& shoot, float position) {
    const std::size_t n = shoot.phytomers.size();
    const double k = std::ceil(double(position) * double(n)) - 1.0;
    return unsigned(std::clamp(k, 0.0, double(n) - 1.0));
}

void changeSeason(const GrowthContext& growth, PlantInstance& plant, bool begin) {
    Grower grower{growth, plant, {}, {}, {}, {}};
    grower.horizon = -1.0;  // nothing is queued: later runs queue from the stored times
    if (begin && plant.stage == PhenologyStage::Dormant) grower.onDormancyBreak(plant.age);
    if (!begin && grower.growingSeason()) grower.onSenescence(plant.age);
}

void growPlant(const GrowthContext& growth, PlantInstance& plant, double days,
               std::vector<ObjectID>& deletes, const std::function<void(double)>& onDay) {
    double target = plant.age + days;
    // Snap to a 1/1024-day grid when within float rounding of it, so steps such as 0.1f x 10
    // or 19.9f + 0.1f land exactly on the day an event is due.
    const double grid = std::nearbyint(target * 1024.0) / 1024.0;
    if (std::abs(target - grid) < 1e-5) target = grid;
    growth.prototypes.clearCallMemos();
    Grower grower{growth, plant, {}, {}, {}, {}};
    grower.onDay = &onDay;
    grower.run(target);
    deletes.insert(deletes.end(), grower.pendingDeletes.begin(), grower.pendingDeletes.end());
    clearSideOrgans(growth.store, growth.prototypes, plant, growth.obstacles,
                    growth.clearanceCounts);
    if (growth.store.groundClipping)
        clipBelowGround(growth.store, growth.prototypes, plant, *growth.store.groundClipping);
    if (plant.phenology.mechanics.enabled)  // shoots bending under load
        bending::bendPlant(growth.store, growth.prototypes, plant);
}

}  // namespace plantarch
