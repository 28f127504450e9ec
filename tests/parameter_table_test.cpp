// The parameter declaration table against the parameter structs: every member of every
// parameter struct (and of each nested struct) is declared exactly once, with a sound
// declaration; the generated docs page and `plantarch info` follow the table.

#include <gtest/gtest.h>

#include <cmath>
#include <cstddef>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "cli_run.h"
#include "plantarch/Error.h"
#include "plantarch/ParameterInfo.h"
#include "plantarch/ParameterTable.h"
#include "plantarch/SpeciesIO.h"

using namespace plantarch;

namespace {

// ---- members of an aggregate, counted at compile time -------------------------------------

// Converts to any member type, so T{AnyMember{}, ...} compiles for up to as many
// initializers as T has members (each initializes one member; none is elided into a nested
// struct, which AnyMember converts to directly).
struct AnyMember {
    template <class T>
    operator T() const;  // only named in unevaluated requires-expressions
};

template <class T, std::size_t... I>
constexpr bool initializableFrom(std::index_sequence<I...>) {
    return requires {
        T{(void(I), AnyMember{})...};
    };
}

template <class T, std::size_t N = 0>
constexpr std::size_t memberCount() {
    static_assert(std::is_aggregate_v<T>, "a parameter struct is an aggregate");
    if constexpr (initializableFrom<T>(std::make_index_sequence<N + 1>{}))
        return memberCount<T, N + 1>();
    else
        return N;
}

static_assert(memberCount<PhenologyParameters>() == 14);  // the counter itself works

// ---- the check: one level of the table against its struct, then each nested group ---------

// Records what describeParameters declares at one level: how many entries, at which member
// addresses, under which names; nested groups are checked in turn.
template <class S>
struct LevelCheck {
    const S& object;
    std::string path;
    std::vector<std::string>& problems;
    std::size_t declared = 0;
    std::set<const void*> addresses;
    std::set<std::string> names;

    void record(const char* name, const void* member, std::size_t size) {
        ++declared;
        const auto* base = reinterpret_cast<const char*>(&object);
        const auto* at = static_cast<const char*>(member);
        if (at < base || at + size > base + sizeof(S))
            problems.push_back(path + name + ": not a member of this struct");
        if (!addresses.insert(member).second)
            problems.push_back(path + name + ": a member declared twice");
        if (!names.insert(name).second) problems.push_back(path + name + ": a name used twice");
    }

    template <class T>
    void field(const params::FieldInfo& f, const T& member) {
        record(f.name, &member, sizeof(T));
        const std::string where = path + f.name;
        if (!f.doc || !*f.doc) problems.push_back(where + ": no description");
        if (!f.unit) problems.push_back(where + ": no unit (\"\" when dimensionless)");
        if (!(f.min <= f.max)) problems.push_back(where + ": min > max");
        if constexpr (requires { typename T::key_type; })
            if (!f.entries.element || !f.entries.key)
                problems.push_back(where + ": a map without its entry spelling");
        if constexpr (params::ChoiceType<T>) {
            std::set<std::string> choiceNames;
            for (const auto& c : params::kChoices<T>)
                if (!choiceNames.insert(c.name).second || !c.doc || !*c.doc)
                    problems.push_back(where + ": choice '" + c.name +
                                       "' repeated or undocumented");
        }
        if constexpr (std::is_enum_v<T> && !params::ChoiceType<T>)
            problems.push_back(where + ": an enum field without a Choice list");
    }

    template <class G, class Fn>
    void group(const char* name, const G& member, Fn&& visit) {
        record(name, &member, sizeof(G));
        checkLevel(member, path + name + ".", problems, visit);
    }

    // A list of structs: the list is one member here, and its element struct is checked
    // as a level of its own.
    template <class E, class Fn>
    void list(const params::FieldInfo& f, const char* item, const std::vector<E>& member,
              Fn&& visit) {
        record(f.name, &member, sizeof(member));
        if (!f.doc || !*f.doc) problems.push_back(path + f.name + ": no description");
        const E element{};
        checkLevel(element, path + f.name + "." + item + ".", problems,
                   [&](auto& v) { visit(element, v); });
    }

    template <class G, class Visit>
    static void checkLevel(const G& object, const std::string& path,
                           std::vector<std::string>& problems, Visit&& visit) {
        LevelCheck<G> level{object, path, problems};
        visit(level);
        if (level.declared != memberCount<G>())
            problems.push_back((path.empty() ? std::string("top level") : path) + ": " +
                               std::to_string(memberCount<G>()) + " members, " +
                               std::to_string(level.declared) + " declared in the table");
    }
};

// Problems of the table for struct S, from its top level down.
template <class S>
std::vector<std::string> tableProblems(const S& object) {
    std::vector<std::string> problems;
    LevelCheck<S>::checkLevel(object, "", problems,
                              [&](auto& v) { params::describeParameters(object, v); });
    return problems;
}

std::string joined(const std::vector<std::string>& lines) {
    std::string s;
    for (const std::string& l : lines) s += l + "\n";
    return s;
}

}  // namespace

TEST(ParameterTable, EveryMemberIsDeclared) {
    // Shoot types reach the phytomer and all its parts (internode, petiole, leaf with its
    // prototype, peduncle, inflorescence) through their groups; phenology is a root of its own.
    EXPECT_EQ(joined(tableProblems(ShootParameters{})), "");
    EXPECT_EQ(joined(tableProblems(PhenologyParameters{})), "");
    EXPECT_EQ(joined(tableProblems(PhytomerParameters{})), "");
}

// A struct standing for a parameter struct with a member added but not declared: the check
// must report it (and a declaration pointing outside the struct).
namespace {
struct Grown {
    RandomFloat pitch = 1.0f;
    RandomFloat added = 2.0f;
    unsigned count = 3;
};
}  // namespace

TEST(ParameterTable, CheckReportsAnUndeclaredMember) {
    static_assert(memberCount<Grown>() == 3);
    const Grown g;
    std::vector<std::string> problems;
    LevelCheck<Grown>::checkLevel(g, "grown.", problems, [&](auto& v) {
        v.field({"pitch", "degrees", -180, 180, "Pitch"}, g.pitch);
        v.field({"count", "", 0, 10, "Count"}, g.count);
    });
    ASSERT_EQ(problems.size(), 1u) << joined(problems);
    EXPECT_EQ(problems[0], "grown.: 3 members, 2 declared in the table");

    problems.clear();
    const Grown other;
    LevelCheck<Grown>::checkLevel(g, "grown.", problems, [&](auto& v) {
        v.field({"pitch", "degrees", -180, 180, "Pitch"}, g.pitch);
        v.field({"pitch", "degrees", -180, 180, "Pitch"}, g.pitch);
        v.field({"count", "", 0, 10, "Count"}, other.count);
    });
    EXPECT_NE(joined(problems).find("grown.pitch: a member declared twice"), std::string::npos);
    EXPECT_NE(joined(problems).find("grown.count: not a member of this struct"), std::string::npos);
}

TEST(ParameterTable, DefaultsAreValid) {
    EXPECT_NO_THROW(validate(ShootParameters{}));
    EXPECT_NO_THROW(validate(PhenologyParameters{}));
}

TEST(ParameterTable, ChoiceNamesRoundTrip) {
    for (const auto& c : params::kChoices<LeafShape>) {
        EXPECT_STREQ(params::choiceName(c.value), c.name);
        EXPECT_EQ(params::choiceNamed<LeafShape>(c.name), c.value);
    }
    EXPECT_EQ(params::choiceNamed<FlowerArrangement>("opposite"), FlowerArrangement::Opposite);
    EXPECT_FALSE(params::choiceNamed<FlowerArrangement>("Opposite").has_value());
    EXPECT_EQ(params::choiceName(static_cast<FlowerArrangement>(9)), nullptr);
}

// A species file with one enum-like value and one build-step flag set as given.
std::string speciesWith(const std::string& arrangement, const std::string& apex) {
    return "<plantarch_species format=\"1\"><name>t</name><shoot_type label=\"stem\"><phytomer>"
           "<inflorescence><flower_arrangement>" +
           arrangement +
           "</flower_arrangement></inflorescence></phytomer></shoot_type><build>"
           "<base_stem type=\"stem\" apex=\"" +
           apex + "\"/></build></plantarch_species>";
}

TEST(ParameterTable, ChoicesAndFlagsAreTypedWhenRead) {
    const SpeciesModel m = readSpeciesString(speciesWith("opposite", "false"), "t.xml");
    EXPECT_EQ(m.shootTypes.at("stem").phytomer_parameters.inflorescence.flower_arrangement,
              FlowerArrangement::Opposite);
    EXPECT_FALSE(m.build.at(0).apex);
    EXPECT_TRUE(m.build.at(0).leaves);
    // Written back by name, read back the same.
    const std::string text = writeSpeciesString(m);
    EXPECT_NE(text.find("<flower_arrangement>opposite</flower_arrangement>"), std::string::npos);
    EXPECT_NE(text.find("apex=\"false\""), std::string::npos);
    EXPECT_EQ(writeSpeciesString(readSpeciesString(text, "back.xml")), text);

    // The valid names in the error are the table's.
    try {
        readSpeciesString(speciesWith("oposite", "true"), "t.xml");
        FAIL() << "expected an error";
    } catch (const Error& e) {
        EXPECT_EQ(e.parameter(), "stem.phytomer.inflorescence.flower_arrangement");
        EXPECT_EQ(e.validRange(), "one of: alternate, opposite");
        EXPECT_NE(std::string(e.what()).find("did you mean 'opposite'"), std::string::npos);
    }
    EXPECT_THROW(readSpeciesString(speciesWith("alternate", "no"), "t.xml"), Error);
}

// ---- what front ends see -----------------------------------------------------------------

namespace {
// Counts the leaf fields of the table, all levels.
struct LeafCount {
    std::size_t n = 0;
    template <class T>
    void field(const params::FieldInfo&, const T&) {
        ++n;
    }
    template <class G, class Fn>
    void group(const char*, const G&, Fn&& visit) {
        visit(*this);
    }
    template <class E, class Fn>
    void list(const params::FieldInfo&, const char*, const std::vector<E>&, Fn&& visit) {
        ++n;  // the list's own entry, then its element's fields
        const E element{};
        visit(element, *this);
    }
};
}  // namespace

TEST(ParameterInfo, ListsEveryFieldWithItsDeclaration) {
    ShootParameters s;
    s.phytomer_parameters.leaf.prototype.shape = LeafShape::Cordate;
    s.phytomer_parameters.petiole.pitch = RandomFloat::uniform(10.0f, 30.0f);
    s.child_shoot_types = {{"a", 0.25f}, {"b", 0.75f}};
    const std::vector<ParameterInfo> list = parameterInfo(s);

    LeafCount count;
    params::describeParameters(s, count);
    EXPECT_EQ(list.size(), count.n);

    auto find = [&](const std::string& path) -> const ParameterInfo& {
        for (const ParameterInfo& p : list)
            if (p.path == path) return p;
        static const ParameterInfo none;
        ADD_FAILURE() << "no " << path;
        return none;
    };
    const ParameterInfo& shape = find("phytomer.leaf.prototype.shape");
    EXPECT_EQ(shape.kind, ParameterKind::Choice);
    EXPECT_EQ(shape.value, "cordate");
    ASSERT_EQ(shape.choices.size(), params::kChoices<LeafShape>.size());
    EXPECT_EQ(shape.choices[0].name, "elliptic");
    EXPECT_FALSE(shape.hasRange());

    const ParameterInfo& pitch = find("phytomer.petiole.pitch");
    EXPECT_EQ(pitch.kind, ParameterKind::RandomNumber);
    EXPECT_EQ(pitch.value, "uniform(10, 30)");
    EXPECT_EQ(pitch.unit, "degrees");
    EXPECT_EQ(pitch.rangeText(), "-180 to 180");

    const ParameterInfo& children = find("child_shoot_types");
    EXPECT_EQ(children.kind, ParameterKind::NumberMap);
    EXPECT_TRUE(children.probabilities);
    EXPECT_EQ(children.entry, "<type label=\"NAME\" probability=\"NUMBER\"/>");
    EXPECT_EQ(children.value, "a 0.25, b 0.75");

    EXPECT_EQ(find("phytomer.leaf.prototype.leaf_texture_file").entry,
              "<image leaflet=\"INDEX\">TEXT</image>");
    EXPECT_EQ(parameterInfo(PhenologyParameters{}).back().path,
              "leaf_angles.azimuth_concentration");
}

// The page is what the command generates now: a field added to the table without
// regenerating the page (or a page edited by hand) fails here.
TEST(ParameterDocs, PageMatchesTheTable) {
    const cli::Result r = cli::run("info --parameters-markdown");
    ASSERT_EQ(r.status, 0) << r.out;
    std::ifstream in(std::string(PLANTARCH_SOURCE_DIR) + "/docs/parameters.md", std::ios::binary);
    std::stringstream page;
    page << in.rdbuf();
    EXPECT_TRUE(page.str() == r.out)
        << "docs/parameters.md differs from the table; regenerate it with\n"
           "  build/plantarch info --parameters-markdown > docs/parameters.md";
    // Every field of the table is on the page, with its unit.
    for (const ParameterInfo& p : parameterInfo(ShootParameters{}))
        EXPECT_NE(r.out.find("| `" + p.name + "` | "), std::string::npos) << p.path;
    EXPECT_NE(r.out.find("| `phyllochron_min` | random number | days | 0.001 to 10000 | `2` |"),
              std::string::npos);
}

// `plantarch info SPECIES`: rows come from the table, with its units; --all lists each field.
TEST(InfoCli, ShowsSetParametersWithTheirUnits) {
    const cli::Result r = cli::run("info bean");
    ASSERT_EQ(r.status, 0) << r.out;
    EXPECT_NE(r.out.find("phytomer.leaf.prototype:\n"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find(" shape "), std::string::npos);
    EXPECT_NE(r.out.find("0.025 m\n"), std::string::npos);  // internode_length_max
    EXPECT_NE(r.out.find("time_to_flower_initiation      40 days\n"), std::string::npos) << r.out;

    const cli::Result all = cli::run("info bean --all");
    ASSERT_EQ(all.status, 0) << all.out;
    const std::size_t fields = parameterInfo(ShootParameters{}).size();
    EXPECT_NE(all.out.find("(" + std::to_string(fields) + " parameters)"), std::string::npos);
    for (const ParameterInfo& p : parameterInfo(ShootParameters{}))
        EXPECT_NE(all.out.find("  " + p.name + " "), std::string::npos) << p.path;

    const cli::Result table = cli::run("info --parameters");
    ASSERT_EQ(table.status, 0) << table.out;
    EXPECT_NE(table.out.find("phytomer.inflorescence.flower_arrangement: one of"),
              std::string::npos)
        << table.out;
    EXPECT_NE(table.out.find("opposite: Two flowers per position"), std::string::npos);

    const cli::Result none = cli::run("info");
    EXPECT_EQ(none.status, 2) << none.out;
}
