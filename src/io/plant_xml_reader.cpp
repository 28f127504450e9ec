// Reader of plant structure files (docs/plant-xml.md).
//
// One engine reads both tables: the plant state table (io/plant_state_table.h) and the
// species parameter table (model/parameter_table.h). At each element it visits the table
// of the object being filled; every declared name takes its value from the child element of
// that name, every child must be declared (else "unknown element ..., did you mean ...") and
// appear once. State values are range checked as they are read; embedded shoot types and
// phenology are validated as species files are. A value not in the file is reported (one
// warning per plant) and completed afterwards (completePlant).

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstring>
#include <map>
#include <optional>
#include <pugixml.hpp>
#include <type_traits>

#include "io/plant_state_table.h"
#include "io/plant_structure.h"
#include "library/value_text.h"
#include "library/xml_source.h"
#include "plantarch/Error.h"

namespace plantarch::plant_io {

namespace {

using pugi::xml_node;

bool isElement(xml_node n) {
    return n.type() == pugi::node_element;
}
bool isText(xml_node n) {
    return n.type() == pugi::node_pcdata || n.type() == pugi::node_cdata;
}

std::string number(double v) {
    return text::formatDouble(v);
}

std::string rangeText(double lo, double hi) {
    return number(lo) + " to " + number(hi);
}

// ---- the document ------------------------------------------------------------------------

// The element a path such as "shoot[2].phytomer[0].internode.petiole[1]" names, starting at
// `from` (as far as the path can be followed), for locating errors found after reading.
xml_node resolve(xml_node from, const std::string& path) {
    xml_node at = from;
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
        xml_node next;
        for (xml_node c = at.child(part.c_str()); c; c = c.next_sibling(part.c_str())) {
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

// ---- value parsing -------------------------------------------------------------------

bool readDouble(std::string_view s, double& out) {
    if (s.size() > 1 && s[0] == '+' && s[1] != '-') s.remove_prefix(1);
    if (s.empty()) return false;
    const auto r = std::from_chars(s.data(), s.data() + s.size(), out);
    return r.ec == std::errc() && r.ptr == s.data() + s.size() && std::isfinite(out);
}

double parseDouble(std::string_view raw) {
    const std::string_view s = text::trim(raw);
    double v = 0.0;
    if (!readDouble(s, v))
        throw Error("expected a number",
                    {.value = std::string(s), .validRange = "a finite number"});
    return v;
}

std::uint64_t parseU64(std::string_view s) {
    std::uint64_t v = 0;
    const auto r = std::from_chars(s.data(), s.data() + s.size(), v);
    if (s.empty() || r.ec != std::errc() || r.ptr != s.data() + s.size())
        throw Error("expected two whole numbers (generator state and increment)",
                    {.value = std::string(s), .validRange = "two numbers from 0 to 2^64 - 1"});
    return v;
}

Rng parseRng(std::string_view raw) {
    const std::string_view s = text::trim(raw);
    const auto space = s.find_first_of(" \t\r\n");
    if (space == std::string_view::npos)
        throw Error("expected two whole numbers (generator state and increment)",
                    {.value = std::string(s), .validRange = "'state increment'"});
    return Rng::fromState(parseU64(s.substr(0, space)), parseU64(text::trim(s.substr(space))));
}

template <class Enum, class NameOf>
Enum parseEnum(std::string_view raw, int count, NameOf&& nameOf) {
    const std::string_view s = text::trim(raw);
    std::vector<std::string> names;
    for (int i = 0; i < count; ++i) {
        if (s == nameOf(Enum(i))) return Enum(i);
        names.emplace_back(nameOf(Enum(i)));
    }
    const std::string near = text::closestMatch(s, names);
    throw Error("unknown value" + (near.empty() ? std::string() : ", did you mean '" + near + "'?"),
                {.value = std::string(s), .validRange = "one of: " + text::joinNames(names)});
}

// The value of an enum-like parameter, by the names the parameter table declares.
template <params::ChoiceType E>
E parseChoice(std::string_view raw) {
    const std::string_view s = text::trim(raw);
    if (const auto value = params::choiceNamed<E>(s)) return *value;
    const std::vector<std::string> names = params::choiceNames<E>();
    const std::string near = text::closestMatch(s, names);
    throw Error("unknown value" + (near.empty() ? std::string() : ", did you mean '" + near + "'?"),
                {.value = std::string(s), .validRange = "one of: " + text::joinNames(names)});
}

// Labels: letters, digits, '_' and '-'.
bool isLabel(std::string_view s) {
    return !s.empty() && std::all_of(s.begin(), s.end(), [](char c) {
        return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-';
    });
}

// ---- the reader ------------------------------------------------------------------------

// State shared while one plant is read: where errors go, the element path (for messages)
// and what was missing.
struct PlantReader {
    const XmlSource& doc;
    Presence presence = Presence::recordingMissing();
    std::map<std::string, int> missingCounts;       // "shoot.phytomer.age" -> how many
    std::vector<std::pair<const char*, int>> path;  // element names (and list index, or -1)

    std::string pathTo(const char* leaf, bool indices = true) const {
        std::string out;
        for (const auto& [name, index] : path) {
            if (!out.empty()) out += '.';
            out += name;
            if (indices && index >= 0) out.append("[").append(std::to_string(index)).append("]");
        }
        if (leaf) {
            if (!out.empty()) out += '.';
            out += leaf;
        }
        return out;
    }

    void missing(const char* name, const void* member) {
        presence.note(member);
        // The report names the kind of value, without the plant_instance[k] prefix.
        std::string key;
        for (std::size_t i = 1; i < path.size(); ++i) {
            key += path[i].first;
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
    template <class Fn>
    void group(const char* name, Fn&& fn) {
        r.path.emplace_back(name, -1);
        fn(*this);
        r.path.pop_back();
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
    ElementReader(PlantReader& r, xml_node node, std::vector<const char*> attributes = {})
        : r_(r), node_(node) {
        for (xml_node c = node.first_child(); c; c = c.next_sibling()) {
            if (isElement(c)) {
                kids_.push_back({c, false});
            } else if (isText(c) && !text::trim(c.value()).empty()) {
                r_.doc.fail(
                    c, r_.pathTo(nullptr),
                    std::string("unexpected text inside <") + node.name() + ">, expected elements",
                    std::string(text::trim(c.value())).substr(0, 40));
            }
        }
        for (pugi::xml_attribute a = node.first_attribute(); a; a = a.next_attribute()) {
            const bool known =
                std::any_of(attributes.begin(), attributes.end(),
                            [&](const char* n) { return std::strcmp(n, a.name()) == 0; });
            if (!known)
                r_.doc.fail(
                    node, r_.pathTo(a.name()),
                    std::string("unknown attribute '") + a.name() + "' of <" + node.name() + ">",
                    a.value(),
                    attributes.empty() ? "no attributes" : "one of: " + joined(attributes));
        }
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
    template <class Info, class T>
    void fieldOf(const Info& f, T& member) {
        names_.push_back(f.name);
        Kid* k = take(f.name);
        if (!k) {
            r_.missing(f.name, &member);
            return;
        }
        readValue(f, k->node, member);
    }

    // An element of the listing that carries nothing plantarch keeps: a number, checked.
    void legacy(const char* name) {
        names_.push_back(name);
        if (Kid* k = take(name)) convert(k->node, name, valueOf(k->node, name), text::parseFloat);
    }

    // State table group: fn(visitor) visits the nested element's content.
    template <class Fn>
    void group(const char* name, Fn&& fn) {
        names_.push_back(name);
        Kid* k = take(name);
        if (!k) {  // every value inside is missing
            r_.path.emplace_back(name, -1);
            MissingVisitor absent{r_};
            fn(absent);
            r_.path.pop_back();
            return;
        }
        r_.path.emplace_back(name, -1);
        ElementReader sub(r_, k->node);
        fn(sub);
        sub.finish();
        r_.path.pop_back();
    }
    // Parameter table group.
    template <class G, class Fn>
    void group(const char* name, G& member, Fn&& fn) {
        names_.push_back(name);
        Kid* k = take(name);
        if (!k) {
            r_.missing(name, &member);
            return;
        }
        r_.path.emplace_back(name, -1);
        ElementReader sub(r_, k->node);
        fn(sub);
        sub.finish();
        r_.path.pop_back();
    }

    template <class T>
    void list(const char* name, std::vector<T>& items, bool ids = false) {
        names_.push_back(name);
        std::size_t count = 0;
        for (const Kid& k : kids_)
            if (std::strcmp(k.node.name(), name) == 0) ++count;
        items.resize(count);  // at most the elements present: bounded by the input
        std::size_t i = 0;
        for (Kid& k : kids_) {
            if (std::strcmp(k.node.name(), name) != 0) continue;
            k.used = true;
            r_.path.emplace_back(name, int(i));
            if (ids) checkID(k.node, i);
            ElementReader sub(r_, k.node,
                              ids ? std::vector<const char*>{"ID"} : std::vector<const char*>{});
            state::describeState(items[i], sub);
            sub.finish();
            r_.path.pop_back();
            ++i;
        }
    }

    // Parameter table list: <name><item>...</item>...</name>.
    template <class E, class Fn>
    void list(const params::FieldInfo& f, const char* item, std::vector<E>& items, Fn&& visit) {
        const char* name = f.name;
        names_.push_back(name);
        Kid* k = take(name);
        if (!k) {
            r_.missing(name, &items);
            return;
        }
        r_.path.emplace_back(name, -1);
        ElementReader holder(r_, k->node);
        std::size_t count = 0;
        for (const Kid& c : holder.kids_)
            if (std::strcmp(c.node.name(), item) == 0) ++count;
        items.assign(count, E{});  // at most the elements present: bounded by the input
        std::size_t i = 0;
        holder.names_.push_back(item);
        for (Kid& c : holder.kids_) {
            if (std::strcmp(c.node.name(), item) != 0) continue;
            c.used = true;
            r_.path.emplace_back(item, int(i));
            ElementReader sub(r_, c.node);
            visit(items[i], sub);
            sub.finish();
            r_.path.pop_back();
            ++i;
        }
        holder.finish();
        r_.path.pop_back();
    }

    // Every <name> child is one value of the list (none: an empty list).
    template <class T>
    void values(const state::FieldInfo& f, std::vector<T>& items) {
        names_.push_back(f.name);
        std::size_t count = 0;
        for (const Kid& k : kids_)
            if (std::strcmp(k.node.name(), f.name) == 0) ++count;
        items.assign(count, T{});  // at most the elements present: bounded by the input
        std::size_t i = 0;
        for (Kid& k : kids_) {
            if (std::strcmp(k.node.name(), f.name) != 0) continue;
            k.used = true;
            readValue(f, k.node, items[i++]);  // errors name the element's line
        }
    }

    // An optional element: absent, the member is none (and nothing is missing).
    template <class T>
    void optional(const char* name, std::optional<T>& member) {
        names_.push_back(name);
        Kid* k = take(name);
        if (!k) {
            member.reset();
            return;
        }
        member.emplace();
        r_.path.emplace_back(name, -1);
        ElementReader sub(r_, k->node);
        state::describeState(*member, sub);
        sub.finish();
        r_.path.pop_back();
    }

    void parameters(const char* name, PhenologyParameters& p) {
        names_.push_back(name);
        Kid* k = take(name);
        if (!k) {
            r_.missing(name, &p);
            return;
        }
        r_.path.emplace_back(name, -1);
        ElementReader sub(r_, k->node);
        params::describeParameters(p, sub);
        sub.finish();
        try {
            validate(p);
        } catch (const Error& e) {
            const std::string path = r_.pathTo(e.parameter().c_str());
            r_.path.pop_back();
            r_.doc.relocate(e, resolve(k->node, e.parameter()), path);
        }
        r_.path.pop_back();
    }

    void parameters(const char* name, std::map<std::string, ShootParameters>& types) {
        names_.push_back(name);
        bool any = false;
        for (Kid& k : kids_) {
            if (std::strcmp(k.node.name(), name) != 0) continue;
            k.used = true;
            any = true;
            const std::string label(text::trim(k.node.attribute("label").value()));
            const std::string here = r_.pathTo(name);
            if (!k.node.attribute("label"))
                r_.doc.fail(k.node, here + ".label",
                            std::string("missing required attribute 'label' of <") + name + ">");
            if (!isLabel(label))
                r_.doc.fail(k.node, here + ".label",
                            "a shoot type label is letters, digits, '_' or '-'", label);
            if (types.count(label))
                r_.doc.fail(k.node, here + ".label", "duplicate shoot type '" + label + "'", label);
            ShootParameters params;
            r_.path.emplace_back(name, -1);
            ElementReader sub(r_, k.node, {"label"});
            params::describeParameters(params, sub);
            sub.finish();
            r_.path.pop_back();
            try {
                validate(params);
            } catch (const Error& e) {
                r_.doc.relocate(e, resolve(k.node, e.parameter()),
                                here + "[" + label + "]." + e.parameter());
            }
            types.emplace(label, std::move(params));
        }
        if (!any) r_.missing(name, &types);
    }

    // Every child element must have been taken: else it is unknown or a duplicate.
    void finish() {
        for (const Kid& k : kids_) {
            if (k.used) continue;
            const std::string name = k.node.name();
            const std::string path = r_.pathTo(name.c_str());
            const bool declared =
                std::any_of(names_.begin(), names_.end(), [&](const char* n) { return name == n; });
            if (declared) {
                int first = 0;
                for (const Kid& o : kids_)
                    if (o.used && name == o.node.name()) {
                        first = r_.doc.line(o.node);
                        break;
                    }
                r_.doc.fail(k.node, path,
                            "duplicate element <" + name + "> (first at line " +
                                std::to_string(first) + ")");
            }
            std::vector<std::string> valid(names_.begin(), names_.end());
            const std::string near = text::closestMatch(name, valid);
            r_.doc.fail(k.node, path,
                        "unknown element <" + name + "> in <" + node_.name() + ">" +
                            (near.empty() ? "" : ", did you mean <" + near + ">?"),
                        "", "one of: " + text::joinNames(valid));
        }
    }

private:
    struct Kid {
        xml_node node;
        bool used;
    };

    static std::string joined(const std::vector<const char*>& names) {
        std::string out;
        for (const char* n : names) out += (out.empty() ? "" : ", ") + std::string(n);
        return out;
    }

    // The first unused child called `name`; children usually come in table order, so the
    // search starts after the last one taken.
    Kid* take(const char* name) {
        const std::size_t n = kids_.size();
        for (std::size_t j = 0; j < n; ++j) {
            Kid& k = kids_[(cursor_ + j) % n];
            if (!k.used && std::strcmp(k.node.name(), name) == 0) {
                k.used = true;
                cursor_ = (cursor_ + j + 1) % n;
                return &k;
            }
        }
        return nullptr;
    }

    void checkID(xml_node e, std::size_t index) {
        pugi::xml_attribute a = e.attribute("ID");
        if (!a) return;  // optional: the position gives the ID
        const std::string_view text = text::trim(a.value());
        unsigned id = 0;
        const auto r = std::from_chars(text.data(), text.data() + text.size(), id);
        if (text.empty() || r.ec != std::errc() || r.ptr != text.data() + text.size() ||
            id != index)
            r_.doc.fail(e, r_.pathTo("ID"),
                        std::string("<") + e.name() + "> IDs must count 0, 1, 2, ... in file order",
                        std::string(text), std::to_string(index));
    }

    // The text of an element that holds a value (no child elements), trimmed.
    std::string_view valueOf(xml_node e, const char* name) {
        if (e.first_attribute())
            r_.doc.fail(e, r_.pathTo(name) + "." + e.first_attribute().name(),
                        std::string("<") + e.name() + "> takes no attributes",
                        e.first_attribute().value());
        xml_node first = e.first_child();
        if (!first) return {};
        if (isText(first) && !first.next_sibling()) return text::trim(first.value());
        scratch_.clear();
        for (xml_node c = first; c; c = c.next_sibling()) {
            if (isText(c))
                scratch_ += c.value();
            else if (isElement(c))
                r_.doc.fail(c, r_.pathTo(name),
                            std::string("<") + e.name() + "> holds a value, not elements (found <" +
                                c.name() + ">)");
        }
        return text::trim(scratch_);
    }

    template <class Parse>
    std::invoke_result_t<Parse, std::string_view> convert(xml_node e, const char* name,
                                                          std::string_view value, Parse&& parse) {
        try {
            return parse(value);
        } catch (const Error& err) {
            r_.doc.relocate(err, e, r_.pathTo(name));
        }
    }

    template <class Parse>
    std::invoke_result_t<Parse, std::string_view> convert(xml_node e, const std::string& path,
                                                          std::string_view value, Parse&& parse) {
        try {
            return parse(value);
        } catch (const Error& err) {
            r_.doc.relocate(err, e, path);
        }
    }

    void checkRange(const state::FieldInfo& f, xml_node e, double v, std::string_view text) {
        const bool openMin =
            f.check == state::Check::ExclusiveMin || f.check == state::Check::Exclusive;
        const bool openMax = f.check == state::Check::Exclusive;
        const bool inside =
            (openMin ? v > f.min : v >= f.min) && (openMax ? v < f.max : v <= f.max);
        if (inside) return;
        const std::string range =
            !openMin ? rangeText(f.min, f.max)
                     : "> " + number(f.min) + " and " + (openMax ? "< " : "<= ") + number(f.max);
        r_.doc.fail(e, r_.pathTo(f.name), "out of range", std::string(text), range);
    }
    void checkRange(const params::FieldInfo&, xml_node, double, std::string_view) {
    }  // parameters: validate() afterwards

    template <class Info, class T>
    requires std::is_same_v<T, float> || std::is_same_v<T, double> || std::is_same_v<T, int> ||
        std::is_same_v<T, unsigned>
    void readValue(const Info& f, xml_node e, T& m) {
        const std::string_view s = valueOf(e, f.name);
        if constexpr (std::is_same_v<T, float>)
            m = convert(e, f.name, s, text::parseFloat);
        else if constexpr (std::is_same_v<T, double>)
            m = convert(e, f.name, s, parseDouble);
        else if constexpr (std::is_same_v<T, int>)
            m = convert(e, f.name, s, text::parseInt);
        else
            m = convert(e, f.name, s, text::parseUnsigned);
        checkRange(f, e, m, s);
    }
    template <class Info>
    void readValue(const Info& f, xml_node e, bool& m) {
        m = convert(e, f.name, valueOf(e, f.name), text::parseBool);
    }
    template <class Info>
    void readValue(const Info& f, xml_node e, vec3& m) {
        const std::string_view s = valueOf(e, f.name);
        m = convert(e, f.name, s, text::parseVec3);
        for (int i = 0; i < 3; ++i) checkRange(f, e, m[i], s);
        if constexpr (std::is_same_v<Info, state::FieldInfo>) {
            const double length =
                std::sqrt(double(m.x) * m.x + double(m.y) * m.y + double(m.z) * m.z);
            if (f.check == state::Check::UnitVector && std::abs(length - 1.0) > 1e-3)
                r_.doc.fail(e, r_.pathTo(f.name),
                            "not a unit vector (length " + number(length) + ")", std::string(s),
                            "a direction of length 1");
        }
    }
    void readValue(const state::FieldInfo& f, xml_node e, AxisRotation& m) {
        const std::string_view s = valueOf(e, f.name);
        const vec3 v = convert(e, f.name, s, text::parseVec3);
        for (int i = 0; i < 3; ++i) checkRange(f, e, v[i], s);
        m = {v.x, v.y, v.z};
    }
    void readValue(const params::FieldInfo& f, xml_node e, Formula& m) {
        const std::string_view s = valueOf(e, f.name);
        m = s.empty() ? Formula() : convert(e, f.name, s, NodeRule::formula);
    }
    template <class Info>
    void readValue(const Info& f, xml_node e, std::string& m) {
        m = std::string(valueOf(e, f.name));
        if constexpr (std::is_same_v<Info, state::FieldInfo>) {
            const bool optional = f.check == state::Check::LabelOrEmpty;
            if ((f.check == state::Check::Label || optional) && !(optional && m.empty()) &&
                !isLabel(m))
                r_.doc.fail(e, r_.pathTo(f.name),
                            "a shoot type label is letters, digits, '_' or '-'", m,
                            optional ? "a label, or nothing" : "a label");
        }
    }
    // Labels separated by white space.
    void readValue(const state::FieldInfo& f, xml_node e, std::vector<std::string>& m) {
        const std::string_view s = valueOf(e, f.name);
        m.clear();
        std::size_t at = 0;
        while (at < s.size()) {
            const std::size_t start = s.find_first_not_of(" \t\r\n", at);
            if (start == std::string_view::npos) break;
            std::size_t end = s.find_first_of(" \t\r\n", start);
            if (end == std::string_view::npos) end = s.size();
            const std::string label(s.substr(start, end - start));
            if (!isLabel(label))
                r_.doc.fail(e, r_.pathTo(f.name),
                            "a shoot type label is letters, digits, '_' or '-'", label,
                            "shoot type labels separated by spaces");
            m.push_back(label);
            at = end;
        }
    }
    void readValue(const state::FieldInfo& f, xml_node e, BudState& m) {
        m = convert(e, f.name, valueOf(e, f.name),
                    [](std::string_view s) { return parseEnum<BudState>(s, 4, budStateName); });
    }
    void readValue(const state::FieldInfo& f, xml_node e, FloralStage& m) {
        m = convert(e, f.name, valueOf(e, f.name), [](std::string_view s) {
            return parseEnum<FloralStage>(s, 5, floralStageName);
        });
    }
    void readValue(const state::FieldInfo& f, xml_node e, PhenologyStage& m) {
        m = convert(e, f.name, valueOf(e, f.name), [](std::string_view s) {
            return parseEnum<PhenologyStage>(s, 4, phenologyStageName);
        });
    }
    void readValue(const state::FieldInfo& f, xml_node e, Rng& m) {
        m = convert(e, f.name, valueOf(e, f.name), parseRng);
    }
    template <params::ChoiceType E>
    void readValue(const params::FieldInfo& f, xml_node e, E& m) {
        m = convert(e, f.name, valueOf(e, f.name), parseChoice<E>);
    }
    void readValue(const params::FieldInfo& f, xml_node e, RandomFloat& m) {
        m = convert(e, f.name, valueOf(e, f.name), text::parseRandomFloat);
    }
    void readValue(const params::FieldInfo& f, xml_node e, RandomInt& m) {
        m = convert(e, f.name, valueOf(e, f.name), text::parseRandomInt);
    }

    // Map parameters: one child element per entry, spelled as the table declares (f.entries).
    template <class Key, class Value, class ParseKey, class ParseValue>
    void readMap(const params::FieldInfo& f, xml_node e, std::map<Key, Value>& m,
                 ParseKey&& parseKey, ParseValue&& parseValue) {
        const std::string path = r_.pathTo(f.name);
        const params::MapEntries& spell = f.entries;
        if (e.first_attribute())
            r_.doc.fail(e, path + "." + e.first_attribute().name(),
                        std::string("<") + e.name() + "> takes no attributes");
        m.clear();
        for (xml_node c = e.first_child(); c; c = c.next_sibling()) {
            if (isText(c) && !text::trim(c.value()).empty())
                r_.doc.fail(c, path, std::string("unexpected text inside <") + f.name + ">",
                            std::string(text::trim(c.value())).substr(0, 40));
            if (!isElement(c)) continue;
            if (std::strcmp(c.name(), spell.element) != 0)
                r_.doc.fail(c, path + "." + c.name(),
                            std::string("unknown element <") + c.name() + "> in <" + f.name + ">",
                            "", std::string("<") + spell.element + ">");
            for (pugi::xml_attribute a = c.first_attribute(); a; a = a.next_attribute()) {
                const bool known = std::strcmp(a.name(), spell.key) == 0 ||
                                   (spell.value && std::strcmp(a.name(), spell.value) == 0);
                if (!known)
                    r_.doc.fail(c, path + "." + a.name(),
                                std::string("unknown attribute '") + a.name() + "'", a.value());
            }
            pugi::xml_attribute keyAttr = c.attribute(spell.key);
            if (!keyAttr)
                r_.doc.fail(c, path, std::string("missing required attribute '") + spell.key + "'");
            const std::string keyText(text::trim(keyAttr.value()));
            const std::string entry = path + "." + keyText;
            const Key key = convert(c, entry, keyText, parseKey);
            std::string_view valueText;
            if (spell.value) {
                pugi::xml_attribute v = c.attribute(spell.value);
                if (!v)
                    r_.doc.fail(c, entry,
                                std::string("missing required attribute '") + spell.value + "'");
                if (c.first_child())
                    r_.doc.fail(c, entry, std::string("<") + spell.element + "> takes no content");
                valueText = text::trim(v.value());
            } else {
                xml_node t = c.first_child();
                if (t && (!isText(t) || t.next_sibling()))
                    r_.doc.fail(c, entry, std::string("<") + spell.element + "> holds a value");
                valueText = t ? text::trim(t.value()) : std::string_view();
            }
            const Value value = convert(c, entry, valueText, parseValue);
            if (!m.emplace(key, value).second)
                r_.doc.fail(c, entry, "duplicate " + std::string(spell.key) + " '" + keyText + "'");
        }
    }
    void readValue(const params::FieldInfo& f, xml_node e, std::map<int, std::string>& m) {
        readMap(f, e, m, text::parseInt, [](std::string_view s) { return std::string(s); });
    }
    void readValue(const params::FieldInfo& f, xml_node e, std::map<std::string, float>& m) {
        auto key = [](std::string_view s) {
            if (!isLabel(s))
                throw Error("expected a name of letters, digits, '_' or '-'",
                            {.value = std::string(s), .validRange = "a non-empty name"});
            return std::string(s);
        };
        readMap(f, e, m, key, text::parseFloat);
    }

    PlantReader& r_;
    xml_node node_;
    std::vector<Kid> kids_;
    std::vector<const char*> names_;
    std::size_t cursor_ = 0;
    std::string scratch_;
};

std::string missingReport(const std::map<std::string, int>& counts) {
    std::string out;
    for (const auto& [path, n] : counts) {
        if (!out.empty()) out += ", ";
        out += path;
        if (n > 1) out += " (" + std::to_string(n) + ")";
    }
    return out;
}

xml_node rootOf(const pugi::xml_document& doc, const XmlSource& d) {
    xml_node root;
    for (xml_node n = doc.first_child(); n; n = n.next_sibling()) {
        if (isText(n) && !text::trim(n.value()).empty())
            d.fail(n, "", "text outside the root element",
                   std::string(text::trim(n.value())).substr(0, 40));
        if (!isElement(n)) continue;
        if (root)
            d.fail(n, "",
                   std::string("a second root element <") + n.name() + "> after <" + root.name() +
                       ">");
        root = n;
    }
    return root;
}

}  // namespace

ReadResult readPlantsXML(const std::string& xml, const std::string& fileName,
                         const Defaults& defaults) {
    XmlSource d(xml, fileName);
    if (text::trim(xml).empty())
        throw Error(std::string("empty file, expected a <") + kRoot + "> document",
                    {.file = fileName, .line = 1});
    pugi::xml_document doc;
    const pugi::xml_parse_result parsed =
        doc.load_buffer(xml.data(), xml.size(), pugi::parse_default, pugi::encoding_utf8);
    if (!parsed) {
        if (parsed.status == pugi::status_no_document_element)
            throw Error(std::string("not an XML file: no root element, expected <") + kRoot + ">",
                        {.file = fileName, .line = 1});
        std::string message = std::string("malformed XML: ") + parsed.description();
        const std::size_t end = xml.find_last_not_of(" \t\r\n");
        if (parsed.offset >= std::ptrdiff_t(end)) message += " (the file ends too early)";
        throw Error(message, {.file = fileName, .line = d.lineAt(parsed.offset)});
    }
    const xml_node root = rootOf(doc, d);
    const std::string rootName = root.name();
    const bool listing = rootName == kListingRoot;
    if (!listing && rootName != kRoot)
        d.fail(root, "", "not a plant structure file: root element <" + rootName + ">", "",
               std::string("<") + kRoot + ">");
    for (pugi::xml_attribute a = root.first_attribute(); a; a = a.next_attribute())
        if (listing || std::strcmp(a.name(), "format") != 0)
            d.fail(root, a.name(),
                   std::string("unknown attribute '") + a.name() + "' of <" + rootName + ">",
                   a.value(), listing ? "no attributes" : "format");
    if (!listing) {
        const pugi::xml_attribute format = root.attribute("format");
        if (!format)
            d.fail(root, "format",
                   std::string("missing required attribute 'format' of <") + kRoot + ">", "",
                   std::to_string(kFormatVersion));
        const std::string version(text::trim(format.value()));
        if (version != std::to_string(kFormatVersion)) {
            int v = 0;
            const auto r = std::from_chars(version.data(), version.data() + version.size(), v);
            const bool newer = r.ec == std::errc() && r.ptr == version.data() + version.size() &&
                               v > kFormatVersion;
            d.fail(root, "format",
                   newer ? "the file is of a newer format than this plantarch reads"
                         : "unknown format version",
                   version, std::to_string(kFormatVersion));
        }
    }

    ReadResult result;
    unsigned index = 0;
    for (xml_node e = root.first_child(); e; e = e.next_sibling()) {
        if (isText(e) && !text::trim(e.value()).empty())
            d.fail(e, "", "unexpected text inside <" + rootName + ">, expected <plant_instance>",
                   std::string(text::trim(e.value())).substr(0, 40));
        if (!isElement(e)) continue;
        if (std::strcmp(e.name(), "plant_instance") != 0) {
            const std::string near = text::closestMatch(e.name(), {"plant_instance"});
            d.fail(e, e.name(),
                   std::string("unknown element <") + e.name() + "> in <" + rootName + ">" +
                       (near.empty() ? "" : ", did you mean <plant_instance>?"),
                   "", "<plant_instance>");
        }
        const std::string where = "plant_instance[" + std::to_string(index) + "]";
        if (pugi::xml_attribute id = e.attribute("ID")) {
            try {
                text::parseUnsigned(id.value());
            } catch (const Error& err) {
                d.relocate(err, e, where + ".ID");
            }
        }
        PlantInstance plant;
        PlantReader reader{d};
        reader.path.emplace_back("plant_instance", int(index));
        ElementReader top(reader, e, {"ID"});
        state::describeState(plant, top);
        top.finish();
        std::vector<std::string> notes;
        try {
            if (!reader.presence.complete())
                completePlant(plant, reader.presence, defaults, defaults.firstPlantID + index,
                              notes, where);
            checkPlant(plant, where);
        } catch (const Error& err) {
            std::string rel = err.parameter();
            if (rel.compare(0, where.size() + 1, where + ".") == 0) rel.erase(0, where.size() + 1);
            d.relocate(err, resolve(e, rel), err.parameter());
        }
        if (!reader.missingCounts.empty()) {
            std::string w =
                fileName + ": plant_instance " + std::to_string(index) +
                ": values missing, defaults used: " + missingReport(reader.missingCounts);
            for (const std::string& n : notes) w += "; " + n;
            result.warnings.push_back(std::move(w));
        }
        result.plants.push_back(std::move(plant));
        ++index;
    }
    return result;
}

}  // namespace plantarch::plant_io
