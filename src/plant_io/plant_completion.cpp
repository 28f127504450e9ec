// Completing plants read from partial input (the specification's listing form, plant
// strings) and checking that every plant read is consistent.
//
// Defaults follow what plantarch itself would have made: the PlantArchitecture's current
// shoot types and phenology, its seed's stream for the plant, realized shoot values at the
// means of their distributions, phytomers fully grown, leaflets numbered and placed as
// compound leaves are, and internode frames rebuilt from the listed angles (straight shoot
// axes: the listing does not record curvature or random-walk turns).

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <map>
#include <optional>
#include <pugixml.hpp>
#include <set>
#include <type_traits>

#include "core/math.h"
#include "core/value_text.h"
#include "plant_io/plant_structure.h"
#include "plantarch/Error.h"
#include "plantarch/PlantStateTable.h"

namespace plantarch::plant_io {

namespace {

// A shoot start turned from `parent` by its base rotation, as PlantArchitecture makes it.
AxisFrame orient(const AxisFrame& parent, const AxisRotation& r) {
    return turnedFrame(parent, r.pitch, r.yaw, r.roll);
}

class Completer {
public:
    Completer(PlantInstance& p, const Presence& m, const Defaults& d,
              std::vector<std::string>& notes, std::string where)
        : p_(p), m_(m), d_(d), notes_(notes), where_(std::move(where)) {}

    void run(unsigned stream) {
        p_.stream = stream;
        if (m_.missing(&p_.rng)) p_.rng = Rng::forPlant(d_.seed, stream);
        if (m_.missing(&p_.phenology)) p_.phenology = d_.phenology;
        if (m_.missing(&p_.groundClearance)) p_.groundClearance = d_.groundClearance;
        if (m_.missing(&p_.nextDormancyBreak)) {
            const float wait = p_.phenology.time_to_dormancy_break;
            p_.nextDormancyBreak = wait < 0.0f ? -1.0 : p_.age + wait;
        }
        shootTypes();
        int maxID = -1;
        forEachLeaf([&](LeafOrgan& l) {
            if (!m_.missing(&l.leafID)) maxID = std::max(maxID, l.leafID);
        });
        nextLeafID_ = maxID + 1;
        for (std::size_t i = 0; i < p_.shoots.size(); ++i) shoot(p_.shoots[i], i);
        if (m_.missing(&p_.nextLeafID)) p_.nextLeafID = nextLeafID_;
    }

private:
    template <class F>
    void forEachLeaf(F&& f) {
        for (Shoot& s : p_.shoots)
            for (Phytomer& ph : s.phytomers)
                for (Petiole& pt : ph.petioles)
                    for (LeafOrgan& l : pt.leaves) f(l);
    }

    // Shoot types the file does not hold: from the PlantArchitecture, else plantarch's defaults.
    void shootTypes() {
        if (m_.missing(&p_.shootTypes) && d_.shootTypes) {
            p_.shootTypes = *d_.shootTypes;
            if (!p_.shootTypes.empty())
                notes_.push_back("shoot types: the current ones of the PlantArchitecture");
        }
        std::set<std::string> needed;
        for (Shoot& s : p_.shoots) {
            if (s.type.empty()) continue;
            needed.insert(s.type);
            for (Phytomer& ph : s.phytomers)
                if (!m_.missing(&ph.parametersLabel) && !ph.parametersLabel.empty())
                    needed.insert(ph.parametersLabel);
        }
        for (const std::string& label : needed) {
            if (p_.shootTypes.count(label)) continue;
            if (d_.shootTypes && d_.shootTypes->count(label)) {
                p_.shootTypes.emplace(label, d_.shootTypes->at(label));
                notes_.push_back("shoot type " + label + ": the PlantArchitecture's");
            } else {
                ShootParameters t;
                const std::string variants = coverVariants(label, t.phytomer_parameters);
                p_.shootTypes.emplace(label, std::move(t));
                notes_.push_back("shoot type " + label + ": plantarch's default parameters" +
                                 variants);
            }
        }
    }

    // The shape variants the input gives for organs of shoot type `label` (which the
    // PlantArchitecture does not know): the default parameters get as many leaf and flower
    // variants as the input names, so that every organ keeps its variant (a string written
    // again is the same). Returns what changed, for the warning ("" when nothing did). A
    // count beyond the parameter's range is left as it was: checkPlant then names the variant.
    std::string coverVariants(const std::string& label, PhytomerParameters& pp) const {
        unsigned leaves = 0, flowers = 0;  // highest variant + 1
        auto floral = [&](const FloralBud& fb) {
            for (const FlowerOrgan& fl : fb.flowers) flowers = std::max(flowers, fl.variant + 1);
        };
        for (const Shoot& s : p_.shoots) {
            if (s.type == label)
                for (const FloralBud& fb : s.terminalFloralBuds) floral(fb);
            for (const Phytomer& ph : s.phytomers) {
                const bool own = m_.missing(&ph.parametersLabel) || ph.parametersLabel.empty();
                if ((own ? s.type : ph.parametersLabel) != label) continue;
                for (const Petiole& pt : ph.petioles) {
                    for (const LeafOrgan& l : pt.leaves) leaves = std::max(leaves, l.variant + 1);
                    for (const FloralBud& fb : pt.floralBuds) floral(fb);
                }
            }
        }
        std::string out;
        auto cover = [&](unsigned& count, unsigned needed, const char* what) {
            if (needed <= count) return;
            const unsigned was = count;
            count = needed;
            try {
                validate(pp);  // the parameter table's range of the count
                out += ", " + std::to_string(needed) + " " + what + " shape variants as given";
            } catch (const Error&) {
                count = was;
            }
        };
        cover(pp.leaf.prototype.unique_prototypes, leaves, "leaf");
        cover(pp.inflorescence.unique_prototypes, flowers, "flower");
        return out;
    }

    const ShootParameters* typeOf(const std::string& label) const {
        auto it = p_.shootTypes.find(label);
        return it == p_.shootTypes.end() ? nullptr : &it->second;
    }

    void realized(Shoot& s, const ShootParameters& t) {
        auto fill = [&](auto& member, auto value) {
            if (m_.missing(&member))
                member = static_cast<std::remove_reference_t<decltype(member)>>(value);
        };
        fill(s.maxNodes, std::lround(t.max_nodes.mean()));
        fill(s.maxNodesPerSeason, std::lround(t.max_nodes_per_season.mean()));
        fill(s.internodeLengthMax, t.internode_length_max.mean());
        fill(s.phyllochron, t.phyllochron_min.mean());
        fill(s.elongationRate, t.elongation_rate_max.mean());
        fill(s.gravitropicCurvature, t.gravitropic_curvature.mean());
        fill(s.tortuosity, t.tortuosity.mean());
        fill(s.girthAreaFactor, t.girth_area_factor.mean());
    }

    // Frame of the first phytomer of shoot `s` (index i), as the builder makes it.
    AxisFrame startFrame(const Shoot& s, std::size_t i) const {
        const AxisFrame upright{vec3(0, 0, 1), vec3(1, 0, 0)};
        if (s.parent < 0 || std::size_t(s.parent) >= i) return orient(upright, s.baseRotation);
        const Shoot& parent = p_.shoots[std::size_t(s.parent)];
        if (parent.phytomers.empty()) return orient(upright, s.baseRotation);
        const bool appended = !m_.missing(&s.rank) && s.rank == parent.rank;
        if (appended) {
            const Internode& tip = parent.phytomers.back().internode;
            return orient({tip.guide, tip.rollReference}, s.baseRotation);
        }
        const std::size_t node = std::min<std::size_t>(std::size_t(std::max(s.parentNode, 0)),
                                                       parent.phytomers.size() - 1);
        const Phytomer& ph = parent.phytomers[node];
        const Internode& in = ph.internode;
        const float az = std::size_t(s.parentPetiole) < ph.petioles.size()
                             ? ph.petioles[std::size_t(s.parentPetiole)].azimuth
                             : in.azimuth;
        const vec3 side = azimuthDirection(in.guide, in.rollReference, az);
        const float angle = m_.missing(&s.insertionAngle) ? s.baseRotation.pitch : s.insertionAngle;
        return lateralFrame(in.direction, side, angle, s.baseRotation.yaw, s.baseRotation.roll);
    }

    void shoot(Shoot& s, std::size_t i) {
        if (m_.missing(&s.type) || s.type.empty())
            throw Error("missing <shoot_type_label>",
                        {.parameter = where_ + ".shoot[" + std::to_string(i) + "].shoot_type_label",
                         .validRange = "the label of a shoot type"});
        if (m_.missing(&s.rank))
            s.rank = s.parent >= 0 && std::size_t(s.parent) < i
                         ? p_.shoots[std::size_t(s.parent)].rank + 1
                         : 0;
        const ShootParameters* t = typeOf(s.type);
        if (t) realized(s, *t);
        if (m_.missing(&s.apicalBud.state)) s.apicalBud.state = BudState::Active;
        if (m_.missing(&s.nodesThisSeason)) s.nodesThisSeason = int(s.phytomers.size());
        const AxisFrame start = startFrame(s, i);
        for (std::size_t k = 0; k < s.phytomers.size(); ++k) phytomer(s, k, start);
        const std::size_t n = s.terminalFloralBuds.size();
        for (std::size_t b = 0; b < n; ++b) {
            FloralBud& fb = s.terminalFloralBuds[b];
            if (m_.missing(&fb.terminal)) fb.terminal = true;
            // Evenly around the tip, as growth places them.
            if (m_.missing(&fb.terminalAzimuth)) fb.terminalAzimuth = 360.0f * float(b) / float(n);
            floral(fb);
        }
    }

    void phytomer(Shoot& s, std::size_t k, const AxisFrame& start) {
        Phytomer& ph = s.phytomers[k];
        if (m_.missing(&ph.parametersLabel)) ph.parametersLabel = s.type;
        if (m_.missing(&ph.birth)) ph.birth = 0.0;
        if (m_.missing(&ph.age)) ph.age = float(std::max(0.0, p_.age - ph.birth));
        Internode& in = ph.internode;
        if (m_.missing(&ph.radiusInitial)) ph.radiusInitial = in.radius;
        const Internode* prev = k > 0 ? &s.phytomers[k - 1].internode : nullptr;
        if (m_.missing(&in.azimuth))
            in.azimuth = prev ? std::fmod(prev->azimuth + in.phyllotacticAngle, 360.0f) : 0.0f;
        if (m_.missing(&in.guide)) in.guide = prev ? prev->guide : start.axis;
        if (m_.missing(&in.rollReference))
            in.rollReference =
                prev ? carriedRollReference(prev->rollReference, in.guide) : start.reference;
        if (m_.missing(&in.direction)) in.direction = internodeDirection(in);
        const ShootParameters* t = typeOf(ph.parametersLabel);
        const std::size_t n = ph.petioles.size();
        for (std::size_t j = 0; j < n; ++j) {
            Petiole& pt = ph.petioles[j];
            if (m_.missing(&pt.azimuth)) pt.azimuth = petioleAzimuth(in.azimuth, j, n);
            if (m_.missing(&pt.taper) && t) pt.taper = t->phytomer_parameters.petiole.taper.mean();
            leaves(ph, pt, t);
            for (FloralBud& fb : pt.floralBuds) floral(fb);
        }
    }

    // Leaflets in the order compound leaves are made: an odd count starts with the tip
    // leaflet (index 0), then pairs -1, 1, -2, 2, ... each a leaflet_offset further down.
    void leaves(const Phytomer& ph, Petiole& pt, const ShootParameters* t) {
        const int n = int(pt.leaves.size());
        const float offset = t ? t->phytomer_parameters.leaf.leaflet_offset.mean() : 0.0f;
        for (int i = 0; i < n; ++i) {
            LeafOrgan& l = pt.leaves[std::size_t(i)];
            const bool tip = n % 2 == 1 && i == 0;
            const int pair = n % 2 == 1 ? (i + 1) / 2 : i / 2 + 1;  // 1-based pair number
            const int step = n % 2 == 1 ? pair : pair - 1;          // pair steps from the tip
            if (m_.missing(&l.leafletIndex))
                l.leafletIndex = tip ? 0 : ((i - (n % 2)) % 2 == 0 ? -pair : pair);
            if (m_.missing(&l.position))
                l.position = tip || n == 1 ? 1.0f : std::max(0.0f, 1.0f - float(step) * offset);
            if (m_.missing(&l.leafID)) l.leafID = nextLeafID_++;
            if (m_.missing(&l.birth)) l.birth = ph.birth;
            if (m_.missing(&l.age)) l.age = float(std::max(0.0, p_.age - l.birth));
        }
    }

    void floral(FloralBud& fb) {
        const bool shown = fb.stage != FloralStage::Bud && fb.stage != FloralStage::Removed;
        if (m_.missing(&fb.state) && shown) fb.state = BudState::Broken;
        if (m_.missing(&fb.stageTime)) fb.stageTime = p_.age;
    }

    PlantInstance& p_;
    const Presence& m_;
    const Defaults& d_;
    std::vector<std::string>& notes_;
    std::string where_;
    int nextLeafID_ = 0;
};

[[noreturn]] void inconsistent(const std::string& path, const std::string& message,
                               const std::string& value, const std::string& range) {
    throw Error(message, {.parameter = path, .value = value, .validRange = range});
}

// Every value of a plant held to its declared range (plantarch/PlantStateTable.h), whichever
// reader filled it: the shared check after reading. Paths are the plant structure file's
// ("shoot[2].phytomer[0].internode.petiole[1].leaf[0].leaf_scale" below `where`).
class ValueCheck {
public:
    explicit ValueCheck(std::string where) : path_(std::move(where)) {}

    template <class T>
    void field(const state::FieldInfo& f, T& member) {
        check(f, member);
    }
    template <class T>
    void field(const params::FieldInfo&, T&) {}  // parameters: validated as species are
    void legacy(const char*) {}
    template <class T>
    void objects(const char*, T&) {}
    template <class Fn>
    void group(const char* name, Fn&& fn) {
        const std::size_t size = push(name);
        fn(*this);
        path_.resize(size);
    }
    template <class T>
    void list(const char* name, std::vector<T>& items, bool = false) {
        for (std::size_t i = 0; i < items.size(); ++i) {
            const std::size_t size = push(std::string(name) + "[" + std::to_string(i) + "]");
            state::describeState(items[i], *this);
            path_.resize(size);
        }
    }
    template <class T>
    void values(const state::FieldInfo& f, std::vector<T>& items) {
        for (T& v : items) check(f, v);
    }
    template <class T>
    void optional(const char* name, std::optional<T>& member) {
        if (member) group(name, [&](auto& v) { state::describeState(*member, v); });
    }
    template <class P>
    void parameters(const char*, P&) {}

private:
    std::size_t push(const std::string& name) {
        const std::size_t size = path_.size();
        if (!path_.empty()) path_ += '.';
        path_ += name;
        return size;
    }

    [[noreturn]] void fail(const state::FieldInfo& f, const std::string& value,
                           const std::string& message, const std::string& range) {
        push(f.name);
        inconsistent(path_, message, value, range);
    }

    void number(const state::FieldInfo& f, double v, const std::string& shown) {
        if (!std::isfinite(v)) fail(f, shown, "not a finite number", rangeText(f.range()));
        if (!state::inside(f, v)) fail(f, shown, "out of range", rangeText(f.range()));
    }

    template <class T>
    requires std::is_arithmetic_v<T>
    void check(const state::FieldInfo& f, const T& v) {
        if constexpr (std::is_same_v<T, bool>)
            return;
        else if constexpr (std::is_same_v<T, float>)
            number(f, double(v), text::formatFloat(v));
        else if constexpr (std::is_floating_point_v<T>)
            number(f, double(v), text::formatDouble(double(v)));
        else
            number(f, double(v), std::to_string(v));
    }
    void check(const state::FieldInfo& f, const vec3& v) {
        const std::string shown =
            text::formatFloat(v.x) + " " + text::formatFloat(v.y) + " " + text::formatFloat(v.z);
        for (int i = 0; i < 3; ++i) {
            if (!std::isfinite(v[i])) fail(f, shown, "not a finite number", rangeText(f.range()));
            // A direction's components may pass 1 by a rounding: its reader checks its length.
            if (f.check != state::Check::UnitVector && !state::inside(f, v[i]))
                fail(f, shown, "out of range", rangeText(f.range()));
        }
    }
    void check(const state::FieldInfo& f, const AxisRotation& r) {
        check(f, vec3(r.pitch, r.yaw, r.roll));
    }
    void check(const state::FieldInfo& f, const std::string& s) {
        const bool optional = f.check == state::Check::LabelOrEmpty;
        if ((f.check == state::Check::Label || optional) && !(optional && s.empty()) &&
            !text::isLabel(s))
            fail(f, s, "a shoot type label is letters, digits, '_' or '-'",
                 optional ? "a label, or nothing" : "a label");
    }
    template <class T>
    void check(const state::FieldInfo&, const T&) {}  // enumerations, generators, label lists

    std::string path_;
};

// Where an organ is in a plant: shoot, phytomer, petiole, item (bud or leaf); its path, made
// only for an error.
struct Place {
    std::size_t shoot = 0, node = 0, petiole = 0, item = 0;
    bool apical = false;  ///< the shoot's apical bud

    std::string path(const std::string& where, const char* kind) const {
        const std::string at = where + ".shoot[" + std::to_string(shoot) + "]";
        if (apical) return at + ".apical_bud.child_shoot_ID";
        return at + ".phytomer[" + std::to_string(node) + "].internode.petiole[" +
               std::to_string(petiole) + "]." + kind + "[" + std::to_string(item) + "]." +
               (std::string(kind) == "leaf" ? "leaf_ID" : "child_shoot_ID");
    }
};

// References between shoots, buds and leaves: every bud's shoot grows from that bud, no two
// buds claim one shoot, leaf IDs are unique and below the plant's next leaf ID.
void checkReferences(const PlantInstance& p, const std::string& where) {
    const std::size_t n = p.shoots.size();
    std::vector<std::optional<Place>> claimedBy(n);
    auto bud = [&](const VegetativeBud& b, const Place& at) {
        const int c = b.childShoot;
        if (c < 0) return;
        const std::string value = std::to_string(c);
        const std::string path = at.path(where, "vegetative_bud");
        if (std::size_t(c) >= n)
            inconsistent(path, "no such shoot", value, "-1 to " + std::to_string(n - 1));
        if (std::size_t(c) == at.shoot)
            inconsistent(path, "a bud's shoot cannot be the shoot the bud is on", value,
                         "-1 or a shoot growing from this bud");
        const Shoot& child = p.shoots[std::size_t(c)];
        const bool here = child.parent == int(at.shoot) &&
                          (at.apical ? child.rank == p.shoots[at.shoot].rank
                                     : child.parentNode == int(at.node) &&
                                           child.parentPetiole == int(at.petiole));
        if (!here)
            inconsistent(path, "shoot " + value + " does not grow from this bud", value,
                         "-1 or a shoot growing from this bud");
        if (claimedBy[std::size_t(c)])
            inconsistent(path,
                         "two buds claim shoot " + value + " (the other: " +
                             claimedBy[std::size_t(c)]->path(where, "vegetative_bud") + ")",
                         value, "each shoot grows from at most one bud");
        claimedBy[std::size_t(c)] = at;
    };
    std::map<int, Place> leafIDs;
    for (std::size_t i = 0; i < n; ++i) {
        const Shoot& s = p.shoots[i];
        bud(s.apicalBud, {.shoot = i, .apical = true});
        for (std::size_t k = 0; k < s.phytomers.size(); ++k) {
            const Phytomer& ph = s.phytomers[k];
            for (std::size_t j = 0; j < ph.petioles.size(); ++j) {
                const Petiole& pt = ph.petioles[j];
                for (std::size_t b = 0; b < pt.vegetativeBuds.size(); ++b)
                    bud(pt.vegetativeBuds[b], {i, k, j, b});
                for (std::size_t l = 0; l < pt.leaves.size(); ++l) {
                    const int id = pt.leaves[l].leafID;
                    if (id < 0) continue;
                    const Place at{i, k, j, l};
                    const auto [it, fresh] = leafIDs.emplace(id, at);
                    if (!fresh)
                        inconsistent(
                            at.path(where, "leaf"),
                            "leaf ID given twice (also " + it->second.path(where, "leaf") + ")",
                            std::to_string(id), "IDs unique within the plant");
                }
            }
        }
    }
    if (!leafIDs.empty() && p.nextLeafID <= leafIDs.rbegin()->first)
        inconsistent(where + ".next_leaf_ID",
                     "not above every leaf ID (" + leafIDs.rbegin()->second.path(where, "leaf") +
                         " is " + std::to_string(leafIDs.rbegin()->first) + ")",
                     std::to_string(p.nextLeafID),
                     "at least " + std::to_string(leafIDs.rbegin()->first + 1));
}

}  // namespace

vec3 carriedRollReference(vec3 previous, vec3 guide) {
    return unitOr(previous - glm::dot(previous, guide) * guide, anyPerpendicular(guide));
}

vec3 internodeDirection(const Internode& in) {
    return internodeLean(in.guide, in.rollReference, in.azimuth, in.pitch);
}

float petioleAzimuth(float internodeAzimuth, std::size_t j, std::size_t n) {
    return internodeAzimuth + 360.0f * float(j) / float(n);
}

void completePlant(PlantInstance& plant, const Presence& presence, const Defaults& defaults,
                   unsigned stream, std::vector<std::string>& notes, const std::string& where) {
    Completer(plant, presence, defaults, notes, where).run(stream);
}

void checkPlant(PlantInstance& p, const std::string& where) {
    const std::size_t n = p.shoots.size();
    auto at = [&](std::size_t i, const std::string& rest) {
        return where + ".shoot[" + std::to_string(i) + "]" + (rest.empty() ? "" : "." + rest);
    };
    auto typeLabels = [&] {
        std::string out;
        for (const auto& [label, t] : p.shootTypes) out += (out.empty() ? "" : ", ") + label;
        return out.empty() ? std::string("no shoot types defined") : "one of: " + out;
    };
    for (const auto& [label, t] : p.shootTypes)
        for (const auto& [child, prob] : t.child_shoot_types)
            if (!p.shootTypes.count(child))
                inconsistent(where + ".shoot_type[" + label + "].child_shoot_types." + child,
                             "unknown shoot type", child, typeLabels());
    for (std::size_t i = 0; i < n; ++i) {
        Shoot& s = p.shoots[i];
        s.id = unsigned(i);
        s.children.clear();
        if (!p.shootTypes.count(s.type))
            inconsistent(at(i, "shoot_type_label"), "unknown shoot type", s.type, typeLabels());
        if (i == 0 && s.parent != -1)
            inconsistent(at(i, "parent_shoot_ID"), "shoot 0 is the base stem: it has no parent",
                         std::to_string(s.parent), "-1");
        if (i > 0 && (s.parent < 0 || std::size_t(s.parent) >= i))
            inconsistent(at(i, "parent_shoot_ID"), "a shoot grows from a shoot listed before it",
                         std::to_string(s.parent), "0 to " + std::to_string(i - 1));
        for (std::size_t k = 0; k < s.phytomers.size(); ++k) {
            Phytomer& ph = s.phytomers[k];
            const std::string phPath = at(i, "phytomer[" + std::to_string(k) + "]");
            auto type = p.shootTypes.find(ph.parametersLabel);
            if (type == p.shootTypes.end())
                inconsistent(phPath + ".parameters_label", "unknown shoot type", ph.parametersLabel,
                             typeLabels());
            const PhytomerParameters& pp = type->second.phytomer_parameters;
            const unsigned leafVariants = pp.leaf.prototype.unique_prototypes;
            for (std::size_t j = 0; j < ph.petioles.size(); ++j) {
                Petiole& pt = ph.petioles[j];
                const std::string ptPath = phPath + ".internode.petiole[" + std::to_string(j) + "]";
                for (std::size_t l = 0; l < pt.leaves.size(); ++l)
                    if (leafVariants > 0 && pt.leaves[l].variant >= leafVariants)
                        inconsistent(ptPath + ".leaf[" + std::to_string(l) + "].variant",
                                     "variant out of range", std::to_string(pt.leaves[l].variant),
                                     "0 to " + std::to_string(leafVariants - 1));
                for (std::size_t b = 0; b < pt.vegetativeBuds.size(); ++b) {
                    const VegetativeBud& bud = pt.vegetativeBuds[b];
                    const std::string budPath =
                        ptPath + ".vegetative_bud[" + std::to_string(b) + "]";
                    if (bud.childShoot >= int(n))
                        inconsistent(budPath + ".child_shoot_ID", "no such shoot",
                                     std::to_string(bud.childShoot),
                                     "-1 to " + std::to_string(n - 1));
                    if (!bud.shootType.empty() && !p.shootTypes.count(bud.shootType))
                        inconsistent(budPath + ".shoot_type_label", "unknown shoot type",
                                     bud.shootType, typeLabels());
                }
                for (std::size_t b = 0; b < pt.floralBuds.size(); ++b) {
                    const unsigned variants = std::max(1u, pp.inflorescence.unique_prototypes);
                    for (std::size_t f = 0; f < pt.floralBuds[b].flowers.size(); ++f)
                        if (pt.floralBuds[b].flowers[f].variant >= variants)
                            inconsistent(ptPath + ".floral_bud[" + std::to_string(b) +
                                             "].peduncle.flower[" + std::to_string(f) + "].variant",
                                         "variant out of range",
                                         std::to_string(pt.floralBuds[b].flowers[f].variant),
                                         "0 to " + std::to_string(variants - 1));
                }
            }
        }
        const unsigned terminalVariants = std::max(
            1u, p.shootTypes.at(s.type).phytomer_parameters.inflorescence.unique_prototypes);
        for (std::size_t b = 0; b < s.terminalFloralBuds.size(); ++b)
            for (const FlowerOrgan& fl : s.terminalFloralBuds[b].flowers)
                if (fl.variant >= terminalVariants)
                    inconsistent(at(i, "terminal_floral_bud[" + std::to_string(b) + "]"),
                                 "flower variant out of range", std::to_string(fl.variant),
                                 "0 to " + std::to_string(terminalVariants - 1));
        if (s.removed || s.parent < 0) continue;
        Shoot& parent = p.shoots[std::size_t(s.parent)];
        if (parent.removed)
            inconsistent(at(i, "removed"),
                         "a shoot growing from a removed shoot must be removed too", "false",
                         "true");
        if (s.parentNode < 0 || std::size_t(s.parentNode) >= parent.phytomers.size())
            inconsistent(at(i, "parent_node_index"), "no such node on the parent shoot",
                         std::to_string(s.parentNode),
                         parent.phytomers.empty()
                             ? "the parent has no phytomers"
                             : "0 to " + std::to_string(parent.phytomers.size() - 1));
        // A branch grows from a petiole's axil (a node without petioles: index 0, as a shoot
        // appended at the tip has).
        const std::size_t petioles = parent.phytomers[std::size_t(s.parentNode)].petioles.size();
        if (std::size_t(s.parentPetiole) >= std::max<std::size_t>(petioles, 1))
            inconsistent(at(i, "parent_petiole_index"), "no such petiole at the parent's node",
                         std::to_string(s.parentPetiole),
                         petioles == 0 ? "0 (the node has no petioles)"
                                       : "0 to " + std::to_string(petioles - 1));
        parent.children.push_back(unsigned(i));
    }
    if (p.nextLeafID < 0)
        inconsistent(where + ".next_leaf_ID", "negative", std::to_string(p.nextLeafID), ">= 0");
    ValueCheck values(where);
    state::describeState(p, values);
    checkReferences(p, where);
}

// ---- reporting what a read file left out or got wrong ------------------------------------

pugi::xml_node locateElement(pugi::xml_node from, const std::string& path) {
    pugi::xml_node at = from;
    std::size_t start = 0;
    while (start < path.size()) {
        std::size_t end = path.find('.', start);
        if (end == std::string::npos) end = path.size();
        std::string part = path.substr(start, end - start);
        start = end + 1;
        // "name[3]": the fourth <name>; "name[label]": the <name label="label">.
        std::string key;
        if (const auto b = part.find('['); b != std::string::npos) {
            key = part.substr(b + 1, part.size() - b - 2);
            part.resize(b);
        }
        const bool numeric = !key.empty() && std::all_of(key.begin(), key.end(), [](char c) {
            return c >= '0' && c <= '9';
        });
        int index = numeric ? std::atoi(key.c_str()) : 0;
        pugi::xml_node next;
        for (pugi::xml_node c = at.child(part.c_str()); c; c = c.next_sibling(part.c_str())) {
            const bool hit = key.empty() || numeric
                                 ? index-- == 0
                                 : key == text::trim(c.attribute("label").value());
            if (hit) {
                next = c;
                break;
            }
        }
        if (!next) break;
        at = next;
    }
    return at;
}

std::string missingReport(const std::map<std::string, int>& counts) {
    std::string out;
    for (const auto& [path, n] : counts) {
        if (!out.empty()) out += ", ";
        out += path;
        if (n > 1) out += " (" + std::to_string(n) + ")";
    }
    return out;
}

}  // namespace plantarch::plant_io
