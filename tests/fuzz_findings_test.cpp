// Inputs the fuzzers found (docs/testing.md), kept as regression tests. Each once read
// successfully but was written back as a file that did not read again (or read differently).

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "plantarch/Error.h"
#include "plantarch/PlantArchitecture.h"
#include "plantarch/SpeciesIO.h"

using namespace plantarch;

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
    const std::string path = std::string(PLANTARCH_SOURCE_DIR) +
                             "/fuzz/corpus/species/stack-overflow-nested-formula.xml";
    std::ifstream in(path, std::ios::binary);
    ASSERT_TRUE(in) << path;
    std::stringstream text;
    text << in.rdbuf();
    try {
        readSpeciesString(text.str(), "nested.xml");
        FAIL() << "read a formula nested 4088 levels deep";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("nested deeper than 200 levels"), std::string::npos)
            << e.what();
    }
}
