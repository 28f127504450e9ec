// `<helios>` plant structure files (docs/plant-xml.md, "Files with the root <helios>"): a
// file in the reference system's layout builds the plant it describes and grows on; bad
// values are one line naming file:line:path; plantarch writes the layout that system reads,
// and reading it back gives the same organs.

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <map>
#include <pugixml.hpp>
#include <set>

#include "cli_run.h"
#include "plant_geometry_bytes.h"
#include "plantarch/Error.h"
#include "plantarch/HeliosPlantXML.h"
#include "plantarch/PlantArchitecture.h"

using namespace plantarch;

namespace {

namespace fs = std::filesystem;

const std::string kFixture =
    std::string(PLANTARCH_SOURCE_DIR) + "/tests/data/bean_reference.helios.xml";

std::string fixtureText() {
    return plantarch::testing::fileBytes(kFixture);
}

struct Counts {
    std::size_t shoots = 0, leaves = 0, closed = 0, open = 0, fruit = 0, buds = 0;
};

Counts countsOf(const PlantInstance& p) {
    Counts c;
    auto floral = [&](const FloralBud& fb) {
        ++c.buds;
        const std::size_t n = fb.flowers.size();
        if (fb.stage == FloralStage::FlowerClosed) c.closed += n;
        if (fb.stage == FloralStage::FlowerOpen) c.open += n;
        if (fb.stage == FloralStage::Fruit) c.fruit += n;
    };
    for (const Shoot& s : p.shoots) {
        if (s.removed) continue;
        ++c.shoots;
        for (const Phytomer& ph : s.phytomers)
            for (const Petiole& pt : ph.petioles) {
                for (const LeafOrgan& l : pt.leaves) c.leaves += !l.removed;
                for (const FloralBud& fb : pt.floralBuds) floral(fb);
            }
        for (const FloralBud& fb : s.terminalFloralBuds) floral(fb);
    }
    return c;
}

std::string readError(const std::string& xml) {
    Context ctx;
    PlantArchitecture arch(&ctx);
    arch.loadPlantModelFromLibrary("bean");
    PlantStructureReadOptions o;
    o.nameForErrors = "ref.xml";
    try {
        arch.readPlantStructureXMLString(xml, o);
    } catch (const Error& e) {
        EXPECT_TRUE(arch.getAllPlantIDs().empty());
        return e.what();
    }
    return "";
}

int lineOf(const std::string& text, const std::string& needle) {
    const auto at = text.find(needle);
    return at == std::string::npos
               ? -1
               : 1 + int(std::count(text.begin(), text.begin() + long(at), '\n'));
}

std::string replacedFirst(std::string s, const std::string& from, const std::string& to) {
    const auto at = s.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    if (at != std::string::npos) s.replace(at, from.size(), to);
    return s;
}

void expectError(const std::string& from, const std::string& to, const std::string& message) {
    SCOPED_TRACE(to);
    const std::string bad = replacedFirst(fixtureText(), from, to);
    const std::string e = readError(bad);
    EXPECT_EQ(e.rfind("ref.xml:" + std::to_string(lineOf(bad, to)) + ": ", 0), 0u) << e;
    EXPECT_NE(e.find(message), std::string::npos) << e;
    EXPECT_EQ(e.find('\n'), std::string::npos) << e;
}

}  // namespace

TEST(HeliosFormat, ReferenceFileBuildsThePlantItDescribes) {
    Context ctx;
    PlantArchitecture arch(&ctx);
    arch.loadPlantModelFromLibrary("bean");
    std::vector<std::string> warnings;
    PlantStructureReadOptions o;
    o.onWarning = [&](const std::string& w) { warnings.push_back(w); };
    const auto ids = arch.readPlantStructureXML(kFixture, o);
    ASSERT_EQ(ids.size(), 1u);
    ASSERT_EQ(warnings.size(), 1u) << "one warning per plant";
    EXPECT_NE(warnings[0].find("values the file gives nowhere"), std::string::npos);
    EXPECT_EQ(warnings[0].find("values missing"), std::string::npos) << warnings[0];
    // A value given for some organs and left out for others is named, with its count.
    std::string partial = fixtureText();
    const std::string pitch = "<petiole_pitch>";
    const auto at = partial.find(pitch);
    ASSERT_NE(at, std::string::npos);
    partial.erase(at, partial.find("</petiole_pitch>", at) + 16 - at);
    Context ctx2;
    PlantArchitecture arch2(&ctx2);
    arch2.loadPlantModelFromLibrary("bean");
    warnings.clear();
    arch2.readPlantStructureXMLString(partial, o);
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_NE(warnings[0].find("; values missing, defaults used: "
                               "shoot.phytomer.internode.petiole.petiole_pitch; "),
              std::string::npos)
        << warnings[0];

    const PlantInstance& p = arch.plant(ids[0]);
    EXPECT_EQ(p.age, 42.0);
    const Counts c = countsOf(p);
    EXPECT_EQ(c.shoots, 2u);
    EXPECT_EQ(c.leaves, 18u);
    EXPECT_EQ(c.open, 3u);
    EXPECT_EQ(c.closed, 1u);
    EXPECT_EQ(c.fruit, 2u);
    EXPECT_EQ(c.buds, 4u);
    ASSERT_EQ(p.shoots[1].terminalFloralBuds.size(), 1u);
    EXPECT_EQ(p.shoots[1].parent, 0);
    EXPECT_EQ(p.shoots[1].parentNode, 1);

    // Current sizes become full sizes and fractions; leaflets listed left to right.
    const Phytomer& young = p.shoots[0].phytomers[3];
    EXPECT_FLOAT_EQ(young.internodeFraction, 0.031f / 0.04f);
    EXPECT_EQ(young.internode.length, 0.04f);
    EXPECT_EQ(young.leafFraction, 0.55f);
    EXPECT_FLOAT_EQ(young.petioles[0].length, 0.05f / 0.55f);
    std::map<int, const LeafOrgan*> byIndex;
    for (const LeafOrgan& l : young.petioles[0].leaves) byIndex[l.leafletIndex] = &l;
    ASSERT_EQ(byIndex.size(), 3u);
    EXPECT_FLOAT_EQ(byIndex.at(0)->scale, 0.041f / 0.55f);
    // The first pair half a leaflet_offset (0.2) below the tip, as the reference places it.
    EXPECT_FLOAT_EQ(byIndex.at(1)->position, 0.9f);
    EXPECT_FLOAT_EQ(byIndex.at(-1)->position, 0.9f);
    EXPECT_EQ(young.petioles[0].leaves[0].leafletIndex, 0) << "tip first, as growth orders them";
    const FloralBud& pods = p.shoots[0].phytomers[2].petioles[0].floralBuds.at(0);
    EXPECT_EQ(pods.stage, FloralStage::Fruit);
    EXPECT_EQ(pods.fruitGrowth, 0.6f);
    EXPECT_EQ(pods.peduncleLength, 0.03f);
    EXPECT_EQ(pods.flowers.at(1).azimuth, 180.0f);
    EXPECT_EQ(pods.flowers.at(1).fruitScale, 0.085f);
    EXPECT_FLOAT_EQ(pods.flowers.at(1).position, 0.88f);
    // The perturbations turn the shoot axis: the second internode leans off vertical.
    EXPECT_LT(p.shoots[0].phytomers[1].internode.direction.z, 1.0f);

    // Geometry is made for every organ that has a size.
    EXPECT_EQ(arch.getPlantObjectIDs(ids[0], OrganKind::Internode).size(), 6u);
    EXPECT_EQ(arch.getPlantObjectIDs(ids[0], OrganKind::Petiole).size(), 6u);
    EXPECT_GE(arch.getPlantObjectIDs(ids[0], OrganKind::Leaf).size(), 18u);
    EXPECT_GE(arch.getPlantObjectIDs(ids[0], OrganKind::FlowerOpen).size(), 3u);
    EXPECT_GE(arch.getPlantObjectIDs(ids[0], OrganKind::FlowerClosed).size(), 1u);
    EXPECT_GE(arch.getPlantObjectIDs(ids[0], OrganKind::Fruit).size(), 2u);
    EXPECT_EQ(arch.getPlantObjectIDs(ids[0], OrganKind::Peduncle).size(), 3u);

    // It grows on with the bean's parameters.
    const std::size_t nodes = arch.getShootNodeCount(ids[0], 0);
    arch.advanceTime(15.0);
    EXPECT_EQ(arch.getPlantAge(ids[0]), 57.0f);
    EXPECT_GE(arch.getShootNodeCount(ids[0], 0), nodes);
    EXPECT_GT(countsOf(arch.plant(ids[0])).leaves, 18u);
}

TEST(HeliosFormat, BadValuesAreOneLineNamingFileLineAndPath) {
    expectError("<leaf_pitch>12.5</leaf_pitch>", "<leaf_pitch>abc</leaf_pitch>",
                "plant_instance[0].shoot[0].phytomer[0].internode.petiole[0].leaf[0].leaf_pitch = "
                "abc");
    expectError("<leaf_roll>-10</leaf_roll>", "<leaf_rol>-10</leaf_rol>",
                "did you mean <leaf_roll>?");
    expectError("<bud_state>3</bud_state>", "<bud_state>7</bud_state>",
                "floral_bud[0].bud_state = 7: out of range (valid: 0 to 5)");
    expectError("<current_leaf_scale_factor>0.55</current_leaf_scale_factor>",
                "<current_leaf_scale_factor>1.5</current_leaf_scale_factor>",
                "current_leaf_scale_factor = 1.5: out of range (valid: 0 to 1)");
    expectError("<curvature_perturbations>-3;-3;-2.4</curvature_perturbations>",
                "<curvature_perturbations>-3;x;-2.4</curvature_perturbations>",
                "expected numbers separated by ';'");
    expectError("<internode_length_max>0.052</internode_length_max>",
                "<internode_length_max>0.01</internode_length_max>",
                "shorter than <internode_length>");
    expectError("<flower_base_scale>0.011</flower_base_scale>",
                "<flower_base_scal>0.011</flower_base_scal>", "did you mean <flower_base_scale>?");
}

namespace {

// The children names of every element of a `<helios>` document, by element name.
void childNames(pugi::xml_node n, std::map<std::string, std::set<std::string>>& out) {
    for (pugi::xml_node c : n.children())
        if (c.type() == pugi::node_element) {
            out[n.name()].insert(c.name());
            childNames(c, out);
        }
}

}  // namespace

TEST(HeliosFormat, WrittenFileHasTheReferenceLayoutAndReadsBackTheSame) {
    Context ctx;
    PlantArchitecture a(&ctx);
    a.loadPlantModelFromLibrary("bean");
    const unsigned id = a.buildPlantInstanceFromLibrary(vec3(0.1f, 0.2f, 0.0f), 60.0f);
    const std::string text = getHeliosPlantStructureXML(a, {id});

    // The layout the reference system's reader asks for.
    pugi::xml_document doc;
    ASSERT_TRUE(doc.load_string(text.c_str()));
    std::map<std::string, std::set<std::string>> names;
    childNames(doc, names);
    using Set = std::set<std::string>;
    EXPECT_EQ(names[""], Set{"helios"});
    EXPECT_EQ(names["helios"], Set{"plant_instance"});
    EXPECT_EQ(names["plant_instance"], (Set{"base_position", "plant_age", "shoot"}));
    EXPECT_EQ(names["shoot"], (Set{"shoot_type_label", "parent_shoot_ID", "parent_node_index",
                                   "parent_petiole_index", "base_rotation", "phytomer"}));
    EXPECT_EQ(names["phytomer"], Set{"internode"});
    EXPECT_EQ(names["internode"], (Set{"internode_length", "internode_radius", "internode_pitch",
                                       "internode_phyllotactic_angle", "internode_length_max",
                                       "internode_length_segments", "curvature_perturbations",
                                       "yaw_perturbations", "petiole"}));
    EXPECT_EQ(names["petiole"],
              (Set{"petiole_length", "petiole_radius", "petiole_pitch", "petiole_curvature",
                   "current_leaf_scale_factor", "petiole_taper", "petiole_length_segments",
                   "petiole_radial_subdivisions", "leaflet_scale", "leaflet_offset", "leaf",
                   "floral_bud"}));
    // (leaf_angles: plantarch's own, where the reference's angles cannot turn a leaf so)
    EXPECT_EQ(names["leaf"],
              (Set{"leaf_scale", "leaf_pitch", "leaf_yaw", "leaf_roll", "leaf_angles"}));
    EXPECT_EQ(names["floral_bud"],
              (Set{"bud_state", "parent_index", "bud_index", "is_terminal",
                   "current_fruit_scale_factor", "peduncle", "inflorescence"}));
    EXPECT_EQ(names["peduncle"], (Set{"length", "radius", "pitch", "roll", "curvature"}));
    EXPECT_EQ(names["inflorescence"], (Set{"flower_offset", "flower"}));
    EXPECT_EQ(names["flower"], (Set{"flower_pitch", "flower_yaw", "flower_roll", "flower_azimuth",
                                    "flower_base_scale"}));

    // Read back: the same organs, sizes and angles within the text's float precision.
    Context ctx2;
    PlantArchitecture b(&ctx2);
    b.loadPlantModelFromLibrary("bean");
    const unsigned q = b.readPlantStructureXMLString(text).at(0);
    const PlantInstance& p = a.plant(id);
    const PlantInstance& r = b.plant(q);
    const Counts cp = countsOf(p), cr = countsOf(r);
    EXPECT_GT(cp.open + cp.closed + cp.fruit, 0u) << "the test needs flowers or fruit";
    EXPECT_EQ(cr.shoots, cp.shoots);
    EXPECT_EQ(cr.leaves, cp.leaves);
    EXPECT_EQ(cr.open, cp.open);
    EXPECT_EQ(cr.closed, cp.closed);
    EXPECT_EQ(cr.fruit, cp.fruit);
    auto near = [](float x, float y) {
        return std::abs(x - y) <= 1e-5f * std::max(1.0f, std::abs(y));
    };
    ASSERT_EQ(r.shoots.size(), p.shoots.size());  // the bean prunes nothing by 60 days
    for (std::size_t s = 0; s < p.shoots.size(); ++s) {
        const Shoot& sp = p.shoots[s];
        const Shoot& sr = r.shoots[s];
        EXPECT_EQ(sr.type, sp.type);
        ASSERT_EQ(sr.phytomers.size(), sp.phytomers.size());
        for (std::size_t k = 0; k < sp.phytomers.size(); ++k) {
            const Phytomer& a1 = sp.phytomers[k];
            const Phytomer& b1 = sr.phytomers[k];
            EXPECT_TRUE(near(b1.internode.length * b1.internodeFraction,
                             a1.internode.length * a1.internodeFraction));
            EXPECT_TRUE(near(b1.internode.pitch, a1.internode.pitch));
            // The same internode directions (the layout keeps the turns, not the frames).
            EXPECT_LT(glm::length(b1.internode.direction - a1.internode.direction), 1e-4f)
                << s << " " << k;
            ASSERT_EQ(b1.petioles.size(), a1.petioles.size());
            for (std::size_t j = 0; j < a1.petioles.size(); ++j) {
                const Petiole& pa = a1.petioles[j];
                const Petiole& pb = b1.petioles[j];
                EXPECT_TRUE(near(pb.length * b1.leafFraction, pa.length * a1.leafFraction));
                // The same petiole (a turn that kept it off the ground is part of its pitch in
                // the file, so the pitches may differ).
                // Its base moves by half the internode radius toward its side, and the side
                // the file gives includes the turn: a fraction of a millimetre.
                const AABB ba = ctx.objectBoundingBox(pa.object);
                const AABB bb = ctx2.objectBoundingBox(pb.object);
                EXPECT_LT(glm::length(ba.min - bb.min) + glm::length(ba.max - bb.max), 5e-4f)
                    << s << " " << k << " " << j;
                EXPECT_TRUE(near(pb.curvature, pa.curvature));
                std::map<int, const LeafOrgan*> leaves;
                for (const LeafOrgan& l : pb.leaves) leaves[l.leafletIndex] = &l;
                for (const LeafOrgan& l : pa.leaves) {
                    if (l.removed) continue;
                    ASSERT_TRUE(leaves.count(l.leafletIndex));
                    const LeafOrgan& m = *leaves.at(l.leafletIndex);
                    EXPECT_TRUE(near(m.scale * b1.leafFraction, l.scale * a1.leafFraction));
                    // Within the 0.05 degrees below which the writer leaves a leaf to the
                    // reference's angles alone.
                    EXPECT_NEAR(m.pitch, l.pitch, 0.06f);
                    EXPECT_NEAR(m.yaw, l.yaw, 0.06f);
                    EXPECT_NEAR(m.roll, l.roll, 0.06f) << s << " " << k << " " << j;
                    EXPECT_TRUE(near(m.position, l.position));
                }
                ASSERT_EQ(pb.floralBuds.size(), pa.floralBuds.size());
                for (std::size_t f = 0; f < pa.floralBuds.size(); ++f) {
                    const FloralBud& fa = pa.floralBuds[f];
                    const FloralBud& fb = pb.floralBuds[f];
                    if (fa.stage == FloralStage::Removed) continue;
                    EXPECT_EQ(fb.stage, fa.stage);
                    EXPECT_TRUE(near(fb.pedunclePitch, fa.pedunclePitch));
                    EXPECT_TRUE(near(fb.peduncleLength, fa.peduncleLength));
                    if (fa.stage == FloralStage::Bud) continue;
                    ASSERT_EQ(fb.flowers.size(), fa.flowers.size());
                    for (std::size_t i = 0; i < fa.flowers.size(); ++i) {
                        EXPECT_TRUE(near(currentFloralSize(fb, fb.flowers[i]),
                                         currentFloralSize(fa, fa.flowers[i])));
                        EXPECT_TRUE(near(fb.flowers[i].pitch, fa.flowers[i].pitch));
                        EXPECT_TRUE(near(fb.flowers[i].azimuth, fa.flowers[i].azimuth));
                        EXPECT_TRUE(near(fb.flowers[i].position, fa.flowers[i].position));
                    }
                }
            }
        }
    }
    // Written again, the plant read back gives a document of the same elements (the values
    // may differ in their last bit: current sizes are divided and multiplied again).
    const std::string again = getHeliosPlantStructureXML(b, {q});
    EXPECT_EQ(std::count(again.begin(), again.end(), '<'),
              std::count(text.begin(), text.end(), '<'));
}

TEST(HeliosFormat, CommandLineWritesAndReadsHeliosFiles) {
    const fs::path dir = fs::temp_directory_path() / "helios_cli";
    fs::create_directories(dir);
    const std::string file = (dir / "bean.helios.xml").string();
    const auto built =
        cli::run("build bean --age 40 -o " + file + " -o " + (dir / "own.xml").string());
    ASSERT_EQ(built.status, 0) << built.out;
    const std::string text = plantarch::testing::fileBytes(file);
    EXPECT_EQ(text.find("<helios>"), text.find('\n') + 1) << "the root is <helios>";
    EXPECT_NE(plantarch::testing::fileBytes((dir / "own.xml").string()).find("<plantarch_plants"),
              std::string::npos);
    const auto converted =
        cli::run("convert " + file + " " + (dir / "bean.obj").string() + " --species bean");
    EXPECT_EQ(converted.status, 0) << converted.out;
    EXPECT_TRUE(fs::exists(dir / "bean.obj"));
    const auto canopy = cli::run("canopy bean --count 2x1 --age 20 --separate -o " +
                                 (dir / "field.helios.xml").string());
    EXPECT_EQ(canopy.status, 0) << canopy.out;
    EXPECT_TRUE(fs::exists(dir / "field_0000.helios.xml")) << canopy.out;
    fs::remove_all(dir);
}
