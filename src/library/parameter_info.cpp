// The parameter table as data (plantarch/ParameterInfo.h): a visitor of the declaration
// table that records each field with its value written as species files write it.

#include <cmath>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/value_text.h"
#include "plantarch/ParameterInfo.h"
#include "plantarch/ParameterTable.h"

namespace plantarch {

namespace {

class Collector {
public:
    Collector(std::vector<ParameterInfo>& out, std::string prefix)
        : out_(out), prefix_(std::move(prefix)) {}

    void field(const params::FieldInfo& f, const RandomFloat& v) {
        add(f, ParameterKind::RandomNumber, text::formatRandomFloat(v));
    }
    void field(const params::FieldInfo& f, const RandomInt& v) {
        add(f, ParameterKind::RandomWholeNumber, v.describe());
    }
    void field(const params::FieldInfo& f, const float& v) {
        add(f, ParameterKind::Number, text::formatFloat(v));
    }
    void field(const params::FieldInfo& f, const unsigned& v) {
        add(f, ParameterKind::WholeNumber, std::to_string(v));
    }
    void field(const params::FieldInfo& f, const int& v) {
        add(f, ParameterKind::WholeNumber, std::to_string(v));
    }
    void field(const params::FieldInfo& f, const bool& v) {
        add(f, ParameterKind::Flag, text::formatBool(v));
    }
    void field(const params::FieldInfo& f, const vec3& v) {
        add(f, ParameterKind::Triple, text::formatVec3(v));
    }
    void field(const params::FieldInfo& f, const std::string& v) { add(f, ParameterKind::Text, v); }
    template <params::ChoiceType E>
    void field(const params::FieldInfo& f, const E& v) {
        const char* name = params::choiceName(v);
        ParameterInfo& p = add(f, ParameterKind::Choice, name ? name : "");
        for (const params::Choice<E>& c : params::kChoices<E>) p.choices.push_back({c.name, c.doc});
    }
    void field(const params::FieldInfo& f, const std::map<int, std::string>& m) {
        std::string value;
        for (const auto& [key, text] : m)
            value += (value.empty() ? "" : ", ") + std::to_string(key) + ": " + text;
        add(f, ParameterKind::TextMap, value).entry = entry(f, "INDEX", "TEXT");
    }
    void field(const params::FieldInfo& f, const std::map<std::string, float>& m) {
        std::string value;
        for (const auto& [key, number] : m)
            value += (value.empty() ? "" : ", ") + key + " " + text::formatFloat(number);
        ParameterInfo& p = add(f, ParameterKind::NumberMap, value);
        p.entry = entry(f, "NAME", "NUMBER");
        p.probabilities = f.probabilities;
    }

    void field(const params::FieldInfo& f, const Formula& v) {
        add(f, ParameterKind::Formula, v.text());
    }

    template <class G, class Fn>
    void group(const char* name, const G&, Fn&& visit) {
        Collector sub(out_, prefix_ + name + ".");
        visit(sub);
    }

    // A list: one entry whose value sums up the elements (each one's fields that differ from
    // an element's defaults), then the fields of one element, at their defaults, under
    // "name.item." (what each element may set).
    template <class E, class Fn>
    void list(const params::FieldInfo& f, const char* item, const std::vector<E>& items,
              Fn&& visit) {
        const E blank{};
        std::vector<ParameterInfo> defaults;
        Collector fields(defaults, prefix_ + f.name + "." + item + ".");
        visit(blank, fields);
        std::string summary;
        for (const E& element : items) {
            std::vector<ParameterInfo> mine;
            Collector c(mine, "");
            visit(element, c);
            std::string one;
            for (std::size_t i = 0; i < mine.size(); ++i)
                if (mine[i].value != defaults[i].value)
                    one += (one.empty() ? "" : ", ") + mine[i].name + " " + mine[i].value;
            summary += (summary.empty() ? "" : "; ") + (one.empty() ? "(defaults)" : one);
        }
        add(f, ParameterKind::List, summary).entry =
            std::string("<") + item + ">...</" + item + ">";
        out_.insert(out_.end(), defaults.begin(), defaults.end());
    }

private:
    ParameterInfo& add(const params::FieldInfo& f, ParameterKind kind, std::string value) {
        ParameterInfo p;
        p.path = prefix_ + f.name;
        p.name = f.name;
        p.unit = f.unit;
        p.doc = f.doc;
        p.kind = kind;
        p.min = f.min;
        p.max = f.max;
        p.value = std::move(value);
        out_.push_back(std::move(p));
        return out_.back();
    }

    // `<element key="KEY" value="VALUE"/>` or `<element key="KEY">VALUE</element>`.
    static std::string entry(const params::FieldInfo& f, const char* key, const char* value) {
        const params::MapEntries& e = f.entries;
        std::string s = std::string("<") + e.element + " " + e.key + "=\"" + key + "\"";
        if (e.value) return s + " " + e.value + "=\"" + value + "\"/>";
        return s + ">" + value + "</" + e.element + ">";
    }

    std::vector<ParameterInfo>& out_;
    std::string prefix_;
};

template <class S>
std::vector<ParameterInfo> collect(const S& s) {
    std::vector<ParameterInfo> out;
    Collector c(out, "");
    params::describeParameters(s, c);
    return out;
}

}  // namespace

bool ParameterInfo::hasRange() const {
    switch (kind) {
        case ParameterKind::Number:
        case ParameterKind::RandomNumber:
        case ParameterKind::WholeNumber:
        case ParameterKind::RandomWholeNumber:
        case ParameterKind::Triple:
        case ParameterKind::NumberMap:
            return true;
        case ParameterKind::Flag:
        case ParameterKind::Text:
        case ParameterKind::Choice:
        case ParameterKind::TextMap:
        case ParameterKind::Formula:
        case ParameterKind::List:
            return false;
    }
    return false;
}

NumberRange ParameterInfo::range() const {
    const bool whole =
        kind == ParameterKind::WholeNumber || kind == ParameterKind::RandomWholeNumber;
    return {.min = min, .max = max, .whole = whole};
}

std::string ParameterInfo::rangeText() const {
    return hasRange() ? plantarch::rangeText(range()) : "";
}

std::vector<ParameterInfo> parameterInfo(const ShootParameters& shoot) {
    return collect(shoot);
}

std::vector<ParameterInfo> parameterInfo(const PhenologyParameters& phenology) {
    return collect(phenology);
}

std::string parameterInfoJson(const std::vector<ParameterInfo>& fields) {
    using json = nlohmann::ordered_json;
    const auto bound = [](const ParameterInfo& f, double v) {
        return f.hasRange() && std::isfinite(v) ? json(v) : json(nullptr);
    };
    json list = json::array();
    for (const ParameterInfo& f : fields) {
        json choices = json::array();
        for (const ParameterChoice& c : f.choices)
            choices.push_back({{"name", c.name}, {"doc", c.doc}});
        list.push_back({{"path", f.path},
                        {"name", f.name},
                        {"unit", f.unit},
                        {"doc", f.doc},
                        {"kind", parameterKindText(f.kind)},
                        {"min", bound(f, f.min)},
                        {"max", bound(f, f.max)},
                        {"range", f.rangeText()},
                        {"choices", std::move(choices)},
                        {"entry", f.entry},
                        {"probabilities", f.probabilities},
                        {"value", f.value}});
    }
    return list.dump();
}

const char* parameterKindText(ParameterKind kind) {
    switch (kind) {
        case ParameterKind::Number:
            return "number";
        case ParameterKind::RandomNumber:
            return "random number";
        case ParameterKind::WholeNumber:
            return "whole number";
        case ParameterKind::RandomWholeNumber:
            return "random whole number";
        case ParameterKind::Flag:
            return "true or false";
        case ParameterKind::Triple:
            return "three numbers";
        case ParameterKind::Text:
            return "text";
        case ParameterKind::Choice:
            return "one of the values";
        case ParameterKind::NumberMap:
            return "entries";
        case ParameterKind::TextMap:
            return "entries";
        case ParameterKind::Formula:
            return "formula";
        case ParameterKind::List:
            return "list";
    }
    return "";
}

}  // namespace plantarch
