// Strict reader of species files (docs/species-format.md).
//
// The shoot type and phenology elements are read by a visitor of the parameter declaration
// table (model/parameter_table.h): the names an element may contain are the names the table
// declares at that level, so a field added to the table is readable at once and nothing here
// lists parameter names. Every value read records its line, so the range validation that
// runs afterwards (validate() of parameters.cpp) can point at the offending element.

#include <algorithm>
#include <fstream>
#include <map>
#include <pugixml.hpp>
#include <set>
#include <sstream>

#include "library/expression.h"
#include "library/species_xml.h"
#include "library/value_text.h"
#include "library/xml_source.h"
#include "model/parameter_table.h"
#include "plantarch/Error.h"
#include "plantarch/SpeciesIO.h"

namespace plantarch {

namespace {

using pugi::xml_node;
using Lines = std::map<std::string, int>;

std::string joinPath(const std::string& a, const std::string& b) {
    return a.empty() ? b : a + "." + b;
}

bool isElement(xml_node n) {
    return n.type() == pugi::node_element;
}
bool isText(xml_node n) {
    return n.type() == pugi::node_pcdata || n.type() == pugi::node_cdata;
}

bool contains(const std::vector<std::string>& list, const std::string& s) {
    return std::find(list.begin(), list.end(), s) != list.end();
}

// Labels, ids and names: letters, digits, '_' and '-' (no '.', which separates path parts).
bool isLabel(const std::string& s) {
    if (s.empty()) return false;
    return std::all_of(s.begin(), s.end(), [](char c) {
        return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-';
    });
}

bool isIdentifier(const std::string& s) {
    if (s.empty() || std::isdigit(static_cast<unsigned char>(s[0]))) return false;
    return std::all_of(s.begin(), s.end(), [](char c) {
        return std::isalnum(static_cast<unsigned char>(c)) || c == '_';
    });
}

std::string collapseSpaces(std::string_view s) {
    std::string out;
    bool space = false;
    for (char c : text::trim(s)) {
        if (c == ' ' || c == '\t' || c == '\n' || c == '\r') {
            space = true;
            continue;
        }
        if (space) out += ' ';
        space = false;
        out += c;
    }
    return out;
}

// An error about `path` found after reading (range validation): put it at the line of the
// value it names, or of the nearest enclosing element that was read.
Error locate(const Error& e, const std::string& file, const Lines& lines, int fallbackLine) {
    std::string path = e.parameter();
    while (!path.empty()) {
        auto it = lines.find(path);
        if (it != lines.end()) return e.withFile(file, it->second);
        const auto dot = path.rfind('.');
        if (dot == std::string::npos) break;
        path.resize(dot);
    }
    return e.withFile(file, fallbackLine);
}

// "unknown element 'pitchh' of <petiole>, did you mean 'pitch'?"
std::string unknownMessage(const char* what, const std::string& name,
                           const std::vector<std::string>& valid, const std::string& where = "") {
    const std::string near = text::closestMatch(name, valid);
    return std::string("unknown ") + what + " '" + name + "'" + where +
           (near.empty() ? "" : ", did you mean '" + near + "'?");
}

std::string validList(const std::vector<std::string>& valid) {
    return valid.empty() ? "none" : "one of: " + text::joinNames(valid);
}

// ---- structure checks -----------------------------------------------------------------

void checkAttributes(const XmlSource& src, xml_node e, const std::string& path,
                     const std::vector<std::string>& allowed) {
    std::set<std::string> seen;
    for (pugi::xml_attribute a : e.attributes()) {
        const std::string name = a.name();
        if (!contains(allowed, name))
            src.fail(
                e, joinPath(path, name),
                unknownMessage("attribute", name, allowed, std::string(" of <") + e.name() + ">"),
                a.value(), allowed.empty() ? "no attributes" : validList(allowed));
        if (!seen.insert(name).second)
            src.fail(e, joinPath(path, name), "duplicate attribute '" + name + "'", a.value());
    }
}

std::string requiredAttribute(const XmlSource& src, xml_node e, const std::string& path,
                              const char* name) {
    pugi::xml_attribute a = e.attribute(name);
    if (!a)
        src.fail(e, joinPath(path, name),
                 std::string("missing required attribute '") + name + "' of <" + e.name() + ">");
    return std::string(text::trim(a.value()));
}

// Children must be elements named in `allowed`, each at most once unless in `repeatable`.
void checkChildren(const XmlSource& src, xml_node e, const std::string& path,
                   const std::vector<std::string>& allowed,
                   const std::vector<std::string>& repeatable = {}) {
    std::map<std::string, xml_node> seen;
    for (xml_node c : e.children()) {
        if (isText(c))
            src.fail(c, path,
                     std::string("unexpected text inside <") + e.name() + ">, expected elements",
                     collapseSpaces(c.value()).substr(0, 40));
        if (!isElement(c)) continue;
        const std::string name = c.name();
        if (!contains(allowed, name))
            src.fail(c, joinPath(path, name), unknownMessage("element", name, allowed), "",
                     validList(allowed));
        auto [it, fresh] = seen.emplace(name, c);
        if (!fresh && !contains(repeatable, name))
            src.fail(c, joinPath(path, name),
                     "duplicate element <" + name + "> (first at line " +
                         std::to_string(src.line(it->second)) + ")");
    }
}

// The text of an element that holds a value: no child elements, surrounding space trimmed.
std::string valueText(const XmlSource& src, xml_node e, const std::string& path) {
    std::string out;
    for (xml_node c : e.children()) {
        if (isText(c))
            out += c.value();
        else if (isElement(c))
            src.fail(c, path,
                     std::string("<") + e.name() + "> holds a value, not elements (found <" +
                         c.name() + ">)");
    }
    return std::string(text::trim(out));
}

template <class Parse>
auto convert(const XmlSource& src, xml_node e, const std::string& path, const std::string& text,
             Parse&& parse) {
    try {
        return parse(text);
    } catch (const Error& err) {
        src.relocate(err, e, path);
    }
}

// ---- the table visitor ------------------------------------------------------------------

// Names declared at one level of the table.
struct NameCollector {
    std::vector<std::string> names;
    template <class T>
    void field(const params::FieldInfo& f, T&) {
        names.emplace_back(f.name);
    }
    template <class G, class Fn>
    void group(const char* name, G&, Fn&&) {
        names.emplace_back(name);
    }
    template <class E, class Fn>
    void list(const params::FieldInfo& f, const char*, std::vector<E>&, Fn&&) {
        names.emplace_back(f.name);
    }
};

class FieldReader;

// Reads a group element (shoot type, phenology, phytomer, leaf, ...) through `visit`, which
// runs describeParameters on the struct being filled with the visitor it is given.
template <class Visit>
void readGroup(const XmlSource& src, Lines& lines, xml_node e, const std::string& path,
               const std::vector<std::string>& attributes, Visit&& visit);

class FieldReader {
public:
    FieldReader(const XmlSource& src, Lines& lines, xml_node node, std::string path)
        : src_(src), lines_(lines), node_(node), path_(std::move(path)) {}

    template <class T>
    void field(const params::FieldInfo& f, T& member) {
        xml_node e = node_.child(f.name);
        if (!e) return;
        const std::string path = joinPath(path_, f.name);
        lines_[path] = src_.line(e);
        read(f, e, path, member);
    }

    template <class G, class Fn>
    void group(const char* name, G&, Fn&& visit) {
        xml_node e = node_.child(name);
        if (!e) return;
        const std::string path = joinPath(path_, name);
        lines_[path] = src_.line(e);
        readGroup(src_, lines_, e, path, {}, visit);
    }

    // A list of groups: <name><item>...</item>...</name>, replacing the inherited list whole.
    template <class E, class Fn>
    void list(const params::FieldInfo& f, const char* item, std::vector<E>& items, Fn&& visit) {
        xml_node e = node_.child(f.name);
        if (!e) return;
        const std::string path = joinPath(path_, f.name);
        lines_[path] = src_.line(e);
        checkAttributes(src_, e, path, {});
        checkChildren(src_, e, path, {item}, {item});
        items.clear();
        for (xml_node c : e.children(item)) {
            const std::string at = path + "[" + std::to_string(items.size() + 1) + "]";
            lines_[at] = src_.line(c);
            E element{};
            readGroup(src_, lines_, c, at, {}, [&](auto& v) { visit(element, v); });
            items.push_back(std::move(element));
        }
    }

private:
    std::string scalar(xml_node e, const std::string& path) {
        checkAttributes(src_, e, path, {});
        return valueText(src_, e, path);
    }

    void read(const params::FieldInfo&, xml_node e, const std::string& path, RandomFloat& m) {
        m = convert(src_, e, path, scalar(e, path), text::parseRandomFloat);
    }
    void read(const params::FieldInfo&, xml_node e, const std::string& path, RandomInt& m) {
        m = convert(src_, e, path, scalar(e, path), text::parseRandomInt);
    }
    void read(const params::FieldInfo&, xml_node e, const std::string& path, float& m) {
        m = convert(src_, e, path, scalar(e, path), text::parseFloat);
    }
    void read(const params::FieldInfo&, xml_node e, const std::string& path, unsigned& m) {
        m = convert(src_, e, path, scalar(e, path), text::parseUnsigned);
    }
    void read(const params::FieldInfo&, xml_node e, const std::string& path, int& m) {
        m = convert(src_, e, path, scalar(e, path), text::parseInt);
    }
    void read(const params::FieldInfo&, xml_node e, const std::string& path, bool& m) {
        m = convert(src_, e, path, scalar(e, path), text::parseBool);
    }
    void read(const params::FieldInfo&, xml_node e, const std::string& path, vec3& m) {
        m = convert(src_, e, path, scalar(e, path), text::parseVec3);
    }
    void read(const params::FieldInfo&, xml_node e, const std::string& path, Formula& m) {
        const std::string s = scalar(e, path);
        m = s.empty() ? Formula() : convert(src_, e, path, s, NodeRule::formula);
    }
    void read(const params::FieldInfo&, xml_node e, const std::string& path, std::string& m) {
        m = scalar(e, path);
    }
    template <params::ChoiceType E>
    void read(const params::FieldInfo&, xml_node e, const std::string& path, E& m) {
        const std::string name = scalar(e, path);
        if (const auto value = params::choiceNamed<E>(name)) {
            m = *value;
            return;
        }
        const std::vector<std::string> valid = params::choiceNames<E>();
        src_.fail(e, path, unknownMessage("value", name, valid), name, validList(valid));
    }

    // Map fields: one child element per entry, spelled as the table declares (f.entries).
    template <class Key, class Value, class ParseKey, class ParseValue>
    void readMap(const params::FieldInfo& f, xml_node e, const std::string& path,
                 std::map<Key, Value>& m, ParseKey&& parseKey, ParseValue&& parseValue) {
        const params::MapEntries& spell = f.entries;
        checkAttributes(src_, e, path, {});
        checkChildren(src_, e, path, {spell.element}, {spell.element});
        std::vector<std::string> attributes = {spell.key};
        if (spell.value) attributes.push_back(spell.value);
        m.clear();
        for (xml_node c : e.children(spell.element)) {
            checkAttributes(src_, c, path, attributes);
            const std::string keyText = requiredAttribute(src_, c, path, spell.key);
            const Key key = convert(src_, c, path + "." + keyText, keyText, parseKey);
            const std::string entry = path + "." + keyText;
            std::string valueString;
            if (spell.value) {
                if (c.first_child())
                    src_.fail(c, entry, std::string("<") + spell.element + "> takes no content");
                valueString = requiredAttribute(src_, c, entry, spell.value);
            } else {
                valueString = valueText(src_, c, entry);
            }
            const Value value = convert(src_, c, entry, valueString, parseValue);
            if (!m.emplace(key, value).second)
                src_.fail(c, entry,
                          "duplicate " + std::string(spell.key) + " '" + keyText + "' in <" +
                              f.name + ">");
            lines_[entry] = src_.line(c);
        }
    }

    void read(const params::FieldInfo& f, xml_node e, const std::string& path,
              std::map<int, std::string>& m) {
        readMap(f, e, path, m, text::parseInt, [](const std::string& s) { return s; });
    }
    void read(const params::FieldInfo& f, xml_node e, const std::string& path,
              std::map<std::string, float>& m) {
        auto key = [](const std::string& s) {
            if (!isLabel(s))
                throw Error("expected a name of letters, digits, '_' or '-'",
                            {.value = s, .validRange = "a non-empty name"});
            return s;
        };
        readMap(f, e, path, m, key, text::parseFloat);
    }

    const XmlSource& src_;
    Lines& lines_;
    xml_node node_;
    std::string path_;
};

template <class Visit>
void readGroup(const XmlSource& src, Lines& lines, xml_node e, const std::string& path,
               const std::vector<std::string>& attributes, Visit&& visit) {
    NameCollector names;
    visit(names);
    checkAttributes(src, e, path, attributes);
    checkChildren(src, e, path, names.names);
    FieldReader reader(src, lines, e, path);
    visit(reader);
}

// ---- the species file -------------------------------------------------------------------

const std::vector<std::string> kTopLevel = {"name",       "common_name", "latin_name",
                                            "plant_type", "description", "recommended_age",
                                            "max_height", "phenology",   "build_parameters",
                                            "shoot_type", "build",       "attraction_points"};

class SpeciesReader {
public:
    SpeciesReader(const XmlSource& src, SpeciesModel& model) : src_(src), m_(model) {}

    void read(xml_node root) {
        checkAttributes(src_, root, "", {"format"});
        const std::string format = requiredAttribute(src_, root, "", "format");
        if (format != species_xml::kFormatVersion)
            src_.fail(root, "format", "unsupported species file format", format,
                      species_xml::kFormatVersion);
        checkChildren(src_, root, "", kTopLevel, {"shoot_type"});

        readNames(root);
        if (xml_node e = root.child("phenology")) readPhenology(e);
        if (xml_node e = root.child("build_parameters")) readBuildParameters(e);
        for (xml_node e : root.children("shoot_type")) readShootType(e);
        if (m_.shootTypes.empty())
            src_.fail(root, "shoot_type", "a species needs at least one <shoot_type>");
        checkChildTypes();
        xml_node build = root.child("build");
        if (!build) src_.fail(root, "build", "missing required element <build>");
        readBuild(build);
        if (xml_node e = root.child("attraction_points")) readAttraction(e);
    }

private:
    std::string textOf(xml_node e, const std::string& path) {
        checkAttributes(src_, e, path, {});
        m_.lines[path] = src_.line(e);
        return valueText(src_, e, path);
    }

    void readNames(xml_node root) {
        xml_node name = root.child("name");
        if (!name) src_.fail(root, "name", "missing required element <name>");
        m_.name = textOf(name, "name");
        if (!isLabel(m_.name))
            src_.fail(name, "name", "a species name is letters, digits, '_' or '-'", m_.name);
        if (xml_node e = root.child("common_name"))
            m_.commonName = collapseSpaces(textOf(e, "common_name"));
        if (xml_node e = root.child("latin_name"))
            m_.latinName = collapseSpaces(textOf(e, "latin_name"));
        if (xml_node e = root.child("description"))
            m_.description = collapseSpaces(textOf(e, "description"));
        if (xml_node e = root.child("plant_type")) {
            m_.plantType = textOf(e, "plant_type");
            const auto& types = species_xml::plantTypes();
            if (!contains(types, m_.plantType))
                src_.fail(e, "plant_type", unknownMessage("plant type", m_.plantType, types),
                          m_.plantType, validList(types));
        }
        if (xml_node e = root.child("recommended_age")) readRecommendedAge(e);
        if (xml_node e = root.child("max_height")) {
            m_.maxHeight =
                convert(src_, e, "max_height", textOf(e, "max_height"), text::parseFloat);
            if (m_.maxHeight < 0.0f)
                src_.fail(e, "max_height", "out of range", text::formatFloat(m_.maxHeight),
                          ">= 0 m");
        }
    }

    float floatAttribute(xml_node e, const std::string& path, const char* name) {
        const std::string at = joinPath(path, name);
        return convert(src_, e, at, requiredAttribute(src_, e, path, name), text::parseFloat);
    }

    void readRecommendedAge(xml_node e) {
        const std::string path = "recommended_age";
        checkAttributes(src_, e, path, {"min", "max", "default"});
        checkChildren(src_, e, path, {});
        m_.lines[path] = src_.line(e);
        m_.recommendedAgeMin = floatAttribute(e, path, "min");
        m_.recommendedAgeMax = floatAttribute(e, path, "max");
        m_.recommendedAge = floatAttribute(e, path, "default");
        if (m_.recommendedAgeMin < 0.0f || m_.recommendedAgeMax < m_.recommendedAgeMin)
            src_.fail(e, path + ".max", "recommended age range is empty or negative",
                      text::formatFloat(m_.recommendedAgeMin) + " to " +
                          text::formatFloat(m_.recommendedAgeMax),
                      "0 <= min <= max days");
        if (m_.recommendedAge < m_.recommendedAgeMin || m_.recommendedAge > m_.recommendedAgeMax)
            src_.fail(e, path + ".default", "out of range", text::formatFloat(m_.recommendedAge),
                      text::formatFloat(m_.recommendedAgeMin) + " to " +
                          text::formatFloat(m_.recommendedAgeMax) + " days");
    }

    void readPhenology(xml_node e) {
        m_.lines["phenology"] = src_.line(e);
        readGroup(src_, m_.lines, e, "phenology", {},
                  [&](auto& v) { params::describeParameters(m_.phenology, v); });
        try {
            validate(m_.phenology, "phenology");
        } catch (const Error& err) {
            throw locate(err, src_.file(), m_.lines, src_.line(e));
        }
    }

    void readBuildParameters(xml_node e) {
        checkAttributes(src_, e, "build_parameters", {});
        checkChildren(src_, e, "build_parameters", {"parameter"}, {"parameter"});
        for (xml_node p : e.children("parameter")) {
            const std::string base = "build_parameters";
            checkAttributes(src_, p, base, {"name", "default", "min", "max", "unit", "doc"});
            checkChildren(src_, p, base, {});
            BuildParameter bp;
            bp.name = requiredAttribute(src_, p, base, "name");
            const std::string path = joinPath(base, bp.name);
            if (!isIdentifier(bp.name))
                src_.fail(p, path,
                          "a build parameter name is a letter or '_' followed by "
                          "letters, digits or '_'",
                          bp.name);
            if (contains(expr::reservedNames(), bp.name) || bp.name == "i" || bp.name == "parent_i")
                src_.fail(p, path, "reserved name, choose another", bp.name);
            for (const BuildParameter& other : m_.buildParameters)
                if (other.name == bp.name)
                    src_.fail(p, path,
                              "duplicate build parameter '" + bp.name + "' (first at line " +
                                  std::to_string(m_.lines[path]) + ")");
            bp.value = floatAttribute(p, path, "default");
            bp.min = floatAttribute(p, path, "min");
            bp.max = floatAttribute(p, path, "max");
            bp.unit = std::string(text::trim(p.attribute("unit").value()));
            bp.doc = collapseSpaces(p.attribute("doc").value());
            if (bp.min > bp.max)
                src_.fail(p, path + ".min", "min exceeds max", text::formatFloat(bp.min),
                          "<= max (" + text::formatFloat(bp.max) + ")");
            if (bp.value < bp.min || bp.value > bp.max)
                src_.fail(p, path + ".default", "default out of range", text::formatFloat(bp.value),
                          text::formatFloat(bp.min) + " to " + text::formatFloat(bp.max));
            m_.lines[path] = src_.line(p);
            m_.buildParameters.push_back(bp);
        }
    }

    void readShootType(xml_node e) {
        const std::string label = requiredAttribute(src_, e, "shoot_type", "label");
        if (!isLabel(label))
            src_.fail(e, "shoot_type.label",
                      "a shoot type label is letters, digits, '_' or '-' (no spaces or dots)",
                      label);
        if (m_.shootTypes.count(label))
            src_.fail(e, label,
                      "duplicate shoot type '" + label + "' (first at line " +
                          std::to_string(m_.lines[label]) + ")");
        ShootParameters params;
        if (pugi::xml_attribute base = e.attribute("inherits")) {
            const std::string from(text::trim(base.value()));
            auto it = m_.shootTypes.find(from);
            if (it == m_.shootTypes.end()) {
                std::vector<std::string> known;
                for (const auto& [l, p] : m_.shootTypes) known.push_back(l);
                src_.fail(e, label + ".inherits",
                          unknownMessage("shoot type", from, known) +
                              " (a type can only inherit from one defined above it)",
                          from, validList(known));
            }
            params = it->second;
            // Inherited values keep pointing at the lines they were read from.
            const std::string prefix = from + ".";
            std::vector<std::pair<std::string, int>> copied;
            for (const auto& [path, line] : m_.lines)
                if (path.compare(0, prefix.size(), prefix) == 0)
                    copied.emplace_back(label + "." + path.substr(prefix.size()), line);
            for (const auto& [path, line] : copied) m_.lines[path] = line;
        }
        m_.lines[label] = src_.line(e);
        readGroup(src_, m_.lines, e, label, {"label", "inherits"},
                  [&](auto& v) { params::describeParameters(params, v); });
        try {
            validate(params, label);
        } catch (const Error& err) {
            throw locate(err, src_.file(), m_.lines, src_.line(e));
        }
        m_.shootTypes.emplace(label, std::move(params));
        order_.push_back(label);
    }

    std::vector<std::string> shootTypeLabels() const {
        std::vector<std::string> labels;
        for (const auto& [l, p] : m_.shootTypes) labels.push_back(l);
        return labels;
    }

    void checkChildTypes() {
        const std::vector<std::string> labels = shootTypeLabels();
        for (const std::string& label : order_)
            for (const auto& [child, probability] : m_.shootTypes.at(label).child_shoot_types)
                if (!m_.shootTypes.count(child)) {
                    const std::string path = label + ".child_shoot_types." + child;
                    throw Error(unknownMessage("shoot type", child, labels),
                                {.file = src_.file(),
                                 .line = m_.lines[path],
                                 .parameter = path,
                                 .value = child,
                                 .validRange = validList(labels)});
                }
    }

    void readBuild(xml_node build) {
        checkAttributes(src_, build, "build", {});
        checkChildren(src_, build, "build", species_xml::buildStepElements(),
                      species_xml::buildStepElements());
        std::vector<std::string> names;
        for (const BuildParameter& p : m_.buildParameters) names.push_back(p.name);
        names.push_back("i");
        names.push_back("parent_i");
        std::vector<std::string> ids;
        int index = 0;
        for (xml_node e : build.children()) {
            if (!isElement(e)) continue;
            ++index;
            m_.build.push_back(readStep(e, index, names, ids));
        }
        if (m_.build.empty()) src_.fail(build, "build", "<build> needs a <base_stem> step");
    }

    // <attraction_points half_angle look_ahead inertia shoot_types> with <wire from to
    // spacing/> and <point at/> children; numbers are expressions over the build parameters.
    void readAttraction(xml_node e) {
        const std::string path = "attraction_points";
        checkAttributes(src_, e, path, {"half_angle", "look_ahead", "inertia", "shoot_types"});
        checkChildren(src_, e, path, {"wire", "point"}, {"wire", "point"});
        std::vector<std::string> names;
        for (const BuildParameter& p : m_.buildParameters) names.push_back(p.name);
        auto expression = [&](xml_node n, const std::string& at, const char* attribute, bool vector,
                              bool required, std::string& out) {
            pugi::xml_attribute a = n.attribute(attribute);
            if (!a) {
                if (required) requiredAttribute(src_, n, at, attribute);
                return;
            }
            const std::string value = collapseSpaces(a.value());
            const std::string where = at + "." + attribute;
            const std::vector<std::string> parts =
                vector ? species_xml::splitVector(value) : std::vector<std::string>{value};
            if (parts.size() != 3 && vector)
                src_.fail(n, where, "expected three expressions x, y, z separated by commas", value,
                          "e.g. \"0, 0, wire_height\"");
            for (const std::string& part : parts) {
                try {
                    expr::check(part, names);
                } catch (const Error& err) {
                    src_.relocate(err, n, where);
                }
            }
            out = value;
        };
        SpeciesAttraction a;
        a.line = src_.line(e);
        m_.lines[path] = a.line;
        expression(e, path, "half_angle", false, false, a.halfAngle);
        expression(e, path, "look_ahead", false, false, a.lookAhead);
        expression(e, path, "inertia", false, false, a.inertia);
        if (pugi::xml_attribute t = e.attribute("shoot_types")) {
            std::string list = t.value();
            std::replace(list.begin(), list.end(), ',', ' ');
            std::stringstream ss(list);
            const std::vector<std::string> labels = shootTypeLabels();
            for (std::string label; ss >> label;) {
                if (!m_.shootTypes.count(label))
                    src_.fail(e, path + ".shoot_types", unknownMessage("shoot type", label, labels),
                              label, validList(labels));
                a.shootTypes.push_back(label);
            }
        }
        int wires = 0, points = 0;
        for (xml_node c : e.children()) {
            if (!isElement(c)) continue;
            const std::string kind = c.name();
            if (kind == "wire") {
                const std::string at = path + ".wire[" + std::to_string(++wires) + "]";
                checkAttributes(src_, c, at, {"from", "to", "spacing"});
                checkChildren(src_, c, at, {});
                SpeciesAttraction::Wire w;
                w.line = src_.line(c);
                expression(c, at, "from", true, true, w.from);
                expression(c, at, "to", true, true, w.to);
                expression(c, at, "spacing", false, false, w.spacing);
                a.wires.push_back(w);
            } else {
                const std::string at = path + ".point[" + std::to_string(++points) + "]";
                checkAttributes(src_, c, at, {"at"});
                checkChildren(src_, c, at, {});
                SpeciesAttraction::Point p;
                p.line = src_.line(c);
                expression(c, at, "at", true, true, p.at);
                a.points.push_back(p);
            }
        }
        if (a.wires.empty() && a.points.empty())
            src_.fail(e, path, "<attraction_points> needs at least one <wire> or <point>");
        m_.attraction = std::move(a);
    }

    BuildStep readStep(xml_node e, int index, const std::vector<std::string>& names,
                       std::vector<std::string>& ids) {
        const std::string kind = e.name();
        BuildStep step;
        step.kind = species_xml::buildStepKind(kind).value();  // checkChildren allowed only these
        step.line = src_.line(e);
        const std::string id(text::trim(e.attribute("id").value()));
        const std::string path =
            "build." + (id.empty() ? kind + "[" + std::to_string(index) + "]" : id);
        const auto& attributes = species_xml::buildStepAttributes(step.kind);
        std::vector<std::string> attributeNames;
        for (const species_xml::StepAttribute& a : attributes) attributeNames.push_back(a.name);
        checkAttributes(src_, e, path, attributeNames);
        checkChildren(src_, e, path, {});
        if (step.kind == BuildStep::Kind::BaseStem && index != 1)
            src_.fail(e, path, "<base_stem> must be the first and only base stem step");
        if (step.kind != BuildStep::Kind::BaseStem && index == 1)
            src_.fail(e, path, "the first build step must be a <base_stem>");

        for (const species_xml::StepAttribute& attribute : attributes) {
            pugi::xml_attribute a = e.attribute(attribute.name);
            if (!a) continue;
            const std::string value = collapseSpaces(a.value());
            const std::string at = path + "." + attribute.name;
            switch (attribute.value) {
                case species_xml::StepValue::Flag:
                    step.*attribute.flag = convert(src_, e, at, value, text::parseBool);
                    continue;
                case species_xml::StepValue::Name:
                    if (!isLabel(value))
                        src_.fail(e, at, "expected a name of letters, digits, '_' or '-'", value);
                    break;
                case species_xml::StepValue::Expression:
                    try {
                        expr::check(value, names);
                    } catch (const Error& err) {
                        src_.relocate(err, e, at);
                    }
                    break;
            }
            step.*attribute.text = value;
        }

        step.shootType = requiredAttribute(src_, e, path, "type");
        const std::vector<std::string> labels = shootTypeLabels();
        if (!m_.shootTypes.count(step.shootType))
            src_.fail(e, path + ".type", unknownMessage("shoot type", step.shootType, labels),
                      step.shootType, validList(labels));
        if (step.kind != BuildStep::Kind::BaseStem) {
            requiredAttribute(src_, e, path, "parent");
            if (!contains(ids, step.parent))
                src_.fail(e, path + ".parent",
                          unknownMessage("parent step", step.parent, ids) +
                              " (the parent must be the id of an earlier step)",
                          step.parent, ids.empty() ? "no step ids defined above" : validList(ids));
        }
        if (step.kind == BuildStep::Kind::Child) requiredAttribute(src_, e, path, "node");
        if (!id.empty()) {
            if (contains(ids, id)) src_.fail(e, path + ".id", "duplicate step id '" + id + "'", id);
            ids.push_back(id);
        }
        m_.lines[path] = step.line;
        return step;
    }

    const XmlSource& src_;
    SpeciesModel& m_;
    std::vector<std::string> order_;  // shoot type labels in file order
};

}  // namespace

SpeciesModel readSpeciesString(const std::string& xml, const std::string& nameForErrors) {
    XmlSource src(xml, nameForErrors);
    if (text::trim(xml).empty())
        throw Error("empty file, expected a <plantarch_species> document",
                    {.file = nameForErrors, .line = 1});
    pugi::xml_document doc;
    const pugi::xml_parse_result result =
        doc.load_buffer(xml.data(), xml.size(), pugi::parse_default, pugi::encoding_utf8);
    if (!result) {
        if (result.status == pugi::status_no_document_element)
            throw Error("not an XML file: no root element, expected <plantarch_species>",
                        {.file = nameForErrors, .line = 1});
        std::string message = std::string("malformed XML: ") + result.description();
        const std::size_t end = xml.find_last_not_of(" \t\r\n");
        if (result.offset >= std::ptrdiff_t(end)) message += " (the file ends too early)";
        throw Error(message, {.file = nameForErrors, .line = src.lineAt(result.offset)});
    }
    xml_node root;
    for (xml_node n : doc.children()) {
        if (!isElement(n)) continue;
        if (root)
            src.fail(n, "",
                     std::string("a second root element <") + n.name() + "> after <" + root.name() +
                         ">");
        root = n;
    }
    if (std::string(root.name()) != species_xml::kRoot)
        src.fail(root, "", std::string("not a species file: root element <") + root.name() + ">",
                 "", std::string("<") + species_xml::kRoot + ">");
    SpeciesModel model;
    model.sourceFile = nameForErrors;
    SpeciesReader(src, model).read(root);
    return model;
}

SpeciesModel readSpeciesFile(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw Error("cannot open species file", {.file = path});
    std::ostringstream text;
    text << in.rdbuf();
    if (in.bad()) throw Error("cannot read species file", {.file = path});
    return readSpeciesString(text.str(), path);
}

}  // namespace plantarch
