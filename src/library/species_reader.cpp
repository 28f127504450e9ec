// Strict reader of species files (docs/species-format.md), on the XML reader layer
// (core/xml_reader.h).
//
// The shoot type and phenology elements are read by a visitor of the parameter declaration
// table (plantarch/ParameterTable.h): the names an element may contain are the names the table
// declares at that level, so a field added to the table is readable at once and nothing here
// lists parameter names. Every value read records its line, so the range validation that
// runs afterwards (validate() of parameters.cpp) can point at the offending element.

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "core/input_file.h"
#include "core/value_text.h"
#include "core/xml_reader.h"
#include "library/expression.h"
#include "library/parameter_reader.h"
#include "library/species_xml.h"
#include "plantarch/Error.h"
#include "plantarch/NumberRange.h"
#include "plantarch/ParameterCheck.h"
#include "plantarch/ParameterTable.h"
#include "plantarch/SpeciesIO.h"

namespace plantarch {

namespace {

using pugi::xml_node;
using xml::Children;
using xml::Element;
using Lines = std::map<std::string, int>;
using Names = std::initializer_list<std::string_view>;

bool contains(const std::vector<std::string>& list, const std::string& s) {
    return std::find(list.begin(), list.end(), s) != list.end();
}

bool isIdentifier(const std::string& s) {
    if (s.empty() || std::isdigit(static_cast<unsigned char>(s[0]))) return false;
    return std::all_of(s.begin(), s.end(), [](char c) {
        return std::isalnum(static_cast<unsigned char>(c)) || c == '_';
    });
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

// Errors kept while checking a file whole (checkSpeciesString): an error that leaves the rest
// of the file readable (a bad value, an unknown element, a value out of range) is kept here
// and reading goes on; null when reading stops at the first error (readSpeciesString).
thread_local std::vector<Error>* tCollected = nullptr;

// Keeps `e` when collecting, else throws it.
void keepOrThrow(const Error& e) {
    if (!tCollected) throw e;
    tCollected->push_back(e);
}

// Runs f(); when collecting, an Error it throws is kept instead. Returns whether f finished.
template <class F>
bool attempt(F&& f) {
    if (!tCollected) {
        f();
        return true;
    }
    try {
        f();
        return true;
    } catch (const Error& e) {
        tCollected->push_back(e);
        return false;
    }
}

// Range checks of every field of a struct on its own (params::checkField), keeping each
// error, so one bad value does not hide the next. `where` places an error at its line.
template <class Where>
class FieldChecker {
public:
    FieldChecker(std::string path, Where& where) : path_(std::move(path)), where_(where) {}

    template <class T>
    void field(const params::FieldInfo& f, const T& member) {
        try {
            params::checkField(f, path_, member);
        } catch (const Error& e) {
            ++found;
            keepOrThrow(where_(e));
        }
    }
    template <class G, class Fn>
    void group(const char* name, const G&, Fn&& visit) {
        FieldChecker sub(path_.empty() ? name : path_ + "." + name, where_);
        visit(sub);
        found += sub.found;
    }
    template <class E, class Fn>
    void list(const params::FieldInfo& f, const char*, const std::vector<E>& items, Fn&&) {
        field(f, items);
    }

    int found = 0;

private:
    std::string path_;
    Where& where_;
};

// An element that holds attributes only.
void checkNoChildren(const Element& e) {
    Children(e).finish();
}

// ---- the table visitor ------------------------------------------------------------------

// Reads a group element (shoot type, phenology, phytomer, leaf, ...) through `visit`, which
// runs describeParameters on the struct being filled with the visitor it is given.
template <class Visit>
void readGroup(const Element& e, Lines& lines, Names attributes, Visit&& visit);

// Each name the table declares at one level takes its value from the child of that name.
class FieldReader {
public:
    FieldReader(const Element& e, Lines& lines) : e_(e), children_(e), lines_(lines) {}

    template <class T>
    void field(const params::FieldInfo& f, T& member) {
        const xml_node n = children_.take(f.name);
        if (!n) return;
        const Element value(e_, n, f.name);
        lines_[value.path()] = value.line();
        attempt([&] { species_xml::readParameter(value, f, member, &lines_); });
    }

    template <class G, class Fn>
    void group(const char* name, G&, Fn&& visit) {
        const xml_node n = children_.take(name);
        if (!n) return;
        const Element sub(e_, n, name);
        lines_[sub.path()] = sub.line();
        readGroup(sub, lines_, {}, visit);
    }

    // A list of structs: <name><item>...</item>...</name>, replacing an inherited list whole.
    template <class E, class Fn>
    void list(const params::FieldInfo& f, const char* item, std::vector<E>& items, Fn&& visit) {
        const xml_node n = children_.take(f.name);
        if (!n) return;
        const Element holder(e_, n, f.name);
        lines_[holder.path()] = holder.line();
        holder.checkAttributes({});
        Children children(holder);
        children.allow(item, true);
        children.finish();
        items.clear();
        for (xml_node c : children.elements()) {
            const Element one(holder.document(), c,
                              holder.path() + "[" + std::to_string(items.size() + 1) + "]");
            lines_[one.path()] = one.line();
            E element{};
            readGroup(one, lines_, {}, [&](auto& v) { visit(element, v); });
            items.push_back(std::move(element));
        }
    }

    void finish() const {
        attempt([&] { children_.finish(); });
    }

private:
    const Element& e_;
    Children children_;
    Lines& lines_;
};

template <class Visit>
void readGroup(const Element& e, Lines& lines, Names attributes, Visit&& visit) {
    e.checkAttributes(attributes);
    FieldReader reader(e, lines);
    visit(reader);
    reader.finish();
}

// ---- the species file -------------------------------------------------------------------

// The top-level elements, each at most once but <shoot_type>.
const std::vector<std::string> kTopLevel = {"name",       "common_name", "latin_name",
                                            "plant_type", "description", "recommended_age",
                                            "max_height", "phenology",   "build_parameters",
                                            "shoot_type", "build",       "attraction_points",
                                            "trellis"};

struct TopLevel {
    std::map<std::string_view, xml_node> once;  // every name of kTopLevel but shoot_type
    std::vector<xml_node> shootTypes;

    // Null when absent.
    xml_node operator[](std::string_view name) const { return once.at(name); }
};

class SpeciesReader {
public:
    SpeciesReader(const xml::Document& doc, SpeciesModel& model) : doc_(doc), m_(model) {}

    void read(const Element& root) {
        root.checkAttributes({"format"});
        const std::string format = root.requiredAttribute("format");
        if (format != species_xml::kFormatVersion)
            root.failAt("format", "unsupported species file format", format,
                        species_xml::kFormatVersion);
        const TopLevel top = topLevel(root);

        // Each section on its own: when collecting, an error in one does not stop the next.
        attempt([&] { readNames(root, top); });
        if (top["phenology"]) attempt([&] { readPhenology(top["phenology"]); });
        if (top["build_parameters"]) attempt([&] { readBuildParameters(top["build_parameters"]); });
        bool typesRead = true;  // every shoot type defined: the checks that name them can run
        for (xml_node e : top.shootTypes)
            typesRead = attempt([&] { readShootType(e); }) && typesRead;
        if (m_.shootTypes.empty())
            root.failAt("shoot_type", "a species needs at least one <shoot_type>");
        if (!typesRead) return;
        attempt([&] { checkChildTypes(); });
        if (!top["build"]) root.failAt("build", "missing required element <build>");
        attempt([&] { readBuild(top["build"]); });
        if (top["attraction_points"]) attempt([&] { readAttraction(top["attraction_points"]); });
        if (top["trellis"]) attempt([&] { readTrellis(top["trellis"]); });
    }

private:
    static TopLevel topLevel(const Element& root) {
        Children c(root);
        TopLevel t;
        for (const std::string& name : kTopLevel) {
            if (name == "shoot_type")
                t.shootTypes = c.takeAll(name);
            else
                t.once[name] = c.take(name);
        }
        c.finish();
        return t;
    }

    // The text of a top-level value, its line recorded.
    std::string textOf(xml_node e, const std::string& path) {
        m_.lines[path] = doc_.line(e);
        return Element(doc_, e, path).text();
    }

    void readNames(const Element& root, const TopLevel& top) {
        if (!top["name"]) root.failAt("name", "missing required element <name>");
        m_.name = textOf(top["name"], "name");
        if (!text::isLabel(m_.name))
            doc_.fail(top["name"], "name", "a species name is letters, digits, '_' or '-'",
                      m_.name);
        using Text = std::pair<const char*, std::string SpeciesModel::*>;
        for (const auto& [name, member] : {Text{"common_name", &SpeciesModel::commonName},
                                           Text{"latin_name", &SpeciesModel::latinName},
                                           Text{"description", &SpeciesModel::description}})
            if (const xml_node e = top[name]) m_.*member = text::collapseSpaces(textOf(e, name));
        if (top["plant_type"]) {
            m_.plantType = textOf(top["plant_type"], "plant_type");
            const auto& types = species_xml::plantTypes();
            if (!contains(types, m_.plantType))
                doc_.fail(top["plant_type"], "plant_type",
                          text::unknownMessage("plant type", m_.plantType, types), m_.plantType,
                          text::oneOf(types));
        }
        if (top["recommended_age"]) readRecommendedAge(top["recommended_age"]);
        if (top["max_height"]) {
            const Element e(doc_, top["max_height"], "max_height");
            m_.lines[e.path()] = e.line();
            m_.maxHeight = e.parse(text::parseFloat);
            if (m_.maxHeight < 0.0f)
                e.fail("out of range", text::formatFloat(m_.maxHeight), ">= 0 m");
        }
    }

    void readRecommendedAge(xml_node node) {
        const Element e(doc_, node, "recommended_age");
        e.checkAttributes({"min", "max", "default"});
        checkNoChildren(e);
        m_.lines[e.path()] = e.line();
        m_.recommendedAgeMin = e.parseAttribute("min", text::parseFloat);
        m_.recommendedAgeMax = e.parseAttribute("max", text::parseFloat);
        m_.recommendedAge = e.parseAttribute("default", text::parseFloat);
        const std::string range = text::formatFloat(m_.recommendedAgeMin) + " to " +
                                  text::formatFloat(m_.recommendedAgeMax);
        if (m_.recommendedAgeMin < 0.0f || m_.recommendedAgeMax < m_.recommendedAgeMin)
            e.failAt("max", "recommended age range is empty or negative", range,
                     "0 <= min <= max days");
        if (m_.recommendedAge < m_.recommendedAgeMin || m_.recommendedAge > m_.recommendedAgeMax)
            e.failAt("default", "out of range", text::formatFloat(m_.recommendedAge),
                     range + " days");
    }

    void readPhenology(xml_node node) {
        const Element e(doc_, node, "phenology");
        m_.lines[e.path()] = e.line();
        readGroup(e, m_.lines, {}, [&](auto& v) { params::describeParameters(m_.phenology, v); });
        checkValues(m_.phenology, "phenology", e.line());
    }

    void readBuildParameters(xml_node node) {
        const Element list(doc_, node, "build_parameters");
        list.checkAttributes({});
        Children children(list);
        const std::vector<xml_node> parameters = children.takeAll("parameter");
        children.finish();
        for (xml_node p : parameters) {
            const Element item(doc_, p, list.path());
            item.checkAttributes({"name", "default", "min", "max", "unit", "doc"});
            checkNoChildren(item);
            BuildParameter bp;
            bp.name = item.requiredAttribute("name");
            const Element e(doc_, p, item.pathTo(bp.name));
            if (!isIdentifier(bp.name))
                e.fail(
                    "a build parameter name is a letter or '_' followed by letters, digits or "
                    "'_'",
                    bp.name);
            if (contains(expr::reservedNames(), bp.name) || bp.name == "i" || bp.name == "parent_i")
                e.fail("reserved name, choose another", bp.name);
            for (const BuildParameter& other : m_.buildParameters)
                if (other.name == bp.name)
                    e.fail("duplicate build parameter '" + bp.name + "' (first at line " +
                           std::to_string(m_.lines[e.path()]) + ")");
            bp.value = e.parseAttribute("default", text::parseFloat);
            bp.min = e.parseAttribute("min", text::parseFloat);
            bp.max = e.parseAttribute("max", text::parseFloat);
            bp.unit = e.attribute("unit");
            bp.doc = text::collapseSpaces(p.attribute("doc").value());
            if (bp.min > bp.max)
                e.failAt("min", "min exceeds max", text::formatFloat(bp.min),
                         "<= max (" + text::formatFloat(bp.max) + ")");
            if (bp.value < bp.min || bp.value > bp.max)
                e.failAt("default", "default out of range", text::formatFloat(bp.value),
                         rangeText({.min = bp.min, .max = bp.max, .single = true}));
            m_.lines[e.path()] = e.line();
            m_.buildParameters.push_back(bp);
        }
    }

    void readShootType(xml_node node) {
        const std::string label = Element(doc_, node, "shoot_type").requiredAttribute("label");
        if (!text::isLabel(label))
            doc_.fail(node, "shoot_type.label",
                      "a shoot type label is letters, digits, '_' or '-' (no spaces or dots)",
                      label);
        const Element e(doc_, node, label);
        if (m_.shootTypes.count(label))
            e.fail("duplicate shoot type '" + label + "' (first at line " +
                   std::to_string(m_.lines[label]) + ")");
        ShootParameters params;
        if (e.hasAttribute("inherits")) {
            const std::string from = e.attribute("inherits");
            auto it = m_.shootTypes.find(from);
            if (it == m_.shootTypes.end()) {
                const std::vector<std::string> known = shootTypeLabels();
                e.failAt("inherits",
                         text::unknownMessage("shoot type", from, known) +
                             " (a type can only inherit from one defined above it)",
                         from, text::oneOf(known));
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
        m_.lines[label] = e.line();
        readGroup(e, m_.lines, {"label", "inherits"},
                  [&](auto& v) { params::describeParameters(params, v); });
        checkValues(params, label, e.line());
        m_.shootTypes.emplace(label, std::move(params));
        order_.push_back(label);
    }

    // validate(), placed at the lines of the values; when collecting, every field out of range
    // first (each one line), then the checks across fields if the fields were in range.
    template <class P>
    void checkValues(const P& params, const std::string& path, int line) {
        auto where = [&](const Error& err) { return locate(err, doc_.file(), m_.lines, line); };
        if (tCollected) {
            FieldChecker checker(path, where);
            params::describeParameters(params, checker);
            if (checker.found > 0) return;
        }
        try {
            validate(params, path);
        } catch (const Error& err) {
            keepOrThrow(where(err));
        }
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
                    throw Error(text::unknownMessage("shoot type", child, labels),
                                {.file = doc_.file(),
                                 .line = m_.lines[path],
                                 .parameter = path,
                                 .value = child,
                                 .validRange = text::oneOf(labels)});
                }
    }

    void readBuild(xml_node node) {
        const Element build(doc_, node, "build");
        build.checkAttributes({});
        // Children keeps the names it allows as views: they must outlive it.
        const std::vector<std::string> kinds = species_xml::buildStepElements();
        Children children(build);
        for (const std::string& kind : kinds) children.allow(kind, true);
        children.finish();
        std::vector<std::string> names;
        for (const BuildParameter& p : m_.buildParameters) names.push_back(p.name);
        names.push_back("i");
        names.push_back("parent_i");
        std::vector<std::string> ids;
        int index = 0;
        for (xml_node e : children.elements()) m_.build.push_back(readStep(e, ++index, names, ids));
        if (m_.build.empty()) build.fail("<build> needs a <base_stem> step");
    }

    // An expression attribute (a vector of three when `vector`): checked against the build
    // parameters `names`, returned as written (white space collapsed); "" when absent.
    std::string expressionAttribute(const Element& e, const char* attribute, bool vector,
                                    bool required, const std::vector<std::string>& names) {
        if (!e.hasAttribute(attribute)) {
            if (required) e.requiredAttribute(attribute);
            return "";
        }
        const std::string value = text::collapseSpaces(e.node().attribute(attribute).value());
        const Element at(e, e.node(), attribute);
        const std::vector<std::string> parts =
            vector ? species_xml::splitVector(value) : std::vector<std::string>{value};
        if (parts.size() != 3 && vector)
            at.fail("expected three expressions x, y, z separated by commas", value,
                    "e.g. \"0, 0, wire_height\"");
        for (const std::string& part : parts)
            at.convert(part, [&](std::string_view p) {
                expr::check(std::string(p), names);
                return 0;
            });
        return value;
    }

    // <attraction_points half_angle look_ahead inertia shoot_types> with <wire from to
    // spacing/> and <point at/> children; numbers are expressions over the build parameters.
    void readAttraction(xml_node node) {
        const Element e(doc_, node, "attraction_points");
        e.checkAttributes({"half_angle", "look_ahead", "inertia", "shoot_types"});
        Children children(e);
        children.allow("wire", true);
        children.allow("point", true);
        children.finish();
        std::vector<std::string> names;
        for (const BuildParameter& p : m_.buildParameters) names.push_back(p.name);
        SpeciesAttraction a;
        a.line = e.line();
        m_.lines[e.path()] = a.line;
        a.halfAngle = expressionAttribute(e, "half_angle", false, false, names);
        a.lookAhead = expressionAttribute(e, "look_ahead", false, false, names);
        a.inertia = expressionAttribute(e, "inertia", false, false, names);
        if (e.hasAttribute("shoot_types")) {
            std::string list = e.attribute("shoot_types");
            std::replace(list.begin(), list.end(), ',', ' ');
            std::stringstream ss(list);
            const std::vector<std::string> labels = shootTypeLabels();
            for (std::string label; ss >> label;) {
                if (!m_.shootTypes.count(label))
                    e.failAt("shoot_types", text::unknownMessage("shoot type", label, labels),
                             label, text::oneOf(labels));
                a.shootTypes.push_back(label);
            }
        }
        int wires = 0, points = 0;
        for (xml_node c : children.elements()) {
            const bool wire = std::string_view(c.name()) == "wire";
            const int index = wire ? ++wires : ++points;
            const Element item(doc_, c, e.pathTo(c.name()) + "[" + std::to_string(index) + "]");
            if (wire) {
                item.checkAttributes({"from", "to", "spacing"});
                checkNoChildren(item);
                SpeciesAttraction::Wire w;
                w.line = item.line();
                w.from = expressionAttribute(item, "from", true, true, names);
                w.to = expressionAttribute(item, "to", true, true, names);
                w.spacing = expressionAttribute(item, "spacing", false, false, names);
                a.wires.push_back(w);
            } else {
                item.checkAttributes({"at"});
                checkNoChildren(item);
                SpeciesAttraction::Point p;
                p.line = item.line();
                p.at = expressionAttribute(item, "at", true, true, names);
                a.points.push_back(p);
            }
        }
        if (a.wires.empty() && a.points.empty())
            e.fail("<attraction_points> needs at least one <wire> or <point>");
        m_.attraction = std::move(a);
    }

    // <trellis> with <post at height radius/> and <wire from to radius/> children; numbers
    // are expressions over the build parameters.
    void readTrellis(xml_node node) {
        const Element e(doc_, node, "trellis");
        e.checkAttributes({});
        Children children(e);
        children.allow("post", true);
        children.allow("wire", true);
        children.finish();
        std::vector<std::string> names;
        for (const BuildParameter& p : m_.buildParameters) names.push_back(p.name);
        SpeciesTrellis t;
        t.line = e.line();
        m_.lines[e.path()] = t.line;
        int posts = 0, wires = 0;
        for (xml_node c : children.elements()) {
            const bool wire = std::string_view(c.name()) == "wire";
            const int index = wire ? ++wires : ++posts;
            const Element item(doc_, c, e.pathTo(c.name()) + "[" + std::to_string(index) + "]");
            checkNoChildren(item);
            if (wire) {
                item.checkAttributes({"from", "to", "radius"});
                SpeciesTrellis::Wire w;
                w.line = item.line();
                w.from = expressionAttribute(item, "from", true, true, names);
                w.to = expressionAttribute(item, "to", true, true, names);
                if (item.hasAttribute("radius"))
                    w.radius = expressionAttribute(item, "radius", false, false, names);
                t.wires.push_back(w);
            } else {
                item.checkAttributes({"at", "height", "radius"});
                SpeciesTrellis::Post p;
                p.line = item.line();
                item.requiredAttribute("at");
                p.at = text::collapseSpaces(item.node().attribute("at").value());
                const Element at(item, item.node(), "at");
                if (species_xml::splitVector(p.at).size() != 2)
                    at.fail("expected two expressions x, y separated by commas", p.at,
                            "e.g. \"0, -vine_spacing / 2\"");
                for (const std::string& part : species_xml::splitVector(p.at))
                    at.convert(part, [&](std::string_view q) {
                        expr::check(std::string(q), names);
                        return 0;
                    });
                p.height = expressionAttribute(item, "height", false, true, names);
                if (item.hasAttribute("radius"))
                    p.radius = expressionAttribute(item, "radius", false, false, names);
                t.posts.push_back(p);
            }
        }
        if (t.posts.empty() && t.wires.empty())
            e.fail("<trellis> needs at least one <post> or <wire>");
        m_.trellis = std::move(t);
    }

    BuildStep readStep(xml_node node, int index, const std::vector<std::string>& names,
                       std::vector<std::string>& ids) {
        const std::string kind = node.name();
        BuildStep step;
        step.kind = species_xml::buildStepKind(kind).value();  // <build> allowed only these
        step.line = doc_.line(node);
        const std::string id(text::trim(node.attribute("id").value()));
        const Element e(doc_, node,
                        "build." + (id.empty() ? kind + "[" + std::to_string(index) + "]" : id));
        const auto& attributes = species_xml::buildStepAttributes(step.kind);
        std::vector<std::string> attributeNames;
        for (const species_xml::StepAttribute& a : attributes) attributeNames.push_back(a.name);
        e.checkAttributes(attributeNames);
        checkNoChildren(e);
        if (step.kind == BuildStep::Kind::BaseStem && index != 1)
            e.fail("<base_stem> must be the first and only base stem step");
        if (step.kind != BuildStep::Kind::BaseStem && index == 1)
            e.fail("the first build step must be a <base_stem>");

        for (const species_xml::StepAttribute& attribute : attributes) {
            if (!e.hasAttribute(attribute.name)) continue;
            const std::string value = text::collapseSpaces(node.attribute(attribute.name).value());
            const Element at(e, node, attribute.name);
            switch (attribute.value) {
                case species_xml::StepValue::Flag:
                    step.*attribute.flag = at.convert(value, text::parseBool);
                    continue;
                case species_xml::StepValue::Name:
                    if (!text::isLabel(value))
                        at.fail("expected a name of letters, digits, '_' or '-'", value);
                    break;
                case species_xml::StepValue::Expression:
                    at.convert(value, [&](std::string_view v) {
                        expr::check(std::string(v), names);
                        return 0;
                    });
                    break;
            }
            step.*attribute.text = value;
        }

        step.shootType = e.requiredAttribute("type");
        const std::vector<std::string> labels = shootTypeLabels();
        if (!m_.shootTypes.count(step.shootType))
            e.failAt("type", text::unknownMessage("shoot type", step.shootType, labels),
                     step.shootType, text::oneOf(labels));
        if (step.kind != BuildStep::Kind::BaseStem) {
            e.requiredAttribute("parent");
            if (!contains(ids, step.parent))
                e.failAt("parent",
                         text::unknownMessage("parent step", step.parent, ids) +
                             " (the parent must be the id of an earlier step)",
                         step.parent, ids.empty() ? "no step ids defined above" : text::oneOf(ids));
        }
        if (step.kind == BuildStep::Kind::Child) e.requiredAttribute("node");
        if (!id.empty()) {
            if (contains(ids, id)) e.failAt("id", "duplicate step id '" + id + "'", id);
            ids.push_back(id);
        }
        m_.lines[e.path()] = step.line;
        return step;
    }

    const xml::Document& doc_;
    SpeciesModel& m_;
    std::vector<std::string> order_;  // shoot type labels in file order
};

}  // namespace

SpeciesModel readSpeciesString(const std::string& xml, const std::string& nameForErrors) {
    const xml::Document doc(xml, nameForErrors, {"species file", species_xml::kRoot});
    SpeciesModel model;
    model.sourceFile = nameForErrors;
    SpeciesReader(doc, model).read(Element(doc, doc.root(), ""));
    return model;
}

std::vector<Error> checkSpeciesString(const std::string& xml, const std::string& nameForErrors) {
    std::vector<Error> errors;
    struct Collecting {
        std::vector<Error>* before = tCollected;
        ~Collecting() { tCollected = before; }
    } collecting;
    tCollected = &errors;
    try {
        const xml::Document doc(xml, nameForErrors, {"species file", species_xml::kRoot});
        SpeciesModel model;
        model.sourceFile = nameForErrors;
        SpeciesReader(doc, model).read(Element(doc, doc.root(), ""));
    } catch (const Error& e) {  // an error after which nothing more can be read
        errors.push_back(e);
    }
    std::stable_sort(errors.begin(), errors.end(),
                     [](const Error& a, const Error& b) { return a.line() < b.line(); });
    return errors;
}

std::vector<Error> checkSpeciesFile(const std::string& path) {
    std::string text;
    try {
        text = io::readWholeFile(path, io::kSpeciesFile);
    } catch (const Error& e) {
        return {e};
    }
    return checkSpeciesString(text, path);
}

SpeciesModel readSpeciesFile(const std::string& path) {
    return readSpeciesString(io::readWholeFile(path, io::kSpeciesFile), path);
}

}  // namespace plantarch
