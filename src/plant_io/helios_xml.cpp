// `<helios>` plant structure files (docs/plant-xml.md, "Files with the root <helios>"): the
// layout of the specification's sample listing, extended with what the reference system
// writes (internode perturbations, leaf scale factors, floral buds with their peduncle and
// inflorescence). Reading is strict like every plantarch reader: each element is known at
// its place, appears once (lists excepted) and holds a value in range, else one Error names
// file:line, the element path, the value and what is valid.
//
// What a `<helios>` file gives is mapped onto plantarch's plant state and the rest is left
// to completion (completePlant), as for the listing form: current sizes become full-grown
// sizes and growth fractions, leaflets listed left to right become leaflet indices, floral
// bud states become stages, and each internode's perturbations become a turn of the shoot
// axis from the internode before.

#include <algorithm>
#include <charconv>
#include <cmath>
#include <map>
#include <set>

#include "core/math.h"
#include "core/value_text.h"
#include "core/xml_reader.h"
#include "plant_io/helios_pose.h"
#include "plant_io/plant_structure.h"
#include "plantarch/Error.h"
#include "plantarch/NumberRange.h"
#include "plantarch/PlantStateTable.h"

namespace plantarch::plant_io {

namespace {

using pugi::xml_node;
using xml::Children;
using xml::Element;

constexpr double kLength = 1e6;  // m
constexpr double kAngle = 1e6;   // degrees
constexpr int kSegments = 1000;

float number(const Element& e, double lo, double hi) {
    const std::string s = e.text();
    const float v = e.convert(s, text::parseFloat);
    if (!(v >= lo && v <= hi)) e.fail("out of range", s, rangeText({.min = lo, .max = hi}));
    return v;
}

// A value of the state field `f` (plantarch/PlantStateTable.h): its declared range.
float number(const Element& e, const state::FieldInfo& f) {
    return number(e, f.min, f.max);
}

// The declarations of the state fields this reader fills, looked up once.
struct Fields {
    state::FieldInfo plantAge = state::fieldInfo<PlantInstance>("plant_age");
    state::FieldInfo internodeLength = state::fieldInfo<Internode>("internode_length");
    state::FieldInfo internodeRadius = state::fieldInfo<Internode>("internode_radius");
    state::FieldInfo internodePitch = state::fieldInfo<Internode>("internode_pitch");
    state::FieldInfo petioleLength = state::fieldInfo<Petiole>("petiole_length");
    state::FieldInfo petioleRadius = state::fieldInfo<Petiole>("petiole_radius");
    state::FieldInfo petiolePitch = state::fieldInfo<Petiole>("petiole_pitch");
    state::FieldInfo petioleCurvature = state::fieldInfo<Petiole>("petiole_curvature");
    state::FieldInfo petioleTaper = state::fieldInfo<Petiole>("petiole_taper");
    state::FieldInfo leafScale = state::fieldInfo<LeafOrgan>("leaf_scale");
    state::FieldInfo peduncleLength = state::fieldInfo<FloralBud>("peduncle_length");
    state::FieldInfo peduncleRadius = state::fieldInfo<FloralBud>("peduncle_radius");
    state::FieldInfo pedunclePitch = state::fieldInfo<FloralBud>("peduncle_pitch");
    state::FieldInfo peduncleRoll = state::fieldInfo<FloralBud>("peduncle_roll");
    state::FieldInfo peduncleCurvature = state::fieldInfo<FloralBud>("peduncle_curvature");
    state::FieldInfo flowerScale = state::fieldInfo<FlowerOrgan>("flower_scale");
    state::FieldInfo fruitScale = state::fieldInfo<FlowerOrgan>("fruit_scale");
};

const Fields& fields() {
    static const Fields f;
    return f;
}

int integer(const Element& e, int lo, int hi) {
    const std::string s = e.text();
    const int v = e.convert(s, text::parseInt);
    if (v < lo || v > hi)
        e.fail("out of range", s, rangeText({.min = double(lo), .max = double(hi), .whole = true}));
    return v;
}

vec3 triple(const Element& e, double lo, double hi) {
    const std::string s = e.text();
    const vec3 v = e.convert(s, text::parseVec3);
    for (int i = 0; i < 3; ++i)
        if (!(v[i] >= lo && v[i] <= hi))
            e.fail("out of range", s, rangeText({.min = lo, .max = hi}));
    return v;
}

// "a;b;c": numbers in degrees.
std::vector<float> angleList(const Element& e) {
    const std::string s = e.text();
    std::vector<float> out;
    std::size_t at = 0;
    while (at <= s.size()) {
        std::size_t end = s.find(';', at);
        if (end == std::string::npos) end = s.size();
        const std::string_view item = text::trim(std::string_view(s).substr(at, end - at));
        float v = 0.0f;
        if (!text::readNumber(item, v) || !(std::abs(v) <= kAngle))
            e.fail("expected numbers separated by ';'", s,
                   "angles in degrees, -1e+06 to 1e+06, separated by ';'");
        out.push_back(v);
        if (out.size() > std::size_t(kSegments))
            e.fail("too many values", s, "at most " + std::to_string(kSegments));
        at = end + 1;
    }
    return out;
}

// The full-grown size of an organ listed at `current` size, `fraction` of its full size. It
// is what the plant keeps and what a written file holds, so it is held to the same range as a
// size given outright (a leaf 6e5 m long at 0.4 of its size would be written as 1.6e6 m, which
// no file may hold).
float fullGrown(const Element& c, float current, float fraction, const state::FieldInfo& f) {
    if (fraction <= 0.0f) return 0.0f;
    const float full = current / fraction;
    if (!(double(full) <= f.max))
        c.fail("at current_leaf_scale_factor " + text::formatFloat(fraction) +
                   " it is a full-grown size of " + text::formatFloat(full) + " m",
               c.text(),
               "current size / current_leaf_scale_factor at most " +
                   text::formatFloat(float(f.max)) + " m");
    return full;
}

// An element's child read by `read` when present (returns whether it was).
template <class Read>
bool optionalChild(Children& kids, const Element& parent, const char* name, Read&& read) {
    const xml_node n = kids.take(name);
    if (!n) return false;
    read(Element(parent, n, name));
    return true;
}

const ShootParameters& fallbackType() {
    static const ShootParameters defaults{};
    return defaults;
}

// A leaflet's place in plantarch's order (tip first, then pairs -1, 1, -2, 2, ...) from its
// leaflet index (leafletIndexOf).
int canonicalSlot(int index, int n) {
    const int a = std::abs(index);
    if (n % 2 == 1) return index == 0 ? 0 : 2 * a - 1 + (index > 0);
    return 2 * (a - 1) + (index > 0);
}

// Counts what a file leaves out, by kind of value ("shoot.phytomer.age (3)"), and notes the
// kinds it gives somewhere.
struct MissingReport {
    const Presence& given;
    std::map<std::string, int>& counts;
    std::set<std::string>& seen;
    std::vector<const char*> kinds;

    std::string key(const char* name) const {
        std::string k;
        for (const char* kind : kinds) k.append(kind).append(".");
        return k + name;
    }
    void add(const void* member, const char* name) {
        if (given.missing(member))
            ++counts[key(name)];
        else
            seen.insert(key(name));
    }
    template <class T>
    void field(const state::FieldInfo& f, T& member) {
        add(&member, f.name);
    }
    void legacy(const char*) {}
    template <class T>
    void objects(const char*, T&) {}
    template <class Fn>
    void group(const char* name, Fn&& fn) {
        kinds.push_back(name);
        fn(*this);
        kinds.pop_back();
    }
    template <class T>
    void list(const char* name, std::vector<T>& items, bool = false) {
        kinds.push_back(name);
        for (T& item : items) state::describeState(item, *this);
        kinds.pop_back();
    }
    template <class T>
    void values(const state::FieldInfo&, std::vector<T>&) {}
    template <class T>
    void optional(const char*, std::optional<T>&) {}
    template <class P>
    void parameters(const char* name, P& member) {
        add(&member, name);
    }
};

class HeliosReader {
public:
    HeliosReader(const Defaults& d, Presence& given) : d_(d), given_(given) {}

    void plant(const Element& e, PlantInstance& p) {
        e.checkAttributes({"ID"});
        if (e.hasAttribute("ID"))
            Element(e, e.node(), "ID").convert(e.attribute("ID"), text::parseUnsigned);
        Children kids(e);
        optionalChild(kids, e, "base_position", [&](const Element& c) {
            p.base = triple(c, -kLength, kLength);
            given_.note(&p.base);
        });
        optionalChild(kids, e, "plant_age", [&](const Element& c) {
            p.age = number(c, fields().plantAge);
            given_.note(&p.age);
        });
        const std::vector<xml_node> shoots = kids.takeAll("shoot");
        kids.finish();
        p.shoots.resize(shoots.size());  // sized once: Presence keeps addresses
        for (std::size_t i = 0; i < shoots.size(); ++i)
            shoot(Element(e, shoots[i], "shoot", int(i)), p.shoots[i], i);
    }

    std::map<std::string, int> typeDefaults;  // "petiole_taper" -> how many took the mean
    HeliosExtras extras;                      // what the state has no place for

private:
    const ShootParameters& typeFor(const std::string& label) const {
        if (d_.shootTypes) {
            auto it = d_.shootTypes->find(label);
            if (it != d_.shootTypes->end()) return it->second;
        }
        return fallbackType();
    }

    void note(const void* member) { given_.note(member); }

    void shoot(const Element& e, Shoot& s, std::size_t index) {
        e.checkAttributes({"ID"});
        if (e.hasAttribute("ID")) {
            const std::string id = e.attribute("ID");
            unsigned v = 0;
            if (!text::readNumber(id, v) || v != index)
                e.failAt("ID", "<shoot> IDs must count 0, 1, 2, ... in file order", id,
                         std::to_string(index));
        }
        Children kids(e);
        optionalChild(kids, e, "shoot_type_label", [&](const Element& c) {
            s.type = c.text();
            if (!text::isLabel(s.type))
                c.fail("a shoot type label is letters, digits, '_' or '-'", s.type, "a label");
            note(&s.type);
        });
        optionalChild(kids, e, "parent_shoot_ID", [&](const Element& c) {
            s.parent = integer(c, -1, 1 << 30);
            note(&s.parent);
        });
        optionalChild(kids, e, "parent_node_index", [&](const Element& c) {
            s.parentNode = integer(c, -1, 1 << 30);
            note(&s.parentNode);
        });
        optionalChild(kids, e, "parent_petiole_index", [&](const Element& c) {
            s.parentPetiole = integer(c, 0, 1 << 30);
            note(&s.parentPetiole);
        });
        optionalChild(kids, e, "base_rotation", [&](const Element& c) {
            const vec3 r = triple(c, -kAngle, kAngle);
            s.baseRotation = {r.x, r.y, r.z};
            extras.baseRotations[&s] = s.baseRotation;
            note(&s.baseRotation);
        });
        const std::vector<xml_node> phytomers = kids.takeAll("phytomer");
        kids.finish();
        s.phytomers.resize(phytomers.size());
        // Terminal floral buds sit in the last phytomer's petioles: count them first, so
        // that the shoot's list is sized once.
        if (!phytomers.empty()) {
            std::size_t terminal = 0;
            for (xml_node pt : phytomers.back().child("internode").children("petiole"))
                for (xml_node fb : pt.children("floral_bud"))
                    terminal += text::trim(fb.child("is_terminal").child_value()) == "1";
            s.terminalFloralBuds.resize(terminal);
        }
        const ShootParameters& type = typeFor(s.type);
        std::size_t terminalAt = 0;
        for (std::size_t k = 0; k < phytomers.size(); ++k) {
            const Element ph(e, phytomers[k], "phytomer", int(k));
            ph.checkAttributes({});
            Children phKids(ph);
            const xml_node in = phKids.take("internode");
            phKids.finish();
            Phytomer& p = s.phytomers[k];
            if (!in) continue;  // its values are reported missing
            const bool last = k + 1 == phytomers.size();
            internode(Element(ph, in, "internode"), s, p, type, last, terminalAt);
        }
    }

    void internode(const Element& e, Shoot& s, Phytomer& ph, const ShootParameters& type, bool last,
                   std::size_t& terminalAt) {
        e.checkAttributes({});
        Internode& in = ph.internode;
        Children kids(e);
        float length = 0.0f, lengthMax = -1.0f;
        const bool hasLength = optionalChild(kids, e, "internode_length", [&](const Element& c) {
            length = number(c, fields().internodeLength);
        });
        optionalChild(kids, e, "internode_radius", [&](const Element& c) {
            in.radius = number(c, fields().internodeRadius);
            note(&in.radius);
        });
        optionalChild(kids, e, "internode_pitch", [&](const Element& c) {
            in.pitch = number(c, fields().internodePitch);
            note(&in.pitch);
        });
        // The listing names it phyllotactic_angle, the reference system's files
        // internode_phyllotactic_angle: one of them.
        const bool listed = optionalChild(kids, e, "phyllotactic_angle", [&](const Element& c) {
            in.phyllotacticAngle = number(c, -kAngle, kAngle);
            note(&in.phyllotacticAngle);
        });
        optionalChild(kids, e, "internode_phyllotactic_angle", [&](const Element& c) {
            if (listed)
                c.fail("give either <phyllotactic_angle> or <internode_phyllotactic_angle>",
                       c.text(), "one of the two");
            in.phyllotacticAngle = number(c, -kAngle, kAngle);
            note(&in.phyllotacticAngle);
        });
        optionalChild(kids, e, "internode_length_max", [&](const Element& c) {
            lengthMax = number(c, fields().internodeLength);
            // (within 1e-3: the reference system prints 6 digits of a length it measures
            // along its segments, and that sum may pass the maximum in its last digits)
            if (hasLength && length > lengthMax * (1.0f + 1e-3f))
                c.fail("shorter than <internode_length> (" + text::formatFloat(length) + ")",
                       c.text(), "at least the internode's current length");
        });
        int segments = -1;
        optionalChild(kids, e, "internode_length_segments",
                      [&](const Element& c) { segments = integer(c, 1, kSegments); });
        std::vector<float> curvature, yaw;
        auto perturbations = [&](const char* name, std::vector<float>& out) {
            optionalChild(kids, e, name, [&](const Element& c) {
                out = angleList(c);
                if (segments > 0 && int(out.size()) != segments)
                    c.fail("one value per internode segment (" + std::to_string(segments) + ")",
                           c.text(), std::to_string(segments) + " values");
            });
        };
        perturbations("curvature_perturbations", curvature);
        perturbations("yaw_perturbations", yaw);
        if (hasLength) {
            if (lengthMax < 0.0f) lengthMax = length;
            in.length = lengthMax;
            ph.internodeFraction = lengthMax > 0.0f ? length / lengthMax : 1.0f;
            note(&in.length);
            note(&ph.internodeFraction);
        }
        extras.internodes[&in] = {in.pitch, in.phyllotacticAngle,
                                  unsigned(segments > 0 ? segments : 1), std::move(curvature),
                                  std::move(yaw)};

        const std::vector<xml_node> petioles = kids.takeAll("petiole");
        kids.finish();
        ph.petioles.resize(petioles.size());
        bool fractionGiven = false;
        for (std::size_t j = 0; j < petioles.size(); ++j) {
            const Element pe(e, petioles[j], "petiole", int(j));
            petiole(pe, s, ph, ph.petioles[j], j, type, fractionGiven, last, terminalAt);
        }
    }

    void petiole(const Element& e, Shoot& s, Phytomer& ph, Petiole& pt, std::size_t j,
                 const ShootParameters& type, bool& fractionGiven, bool last,
                 std::size_t& terminalAt) {
        e.checkAttributes({});
        Children kids(e);
        float length = 0.0f;
        xml_node lengthNode;  // set when the petiole's length is given
        optionalChild(kids, e, "petiole_length", [&](const Element& c) {
            length = number(c, fields().petioleLength);
            lengthNode = c.node();
        });
        optionalChild(kids, e, "petiole_radius", [&](const Element& c) {
            pt.radius = number(c, fields().petioleRadius);
            note(&pt.radius);
        });
        HeliosPetiole& extra = extras.petioles[&pt];
        optionalChild(kids, e, "petiole_pitch", [&](const Element& c) {
            pt.pitch = number(c, fields().petiolePitch);
            extra.pitch = pt.pitch;
            note(&pt.pitch);
        });
        optionalChild(kids, e, "petiole_curvature", [&](const Element& c) {
            pt.curvature = number(c, fields().petioleCurvature);
            note(&pt.curvature);
        });
        // Current size / full size of the petiole and its leaves: one per phytomer here.
        optionalChild(kids, e, "current_leaf_scale_factor", [&](const Element& c) {
            const float f = number(c, 0.0, 1.0);
            if (fractionGiven && f != ph.leafFraction)
                c.fail("differs from the phytomer's other petioles (" +
                           text::formatFloat(ph.leafFraction) + ")",
                       c.text(), "the same factor for every petiole of a phytomer");
            ph.leafFraction = f;
            fractionGiven = true;
            note(&ph.leafFraction);
        });
        const float fraction = ph.leafFraction;
        if (!optionalChild(kids, e, "petiole_taper", [&](const Element& c) {
                pt.taper = number(c, fields().petioleTaper);
            })) {
            pt.taper = type.phytomer_parameters.petiole.taper.mean();
            ++typeDefaults["petiole_taper"];
        }
        note(&pt.taper);
        optionalChild(kids, e, "petiole_length_segments", [&](const Element& c) {
            extra.segments = unsigned(integer(c, 1, kSegments));
        });
        optionalChild(kids, e, "petiole_radial_subdivisions",
                      [&](const Element& c) { integer(c, 3, kSegments); });
        optionalChild(kids, e, "leaflet_scale", [&](const Element& c) { number(c, 0.0, kLength); });
        float offset = 0.0f;
        if (!optionalChild(kids, e, "leaflet_offset",
                           [&](const Element& c) { offset = number(c, 0.0, 1.0); })) {
            offset = type.phytomer_parameters.leaf.leaflet_offset.mean();
            ++typeDefaults["leaflet_offset"];
        }
        extra.leafletOffset = offset;
        if (lengthNode) {
            pt.length = fullGrown(Element(e, lengthNode, "petiole_length"), length, fraction,
                                  fields().petioleLength);
            note(&pt.length);
        }
        leaves(e, kids.takeAll("leaf"), pt, fraction);
        const std::vector<xml_node> buds = kids.takeAll("floral_bud");
        kids.finish();
        std::size_t axillary = 0;
        for (xml_node b : buds) axillary += text::trim(b.child("is_terminal").child_value()) != "1";
        pt.floralBuds.resize(axillary);
        std::size_t at = 0;
        for (std::size_t b = 0; b < buds.size(); ++b) {
            const Element fe(e, buds[b], "floral_bud", int(b));
            const bool terminal = text::trim(buds[b].child("is_terminal").child_value()) == "1";
            if (terminal && (!last || terminalAt >= s.terminalFloralBuds.size()))
                fe.failAt("is_terminal", "a terminal floral bud sits on the shoot's last phytomer",
                          "1", "0 here");
            FloralBud& fb = terminal ? s.terminalFloralBuds[terminalAt++] : pt.floralBuds[at++];
            floralBud(fe, fb, terminal, ph.parametersLabel.empty() ? s.type : ph.parametersLabel,
                      j);
        }
    }

    // (Their places along the petiole come from leaflet_offset in poseAsReference.)
    void leaves(const Element& e, const std::vector<xml_node>& nodes, Petiole& pt, float fraction) {
        const int n = int(nodes.size());
        pt.leaves.resize(nodes.size());
        for (int i = 0; i < n; ++i) {
            const Element le(e, nodes[std::size_t(i)], "leaf", i);
            le.checkAttributes({});
            const int index = leafletIndexOf(i, n);
            LeafOrgan& l = pt.leaves[std::size_t(canonicalSlot(index, n))];
            l.leafletIndex = index;
            note(&l.leafletIndex);
            Children kids(le);
            optionalChild(kids, le, "leaf_scale", [&](const Element& c) {
                l.scale = fullGrown(c, number(c, fields().leafScale), fraction, fields().leafScale);
                note(&l.scale);
            });
            auto angle = [&](const char* name, float& member) {
                optionalChild(kids, le, name, [&](const Element& c) {
                    member = number(c, -kAngle, kAngle);
                    note(&member);
                });
            };
            angle("leaf_pitch", l.pitch);
            angle("leaf_yaw", l.yaw);
            angle("leaf_roll", l.roll);
            HeliosLeaf& extra = extras.leaves[&l];
            optionalChild(kids, le, "leaf_angles",
                          [&](const Element& c) { extra.own = triple(c, -kAngle, kAngle); });
            kids.finish();
            extra.pitch = l.pitch;
            extra.yaw = l.yaw;
            extra.roll = l.roll;
        }
    }

    void floralBud(const Element& e, FloralBud& fb, bool terminal, const std::string& typeLabel,
                   std::size_t petioleIndex) {
        e.checkAttributes({});
        Children kids(e);
        const xml_node stateNode = kids.take("bud_state");
        if (!stateNode) e.fail("missing <bud_state>", "", "0 to 5");
        const int state = integer(Element(e, stateNode, "bud_state"), 0, 5);
        // 0 dormant, 1 active, 2 closed flower, 3 open flower, 4 fruit, 5 dead.
        fb.stage = state == 2   ? FloralStage::FlowerClosed
                   : state == 3 ? FloralStage::FlowerOpen
                   : state == 4 ? FloralStage::Fruit
                                : FloralStage::Bud;
        note(&fb.stage);
        // A bud showing flowers or fruit has broken (the layout has no state of its own
        // for it).
        fb.state = state == 0   ? BudState::Dormant
                   : state == 1 ? BudState::Active
                   : state == 5 ? BudState::Dead
                                : BudState::Broken;
        note(&fb.state);
        fb.terminal = terminal;
        note(&fb.terminal);
        optionalChild(kids, e, "parent_index", [&](const Element& c) {
            const int v = integer(c, 0, 1 << 30);
            if (!terminal && std::size_t(v) != petioleIndex)
                c.fail("not the petiole the bud is listed in", c.text(),
                       std::to_string(petioleIndex));
        });
        optionalChild(kids, e, "bud_index", [&](const Element& c) { integer(c, 0, 1 << 30); });
        optionalChild(kids, e, "is_terminal", [&](const Element& c) { integer(c, 0, 1); });
        optionalChild(kids, e, "current_fruit_scale_factor", [&](const Element& c) {
            fb.fruitGrowth = number(c, 0.0, 1.0);
            note(&fb.fruitGrowth);
        });
        const xml_node ped = kids.take("peduncle");
        if (ped) peduncle(Element(e, ped, "peduncle"), fb);
        const ShootParameters& type = typeFor(typeLabel);
        const xml_node inf = kids.take("inflorescence");
        kids.finish();
        if (inf) inflorescence(Element(e, inf, "inflorescence"), fb, type);
    }

    void peduncle(const Element& e, FloralBud& fb) {
        e.checkAttributes({});
        Children kids(e);
        auto value = [&](const char* name, float& member, const state::FieldInfo& f) {
            optionalChild(kids, e, name, [&](const Element& c) {
                member = number(c, f);
                note(&member);
            });
        };
        value("length", fb.peduncleLength, fields().peduncleLength);
        value("radius", fb.peduncleRadius, fields().peduncleRadius);
        value("pitch", fb.pedunclePitch, fields().pedunclePitch);
        value("roll", fb.peduncleRoll, fields().peduncleRoll);
        value("curvature", fb.peduncleCurvature, fields().peduncleCurvature);
        kids.finish();
    }

    void inflorescence(const Element& e, FloralBud& fb, const ShootParameters& type) {
        e.checkAttributes({});
        const InflorescenceParameters& inf = type.phytomer_parameters.inflorescence;
        Children kids(e);
        float offset = inf.flower_offset.mean();
        optionalChild(kids, e, "flower_offset",
                      [&](const Element& c) { offset = number(c, 0.0, kLength); });
        const std::vector<xml_node> flowers = kids.takeAll("flower");
        kids.finish();
        const bool opposite = inf.flower_arrangement == FlowerArrangement::Opposite;
        fb.flowers.resize(flowers.size());
        for (std::size_t i = 0; i < flowers.size(); ++i) {
            const Element fe(e, flowers[i], "flower", int(i));
            fe.checkAttributes({});
            FlowerOrgan& fl = fb.flowers[i];
            // Placed along the peduncle as growth places them, flower_offset apart.
            const std::size_t step = opposite ? i / 2 : i;
            fl.position = std::max(0.0f, 1.0f - float(step) * offset);
            fl.azimuth = (i % 2 ? 180.0f : 0.0f) + (opposite ? 90.0f : 0.0f);
            // One base scale per flower: the fruit's at the fruit stage, the flower's before.
            // The other is the shoot type's mean (the layout holds none).
            fl.flowerScale = inf.flower_prototype_scale.mean();
            fl.fruitScale = inf.fruit_prototype_scale.mean();
            note(fb.stage == FloralStage::Fruit ? &fl.flowerScale : &fl.fruitScale);
            fl.gravityFactor = inf.fruit_gravity_factor_fraction.mean();
            Children fk(fe);
            auto angle = [&](const char* name, float* member) {
                optionalChild(fk, fe, name, [&](const Element& c) {
                    const float v = number(c, -kAngle, kAngle);
                    if (member) *member = v;
                });
            };
            angle("flower_pitch", &fl.pitch);
            angle("flower_yaw", nullptr);  // read and not kept (see docs/plant-xml.md)
            angle("flower_roll", &fl.roll);
            angle("flower_azimuth", &fl.azimuth);
            optionalChild(fk, fe, "flower_base_scale", [&](const Element& c) {
                float& scale = fb.stage == FloralStage::Fruit ? fl.fruitScale : fl.flowerScale;
                scale = number(
                    c, fb.stage == FloralStage::Fruit ? fields().fruitScale : fields().flowerScale);
                note(&scale);
            });
            fk.finish();
            for (const void* v : {(const void*)&fl.position, (const void*)&fl.azimuth,
                                  (const void*)&fl.pitch, (const void*)&fl.roll})
                note(v);
        }
    }

    const Defaults& d_;
    Presence& given_;
};

}  // namespace

ReadResult readHeliosPlants(const xml::Document& doc, const std::string& fileName,
                            const Defaults& defaults) {
    const Element root(doc, doc.root(), "");
    root.checkAttributes({});
    Children children(root);
    const std::vector<xml_node> plants = children.takeAll("plant_instance");
    children.finish();
    ReadResult result;
    for (unsigned index = 0; index < plants.size(); ++index) {
        const Element e(root, plants[index], "plant_instance", int(index));
        const std::string where = e.path();
        PlantInstance plant;
        Presence given = Presence::recordingPresent();
        HeliosReader reader(defaults, given);
        reader.plant(e, plant);
        std::map<std::string, int> missing;
        std::set<std::string> seen;
        MissingReport report{given, missing, seen, {}};
        state::describeState(plant, report);
        poseAsReference(plant, reader.extras, defaults.shootTypes, given);
        // A value the file gives nowhere is one the layout does not hold (or one the whole
        // file leaves out): said once, not named; those it leaves out here and there are named.
        bool growthState = false;
        for (auto it = missing.begin(); it != missing.end();) {
            if (seen.count(it->first)) {
                ++it;
            } else {
                growthState = true;
                it = missing.erase(it);
            }
        }
        std::vector<std::string> notes;
        for (const auto& [name, n] : reader.typeDefaults)
            notes.push_back(name + " (" + std::to_string(n) + "): the shoot type's mean");
        try {
            completePlant(plant, given, defaults, defaults.firstStream + index, notes, where);
            checkPlant(plant, where);
        } catch (const Error& err) {
            // At the element the path names, as far as the file has it (a value completion
            // derived belongs to the organ that lacked it).
            std::string rel = err.parameter();
            if (rel.compare(0, where.size() + 1, where + ".") == 0) rel.erase(0, where.size() + 1);
            doc.relocate(err, locateElement(plants[index], rel), err.parameter());
        }
        if (growthState || !missing.empty() || !notes.empty()) {
            std::string w = fileName + ": plant_instance " + std::to_string(index) + ": ";
            std::string sep;
            if (growthState) {
                w += "values the file gives nowhere (growth state: ages, phenology, random "
                     "generator, ...) take plantarch's defaults";
                sep = "; ";
            }
            if (!missing.empty())
                w += sep + "values missing, defaults used: " + missingReport(missing);
            for (const std::string& n : notes) w += "; " + n;
            result.warnings.push_back(std::move(w));
        }
        result.plants.push_back(std::move(plant));
    }
    return result;
}

// ---- writing -------------------------------------------------------------------------------

namespace {

class HeliosWriter {
public:
    explicit HeliosWriter(std::string& out) : out_(out) {}

    void plant(const PlantInstance& p) {
        out_ += "\t<plant_instance ID=\"" + std::to_string(p.id) + "\">\n";
        line(2, "base_position", vec(p.base));
        line(2, "plant_age", text::formatDouble(p.age));
        // Removed shoots are left out; the others are numbered in order.
        std::vector<int> newID(p.shoots.size(), -1);
        int next = 0;
        for (std::size_t i = 0; i < p.shoots.size(); ++i)
            if (!p.shoots[i].removed) newID[i] = next++;
        angles_ = referenceAngles(p);
        for (std::size_t i = 0; i < p.shoots.size(); ++i)
            if (newID[i] >= 0) shoot(p, p.shoots[i], newID);
        out_ += "\t</plant_instance>\n";
    }

private:
    static std::string num(float v) { return text::formatFloat(v); }
    static std::string vec(vec3 v) { return num(v.x) + " " + num(v.y) + " " + num(v.z); }
    void line(int depth, const char* name, const std::string& value) {
        out_.append(std::size_t(depth), '\t');
        out_.append("<").append(name).append(">");
        text::appendXmlEscaped(out_, value);
        out_.append("</").append(name).append(">\n");
    }
    void open(int depth, const char* name) {
        out_.append(std::size_t(depth), '\t').append("<").append(name).append(">\n");
    }
    void close(int depth, const char* name) {
        out_.append(std::size_t(depth), '\t').append("</").append(name).append(">\n");
    }

    const ShootParameters* typeOf(const PlantInstance& p, const std::string& label) const {
        auto it = p.shootTypes.find(label);
        return it == p.shootTypes.end() ? nullptr : &it->second;
    }

    void shoot(const PlantInstance& p, const Shoot& s, const std::vector<int>& newID) {
        out_ += "\t\t<shoot ID=\"" + std::to_string(newID[s.id]) + "\">\n";
        line(3, "shoot_type_label", s.type);
        line(3, "parent_shoot_ID",
             std::to_string(s.parent < 0 ? -1 : newID[std::size_t(s.parent)]));
        line(3, "parent_node_index", std::to_string(s.parentNode));
        line(3, "parent_petiole_index", std::to_string(s.parentPetiole));
        const auto found = angles_.baseRotations.find(&s);
        const AxisRotation r =
            found == angles_.baseRotations.end() ? AxisRotation{} : found->second;
        line(3, "base_rotation", num(r.pitch) + " " + num(r.yaw) + " " + num(r.roll));
        for (std::size_t k = 0; k < s.phytomers.size(); ++k) phytomer(p, s, k);
        out_ += "\t\t</shoot>\n";
    }

    void phytomer(const PlantInstance& p, const Shoot& s, std::size_t k) {
        const Phytomer& ph = s.phytomers[k];
        const Internode& in = ph.internode;
        const ShootParameters* t = typeOf(p, ph.parametersLabel);
        static const PhytomerParameters fallback{};
        const PhytomerParameters& pp = t ? t->phytomer_parameters : fallback;
        open(3, "phytomer");
        open(4, "internode");
        line(5, "internode_length", num(in.length * ph.internodeFraction));
        line(5, "internode_radius", num(in.radius));
        const HeliosInternode& x = angles_.internodes.at(&in);
        line(5, "internode_pitch", num(x.pitch));
        line(5, "internode_phyllotactic_angle", num(x.phyllotaxis));
        line(5, "internode_length_max", num(in.length));
        line(5, "internode_length_segments", std::to_string(x.segments));
        if (k > 0) {
            line(5, "curvature_perturbations", joined(x.curvature));
            line(5, "yaw_perturbations", joined(x.yaw));
        }
        const std::size_t last = ph.petioles.empty() ? 0 : ph.petioles.size() - 1;
        for (std::size_t j = 0; j < ph.petioles.size(); ++j) {
            const bool tip = k + 1 == s.phytomers.size() && j == last;
            petiole(ph, ph.petioles[j], j, pp, tip ? &s.terminalFloralBuds : nullptr);
        }
        close(4, "internode");
        close(3, "phytomer");
    }

    static std::string joined(const std::vector<float>& values) {
        std::string out;
        for (std::size_t i = 0; i < values.size(); ++i) {
            if (i) out += ';';
            out += num(values[i]);
        }
        return out;
    }

    void petiole(const Phytomer& ph, const Petiole& pt, std::size_t j, const PhytomerParameters& pp,
                 const std::vector<FloralBud>* terminal) {
        open(5, "petiole");
        line(6, "petiole_length", num(pt.length * ph.leafFraction));
        line(6, "petiole_radius", num(pt.radius));
        const HeliosPetiole& px = angles_.petioles.at(&pt);
        line(6, "petiole_pitch", num(px.pitch));
        line(6, "petiole_curvature", num(pt.curvature));
        line(6, "current_leaf_scale_factor", num(ph.leafFraction));
        line(6, "petiole_taper", num(pt.taper));
        line(6, "petiole_length_segments", std::to_string(px.segments));
        line(6, "petiole_radial_subdivisions",
             std::to_string(std::max(3u, pp.petiole.radial_subdivisions)));
        // Leaflets left to right; shed ones are not part of the reference layout.
        std::vector<const LeafOrgan*> leaves;
        for (const LeafOrgan& l : pt.leaves)
            if (!l.removed) leaves.push_back(&l);
        std::stable_sort(leaves.begin(), leaves.end(), [](const LeafOrgan* a, const LeafOrgan* b) {
            return a->leafletIndex < b->leafletIndex;
        });
        // leaflet_scale: the size of the first pair below the tip over the largest leaflet.
        float largest = 0.0f, below = 0.0f;
        for (const LeafOrgan* l : leaves) largest = std::max(largest, l->scale);
        for (const LeafOrgan* l : leaves)
            if (std::abs(l->leafletIndex) == 1) below = l->scale;
        const float offset =
            pt.leaves.size() > 1 ? px.leafletOffset : pp.leaf.leaflet_offset.mean();
        line(6, "leaflet_scale", num(largest > 0.0f && below > 0.0f ? below / largest : 1.0f));
        line(6, "leaflet_offset", num(offset));
        for (const LeafOrgan* l : leaves) {
            open(6, "leaf");
            line(7, "leaf_scale", num(l->scale * ph.leafFraction));
            const HeliosLeaf& a = angles_.leaves.at(l);
            line(7, "leaf_pitch", num(a.pitch));
            line(7, "leaf_yaw", num(a.yaw));
            line(7, "leaf_roll", num(a.roll));
            if (a.own) line(7, "leaf_angles", vec(*a.own));
            close(6, "leaf");
        }
        for (std::size_t b = 0; b < pt.floralBuds.size(); ++b)
            floralBud(pt.floralBuds[b], j, b, false, pp);
        if (terminal)
            for (std::size_t b = 0; b < terminal->size(); ++b)
                floralBud((*terminal)[b], j, b, true, pp);
        close(5, "petiole");
    }

    static int budState(const FloralBud& fb) {
        switch (fb.stage) {
            case FloralStage::FlowerClosed:
                return 2;
            case FloralStage::FlowerOpen:
                return 3;
            case FloralStage::Fruit:
                return 4;
            case FloralStage::Removed:
                return 5;
            case FloralStage::Bud:
                break;
        }
        return fb.state == BudState::Dormant ? 0 : fb.state == BudState::Dead ? 5 : 1;
    }

    void floralBud(const FloralBud& fb, std::size_t j, std::size_t b, bool terminal,
                   const PhytomerParameters& pp) {
        open(6, "floral_bud");
        line(7, "bud_state", std::to_string(budState(fb)));
        line(7, "parent_index", std::to_string(j));
        line(7, "bud_index", std::to_string(b));
        line(7, "is_terminal", terminal ? "1" : "0");
        line(7, "current_fruit_scale_factor", num(std::clamp(fb.fruitGrowth, 0.0f, 1.0f)));
        open(7, "peduncle");
        line(8, "length", num(fb.peduncleLength));
        line(8, "radius", num(fb.peduncleRadius));
        line(8, "pitch", num(fb.pedunclePitch));
        line(8, "roll", num(fb.peduncleRoll));
        line(8, "curvature", num(fb.peduncleCurvature));
        close(7, "peduncle");
        open(7, "inflorescence");
        const bool opposite = pp.inflorescence.flower_arrangement == FlowerArrangement::Opposite;
        float offset = pp.inflorescence.flower_offset.mean();
        for (std::size_t i = 0; i < fb.flowers.size(); ++i) {
            const std::size_t step = opposite ? i / 2 : i;
            if (step > 0) {
                offset = (1.0f - fb.flowers[i].position) / float(step);
                break;
            }
        }
        line(8, "flower_offset", num(offset));
        const bool shown = fb.stage != FloralStage::Bud && fb.stage != FloralStage::Removed;
        if (shown)
            for (const FlowerOrgan& fl : fb.flowers) {
                open(8, "flower");
                line(9, "flower_pitch", num(fl.pitch));
                line(9, "flower_yaw", "0");
                line(9, "flower_roll", num(fl.roll));
                line(9, "flower_azimuth", num(fl.azimuth));
                line(9, "flower_base_scale",
                     num(fb.stage == FloralStage::Fruit ? fl.fruitScale : fl.flowerScale));
                close(8, "flower");
            }
        close(7, "inflorescence");
        close(6, "floral_bud");
    }

    std::string& out_;
    HeliosExtras angles_;  // the plant being written
};

}  // namespace

std::string writeHeliosPlants(const std::vector<const PlantInstance*>& plants) {
    std::string out = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<";
    out += kListingRoot;
    out += ">\n";
    HeliosWriter w(out);
    for (const PlantInstance* p : plants) w.plant(*p);
    out += "</";
    out += kListingRoot;
    out += ">\n";
    return out;
}

}  // namespace plantarch::plant_io
