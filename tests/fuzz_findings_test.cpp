// Inputs the fuzzers found (docs/testing.md), kept as regression tests. Each once read
// successfully but was written back as a file that did not read again (or read differently).

#include <gtest/gtest.h>

#include <cstring>
#include <fstream>
#include <sstream>

#include "plantarch/Error.h"
#include "plantarch/PlantArchitecture.h"
#include "plantarch/SpeciesIO.h"

using namespace plantarch;

namespace {

// A file of the fuzz corpus (fuzz/corpus/...), or "" when it cannot be read.
std::string corpusFile(const std::string& name) {
    std::ifstream in(std::string(PLANTARCH_SOURCE_DIR) + "/fuzz/corpus/" + name, std::ios::binary);
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
}

}  // namespace

// plant_xml: a shoot type label with a space was accepted in a listing-form file, given
// default parameters, and written as a <shoot_type label="..."> that the reader refuses.
TEST(FuzzFindings, ShootTypeLabelWithASpaceIsRefused) {
    Context ctx;
    PlantArchitecture arch(&ctx);
    const std::string xml = R"(<helios><plant_instance><shoot>
        <shoot_type_label>JJJ unifoliate</shoot_type_label>
        <phytomer><internode><internode_length>0.01</internode_length></internode></phytomer>
        </shoot></plant_instance></helios>)";
    try {
        arch.readPlantStructureXMLString(xml);
        FAIL() << "read a label with a space";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("shoot[0].shoot_type_label = JJJ unifoliate: a shoot "
                                             "type label is letters, digits, '_' or '-'"),
                  std::string::npos)
            << e.what();
    }
    EXPECT_TRUE(arch.getAllPlantIDs().empty());
}

// species: a carriage return in a text value (here a file name) was written raw, and XML
// reads a raw carriage return as a line feed.
TEST(FuzzFindings, CarriageReturnInSpeciesTextSurvivesWriting) {
    const std::string xml = R"(<plantarch_species format="1"><name>cr</name>
        <shoot_type label="stem"><phytomer><internode><image_texture>a&#13;b.png</image_texture>
        </internode></phytomer></shoot_type><build><base_stem type="stem"/></build>
        </plantarch_species>)";
    const SpeciesModel model = readSpeciesString(xml, "cr.xml");
    ASSERT_EQ(model.shootTypes.at("stem").phytomer_parameters.internode.image_texture, "a\rb.png");
    const std::string written = writeSpeciesString(model);
    const SpeciesModel again = readSpeciesString(written, "written.xml");
    EXPECT_EQ(again.shootTypes.at("stem").phytomer_parameters.internode.image_texture, "a\rb.png");
    EXPECT_EQ(writeSpeciesString(again), written);
}

// plant_xml: the same for text in a plant structure file (here the plant's name).
TEST(FuzzFindings, LineBreaksInPlantTextSurviveWriting) {
    Context ctx;
    PlantArchitecture arch(&ctx);
    const std::string xml = R"(<plantarch_plants format="1"><plant_instance>
        <plant_name>a&#13;b&#10;c&#9;d</plant_name></plant_instance></plantarch_plants>)";
    const unsigned p = arch.readPlantStructureXMLString(xml).at(0);
    EXPECT_EQ(arch.plant(p).name, "a\rb\nc\td");
    const std::string written = arch.getPlantStructureXML({p});
    Context ctx2;
    PlantArchitecture again(&ctx2);
    const unsigned q = again.readPlantStructureXMLString(written).at(0);
    EXPECT_EQ(again.plant(q).name, "a\rb\nc\td");
    EXPECT_EQ(again.getPlantStructureXML({q}), written);
}

// species: formulas nested 4088 parentheses deep (the input as the fuzzer found it, kept in the
// species corpus) overflowed the formula parser's stack under ASan. It is now refused.
TEST(FuzzFindings, DeeplyNestedFormulaIsRefusedNotAStackOverflow) {
    const std::string text = corpusFile("species/stack-overflow-nested-formula.xml");
    ASSERT_FALSE(text.empty()) << "species/stack-overflow-nested-formula.xml";
    try {
        readSpeciesString(text, "nested.xml");
        FAIL() << "read a formula nested 4088 levels deep";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("nested deeper than 200 levels"), std::string::npos)
            << e.what();
    }
}

// plant_xml: a leaf listed at 636350 m, 0.4 of its full size, was read as a full-grown leaf of
// 1590875 m, and the file written from the plant held that size, over the 1e6 m any file may
// hold, so it did not read back. The full-grown size is now checked as it is derived (the
// petiole's length likewise).
TEST(FuzzFindings, FullGrownSizeDerivedFromAFractionIsHeldToTheRange) {
    const std::string text = corpusFile("plant_xml/leaf-full-size-beyond-range.xml");
    ASSERT_FALSE(text.empty()) << "plant_xml/leaf-full-size-beyond-range.xml";
    Context ctx;
    PlantArchitecture arch(&ctx);
    try {
        arch.readPlantStructureXMLString(text);
        FAIL() << "read a leaf whose full-grown size is 1590875 m";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find(
                      "leaf[3].leaf_scale = 0.0063635e8: at current_leaf_scale_factor 0.4 it is a "
                      "full-grown size of 1590875 m (valid: current size / "
                      "current_leaf_scale_factor at most 1000000 m)"),
                  std::string::npos)
            << e.what();
    }
    EXPECT_TRUE(arch.getAllPlantIDs().empty());
    // The same for a petiole: 6e5 m long at 0.5 of its size.
    std::string petiole = text;
    const std::size_t at = petiole.find("<petiole_length>0.05315401</petiole_length>");
    ASSERT_NE(at, std::string::npos);
    petiole.replace(at, std::strlen("<petiole_length>0.05315401</petiole_length>"),
                    "<petiole_length>600000</petiole_length>");
    std::string leafFixed = petiole;
    leafFixed.replace(leafFixed.find("0.0063635e8"), std::strlen("0.0063635e8"), "0.01");
    try {
        arch.readPlantStructureXMLString(leafFixed);
        FAIL() << "read a petiole whose full-grown length is 1.5e6 m";
    } catch (const Error& e) {
        EXPECT_NE(
            std::string(e.what()).find("petiole_length = 600000: at current_leaf_scale_factor "
                                       "0.4 it is a full-grown size of 1500000 m"),
            std::string::npos)
            << e.what();
    }
}
