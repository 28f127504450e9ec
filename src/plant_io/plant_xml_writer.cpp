// Writer of plant structure files: every field of the state table (plantarch/PlantStateTable.h)
// and of the parameter table, one element per value, numbers in their shortest round-trip
// form, so reading the text back gives the same plant bit for bit.

#include <charconv>
#include <optional>

#include "core/value_text.h"
#include "plant_io/plant_structure.h"
#include "plantarch/ParameterTable.h"
#include "plantarch/PlantStateTable.h"

namespace plantarch::plant_io {

namespace {

void appendNumber(std::string& out, float v) {
    char buf[48];
    // Shortest round-trip text (plain notation unless an exponent is much shorter).
    char fixed[64];
    const auto g = std::to_chars(buf, buf + sizeof buf, v);
    const auto f = std::to_chars(fixed, fixed + sizeof fixed, v, std::chars_format::fixed);
    if (f.ec == std::errc() && f.ptr - fixed <= g.ptr - buf + 2)
        out.append(fixed, f.ptr);
    else
        out.append(buf, g.ptr);
}

void appendNumber(std::string& out, double v) {
    out += text::formatDouble(v);
}

template <class Int>
void appendInteger(std::string& out, Int v) {
    char buf[24];
    const auto r = std::to_chars(buf, buf + sizeof buf, v);
    out.append(buf, r.ptr);
}

// Shared by the state and parameter visitors: elements at an indentation depth.
class XmlOut {
public:
    XmlOut(std::string& out, int depth) : out_(out), depth_(depth) {}

    void indent(int extra = 0) { out_.append(std::size_t(2 * (depth_ + extra)), ' '); }
    void open(const char* name) {
        indent();
        out_ += '<';
        out_ += name;
        out_ += ">\n";
    }
    void close(const char* name) {
        indent();
        out_ += "</";
        out_ += name;
        out_ += ">\n";
    }
    // <name>value</name> with the value appended by `put`, or <name/> when it adds nothing.
    template <class Put>
    void element(const char* name, Put&& put) {
        indent();
        out_ += '<';
        out_ += name;
        out_ += '>';
        const std::size_t start = out_.size();
        put(out_);
        if (out_.size() == start) {
            out_.back() = '/';
            out_ += ">\n";
            return;
        }
        out_ += "</";
        out_ += name;
        out_ += ">\n";
    }

    std::string& out() { return out_; }
    int depth() const { return depth_; }

private:
    std::string& out_;
    int depth_;
};

// Visitor of the parameter table (embedded species parameters), as species files spell them.
class ParameterWriter {
public:
    ParameterWriter(std::string& out, int depth) : x_(out, depth) {}

    void field(const params::FieldInfo& f, const RandomFloat& v) {
        put(f, text::formatRandomFloat(v));
    }
    void field(const params::FieldInfo& f, const RandomInt& v) { put(f, v.describe()); }
    void field(const params::FieldInfo& f, const float& v) {
        x_.element(f.name, [&](std::string& o) { appendNumber(o, v); });
    }
    void field(const params::FieldInfo& f, const unsigned& v) {
        x_.element(f.name, [&](std::string& o) { appendInteger(o, v); });
    }
    void field(const params::FieldInfo& f, const int& v) {
        x_.element(f.name, [&](std::string& o) { appendInteger(o, v); });
    }
    void field(const params::FieldInfo& f, const bool& v) { put(f, text::formatBool(v)); }
    void field(const params::FieldInfo& f, const vec3& v) { put(f, text::formatVec3(v)); }
    void field(const params::FieldInfo& f, const std::string& v) { put(f, v); }
    template <params::ChoiceType E>
    void field(const params::FieldInfo& f, const E& v) {
        put(f, params::choiceName(v));
    }
    void field(const params::FieldInfo& f, const std::map<int, std::string>& m) {
        writeMap(
            f, m, [](std::string& o, int k) { appendInteger(o, k); },
            [](std::string& o, const std::string& v) { text::appendXmlEscaped(o, v); });
    }
    void field(const params::FieldInfo& f, const std::map<std::string, float>& m) {
        writeMap(
            f, m, [](std::string& o, const std::string& k) { text::appendXmlEscaped(o, k); },
            [](std::string& o, float v) { appendNumber(o, v); });
    }
    void field(const params::FieldInfo& f, const Formula& v) { put(f, v.text()); }
    template <class G, class Fn>
    void group(const char* name, const G&, Fn&& visit) {
        x_.open(name);
        ParameterWriter sub(x_.out(), x_.depth() + 1);
        visit(sub);
        x_.close(name);
    }
    template <class E, class Fn>
    void list(const params::FieldInfo& f, const char* item, const std::vector<E>& items,
              Fn&& visit) {
        const char* name = f.name;
        if (items.empty()) {
            x_.element(name, [](std::string&) {});
            return;
        }
        x_.open(name);
        XmlOut inner(x_.out(), x_.depth() + 1);
        for (const E& element : items) {
            inner.open(item);
            ParameterWriter sub(x_.out(), x_.depth() + 2);
            visit(element, sub);
            inner.close(item);
        }
        x_.close(name);
    }

private:
    void put(const params::FieldInfo& f, const std::string& value) {
        x_.element(f.name, [&](std::string& o) { text::appendXmlEscaped(o, value); });
    }

    template <class M, class KeyText, class ValueText>
    void writeMap(const params::FieldInfo& f, const M& m, KeyText&& key, ValueText&& value) {
        const params::MapEntries& spell = f.entries;
        if (m.empty()) {
            x_.element(f.name, [](std::string&) {});
            return;
        }
        x_.open(f.name);
        std::string& o = x_.out();
        for (const auto& [k, v] : m) {
            x_.indent(1);
            o += '<';
            o += spell.element;
            o += ' ';
            o += spell.key;
            o += "=\"";
            key(o, k);
            o += '"';
            if (spell.value) {
                o += ' ';
                o += spell.value;
                o += "=\"";
                value(o, v);
                o += "\"/>\n";
            } else {
                o += '>';
                value(o, v);
                o += "</";
                o += spell.element;
                o += ">\n";
            }
        }
        x_.close(f.name);
    }

    XmlOut x_;
};

// Visitor of the state table.
class StateWriter {
public:
    StateWriter(std::string& out, int depth, bool objectIDs)
        : x_(out, depth), objectIDs_(objectIDs) {}

    void field(const state::FieldInfo& f, const float& v) {
        x_.element(f.name, [&](std::string& o) { appendNumber(o, v); });
    }
    void field(const state::FieldInfo& f, const double& v) {
        x_.element(f.name, [&](std::string& o) { appendNumber(o, v); });
    }
    void field(const state::FieldInfo& f, const int& v) {
        x_.element(f.name, [&](std::string& o) { appendInteger(o, v); });
    }
    void field(const state::FieldInfo& f, const unsigned& v) {
        x_.element(f.name, [&](std::string& o) { appendInteger(o, v); });
    }
    void field(const state::FieldInfo& f, const bool& v) {
        x_.element(f.name, [&](std::string& o) { o += v ? "true" : "false"; });
    }
    void field(const state::FieldInfo& f, const vec3& v) { triple(f.name, v.x, v.y, v.z); }
    void field(const state::FieldInfo& f, const AxisRotation& r) {
        triple(f.name, r.pitch, r.yaw, r.roll);
    }
    void field(const state::FieldInfo& f, const std::string& v) {
        x_.element(f.name, [&](std::string& o) { text::appendXmlEscaped(o, v); });
    }
    void field(const state::FieldInfo& f, const std::vector<std::string>& labels) {
        x_.element(f.name, [&](std::string& o) {
            for (std::size_t i = 0; i < labels.size(); ++i) {
                if (i) o += ' ';
                text::appendXmlEscaped(o, labels[i]);
            }
        });
    }
    template <StateEnum E>
    void field(const state::FieldInfo& f, const E& v) {
        word(f.name, stateName(v));
    }
    void field(const state::FieldInfo& f, const Rng& rng) {
        x_.element(f.name, [&](std::string& o) {
            appendInteger(o, rng.state());
            o += ' ';
            appendInteger(o, rng.increment());
        });
    }

    void legacy(const char*) {}

    void objects(const char* name, const ObjectID& id) {
        if (!objectIDs_ || id == kNoObject) return;
        x_.element(name, [&](std::string& o) { appendInteger(o, id); });
    }
    void objects(const char* name, const std::vector<ObjectID>& ids) {
        if (!objectIDs_ || ids.empty()) return;
        x_.element(name, [&](std::string& o) {
            for (std::size_t i = 0; i < ids.size(); ++i) {
                if (i) o += ' ';
                appendInteger(o, ids[i]);
            }
        });
    }

    void values(const state::FieldInfo& f, const std::vector<vec3>& items) {
        for (const vec3& v : items) triple(f.name, v.x, v.y, v.z);
    }

    template <class T>
    void optional(const char* name, const std::optional<T>& item) {
        if (!item) return;
        x_.open(name);
        StateWriter sub(x_.out(), x_.depth() + 1, objectIDs_);
        state::describeState(*item, sub);
        x_.close(name);
    }

    template <class Fn>
    void group(const char* name, Fn&& visit) {
        x_.open(name);
        StateWriter sub(x_.out(), x_.depth() + 1, objectIDs_);
        visit(sub);
        x_.close(name);
    }

    template <class T>
    void list(const char* name, const std::vector<T>& items, bool ids = false) {
        std::string& o = x_.out();
        for (std::size_t i = 0; i < items.size(); ++i) {
            x_.indent();
            o += '<';
            o += name;
            if (ids) {
                o += " ID=\"";
                appendInteger(o, i);
                o += '"';
            }
            o += ">\n";
            StateWriter sub(o, x_.depth() + 1, objectIDs_);
            state::describeState(items[i], sub);
            x_.close(name);
        }
    }

    void parameters(const char* name, const PhenologyParameters& p) {
        x_.open(name);
        ParameterWriter sub(x_.out(), x_.depth() + 1);
        params::describeParameters(p, sub);
        x_.close(name);
    }
    void parameters(const char* name, const std::map<std::string, ShootParameters>& types) {
        std::string& o = x_.out();
        for (const auto& [label, params] : types) {
            x_.indent();
            o += '<';
            o += name;
            o += " label=\"";
            text::appendXmlEscaped(o, label);
            o += "\">\n";
            ParameterWriter sub(o, x_.depth() + 1);
            params::describeParameters(params, sub);
            x_.close(name);
        }
    }

private:
    void word(const char* name, const char* value) {
        x_.element(name, [&](std::string& o) { o += value; });
    }
    void triple(const char* name, float a, float b, float c) {
        x_.element(name, [&](std::string& o) {
            appendNumber(o, a);
            o += ' ';
            appendNumber(o, b);
            o += ' ';
            appendNumber(o, c);
        });
    }

    XmlOut x_;
    bool objectIDs_;
};

}  // namespace

std::string writePlantsXML(const std::vector<const PlantInstance*>& plants, bool objectIDs,
                           const std::vector<std::vector<unsigned>>* materialIDs) {
    std::string out;
    out.reserve(std::size_t(1) << 16);
    out += "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
    out +=
        "<!-- plantarch plant structure file (docs/plant-xml.md). Units: m, degrees, days. -->\n";
    out += "<";
    out += kRoot;
    out.append(" format=\"").append(std::to_string(kFormatVersion)).append("\">\n");
    for (std::size_t k = 0; k < plants.size(); ++k) {
        const PlantInstance* p = plants[k];
        out += "  <plant_instance ID=\"";
        appendInteger(out, p->id);
        out += "\">\n";
        StateWriter w(out, 2, objectIDs);
        state::describeState(*p, w);
        if (objectIDs && materialIDs && k < materialIDs->size() && !(*materialIDs)[k].empty()) {
            out += "    <material_IDs>";
            for (std::size_t i = 0; i < (*materialIDs)[k].size(); ++i) {
                if (i) out += ' ';
                appendInteger(out, (*materialIDs)[k][i]);
            }
            out += "</material_IDs>\n";
        }
        out += "  </plant_instance>\n";
    }
    out += "</";
    out += kRoot;
    out += ">\n";
    return out;
}

}  // namespace plantarch::plant_io
