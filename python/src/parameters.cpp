// The species parameter structs as Python classes whose attributes come from the one
// parameter table (include/plantarch/ParameterTable.h): names, docs, units and valid ranges are
// read from it, and every assignment is checked against it at once, with the message a species file
// would get for the same value.

#include <cmath>
#include <string>
#include <type_traits>
#include <utility>

#include "bindings.h"
#include "plantarch/ParameterCheck.h"
#include "plantarch/ParameterInfo.h"
#include "plantarch/ParameterTable.h"

namespace plantarch::python {

namespace {

namespace pp = plantarch::params;

// The name a struct has in the table (and so in species files and error paths).
template <class S>
constexpr const char* tableName() {
    if constexpr (std::is_same_v<S, ShootParameters>) return "";
    if constexpr (std::is_same_v<S, PhytomerParameters>) return "phytomer";
    if constexpr (std::is_same_v<S, InternodeParameters>) return "internode";
    if constexpr (std::is_same_v<S, PetioleParameters>) return "petiole";
    if constexpr (std::is_same_v<S, LeafParameters>) return "leaf";
    if constexpr (std::is_same_v<S, LeafPrototype>) return "prototype";
    if constexpr (std::is_same_v<S, PeduncleParameters>) return "peduncle";
    if constexpr (std::is_same_v<S, InflorescenceParameters>) return "inflorescence";
    if constexpr (std::is_same_v<S, NodeRule>) return "rule";
    if constexpr (std::is_same_v<S, PhenologyParameters>) return "phenology";
    if constexpr (std::is_same_v<S, CarbohydrateParameters>) return "carbohydrates";
    if constexpr (std::is_same_v<S, NitrogenParameters>) return "nitrogen";
    if constexpr (std::is_same_v<S, LeafPhysiologyParameters>) return "leaf_physiology";
    if constexpr (std::is_same_v<S, MechanicsParameters>) return "mechanics";
    if constexpr (std::is_same_v<S, LeafAngleParameters>) return "leaf_angles";
    return "";
}

// The range for people, as `plantarch info` and the docs give it ("" without one).
std::string rangeOf(const pp::FieldInfo& f) {
    return f.min == 0 && f.max == 0 ? "" : rangeText(f.range());
}

[[noreturn]] void wrongType(const pp::FieldInfo& f, const std::string& path, py::handle value,
                            const std::string& expected) {
    throw Error("not " + expected, {.parameter = path.empty() ? f.name : path + "." + f.name,
                                    .value = shown(value),
                                    .validRange = rangeOf(f).empty() ? expected : rangeOf(f)});
}

// ---- values: C++ field -> Python ------------------------------------------------------

py::object toPython(const RandomFloat& v) {
    return v.isConstant() ? py::object(py::float_(v.a())) : py::cast(v);
}
py::object toPython(const RandomInt& v) {
    return v.isConstant() ? py::object(py::int_(v.min())) : py::cast(v);
}
py::object toPython(const float& v) {
    return py::float_(v);
}
py::object toPython(const unsigned& v) {
    return py::int_(v);
}
py::object toPython(const int& v) {
    return py::int_(v);
}
py::object toPython(const bool& v) {
    return py::bool_(v);
}
py::object toPython(const vec3& v) {
    return py::cast(v);
}
py::object toPython(const std::string& v) {
    return py::str(v);
}
template <pp::ChoiceType E>
py::object toPython(const E& v) {
    const char* name = pp::choiceName(v);
    return py::str(name ? name : "?");
}
py::object toPython(const std::map<int, std::string>& v) {
    return py::cast(v);
}
py::object toPython(const std::map<std::string, float>& v) {
    return py::cast(v);
}
py::object toPython(const Formula& v) {
    return py::str(v.text());
}
py::object toPython(const std::vector<NodeRule>& v) {
    py::list out;
    for (const NodeRule& r : v) out.append(py::cast(r));
    return out;
}

// ---- values: Python -> C++ field (type checks here; ranges by pp::checkField) --------------

void fromPython(py::handle v, RandomFloat& out, const pp::FieldInfo& f, const std::string& p) {
    if (py::isinstance<RandomFloat>(v)) {
        out = v.cast<RandomFloat>();
    } else if (py::isinstance<RandomInt>(v)) {
        const RandomInt r = v.cast<RandomInt>();
        if (r.kind() != RandomInt::Kind::Uniform && !r.isConstant())
            wrongType(f, p, v, "a number or a distribution of numbers");
        out = r.isConstant() ? RandomFloat::constant(float(r.min()))
                             : RandomFloat::uniform(float(r.min()), float(r.max()));
    } else if (isNumber(v)) {
        const double d = v.cast<double>();
        if (!std::isfinite(d))
            throw Error("not a finite number", {.parameter = p.empty() ? f.name : p + "." + f.name,
                                                .value = shown(v),
                                                .validRange = rangeOf(f)});
        out = RandomFloat::constant(float(d));
    } else {
        wrongType(f, p, v, "a number or a distribution (plantarch.uniform, normal, weibull)");
    }
}

void fromPython(py::handle v, RandomInt& out, const pp::FieldInfo& f, const std::string& p) {
    auto whole = [&](double d) {
        if (!std::isfinite(d) || d != std::floor(d) || std::abs(d) > 2e9)
            wrongType(f, p, v, "a whole number");
        return int(d);
    };
    if (py::isinstance<RandomInt>(v)) {
        out = v.cast<RandomInt>();
    } else if (py::isinstance<RandomFloat>(v)) {
        const RandomFloat r = v.cast<RandomFloat>();
        if (r.isConstant()) {
            out = RandomInt(whole(r.a()));
        } else if (r.kind() == RandomFloat::Kind::Uniform) {
            out = RandomInt::uniform(whole(r.a()), whole(r.b()));
        } else {
            wrongType(f, p, v, "a whole number, uniform(a, b) of whole numbers or discrete([...])");
        }
    } else if (isNumber(v)) {
        out = RandomInt(whole(v.cast<double>()));
    } else {
        wrongType(f, p, v, "a whole number, uniform(a, b) of whole numbers or discrete([...])");
    }
}

void fromPython(py::handle v, float& out, const pp::FieldInfo& f, const std::string& p) {
    if (!isNumber(v)) wrongType(f, p, v, "a number");
    out = float(v.cast<double>());
}

void fromPython(py::handle v, int& out, const pp::FieldInfo& f, const std::string& p) {
    if (!isNumber(v)) wrongType(f, p, v, "a whole number");
    const double d = v.cast<double>();
    if (!std::isfinite(d) || d != std::floor(d)) wrongType(f, p, v, "a whole number");
    if (d < f.min || d > f.max)
        throw Error("out of range", {.parameter = p.empty() ? f.name : p + "." + f.name,
                                     .value = shown(v),
                                     .validRange = rangeOf(f)});
    out = int(d);
}

void fromPython(py::handle v, unsigned& out, const pp::FieldInfo& f, const std::string& p) {
    int i = 0;
    fromPython(v, i, f, p);  // ranges of unsigned fields start at 0 or more
    out = unsigned(i);
}

void fromPython(py::handle v, bool& out, const pp::FieldInfo& f, const std::string& p) {
    if (!py::isinstance<py::bool_>(v)) wrongType(f, p, v, "True or False");
    out = v.cast<bool>();
}

void fromPython(py::handle v, vec3& out, const pp::FieldInfo& f, const std::string& p) {
    try {
        out = toVec3(v, f.name);
    } catch (const Error&) {
        wrongType(f, p, v, "three numbers");
    }
}

void fromPython(py::handle v, std::string& out, const pp::FieldInfo& f, const std::string& p) {
    if (!py::isinstance<py::str>(v)) wrongType(f, p, v, "a text");
    out = v.cast<std::string>();
}

template <pp::ChoiceType E>
void fromPython(py::handle v, E& out, const pp::FieldInfo& f, const std::string& p) {
    std::string valid;
    for (const std::string& name : pp::choiceNames<E>())
        valid += (valid.empty() ? "" : ", ") + name;
    if (py::isinstance<py::str>(v))
        if (auto e = pp::choiceNamed<E>(v.cast<std::string>())) {
            out = *e;
            return;
        }
    throw Error("not a declared value", {.parameter = p.empty() ? f.name : p + "." + f.name,
                                         .value = shown(v),
                                         .validRange = "one of: " + valid});
}

void fromPython(py::handle v, std::map<int, std::string>& out, const pp::FieldInfo& f,
                const std::string& p) {
    try {
        out = v.cast<std::map<int, std::string>>();
    } catch (const py::cast_error&) {
        wrongType(f, p, v, "a dict of whole numbers to texts");
    }
}

void fromPython(py::handle v, std::map<std::string, float>& out, const pp::FieldInfo& f,
                const std::string& p) {
    try {
        out = v.cast<std::map<std::string, float>>();
    } catch (const py::cast_error&) {
        wrongType(f, p, v, "a dict of names to numbers");
    }
}

void fromPython(py::handle v, Formula& out, const pp::FieldInfo& f, const std::string& p) {
    if (!py::isinstance<py::str>(v)) wrongType(f, p, v, "a formula text");
    try {
        out = NodeRule::formula(v.cast<std::string>());
    } catch (const Error& e) {
        throw e.withParameterPrefix(p.empty() ? f.name : p + "." + f.name);
    }
}

void fromPython(py::handle v, std::vector<NodeRule>& out, const pp::FieldInfo& f,
                const std::string& p) {
    if (!py::isinstance<py::sequence>(v) || py::isinstance<py::str>(v))
        wrongType(f, p, v, "a list of NodeRule");
    std::vector<NodeRule> rules;
    for (py::handle item : v) {
        if (!py::isinstance<NodeRule>(item)) wrongType(f, p, item, "a NodeRule");
        rules.push_back(item.cast<NodeRule>());
    }
    out = std::move(rules);
}

// ---- visiting one field of a struct by its position in the table ---------------------------

// Calls op(info, member) for the `target`-th direct field (or list) of the visited struct.
template <class Op>
struct FieldAt {
    int target;
    Op& op;
    int i = 0;
    template <class T>
    void field(const pp::FieldInfo& f, T& member) {
        if (i++ == target) op(f, member);
    }
    template <class G, class Fn>
    void group(const char*, G&, Fn&&) {}
    template <class E, class Fn>
    void list(const pp::FieldInfo& f, const char*, std::vector<E>& items, Fn&&) {
        if (i++ == target) op(f, items);
    }
};

// Finds the `target`-th direct group of the visited struct.
template <class G>
struct GroupAt {
    int target;
    G* found = nullptr;
    int i = 0;
    template <class T>
    void field(const pp::FieldInfo&, T&) {}
    template <class H, class Fn>
    void group(const char*, H& member, Fn&&) {
        if constexpr (std::is_same_v<H, G>)
            if (i == target) found = &member;
        ++i;
    }
    template <class E, class Fn>
    void list(const pp::FieldInfo&, const char*, std::vector<E>&, Fn&&) {}
};

template <class S, class Op>
void withField(S& s, int index, Op&& op) {
    FieldAt<std::remove_reference_t<Op>> visit{index, op};
    pp::describeParameters(s, visit);
}

template <class S, class G>
G& groupOf(S& s, int index) {
    GroupAt<G> visit{index};
    pp::describeParameters(s, visit);
    return *visit.found;
}

// The name a table group has as a Python attribute: the C++ member's name.
std::string attributeName(const char* group) {
    return std::string(group) == "phytomer" ? "phytomer_parameters" : group;
}

template <class T>
const char* kindText() {
    if constexpr (std::is_same_v<T, RandomFloat>) return "number or distribution";
    if constexpr (std::is_same_v<T, RandomInt>) return "whole number or distribution";
    if constexpr (std::is_same_v<T, float>) return "number";
    if constexpr (std::is_same_v<T, int> || std::is_same_v<T, unsigned>) return "whole number";
    if constexpr (std::is_same_v<T, bool>) return "True or False";
    if constexpr (std::is_same_v<T, vec3>) return "three numbers";
    if constexpr (std::is_same_v<T, std::string>) return "text";
    if constexpr (std::is_enum_v<T>) return "name";
    if constexpr (std::is_same_v<T, std::map<int, std::string>>) return "dict int -> text";
    if constexpr (std::is_same_v<T, std::map<std::string, float>>) return "dict name -> number";
    if constexpr (std::is_same_v<T, Formula>) return "formula text";
    return "list of NodeRule";
}

template <class T>
std::string fieldDoc(const pp::FieldInfo& f) {
    std::string doc = f.doc;
    doc += ".\n\nValue: ";
    doc += kindText<T>();
    if (*f.unit) doc += std::string(", in ") + f.unit;
    if (!rangeOf(f).empty()) doc += "; valid: " + rangeOf(f);
    if constexpr (pp::ChoiceType<T>) {
        doc += "; one of:";
        for (const auto& c : pp::kChoices<T>) doc += std::string("\n  ") + c.name + ": " + c.doc;
    }
    doc += ".";
    return doc;
}

// Adds one Python property per table entry of S.
template <class S>
struct Binder {
    py::class_<S>& cls;
    std::string& summary;  // the class docstring's list of fields
    int fieldIndex = 0;
    int groupIndex = 0;

    template <class T>
    void field(const pp::FieldInfo& f, T&) {
        const int index = fieldIndex++;
        cls.def_property(
            f.name,
            [index](S& s) {
                py::object out;
                withField(s, index,
                          [&](const pp::FieldInfo&, auto& member) { out = toPython(member); });
                return out;
            },
            [index](S& s, py::handle value) {
                withField(s, index, [&](const pp::FieldInfo& fi, auto& member) {
                    std::remove_reference_t<decltype(member)> v = member;
                    fromPython(value, v, fi, tableName<S>());
                    pp::checkField(fi, tableName<S>(), v);
                    member = std::move(v);
                });
            },
            fieldDoc<T>(f).c_str());
        summary += std::string("\n  ") + f.name +
                   (*f.unit ? std::string(" [") + f.unit + "]" : "") + ": " + f.doc;
    }
    template <class G, class Fn>
    void group(const char* name, G&, Fn&&) {
        const int index = groupIndex++;
        const std::string attr = attributeName(name);
        cls.def_property(
            attr.c_str(),
            py::cpp_function([index](S& s) -> G& { return groupOf<S, G>(s, index); },
                             py::return_value_policy::reference_internal),
            py::cpp_function([index](S& s, const G& g) { groupOf<S, G>(s, index) = g; }),
            (std::string("The ") + name + " parameters (a view: edits change this object).")
                .c_str());
        summary += "\n  " + attr + ": the " + name + " parameters";
    }
    template <class E, class Fn>
    void list(const pp::FieldInfo& f, const char*, std::vector<E>& items, Fn&&) {
        field(f, items);
    }
};

// Every field as {name: value} (groups nested as dicts).
template <class S>
py::dict toDict(S& s);

struct DictVisitor {
    py::dict& out;
    template <class T>
    void field(const pp::FieldInfo& f, T& member) {
        if constexpr (std::is_same_v<T, std::vector<NodeRule>>) {
            py::list rules;
            for (NodeRule& r : member) rules.append(toDict(r));
            out[f.name] = rules;
        } else {
            py::object v = toPython(member);
            if (py::isinstance<RandomFloat>(v) || py::isinstance<RandomInt>(v)) v = py::str(v);
            if constexpr (std::is_same_v<T, vec3>) v = py::tuple(v);
            out[f.name] = v;
        }
    }
    template <class G, class Fn>
    void group(const char* name, G& member, Fn&&) {
        out[attributeName(name).c_str()] = toDict(member);
    }
    template <class E, class Fn>
    void list(const pp::FieldInfo& f, const char*, std::vector<E>& items, Fn&&) {
        field(f, items);
    }
};

template <class S>
py::dict toDict(S& s) {
    py::dict out;
    DictVisitor v{out};
    pp::describeParameters(s, v);
    return out;
}

template <class S>
py::class_<S> bindStruct(py::module_& m, const char* name, const char* what) {
    py::class_<S> cls(m, name);
    std::string summary;
    S probe;
    Binder<S> binder{cls, summary};
    pp::describeParameters(probe, binder);
    cls.doc() =
        std::string(what) +
        "\n\nAttributes (from the parameter table; assignments are checked at once):" + summary;
    cls.def(py::init<>(), "Every field at its default.")
        .def(py::init<const S&>(), py::arg("other"), "A copy of `other`.")
        .def(
            "copy", [](const S& s) { return S(s); }, "A copy (edits to it leave this one alone).")
        .def("__copy__", [](const S& s) { return S(s); })
        .def(
            "__deepcopy__", [](const S& s, py::handle) { return S(s); }, py::arg("memo"))
        .def(
            "to_dict", [](S& s) { return toDict(s); },
            "Every field as a dict (distributions as their text, groups as nested dicts).")
        .def("__repr__", [name](S& s) {
            return std::string(name) + "(" + std::string(py::repr(toDict(s))) + ")";
        });
    return cls;
}

}  // namespace

void bindParameters(py::module_& m) {
    py::class_<RandomFloat>(
        m, "RandomFloat",
        "A number parameter: a constant or a distribution (uniform, normal, "
        "weibull). Made by plantarch.uniform(...), normal(...), weibull(...) or "
        "constant(...); a plain number may be given instead.")
        .def(py::init([](float v) { return RandomFloat::constant(v); }), py::arg("value"))
        .def_property_readonly(
            "kind",
            [](const RandomFloat& r) {
                switch (r.kind()) {
                    case RandomFloat::Kind::Constant:
                        return "constant";
                    case RandomFloat::Kind::Uniform:
                        return "uniform";
                    case RandomFloat::Kind::Normal:
                        return "normal";
                    case RandomFloat::Kind::Weibull:
                        return "weibull";
                }
                return "?";
            },
            "'constant', 'uniform', 'normal' or 'weibull'")
        .def_property_readonly("a", &RandomFloat::a, "The constant, minimum, mean or shape.")
        .def_property_readonly("b", &RandomFloat::b, "The maximum, standard deviation or scale.")
        .def("mean", &RandomFloat::mean, "The distribution's mean.")
        .def("lower_bound", &RandomFloat::lowerBound, "Smallest value a draw can take.")
        .def("upper_bound", &RandomFloat::upperBound, "Largest value a draw can take.")
        .def("describe", &RandomFloat::describe, "As a species file writes it: 'uniform(10, 30)'.")
        .def("__str__", &RandomFloat::describe)
        .def("__repr__", [](const RandomFloat& r) { return "plantarch." + r.describe(); })
        .def("__eq__", [](const RandomFloat& a, const RandomFloat& b) { return a == b; })
        .def("__eq__",
             [](const RandomFloat& a, double b) { return a.isConstant() && a.a() == float(b); })
        .def("__hash__", [](const RandomFloat& r) { return py::hash(py::str(r.describe())); });
    py::class_<RandomInt>(m, "RandomInt",
                          "A whole-number parameter: a constant, uniform(min, max) inclusive, or "
                          "discrete([values]).")
        .def(py::init<int>(), py::arg("value"))
        .def_property_readonly(
            "kind",
            [](const RandomInt& r) {
                switch (r.kind()) {
                    case RandomInt::Kind::Constant:
                        return "constant";
                    case RandomInt::Kind::Uniform:
                        return "uniform";
                    case RandomInt::Kind::Discrete:
                        return "discrete";
                }
                return "?";
            },
            "'constant', 'uniform' or 'discrete'")
        .def_property_readonly("min", &RandomInt::min, "Smallest value a draw can take.")
        .def_property_readonly("max", &RandomInt::max, "Largest value a draw can take.")
        .def_property_readonly("values", &RandomInt::values, "The values of discrete(...).")
        .def("mean", &RandomInt::mean, "The distribution's mean.")
        .def("describe", &RandomInt::describe, "As a species file writes it: 'uniform(1, 4)'.")
        .def("__str__", &RandomInt::describe)
        .def("__repr__", [](const RandomInt& r) { return "plantarch." + r.describe(); })
        .def("__eq__", [](const RandomInt& a, const RandomInt& b) { return a == b; })
        .def("__eq__", [](const RandomInt& a, double b) { return a.isConstant() && a.min() == b; })
        .def("__hash__", [](const RandomInt& r) { return py::hash(py::str(r.describe())); });

    m.def("constant", &RandomFloat::constant, py::arg("value"),
          "A constant number parameter (a plain number does the same).");
    m.def("uniform", &RandomFloat::uniform, py::arg("min"), py::arg("max"),
          "Uniform on [min, max]. Given to a whole-number parameter, whole bounds give a uniform "
          "whole number (both ends included).");
    m.def("normal", &RandomFloat::normal, py::arg("mean"), py::arg("stddev"),
          "Normal(mean, stddev); stddev >= 0.");
    m.def("weibull", &RandomFloat::weibull, py::arg("shape"), py::arg("scale"),
          "Weibull(shape k, scale lambda); both > 0.");
    m.def("discrete", &RandomInt::discrete, py::arg("values"),
          "One of `values` (whole numbers), each equally likely.");

    bindStruct<LeafPrototype>(m, "LeafPrototype", "How a leaf prototype is built.");
    bindStruct<InternodeParameters>(m, "InternodeParameters", "Internode parameters.");
    bindStruct<PetioleParameters>(m, "PetioleParameters", "Petiole parameters.");
    bindStruct<LeafParameters>(m, "LeafParameters", "Leaf parameters.");
    bindStruct<PeduncleParameters>(m, "PeduncleParameters", "Peduncle parameters.");
    bindStruct<InflorescenceParameters>(m, "InflorescenceParameters",
                                        "Inflorescence, flower and fruit parameters.");
    bindStruct<NodeRule>(m, "NodeRule",
                         "A node rule: conditions on a phytomer's place, rank, age and season, "
                         "and actions on its buds, leaves, sizes and angles.");
    bindStruct<PhytomerParameters>(m, "PhytomerParameters",
                                   "The phytomer template: internode, petiole, leaf, peduncle, "
                                   "inflorescence, rules.");
    bindStruct<ShootParameters>(m, "ShootParameters", "A shoot type's parameters.")
        .def("defineChildShootTypes", &ShootParameters::defineChildShootTypes, py::arg("labels"),
             py::arg("probabilities"),
             "Sets child_shoot_types from parallel lists (probabilities each in 0 to 1, summing "
             "to 1).")
        .def(
            "validate",
            [](const ShootParameters& s, const std::string& prefix) { validate(s, prefix); },
            py::arg("prefix") = "",
            "Checks every field and the fields against each other (raises plantarch.Error).");
    bindStruct<CarbohydrateParameters>(m, "CarbohydrateParameters",
                                       "A plant's carbohydrate budget (docs/physiology.md).");
    bindStruct<NitrogenParameters>(m, "NitrogenParameters",
                                   "A plant's nitrogen model (docs/physiology.md).");
    bindStruct<LeafPhysiologyParameters>(m, "LeafPhysiologyParameters",
                                         "Leaf photosynthesis capacities and optics.");
    bindStruct<MechanicsParameters>(
        m, "MechanicsParameters",
        "How a plant's shoots bend under load (docs/measured-plants.md).");
    bindStruct<LeafAngleParameters>(
        m, "LeafAngleParameters",
        "A plant's leaf inclination and azimuth distribution (docs/measured-plants.md).");
    bindStruct<PhenologyParameters>(m, "PhenologyParameters",
                                    "Timing of a plant's phenological stages, days.");

    // The library's one JSON form of the fields (parameterInfoJson), as Python values.
    auto infoList = [](const std::vector<ParameterInfo>& infos) {
        return py::list(py::module_::import("json").attr("loads")(parameterInfoJson(infos)));
    };
    m.def(
        "parameterInfo",
        [infoList](const ShootParameters& s) { return infoList(parameterInfo(s)); },
        py::arg("params"),
        "Every field of a shoot type as dicts, in file order: path, name, unit, doc, kind, min "
        "and max (None without a bound), range, choices, entry, probabilities, and value as a "
        "species file writes it (the builder's species endpoint gives the same objects).");
    m.def(
        "parameterInfo",
        [infoList](const PhenologyParameters& s) { return infoList(parameterInfo(s)); },
        py::arg("params"), "Every field of the phenology, as above.");
}

}  // namespace plantarch::python
