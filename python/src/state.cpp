// The plant state (PlantState.h) as Python objects: what rule functions see and change, and
// what PlantArchitecture.plant() shows. Every attribute comes from the plant state table
// (plantarch/PlantStateTable.h): its name is the plant structure file's element, its help the
// table's meaning and range, and the traits the table marks editable take assignments held to
// their declared range, as a plant file's values are.

#include <algorithm>
#include <cmath>
#include <string>
#include <type_traits>

#include "bindings.h"
#include "callbacks.h"
#include "plantarch/PhytomerActions.h"
#include "plantarch/PlantArchitecture.h"
#include "plantarch/PlantState.h"
#include "plantarch/PlantStateTable.h"

namespace plantarch::python {

namespace {

// A rule's shoot: copied on first use (the copy outlives the call).
template <class View>
Shoot& shootOf(View& v) {
    const auto& live = v.context();  // raises after the call
    if (!v.shoot) v.shoot = live.shoot;
    return *v.shoot;
}

// The members of a state enum: its table's names and docs (plantarch/PlantState.h).
template <StateEnum E>
void nameEnum(py::enum_<E>& e) {
    for (const StateName<E>& n : kStateNames<E>) e.value(n.name, n.value, n.doc);
}

namespace st = plantarch::state;

// The attribute of a list: the plural of its element ("leaf" -> "leaves").
std::string plural(const std::string& element) {
    if (element.ends_with("leaf")) return element.substr(0, element.size() - 1) + "ves";
    return element + "s";
}

// ---- finding a member of a live object by its element name ---------------------------------

// Visits S's table and hands the member named `name` (a field, a nested struct, a list...) to
// `use`, which takes it by reference. A nested struct's own fields are not searched (its name
// is), so names never clash across structs.
template <class Use>
struct MemberNamed {
    const std::string& name;
    Use& use;
    bool found = false;
    void take(const char* element, auto& member) {
        if (!found && name == element) {
            found = true;
            use(member);
        }
    }
    template <class T>
    void field(const st::FieldInfo& f, T& member) {
        take(f.name, member);
    }
    template <class Fn>
    void group(const char*, Fn&& fn) {
        fn(*this);
    }
    template <class T, class More>
    void member(const char* element, T& m, More&& more) {
        take(element, m);
        more(*this);
    }
    template <class T>
    void list(const char* element, std::vector<T>& items, bool = false) {
        if (!found && name == plural(element)) {
            found = true;
            use(items);
        }
    }
    template <class T>
    void values(const st::FieldInfo& f, std::vector<T>& items) {
        take(f.name, items);
    }
    template <class T>
    void optional(const char* element, std::optional<T>& o) {
        take(element, o);
    }
    template <class P>
    void parameters(const char* element, P& p) {
        if constexpr (std::is_same_v<P, PhenologyParameters>)
            take(element, p);
        else if (!found && name == plural(element)) {
            found = true;
            use(p);
        }
    }
    void legacy(const char*) {}
    template <class T>
    void objects(const char* element, T& ids) {
        take(element, ids);
    }
};

template <class S, class Use>
void withMember(S& s, const std::string& name, Use&& use) {
    MemberNamed<std::remove_reference_t<Use>> finder{name, use};
    st::describeState(s, finder);
}

// ---- values ------------------------------------------------------------------------------

template <class T>
constexpr bool kShownInPython = !std::is_same_v<T, Rng>;  // the generator is the plant's own

[[noreturn]] void refuse(const st::FieldInfo& f, py::handle value, const std::string& why,
                         const std::string& valid) {
    throw Error(why, {.parameter = f.name, .value = shown(value), .validRange = valid});
}

double number(const st::FieldInfo& f, py::handle v, bool whole) {
    if (!isNumber(v))
        refuse(f, v, whole ? "not a whole number" : "not a number", rangeText(f.range()));
    const double d = v.cast<double>();
    if (whole && d != std::floor(d)) refuse(f, v, "not a whole number", rangeText(f.range()));
    if (!st::inside(f, d)) refuse(f, v, "out of range", rangeText(f.range()));
    return d;
}

// An assignment to an editable trait, checked as a plant file's value is.
template <class T>
void assign(const st::FieldInfo& f, py::handle v, T& out) {
    if constexpr (std::is_same_v<T, bool>) {
        if (!py::isinstance<py::bool_>(v)) refuse(f, v, "not True or False", "True or False");
        out = v.cast<bool>();
    } else if constexpr (std::is_same_v<T, float>) {
        const double d = number(f, v, false);
        if (!st::inside(f, double(float(d)))) refuse(f, v, "out of range", rangeText(f.range()));
        out = float(d);
    } else if constexpr (std::is_same_v<T, double>) {
        out = number(f, v, false);
    } else if constexpr (std::is_same_v<T, int> || std::is_same_v<T, unsigned>) {
        out = T(number(f, v, true));
    } else if constexpr (std::is_enum_v<T>) {
        if (!py::isinstance<T>(v)) {
            const std::string type = py::str(py::type::of<T>().attr("__name__"));
            std::string names;
            for (auto item : py::type::of<T>().attr("__members__"))
                names +=
                    (names.empty() ? "" : ", ") + type + "." + py::str(item).cast<std::string>();
            refuse(f, v, "not a " + type, "one of: " + names);
        }
        out = v.cast<T>();
    } else if constexpr (std::is_same_v<T, std::string>) {
        if (!py::isinstance<py::str>(v)) refuse(f, v, "not a text", "a shoot type label");
        std::string label = v.cast<std::string>();
        const bool empty = f.check == st::Check::LabelOrEmpty && label.empty();
        if (!empty) {
            bool ok = !label.empty();
            for (char c : label)
                ok = ok && (std::isalnum((unsigned char)c) || c == '_' || c == '-');
            if (!ok)
                refuse(f, v, "not a label",
                       std::string("letters, digits, '_' or '-'") +
                           (f.check == st::Check::LabelOrEmpty ? ", or empty" : ""));
        }
        out = std::move(label);
    } else {
        static_assert(std::is_same_v<T, float>, "an editable field of a type Python cannot set");
    }
}

std::string help(const st::FieldInfo& f, bool ranged) {
    std::string doc = f.doc[0] ? f.doc : f.name;
    if (ranged && !(f.min == 0 && f.max == 0)) doc += " (valid: " + rangeText(f.range()) + ")";
    doc += f.editable ? "; a phytomer function may set it" : "; read only";
    return doc;
}

// Binds S's attributes by visiting its table: one property per field, nested struct, list,
// optional part and parameter set, named as the plant file names them.
template <class S>
struct StateBinder {
    py::class_<S>& cls;

    // The member named `name` of a live object (the table gives its type M).
    template <class M>
    static M& memberOf(S& s, const std::string& name) {
        M* found = nullptr;
        withMember(s, name, [&](auto& m) {
            if constexpr (std::is_same_v<std::remove_reference_t<decltype(m)>, M>) found = &m;
        });
        return *found;  // the name comes from the same table: always found
    }

    // A read-only attribute: values as copies, structs and lists as views of the object.
    template <class M>
    void getter(const std::string& name, const std::string& doc) {
        cls.def_property_readonly(
            name.c_str(), [name](S& s) -> M& { return memberOf<M>(s, name); },
            py::return_value_policy::reference_internal, doc.c_str());
    }

    template <class T>
    void field(const st::FieldInfo& f, T&) {
        if constexpr (kShownInPython<T>) {
            const std::string name = f.name;
            const bool ranged = std::is_arithmetic_v<T> || std::is_same_v<T, vec3>;
            if constexpr (std::is_arithmetic_v<T> || std::is_enum_v<T> ||
                          std::is_same_v<T, std::string>) {
                if (f.editable) {
                    const st::FieldInfo info = f;
                    cls.def_property(
                        name.c_str(), [name](S& s) -> T { return memberOf<T>(s, name); },
                        [name, info](S& s, py::handle v) { assign(info, v, memberOf<T>(s, name)); },
                        help(f, ranged).c_str());
                    return;
                }
            }
            getter<T>(name, help(f, ranged));
        }
    }
    template <class Fn>
    void group(const char*, Fn&& fn) {
        fn(*this);
    }
    template <class T, class More>
    void member(const char* element, T&, More&& more) {
        getter<T>(element,
                  std::string("its ") + element + " (a view: changes reach this " + "object)");
        more(*this);
    }
    template <class T>
    void list(const char* element, std::vector<T>&, bool = false) {
        std::string what = plural(element);
        std::replace(what.begin(), what.end(), '_', ' ');
        getter<std::vector<T>>(plural(element), "its " + what +
                                                    " (views: changes reach this object; read only "
                                                    "as a list)");
    }
    template <class T>
    void values(const st::FieldInfo& f, std::vector<T>&) {
        getter<std::vector<T>>(f.name, help(f, true));
    }
    template <class T>
    void optional(const char* element, std::optional<T>&) {
        getter<std::optional<T>>(element, std::string("its ") + element + ", or None");
    }
    template <class P>
    void parameters(const char* element, P&) {
        if constexpr (std::is_same_v<P, PhenologyParameters>)
            getter<P>(element, "its phenological thresholds (PhenologyParameters)");
        else
            getter<P>(plural(element), "its own shoot types: label -> ShootParameters");
    }
    void legacy(const char*) {}
    template <class T>
    void objects(const char* element, T&) {
        if constexpr (std::is_same_v<T, ObjectID>)
            getter<T>(element, "its Context object ID (4294967295: none); read only");
        else
            getter<T>(element, "its Context object IDs; read only");
    }
};

template <class S>
py::class_<S> bindStateStruct(py::module_& m, const char* name, const char* doc) {
    py::class_<S> cls(m, name, doc);
    S prototype;  // only visited for its table
    StateBinder<S> binder{cls};
    st::describeState(prototype, binder);
    return cls;
}

}  // namespace

void bindState(py::module_& m) {
    py::enum_<BudState> bud(m, "BudState", "State of a vegetative or floral bud.");
    nameEnum(bud);
    py::enum_<FloralStage> stage(m, "FloralStage", "Stage of a floral bud.");
    nameEnum(stage);
    py::enum_<OrganKind> organ(m, "OrganKind", "Kind of organ (the 'organ' object data).");
    nameEnum(organ);
    py::enum_<PhenologyStage> pheno(m, "PhenologyStage", "Where a plant is in its yearly cycle.");
    nameEnum(pheno);

    bindStateStruct<VegetativeBud>(m, "VegetativeBud", "An axillary or apical vegetative bud.");
    bindStateStruct<FlowerOrgan>(m, "FlowerOrgan", "One flower or fruit on a peduncle.");
    bindStateStruct<FloralBud>(m, "FloralBud",
                               "A floral bud, its peduncle and the flowers or fruit it bears.");
    bindStateStruct<LeafOrgan>(m, "LeafOrgan", "A leaf (or leaflet) on a petiole.");
    bindStateStruct<LeafAngleTarget>(
        m, "LeafAngleTarget", "A leaf's pose drawn from its plant's leaf angle distribution.");
    bindStateStruct<Petiole>(m, "Petiole", "A petiole with its leaves and axillary buds.");
    bindStateStruct<Internode>(m, "Internode", "An internode.");
    bindStateStruct<InternodeBend>(m, "InternodeBend",
                                   "An internode's turn from its rest place under load.");
    bindStateStruct<MeasuredInternode>(m, "MeasuredInternode",
                                       "What was measured of an internode (its radius).");
    bindStateStruct<AttractionPoints>(m, "PlantAttractionPoints",
                                      "A plant's own attraction points and perception cone.");
    bindStateStruct<EpicormicShoots>(m, "EpicormicShoots", "A plant's water sprouts.");
    bindStateStruct<Phytomer>(
        m, "Phytomer",
        "A phytomer: internode, petioles with leaves and buds. Lists such as petioles hold "
        "views of the phytomer: in a rule, ctx.phytomer.petioles[0].vegetative_buds[0].state = "
        "BudState.dead changes the plant.")
        .def("killVegetativeBuds", &killVegetativeBuds,
             "Marks the dormant axillary vegetative buds dead (the remove_vegetative_buds "
             "rule): no branch grows from this node; an active or broken bud keeps growing.")
        .def("killFloralBuds", &killFloralBuds,
             "Marks the unopened floral buds dead and removed (the remove_floral_buds rule): "
             "no flowers from this node; open flowers and fruit stay.")
        .def("removeLeaves", &removeLeaves,
             "Removes the leaves, with their petioles' length and radius (the remove_leaves "
             "rule).")
        .def("scaleLeaves", &scaleLeaves, py::arg("factor"),
             "Multiplies the full-grown size of its leaves (the leaf_scale rule); raises "
             "plantarch.Error, changing nothing, if a leaf's size would leave its range.");
    // Not in the table: a shoot's ID is its place in the plant's list and its children are
    // derived from the parents (as on reading a plant file).
    bindStateStruct<Shoot>(m, "Shoot", "A shoot: a chain of phytomers.")
        .def_readonly("id", &Shoot::id, "shoot ID within the plant (its index in shoots)")
        .def_readonly("children", &Shoot::children, "IDs of the shoots growing from it");
    bindStateStruct<PlantInstance>(m, "PlantInstance",
                                   "A copy of a plant's whole state (read it; change the plant "
                                   "through PlantArchitecture's methods).")
        .def_readonly("id", &PlantInstance::id, "plant ID");

    py::class_<FloralPrototypeRequest>(m, "FloralPrototypeRequest",
                                       "What a flower or fruit prototype function is asked for.")
        .def_readonly("fruit", &FloralPrototypeRequest::fruit, "a fruit (else a flower)")
        .def_readonly("open", &FloralPrototypeRequest::open, "for flowers: open (else closed)")
        .def_readonly("parameters", &FloralPrototypeRequest::parameters,
                      "the species' shape parameters of the family")
        .def_readonly("color", &FloralPrototypeRequest::color, "main colour from the species")
        .def_readonly("subdivisions", &FloralPrototypeRequest::subdivisions, "mesh resolution");

    // Rules get views (callbacks.h): copies that stay valid, and accessors that raise once
    // the rule has returned.
    py::class_<CreationView>(
        m, "PhytomerCreationContext",
        "What a phytomer creation function sees: the new phytomer (change it: kill buds, scale "
        "organs) and where it stands. Valid only during the call: its attributes raise "
        "plantarch.Error after it.")
        .def_property_readonly(
            "phytomer",
            [](CreationView& v) -> Phytomer& {
                v.context();
                return v.phytomer;
            },
            py::return_value_policy::reference_internal,
            "the new phytomer (change it: kill buds, scale organs); a copy written back to the "
            "plant when the function returns")
        .def_property_readonly("shoot", &shootOf<CreationView>,
                               py::return_value_policy::reference_internal,
                               "a copy of the shoot it is on, as the call began (read it)")
        .def_property_readonly(
            "nodeIndex", [](const CreationView& v) { return v.context().nodeIndex; },
            "index of the new phytomer on its shoot")
        .def_property_readonly(
            "parentNodeIndex", [](const CreationView& v) { return v.context().parentNodeIndex; },
            "node of the parent shoot this shoot grows from (-1: none)")
        .def_property_readonly(
            "shootMaxNodes", [](const CreationView& v) { return v.context().shootMaxNodes; },
            "the shoot's realized max_nodes")
        .def_property_readonly(
            "plantAge", [](const CreationView& v) { return v.context().plantAge; }, "days")
        .def_property_readonly(
            "rank", [](const CreationView& v) { return v.context().shoot.rank; },
            "rank of its shoot (0: base stem)");
    py::class_<CallbackView>(
        m, "PhytomerCallbackContext",
        "What a phytomer callback sees, once per phytomer every whole day of plant age. Valid "
        "only during the call: its attributes raise plantarch.Error after it.")
        .def_property_readonly(
            "phytomer",
            [](CallbackView& v) -> Phytomer& {
                v.context();
                return v.phytomer;
            },
            py::return_value_policy::reference_internal,
            "the phytomer (change it); a copy written back to the plant when the function "
            "returns")
        .def_property_readonly("shoot", &shootOf<CallbackView>,
                               py::return_value_policy::reference_internal,
                               "a copy of the shoot it is on, as the call began (read it)")
        .def_property_readonly(
            "nodeIndex", [](const CallbackView& v) { return v.context().nodeIndex; },
            "index of the phytomer on its shoot")
        .def_property_readonly(
            "plantAge", [](const CallbackView& v) { return v.context().plantAge; }, "days")
        .def_property_readonly(
            "nodeBase", [](const CallbackView& v) { return v.context().nodeBase; },
            "world position of the base of its internode today, m");
}

}  // namespace plantarch::python
