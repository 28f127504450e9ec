// Writer of species files: every field of the declaration table, in table order, numbers in
// their shortest round-trip form, so what is written reads back to the same model.

#include <ostream>
#include <sstream>

#include "core/atomic_file.h"
#include "core/value_text.h"
#include "library/species_xml.h"
#include "plantarch/ParameterTable.h"
#include "plantarch/SpeciesIO.h"

namespace plantarch {

namespace {

// Text safe inside <!-- -->: no "--" and no trailing '-'.
std::string commentText(std::string s) {
    for (std::size_t i = 0; (i = s.find("--", i)) != std::string::npos;) s[i + 1] = ' ';
    while (!s.empty() && s.back() == '-') s.pop_back();
    return s;
}

// A field's range for its comment: none when it has no bound.
std::string rangeComment(const params::FieldInfo& f) {
    if (f.min == -params::kInf && f.max == params::kInf) return "";
    return rangeText(f.range());
}

class Writer {
public:
    Writer(std::ostream& out, bool comments) : out_(out), comments_(comments) {}

    void indent(int depth) {
        for (int i = 0; i < depth; ++i) out_ << "  ";
    }

    void comment(const std::string& text) {
        if (comments_ && !text.empty()) out_ << "  <!-- " << commentText(text) << " -->";
    }

    // <name>value</name>, or <name/> when the value is empty.
    void element(int depth, const std::string& name, const std::string& value,
                 const std::string& note = "") {
        indent(depth);
        if (value.empty())
            out_ << "<" << name << "/>";
        else
            out_ << "<" << name << ">" << text::xmlEscaped(value) << "</" << name << ">";
        comment(note);
        out_ << "\n";
    }

    void open(int depth, const std::string& tag, const std::string& note = "") {
        indent(depth);
        out_ << "<" << tag << ">";
        comment(note);
        out_ << "\n";
    }
    void close(int depth, const std::string& name) {
        indent(depth);
        out_ << "</" << name << ">\n";
    }

    std::ostream& out() { return out_; }

private:
    std::ostream& out_;
    bool comments_;
};

// Visitor of the declaration table writing one element per field.
class FieldWriter {
public:
    FieldWriter(Writer& w, int depth) : w_(w), depth_(depth) {}

    void field(const params::FieldInfo& f, const RandomFloat& v) {
        put(f, text::formatRandomFloat(v));
    }
    void field(const params::FieldInfo& f, const RandomInt& v) { put(f, v.describe()); }
    void field(const params::FieldInfo& f, const float& v) { put(f, text::formatFloat(v)); }
    void field(const params::FieldInfo& f, const unsigned& v) { put(f, std::to_string(v)); }
    void field(const params::FieldInfo& f, const int& v) { put(f, std::to_string(v)); }
    void field(const params::FieldInfo& f, const bool& v) { put(f, text::formatBool(v), false); }
    void field(const params::FieldInfo& f, const vec3& v) { put(f, text::formatVec3(v)); }
    void field(const params::FieldInfo& f, const std::string& v) {
        w_.element(depth_, f.name, v, f.doc);
    }
    template <params::ChoiceType E>
    void field(const params::FieldInfo& f, const E& v) {
        std::string names;
        for (const std::string& name : params::choiceNames<E>())
            names += (names.empty() ? "" : ", ") + name;
        w_.element(depth_, f.name, params::choiceName(v), join("one of: " + names, f.doc));
    }
    void field(const params::FieldInfo& f, const std::map<int, std::string>& m) {
        writeMap(
            f, m, [](int k) { return std::to_string(k); }, [](const std::string& v) { return v; });
    }
    void field(const params::FieldInfo& f, const std::map<std::string, float>& m) {
        writeMap(
            f, m, [](const std::string& k) { return k; },
            [](float v) { return text::formatFloat(v); });
    }

    void field(const params::FieldInfo& f, const Formula& v) {
        w_.element(depth_, f.name, v.text(), join(f.unit, f.doc));
    }
    template <class G, class Fn>
    void group(const char* name, const G&, Fn&& visit) {
        w_.open(depth_, name);
        FieldWriter sub(w_, depth_ + 1);
        visit(sub);
        w_.close(depth_, name);
    }
    template <class E, class Fn>
    void list(const params::FieldInfo& f, const char* item, const std::vector<E>& items,
              Fn&& visit) {
        const char* name = f.name;
        if (items.empty()) {
            w_.element(depth_, name, "", f.doc);
            return;
        }
        w_.open(depth_, name, f.doc);
        for (const E& element : items) {
            w_.open(depth_ + 1, item);
            FieldWriter sub(w_, depth_ + 2);
            visit(element, sub);
            w_.close(depth_ + 1, item);
        }
        w_.close(depth_, name);
    }

private:
    static std::string join(const std::string& a, const std::string& b) {
        if (a.empty()) return b;
        if (b.empty()) return a;
        return a + ". " + b;
    }

    void put(const params::FieldInfo& f, const std::string& value, bool withRange = true) {
        std::string note = f.unit;
        const std::string range = withRange ? rangeComment(f) : "";
        if (!range.empty()) note = note.empty() ? range : note + ", " + range;
        w_.element(depth_, f.name, value, join(note, f.doc));
    }

    template <class M, class KeyText, class ValueText>
    void writeMap(const params::FieldInfo& f, const M& m, KeyText&& keyText,
                  ValueText&& valueText) {
        const params::MapEntries& spell = f.entries;
        if (m.empty()) {
            w_.element(depth_, f.name, "", f.doc);
            return;
        }
        w_.open(depth_, f.name, f.doc);
        for (const auto& [key, value] : m) {
            w_.indent(depth_ + 1);
            auto& o = w_.out();
            o << "<" << spell.element << " " << spell.key << "=\"" << text::xmlEscaped(keyText(key))
              << "\"";
            if (spell.value)
                o << " " << spell.value << "=\"" << text::xmlEscaped(valueText(value)) << "\"/>\n";
            else
                o << ">" << text::xmlEscaped(valueText(value)) << "</" << spell.element << ">\n";
        }
        w_.close(depth_, f.name);
    }

    Writer& w_;
    int depth_;
};

void writeBuildParameters(Writer& w, const SpeciesModel& m) {
    if (m.buildParameters.empty()) {
        w.element(1, "build_parameters", "", "adjustable numbers of the initial structure");
        return;
    }
    w.open(1, "build_parameters");
    for (const BuildParameter& p : m.buildParameters) {
        w.indent(2);
        auto& o = w.out();
        o << "<parameter name=\"" << text::xmlEscaped(p.name) << "\" default=\""
          << text::formatFloat(p.value) << "\" min=\"" << text::formatFloat(p.min) << "\" max=\""
          << text::formatFloat(p.max) << "\"";
        if (!p.unit.empty()) o << " unit=\"" << text::xmlEscaped(p.unit) << "\"";
        if (!p.doc.empty()) o << " doc=\"" << text::xmlEscaped(p.doc) << "\"";
        o << "/>\n";
    }
    w.close(1, "build_parameters");
}

void writeBuild(Writer& w, const SpeciesModel& m) {
    w.open(1, "build", "initial structure; angles in degrees, lengths in m");
    for (const BuildStep& step : m.build) {
        const std::string kind = species_xml::buildStepElement(step.kind);
        w.indent(2);
        auto& o = w.out();
        o << "<" << kind;
        for (const species_xml::StepAttribute& a : species_xml::buildStepAttributes(step.kind)) {
            const std::string value = a.flag ? text::formatBool(step.*a.flag) : step.*a.text;
            // An empty id, radius or internode_length means "none" or "the type's value".
            if (value.empty()) continue;
            o << " " << a.name << "=\"" << text::xmlEscaped(value) << "\"";
        }
        o << "/>\n";
    }
    w.close(1, "build");
}

void writeAttraction(Writer& w, const SpeciesAttraction& a) {
    auto& o = w.out();
    w.indent(1);
    o << "<attraction_points half_angle=\"" << text::xmlEscaped(a.halfAngle) << "\" look_ahead=\""
      << text::xmlEscaped(a.lookAhead) << "\" inertia=\"" << text::xmlEscaped(a.inertia) << "\"";
    if (!a.shootTypes.empty()) {
        std::string list;
        for (const std::string& t : a.shootTypes) list += (list.empty() ? "" : " ") + t;
        o << " shoot_types=\"" << text::xmlEscaped(list) << "\"";
    }
    o << ">";
    w.comment("relative to the plant base; degrees, m");
    o << "\n";
    for (const SpeciesAttraction::Wire& wire : a.wires) {
        w.indent(2);
        o << "<wire from=\"" << text::xmlEscaped(wire.from) << "\" to=\""
          << text::xmlEscaped(wire.to) << "\" spacing=\"" << text::xmlEscaped(wire.spacing)
          << "\"/>\n";
    }
    for (const SpeciesAttraction::Point& p : a.points) {
        w.indent(2);
        o << "<point at=\"" << text::xmlEscaped(p.at) << "\"/>\n";
    }
    w.close(1, "attraction_points");
}

void writeTrellis(Writer& w, const SpeciesTrellis& t) {
    auto& o = w.out();
    w.indent(1);
    o << "<trellis>";
    w.comment("relative to the plant base; m");
    o << "\n";
    for (const SpeciesTrellis::Post& p : t.posts) {
        w.indent(2);
        o << "<post at=\"" << text::xmlEscaped(p.at) << "\" height=\"" << text::xmlEscaped(p.height)
          << "\" radius=\"" << text::xmlEscaped(p.radius) << "\"/>\n";
    }
    for (const SpeciesTrellis::Wire& wire : t.wires) {
        w.indent(2);
        o << "<wire from=\"" << text::xmlEscaped(wire.from) << "\" to=\""
          << text::xmlEscaped(wire.to) << "\" radius=\"" << text::xmlEscaped(wire.radius)
          << "\"/>\n";
    }
    w.close(1, "trellis");
}

}  // namespace

void writeSpecies(const SpeciesModel& m, std::ostream& out, const SpeciesWriteOptions& options) {
    Writer w(out, options.comments);
    out << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
    if (options.comments)
        out << "<!-- plantarch species file, format " << species_xml::kFormatVersion
            << " (docs/species-format.md). Units: m, degrees, days. -->\n";
    out << "<" << species_xml::kRoot << " format=\"" << species_xml::kFormatVersion << "\">\n";
    w.element(1, "name", m.name);
    w.element(1, "common_name", m.commonName);
    w.element(1, "latin_name", m.latinName);
    if (!m.plantType.empty()) w.element(1, "plant_type", m.plantType);
    w.element(1, "description", m.description);
    w.indent(1);
    out << "<recommended_age min=\"" << text::formatFloat(m.recommendedAgeMin) << "\" max=\""
        << text::formatFloat(m.recommendedAgeMax) << "\" default=\""
        << text::formatFloat(m.recommendedAge) << "\"/>";
    w.comment("days");
    out << "\n";
    w.element(1, "max_height", text::formatFloat(m.maxHeight),
              "m, plausible upper bound of the plant height (0: unchecked)");

    w.open(1, "phenology");
    FieldWriter phenology(w, 2);
    params::describeParameters(m.phenology, phenology);
    w.close(1, "phenology");

    writeBuildParameters(w, m);

    for (const auto& [label, params] : m.shootTypes) {
        w.indent(1);
        out << "<shoot_type label=\"" << text::xmlEscaped(label) << "\">\n";
        FieldWriter fields(w, 2);
        params::describeParameters(params, fields);
        w.close(1, "shoot_type");
    }

    writeBuild(w, m);
    if (m.attraction) writeAttraction(w, *m.attraction);
    if (m.trellis) writeTrellis(w, *m.trellis);
    out << "</" << species_xml::kRoot << ">\n";
}

std::string writeSpeciesString(const SpeciesModel& model, const SpeciesWriteOptions& options) {
    std::ostringstream out;
    writeSpecies(model, out, options);
    return out.str();
}

void writeSpeciesFile(const SpeciesModel& model, const std::string& path,
                      const SpeciesWriteOptions& options) {
    const std::string text = writeSpeciesString(model, options);
    io::AtomicFile file(path);
    file.write(text);
    file.commit();
}

}  // namespace plantarch
