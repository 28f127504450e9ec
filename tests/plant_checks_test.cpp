// The shared check after reading a plant (plant_io::checkPlant): plant structure files,
// plant strings and `<helios>` files are held alike to the state table's ranges and to
// consistent references between shoots, buds and leaves. A valid plant still reads exactly
// (its file and string written again are the same); each bad one is refused with one line
// naming the file, the line (in a string: the character), the element path, the value and
// the valid range, and adds nothing.

#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "plant_io/plant_structure.h"
#include "plantarch/Error.h"
#include "plantarch/HeliosPlantXML.h"
#include "plantarch/PlantArchitecture.h"

using namespace plantarch;

namespace {

// A bean grown 40 days (branches, buds that grew into them, leaves with IDs).
const PlantInstance& bean() {
    static const PlantInstance plant = [] {
        Context ctx;
        PlantArchitecture arch(&ctx);
        arch.loadPlantModelFromLibrary("bean");
        return arch.plant(arch.buildPlantInstanceFromLibrary(vec3(0.0f), 40.0f));
    }();
    return plant;
}

std::string xmlOf(const PlantInstance& p) {
    return plant_io::writePlantsXML({&p});
}

int lineAt(const std::string& text, std::size_t pos) {
    return 1 + int(std::count(text.begin(), text.begin() + std::ptrdiff_t(pos), '\n'));
}

// The line of the first `element` after the n-th `<shoot ID="i">` opening ...
int lineOf(const std::string& xml, unsigned shoot, const std::string& element,
           std::size_t skip = 0) {
    std::size_t at = xml.find("<shoot ID=\"" + std::to_string(shoot) + "\">");
    EXPECT_NE(at, std::string::npos);
    for (std::size_t i = 0; i <= skip; ++i) at = xml.find("<" + element + ">", at + 1);
    EXPECT_NE(at, std::string::npos) << element;
    return lineAt(xml, at);
}

// The error of reading `text` (a plant structure or `<helios>` document) as plants.xml into
// a PlantArchitecture with the bean loaded ("" when it reads); nothing may be added.
std::string readError(const std::string& text) {
    Context ctx;
    PlantArchitecture arch(&ctx);
    arch.loadPlantModelFromLibrary("bean");
    PlantStructureReadOptions o;
    o.nameForErrors = "plants.xml";
    try {
        arch.readPlantStructureXMLString(text, o);
    } catch (const Error& e) {
        EXPECT_TRUE(arch.getAllPlantIDs().empty()) << "a failed read adds nothing";
        EXPECT_EQ(ctx.objectCount(), 0u);
        return e.what();
    }
    return "";
}

std::string stringError(const std::string& text) {
    Context ctx;
    PlantArchitecture arch(&ctx);
    arch.loadPlantModelFromLibrary("bean");
    try {
        arch.generatePlantFromString(text);
    } catch (const Error& e) {
        EXPECT_TRUE(arch.getAllPlantIDs().empty()) << "a failed read adds nothing";
        return e.what();
    }
    return "";
}

// A branch of the bean (a shoot growing from a petiole's axil) and the bud it grew from.
struct Branch {
    unsigned shoot = 0, parent = 0, node = 0, petiole = 0, bud = 0;
};
Branch branchOf(const PlantInstance& p) {
    for (const Shoot& s : p.shoots) {
        if (s.parent < 0 || s.rank == p.shoots[unsigned(s.parent)].rank) continue;
        const Petiole& pt = p.shoots[unsigned(s.parent)]
                                .phytomers[unsigned(s.parentNode)]
                                .petioles[unsigned(s.parentPetiole)];
        for (std::size_t b = 0; b < pt.vegetativeBuds.size(); ++b)
            if (pt.vegetativeBuds[b].childShoot == int(s.id))
                return {s.id, unsigned(s.parent), unsigned(s.parentNode), unsigned(s.parentPetiole),
                        unsigned(b)};
    }
    ADD_FAILURE() << "the bean has no branch grown from a bud";
    return {};
}

std::string budPath(const Branch& b) {
    return "plant_instance[0].shoot[" + std::to_string(b.parent) + "].phytomer[" +
           std::to_string(b.node) + "].internode.petiole[" + std::to_string(b.petiole) +
           "].vegetative_bud[" + std::to_string(b.bud) + "].child_shoot_ID";
}

}  // namespace

TEST(PlantChecks, ValidPlantsStillReadExactly) {
    const PlantInstance& p = bean();
    Context ctx;
    PlantArchitecture arch(&ctx);
    arch.loadPlantModelFromLibrary("bean");
    const std::string xml = xmlOf(p);
    const unsigned fromXML = arch.readPlantStructureXMLString(xml).at(0);
    EXPECT_EQ(xmlOf(arch.plant(fromXML)).substr(xml.find("<plant_name>")),
              xml.substr(xml.find("<plant_name>")))
        << "a plant structure file written again is the same";
    for (int digits : {0, 4}) {
        const std::string s = arch.getPlantString(fromXML, {digits});
        EXPECT_EQ(arch.getPlantString(arch.generatePlantFromString(s), {digits}), s);
    }
    const std::string helios = getHeliosPlantStructureXML(arch, {fromXML});
    const unsigned fromHelios = arch.readPlantStructureXMLString(helios).at(0);
    EXPECT_EQ(arch.getShootCount(fromHelios), arch.getShootCount(fromXML));
}

TEST(PlantChecks, NegativeSizesAreRefusedInEveryFormat) {
    PlantInstance p = bean();
    p.shoots[1].phytomers[0].petioles[0].leaves[0].scale = -0.0625f;
    const std::string xml = xmlOf(p);
    EXPECT_EQ(readError(xml),
              "plants.xml:" + std::to_string(lineAt(xml, xml.find("<leaf_scale>-0.0625"))) +
                  ": plant_instance[0].shoot[1].phytomer[0].internode.petiole[0].leaf[0]."
                  "leaf_scale = -0.0625: out of range (valid: 0 to 1000000)");
    p = bean();
    p.shoots[0].phytomers[0].internode.radius = -0.001f;
    EXPECT_NE(readError(xmlOf(p)).find("internode.internode_radius = -0.001: out of range (valid: "
                                       "0 to 1000000)"),
              std::string::npos);

    // A plant string: placed at the character where the organ starts.
    Context ctx;
    PlantArchitecture arch(&ctx);
    arch.loadPlantModelFromLibrary("bean");
    const std::string s = arch.getPlantString(arch.readPlantStructureXMLString(xmlOf(bean()))[0]);
    const std::size_t leaf = s.find("L0(");
    std::string bad = s;
    bad.insert(leaf + 3, "-");
    const std::string e = stringError(bad);
    EXPECT_EQ(e.find("plant string, character " + std::to_string(leaf + 1) + ": shoot[0]."), 0u)
        << e;
    EXPECT_NE(e.find(".leaf[0].leaf_scale = -"), std::string::npos) << e;
    EXPECT_NE(e.find(": out of range (valid: 0 to 1000000)"), std::string::npos) << e;
    bad = s;
    bad.insert(s.find("I(") + 2, "-");
    EXPECT_NE(stringError(bad).find("internode.internode_length = -"), std::string::npos);

    // A `<helios>` file: at the value's line (it always refused negative lengths; a negative
    // taper too now, from the same table).
    const std::string helios = getHeliosPlantStructureXML(arch, arch.getAllPlantIDs());
    const std::size_t taper = helios.find("<petiole_taper>");
    std::string badHelios = helios;
    badHelios.replace(taper, helios.find('<', taper + 1) - taper, "<petiole_taper>-0.5");
    EXPECT_EQ(readError(badHelios).find("plants.xml:" + std::to_string(lineAt(helios, taper)) +
                                        ": plant_instance[0].shoot[0].phytomer[0].internode."
                                        "petiole[0].petiole_taper = -0.5: out of range (valid: 0 "
                                        "to 1000000)"),
              0u)
        << readError(badHelios);
}

TEST(PlantChecks, ReferencesBetweenShootsBudsAndLeavesMustHold) {
    const Branch b = branchOf(bean());
    const std::string bud = budPath(b);

    // A parent petiole index beyond the node's petioles.
    PlantInstance p = bean();
    p.shoots[b.shoot].parentPetiole = 7;
    std::string xml = xmlOf(p);
    const std::size_t petioles = p.shoots[b.parent].phytomers[b.node].petioles.size();
    EXPECT_EQ(readError(xml),
              "plants.xml:" + std::to_string(lineOf(xml, b.shoot, "parent_petiole_index")) +
                  ": plant_instance[0].shoot[" + std::to_string(b.shoot) +
                  "].parent_petiole_index = 7: no such petiole at the parent's node (valid: 0 to " +
                  std::to_string(petioles - 1) + ")");

    // A bud whose shoot is the stem it is on.
    p = bean();
    p.shoots[b.parent].phytomers[b.node].petioles[b.petiole].vegetativeBuds[b.bud].childShoot =
        int(b.parent);
    EXPECT_NE(readError(xmlOf(p)).find(bud + " = " + std::to_string(b.parent) +
                                       ": a bud's shoot cannot be the shoot the bud is on"),
              std::string::npos)
        << readError(xmlOf(p));

    // Two buds claiming one shoot.
    p = bean();
    auto& buds = p.shoots[b.parent].phytomers[b.node].petioles[b.petiole].vegetativeBuds;
    buds.insert(buds.begin() + b.bud + 1, buds[b.bud]);
    std::string e = readError(xmlOf(p));
    EXPECT_NE(
        e.find("two buds claim shoot " + std::to_string(b.shoot) + " (the other: " + bud + ")"),
        std::string::npos)
        << e;

    // A bud claiming a shoot that grows elsewhere.
    p = bean();
    p.shoots[0].apicalBud.childShoot = int(b.shoot);
    e = readError(xmlOf(p));
    EXPECT_NE(
        e.find("plant_instance[0].shoot[0].apical_bud.child_shoot_ID = " + std::to_string(b.shoot) +
               ": shoot " + std::to_string(b.shoot) + " does not grow from this bud"),
        std::string::npos)
        << e;

    // Duplicate leaf IDs, and a next leaf ID that growth would hand out again.
    p = bean();
    Petiole& pt = p.shoots[1].phytomers[0].petioles[0];
    pt.leaves[1].leafID = pt.leaves[0].leafID;
    xml = xmlOf(p);
    e = readError(xml);
    EXPECT_NE(e.find("plant_instance[0].shoot[1].phytomer[0].internode.petiole[0].leaf[1].leaf_ID "
                     "= " +
                     std::to_string(pt.leaves[0].leafID) + ": leaf ID given twice (also "),
              std::string::npos)
        << e;
    p = bean();
    p.nextLeafID = 1;
    EXPECT_NE(readError(xmlOf(p)).find("next_leaf_ID = 1: not above every leaf ID"),
              std::string::npos);

    // In a `<helios>` file: at the element's line.
    Context ctx;
    PlantArchitecture arch(&ctx);
    arch.loadPlantModelFromLibrary("bean");
    const std::string helios =
        getHeliosPlantStructureXML(arch, {arch.readPlantStructureXMLString(xmlOf(bean()))[0]});
    const std::size_t shoot = helios.find("<parent_shoot_ID>0</parent_shoot_ID>");
    ASSERT_NE(shoot, std::string::npos);
    const std::size_t at = helios.find("<parent_petiole_index>", shoot);
    std::string badHelios = helios;
    badHelios.replace(at, helios.find("</", at) - at, "<parent_petiole_index>5");
    e = readError(badHelios);
    EXPECT_EQ(e.find("plants.xml:" + std::to_string(lineAt(helios, at)) + ": plant_instance[0]."),
              0u)
        << e;
    EXPECT_NE(e.find(".parent_petiole_index = 5: no such petiole at the parent's node"),
              std::string::npos)
        << e;
}

// The documentation promises that a string's unknown shoot type gets default parameters and
// a warning: it does, with as many shape variants as the string names (so each leaf keeps its
// own, and the string reads back the same) where it was "variant out of range".
TEST(PlantChecks, AStringsUnknownShootTypeGetsDefaultsWithItsVariants) {
    Context ctx;
    PlantArchitecture arch(&ctx);
    arch.loadPlantModelFromLibrary("bean");
    const std::string s = arch.getPlantString(arch.readPlantStructureXMLString(xmlOf(bean()))[0]);
    unsigned most = 0;
    for (const Shoot& sh : bean().shoots)
        for (const Phytomer& ph : sh.phytomers)
            for (const Petiole& pt : ph.petioles)
                for (const LeafOrgan& l : pt.leaves)
                    if (!l.removed) most = std::max(most, l.variant);
    ASSERT_GT(most, 0u) << "the test needs leaves of several variants";

    Context other;
    PlantArchitecture fresh(&other);  // knows no bean shoot types
    std::vector<std::string> warnings;
    PlantStructureReadOptions o;
    o.onWarning = [&](const std::string& w) { warnings.push_back(w); };
    const unsigned p = fresh.generatePlantFromString(s, o);
    EXPECT_EQ(fresh.getPlantString(p), s);
    bool named = false;
    for (const std::string& w : warnings)
        named = named || w.find("plantarch's default parameters, " + std::to_string(most + 1) +
                                " leaf shape variants as given") != std::string::npos;
    EXPECT_TRUE(named) << (warnings.empty() ? "no warning" : warnings[0]);
}

TEST(PlantChecks, DistributionTailsNeverRealizeAValueTheCheckRefuses) {
    // normal(0.09, 0.03) fits prototype_scale's range (0 to 10) only by its mean - 3 stddev
    // (0, to float rounding); a draw further out takes that limit, so thousands of leaves hold
    // no negative scale, some sit exactly at the limit, and the file written reads back.
    Context ctx;
    PlantArchitecture arch(&ctx);
    ShootParameters sp;
    sp.phytomer_parameters.leaf.leaves_per_petiole = 5;
    sp.phytomer_parameters.leaf.leaflet_offset = 0.2f;
    const RandomFloat scale = RandomFloat::normal(0.09f, 0.03f);
    ASSERT_GE(scale.lowerBound(), 0.0f);
    ASSERT_LT(scale.lowerBound(), 1e-6f);
    sp.phytomer_parameters.leaf.prototype_scale = scale;
    sp.max_nodes = 60;
    arch.defineShootType("stem", sp);
    std::vector<unsigned> ids;
    for (int i = 0; i < 20; ++i) {
        const unsigned p = arch.addPlantInstance(vec3(float(i), 0, 0), 0.0f);
        arch.addBaseStemShoot(p, {60, {0, 0, 0}, {0.002f, 0.02f, 1.0f, 1.0f}, 0.0f, "stem"});
        ids.push_back(p);
    }
    std::size_t leaves = 0, atLimit = 0;
    float smallest = 1.0f;
    for (unsigned id : ids)
        for (const Shoot& s : arch.plant(id).shoots)
            for (const Phytomer& ph : s.phytomers)
                for (const Petiole& pt : ph.petioles)
                    for (const LeafOrgan& l : pt.leaves) {
                        ++leaves;
                        smallest = std::min(smallest, l.scale);
                        atLimit += l.scale == scale.lowerBound() ? 1 : 0;
                    }
    EXPECT_EQ(leaves, 20u * 60u * 5u);
    EXPECT_EQ(smallest, scale.lowerBound());
    EXPECT_GT(atLimit, 0u);  // about 0.135 % of 6000 leaves
    const std::string xml = arch.getPlantStructureXML(ids);
    EXPECT_EQ(xml.find("<leaf_scale>-"), std::string::npos);
    Context ctx2;
    PlantArchitecture back(&ctx2);
    EXPECT_EQ(back.readPlantStructureXMLString(xml).size(), ids.size());
    EXPECT_EQ(back.getPlantStructureXML(back.getAllPlantIDs()), xml);
}
