// Reader of plant structure files (docs/plant-xml.md), on the XML reader layer
// (core/xml_reader.h).
//
// One engine reads both tables: the plant state table (plantarch/PlantStateTable.h) and the
// species parameter table (plantarch/ParameterTable.h). At each element it visits the table
// of the object being filled; every declared name takes its value from the child element of
// that name, every child must be declared (else "unknown element ..., did you mean ...") and
// appear once. State values are range checked as they are read; parameters are read as
// species files spell them (library/parameter_reader.h), and embedded shoot types and
// phenology are validated as species files are. A value not in the file is reported (one
// warning per plant) and completed afterwards (completePlant).

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <span>
#include <type_traits>

#include "core/value_text.h"
#include "core/xml_reader.h"
#include "library/parameter_reader.h"
#include "plant_io/plant_structure.h"
#include "plantarch/Error.h"
#include "plantarch/PlantStateTable.h"

namespace plantarch::plant_io {

namespace {

using pugi::xml_node;
using xml::Children;
using xml::Element;
using Attributes = std::span<const std::string_view>;

constexpr std::string_view kID[] = {"ID"};
constexpr std::string_view kLabel[] = {"label"};

std::string number(double v) {
    return text::formatDouble(v);
}

// ---- the document ------------------------------------------------------------------------

}  // namespace

namespace {

// ---- value parsing -------------------------------------------------------------------

Rng parseRng(std::string_view raw) {
    const std::string_view s = text::trim(raw);
    const auto space = s.find_first_of(" \t\r\n");
    if (space == std::string_view::npos)
        throw Error("expected two whole numbers (generator state and increment)",
                    {.value = std::string(s), .validRange = "'state increment'"});
    std::uint64_t state = 0, increment = 0;
    if (!text::readNumber(s.substr(0, space), state) ||
        !text::readNumber(text::trim(s.substr(space)), increment))
        throw Error("expected two whole numbers (generator state and increment)",
                    {.value = std::string(s), .validRange = "two numbers from 0 to 2^64 - 1"});
    return Rng::fromState(state, increment);
}

ObjectID objectID(std::string_view raw) {
    unsigned v = 0;
    const std::string_view s = text::trim(raw);
    if (!text::readNumber(s, v) || v > (1u << 30))
        throw Error("expected an object ID", {.value = std::string(s), .validRange = "0 to 2^30"});
    return v;
}

// A value of a state enum by its name (plantarch/PlantState.h's tables).
template <StateEnum E>
E parseStateName(std::string_view raw) {
    const std::string_view s = text::trim(raw);
    if (const std::optional<E> v = stateNamed<E>(s)) return *v;
    return kStateNames<E>[text::parseChoice(s, stateNames<E>())].value;  // throws
}

// ---- the reader ------------------------------------------------------------------------

// What one plant's reading shares: the values that were missing.
struct PlantReader {
    Presence presence = Presence::recordingMissing();
    std::map<std::string, int> missingCounts;  // "shoot.phytomer.age" -> how many
    std::vector<const char*> kinds;  // names of the elements being read, below plant_instance

    void missing(const char* name, const void* member) {
        presence.note(member);
        // The report names the kind of value, without the plant_instance[k] prefix.
        std::string key;
        for (const char* k : kinds) {
            key += k;
            key += '.';
        }
        key += name;
        ++missingCounts[key];
    }
};

// Visits the content of an element that is absent: every value in it is missing.
struct MissingVisitor {
    PlantReader& r;
    template <class T>
    void field(const state::FieldInfo& f, T& member) {
        r.missing(f.name, &member);
    }
    template <class T>
    void field(const params::FieldInfo& f, T& member) {
        r.missing(f.name, &member);
    }
    void legacy(const char*) {}
    template <class T>
    void objects(const char*, T&) {}
    template <class Fn>
    void group(const char* name, Fn&& fn) {
        r.kinds.push_back(name);
        fn(*this);
        r.kinds.pop_back();
    }
    template <class T>
    void list(const char*, std::vector<T>&, bool = false) {}
    template <class E, class Fn>
    void list(const params::FieldInfo& f, const char*, std::vector<E>& items, Fn&&) {
        r.missing(f.name, &items);
    }
    template <class T>
    void values(const state::FieldInfo&, std::vector<T>&) {}
    template <class T>
    void optional(const char*, std::optional<T>&) {}  // absent: none, nothing missing
    template <class P>
    void parameters(const char* name, P& member) {
        r.missing(name, &member);
    }
};

class ElementReader {
public:
    ElementReader(PlantReader& r, const Element& e, Attributes attributes = {})
        : r_(r), e_(e), children_(e) {
        e.checkAttributes(attributes);
    }

    // A value of either table.
    template <class T>
    void field(const state::FieldInfo& f, T& member) {
        fieldOf(f, member);
    }
    template <class T>
    void field(const params::FieldInfo& f, T& member) {
        fieldOf(f, member);
    }

    // An element of the listing that carries nothing plantarch keeps: a number, checked.
    void legacy(const char* name) {
        if (const xml_node n = children_.take(name)) Element(e_, n, name).parse(text::parseFloat);
    }

    // Object IDs: optional, absent means none (no missing-value report).
    void objects(const char* name, ObjectID& id) {
        id = kNoObject;
        if (const xml_node n = children_.take(name))
            id = Element(e_, n, name).parse([](std::string_view s) { return objectID(s); });
    }
    void objects(const char* name, std::vector<ObjectID>& ids) {
        ids.clear();
        if (const xml_node n = children_.take(name))
            ids = idList(Element(e_, n, name), 1000, "object IDs");
    }

    // Whole numbers separated by white space, at most `most` of them.
    static std::vector<unsigned> idList(const Element& e, std::size_t most, const char* what) {
        std::vector<unsigned> ids;
        const std::string s = e.text();
        std::size_t at = 0;
        while (at < s.size()) {
            const std::size_t start = s.find_first_not_of(" \t\r\n", at);
            if (start == std::string::npos) break;
            if (ids.size() == most)
                e.fail(std::string("too many ") + what, s, "at most " + std::to_string(most));
            std::size_t end = s.find_first_of(" \t\r\n", start);
            if (end == std::string::npos) end = s.size();
            ids.push_back(e.convert(s.substr(start, end - start),
                                    [](std::string_view v) { return objectID(v); }));
            at = end;
        }
        return ids;
    }

    // State table group: fn(visitor) visits the nested element's content.
    template <class Fn>
    void group(const char* name, Fn&& fn) {
        const xml_node n = children_.take(name);
        r_.kinds.push_back(name);
        if (n) {
            nested(Element(e_, n, name), fn);
        } else {  // every value inside is missing
            MissingVisitor absent{r_};
            fn(absent);
        }
        r_.kinds.pop_back();
    }
    // Parameter table group.
    template <class G, class Fn>
    void group(const char* name, G& member, Fn&& fn) {
        const xml_node n = children_.take(name);
        if (!n) return r_.missing(name, &member);
        r_.kinds.push_back(name);
        nested(Element(e_, n, name), fn);
        r_.kinds.pop_back();
    }

    template <class T>
    void list(const char* name, std::vector<T>& items, bool ids = false) {
        const std::vector<xml_node> nodes = children_.takeAll(name);
        items.resize(nodes.size());  // at most the elements present: bounded by the input
        r_.kinds.push_back(name);
        for (std::size_t i = 0; i < nodes.size(); ++i) {
            const Element item(e_, nodes[i], name, int(i));
            if (ids) checkID(item, i);
            nested(
                item, [&](auto& v) { state::describeState(items[i], v); },
                ids ? Attributes(kID) : Attributes());
        }
        r_.kinds.pop_back();
    }

    // Parameter table list: <name><item>...</item>...</name>.
    template <class E, class Fn>
    void list(const params::FieldInfo& f, const char* item, std::vector<E>& items, Fn&& visit) {
        const xml_node n = children_.take(f.name);
        if (!n) return r_.missing(f.name, &items);
        const Element holder(e_, n, f.name);
        holder.checkAttributes({});
        Children children(holder);
        const std::vector<xml_node> nodes = children.takeAll(item);
        children.finish();
        items.assign(nodes.size(), E{});  // at most the elements present: bounded by the input
        r_.kinds.push_back(f.name);
        for (std::size_t i = 0; i < nodes.size(); ++i)
            nested(Element(holder, nodes[i], item, int(i)), [&](auto& v) { visit(items[i], v); });
        r_.kinds.pop_back();
    }

    // Every <name> child is one value of the list (none: an empty list).
    template <class T>
    void values(const state::FieldInfo& f, std::vector<T>& items) {
        const std::vector<xml_node> nodes = children_.takeAll(f.name);
        items.assign(nodes.size(), T{});  // at most the elements present: bounded by the input
        for (std::size_t i = 0; i < nodes.size(); ++i)
            readValue(f, Element(e_, nodes[i], f.name), items[i]);  // errors name its line
    }

    // An optional element: absent, the member is none (and nothing is missing).
    template <class T>
    void optional(const char* name, std::optional<T>& member) {
        const xml_node n = children_.take(name);
        if (!n) return member.reset();
        member.emplace();
        r_.kinds.push_back(name);
        nested(Element(e_, n, name), [&](auto& v) { state::describeState(*member, v); });
        r_.kinds.pop_back();
    }

    void parameters(const char* name, PhenologyParameters& p) {
        const xml_node n = children_.take(name);
        if (!n) return r_.missing(name, &p);
        const Element e(e_, n, name);
        r_.kinds.push_back(name);
        nested(e, [&](auto& v) { params::describeParameters(p, v); });
        r_.kinds.pop_back();
        validated(e, [&] { validate(p); });
    }

    void parameters(const char* name, std::map<std::string, ShootParameters>& types) {
        const std::vector<xml_node> nodes = children_.takeAll(name);
        if (nodes.empty()) return r_.missing(name, &types);
        for (xml_node n : nodes) {
            const Element at(e_, n, name);
            const std::string label = at.requiredAttribute("label");
            if (!text::isLabel(label))
                at.failAt("label", "a shoot type label is letters, digits, '_' or '-'", label);
            if (types.count(label))
                at.failAt("label", "duplicate shoot type '" + label + "'", label);
            const Element e(e_.document(), n, at.path() + "[" + label + "]");
            ShootParameters params;
            r_.kinds.push_back(name);
            nested(
                e, [&](auto& v) { params::describeParameters(params, v); }, kLabel);
            r_.kinds.pop_back();
            validated(e, [&] { validate(params); });
            types.emplace(label, std::move(params));
        }
    }

    // The plant's optional <material_IDs> (whole numbers separated by spaces).
    std::vector<unsigned> materialIDs() {
        const xml_node n = children_.take("material_IDs");
        if (!n) return {};
        return idList(Element(e_, n, "material_IDs"), 100000, "material IDs");
    }

    // Every child element must have been taken: else it is unknown or a duplicate.
    void finish() const { children_.finish(); }

private:
    template <class Info, class T>
    void fieldOf(const Info& f, T& member) {
        const xml_node n = children_.take(f.name);
        if (!n) return r_.missing(f.name, &member);
        readValue(f, Element(e_, n, f.name), member);
    }

    // The content of element `e`, visited by `visit`.
    template <class Visit>
    void nested(const Element& e, Visit&& visit, Attributes attributes = {}) {
        ElementReader sub(r_, e, attributes);
        visit(sub);
        sub.finish();
    }

    // Runs a validation of what `e` holds; an error it finds is placed at the element it
    // names below `e`.
    template <class Check>
    void validated(const Element& e, Check&& check) {
        try {
            check();
        } catch (const Error& err) {
            e.document().relocate(err, locateElement(e.node(), err.parameter()),
                                  e.pathTo(err.parameter()));
        }
    }

    static void checkID(const Element& item, std::size_t index) {
        if (!item.hasAttribute("ID")) return;  // optional: the position gives the ID
        const std::string text = item.attribute("ID");
        unsigned id = 0;
        if (!text::readNumber(text, id) || id != index)
            item.failAt(
                "ID",
                std::string("<") + item.name() + "> IDs must count 0, 1, 2, ... in file order",
                text, std::to_string(index));
    }

    static void checkRange(const state::FieldInfo& f, const Element& e, double v,
                           std::string_view text) {
        if (!state::inside(f, v)) e.fail("out of range", std::string(text), rangeText(f.range()));
    }

    // Parameters: as species files spell them.
    template <class T>
    static void readValue(const params::FieldInfo& f, const Element& e, T& m) {
        species_xml::readParameter(e, f, m);
    }

    template <class T>
    requires std::is_same_v<T, float> || std::is_same_v<T, double> || std::is_same_v<T, int> ||
        std::is_same_v<T, unsigned>
    static void readValue(const state::FieldInfo& f, const Element& e, T& m) {
        const std::string s = e.text();
        m = e.convert(s, text::parse<T>);
        checkRange(f, e, m, s);
    }
    static void readValue(const state::FieldInfo&, const Element& e, bool& m) {
        m = e.parse(text::parseBool);
    }
    static void readValue(const state::FieldInfo& f, const Element& e, vec3& m) {
        const std::string s = e.text();
        m = e.convert(s, text::parseVec3);
        // A direction's components may pass 1 by a rounding (-1.0000001 after normalizing):
        // its length, within 1e-3 of 1, bounds them instead.
        if (f.check != state::Check::UnitVector)
            for (int i = 0; i < 3; ++i) checkRange(f, e, m[i], s);
        const double length = std::sqrt(double(m.x) * m.x + double(m.y) * m.y + double(m.z) * m.z);
        if (f.check == state::Check::UnitVector && std::abs(length - 1.0) > 1e-3)
            e.fail("not a unit vector (length " + number(length) + ")", s,
                   "a direction of length 1");
    }
    static void readValue(const state::FieldInfo& f, const Element& e, AxisRotation& m) {
        const std::string s = e.text();
        const vec3 v = e.convert(s, text::parseVec3);
        for (int i = 0; i < 3; ++i) checkRange(f, e, v[i], s);
        m = {v.x, v.y, v.z};
    }
    static void readValue(const state::FieldInfo& f, const Element& e, std::string& m) {
        m = e.text();
        const bool optional = f.check == state::Check::LabelOrEmpty;
        if ((f.check == state::Check::Label || optional) && !(optional && m.empty()) &&
            !text::isLabel(m))
            e.fail("a shoot type label is letters, digits, '_' or '-'", m,
                   optional ? "a label, or nothing" : "a label");
    }
    // Labels separated by white space.
    static void readValue(const state::FieldInfo&, const Element& e, std::vector<std::string>& m) {
        const std::string s = e.text();
        m.clear();
        std::size_t at = 0;
        while (at < s.size()) {
            const std::size_t start = s.find_first_not_of(" \t\r\n", at);
            if (start == std::string::npos) break;
            std::size_t end = s.find_first_of(" \t\r\n", start);
            if (end == std::string::npos) end = s.size();
            const std::string label = s.substr(start, end - start);
            if (!text::isLabel(label))
                e.fail("a shoot type label is letters, digits, '_' or '-'", label,
                       "shoot type labels separated by spaces");
            m.push_back(label);
            at = end;
        }
    }
    template <StateEnum E>
    static void readValue(const state::FieldInfo&, const Element& e, E& m) {
        m = e.parse(parseStateName<E>);
    }
    static void readValue(const state::FieldInfo&, const Element& e, Rng& m) {
        m = e.parse(parseRng);
    }

    PlantReader& r_;
    const Element& e_;
    Children children_;
};

void checkFormat(const Element& root) {
    if (std::string_view(root.name()) == kListingRoot) return root.checkAttributes({});
    root.checkAttributes({"format"});
    const std::string expected = std::to_string(kFormatVersion);
    const std::string version = root.requiredAttribute("format", expected);
    if (version == expected) return;
    int v = 0;
    root.failAt("format",
                text::readNumber(version, v) && v > kFormatVersion
                    ? "the file is of a newer format than this plantarch reads"
                    : "unknown format version",
                version, expected);
}

}  // namespace

ReadResult readPlantsXML(const std::string& xml, const std::string& fileName,
                         const Defaults& defaults) {
    const xml::Document doc(xml, fileName, {"plant structure file", kRoot, kListingRoot});
    if (std::string_view(doc.root().name()) == kListingRoot)
        return readHeliosPlants(doc, fileName, defaults);
    const Element root(doc, doc.root(), "");
    checkFormat(root);
    Children children(root);
    const std::vector<xml_node> plants = children.takeAll("plant_instance");
    children.finish();

    ReadResult result;
    for (unsigned index = 0; index < plants.size(); ++index) {
        const xml_node node = plants[index];
        const Element e(root, node, "plant_instance", int(index));
        const std::string where = e.path();
        if (e.hasAttribute("ID"))
            Element(e, node, "ID").convert(e.attribute("ID"), text::parseUnsigned);
        PlantInstance plant;
        PlantReader reader;
        ElementReader top(reader, e, kID);
        state::describeState(plant, top);
        result.materialIDs.push_back(top.materialIDs());
        top.finish();
        std::vector<std::string> notes;
        try {
            if (!reader.presence.complete())
                completePlant(plant, reader.presence, defaults, defaults.firstStream + index, notes,
                              where);
            checkPlant(plant, where);
        } catch (const Error& err) {
            std::string rel = err.parameter();
            if (rel.compare(0, where.size() + 1, where + ".") == 0) rel.erase(0, where.size() + 1);
            doc.relocate(err, locateElement(node, rel), err.parameter());
        }
        if (!reader.missingCounts.empty()) {
            std::string w =
                fileName + ": plant_instance " + std::to_string(index) +
                ": values missing, defaults used: " + missingReport(reader.missingCounts);
            for (const std::string& n : notes) w += "; " + n;
            result.warnings.push_back(std::move(w));
        }
        result.plants.push_back(std::move(plant));
    }
    return result;
}

}  // namespace plantarch::plant_io
