// The XML reader layer (core/xml_reader.h) and the number reader (core/value_text.h): the
// checks both file kinds share, and that species files and plant structure files word the
// same mistake alike.

#include "core/xml_reader.h"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "core/value_text.h"
#include "error_of.h"
#include "plantarch/Error.h"
#include "plantarch/PlantArchitecture.h"
#include "plantarch/SpeciesIO.h"

using namespace plantarch;
using plantarch::testing::errorOf;

namespace {

const xml::DocumentKind kKind{"test file", "top", "other_top"};

Error documentError(const std::string& text) {
    return errorOf([&] { xml::Document doc(text, "t.xml", kKind); });
}

std::string readText(const std::string& path) {
    std::ifstream in(path);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

}  // namespace

TEST(XmlDocument, RejectsWhatIsNotOneDocumentOfItsKind) {
    struct Case {
        std::string text;
        int line;
        std::string message;
    };
    const std::vector<Case> cases = {
        {"  \n ", 1, "empty file, expected a <top> document"},
        {"just text", 1, "not an XML file: no root element, expected <top>"},
        {"<top>\n<a>\n", 2, "(the file ends too early)"},
        {"<top/>\n<top/>", 2, "a second root element <top> after <top>"},
        {"<top/>\n<![CDATA[stray]]>", 2, "text outside the root element"},
        {"\n<wrong/>", 2, "not a test file: root element <wrong>"},
    };
    for (const Case& c : cases) {
        SCOPED_TRACE(c.text);
        const Error e = documentError(c.text);
        EXPECT_EQ(e.file(), "t.xml");
        EXPECT_EQ(e.line(), c.line) << e.what();
        EXPECT_NE(std::string(e.what()).find(c.message), std::string::npos) << e.what();
    }
    EXPECT_EQ(documentError("<wrong/>").validRange(), "<top>");
    // Both accepted roots read; lines count from 1 at every '\n'.
    const std::string text = "<!-- a -->\n<other_top>\n\n  <b/>\n</other_top>\n";
    const xml::Document doc(text, "t.xml", kKind);
    EXPECT_STREQ(doc.root().name(), "other_top");
    EXPECT_EQ(doc.line(doc.root()), 2);
    EXPECT_EQ(doc.line(doc.root().child("b")), 4);
    EXPECT_EQ(doc.lineAt(0), 1);
    EXPECT_EQ(doc.lineAt(std::ptrdiff_t(text.size())), 6);
}

TEST(XmlElement, AttributesAndValuesAreStrictAndNamePathAndLine) {
    const std::string text =
        "<top>\n"
        "  <leaf kind=\" ovate \" sizee=\"3\"/>\n"
        "  <pitch unit=\"deg\">30</pitch>\n"
        "  <roll>\n  12 <x/></roll>\n"
        "  <yaw> 1.5e3 </yaw>\n"
        "</top>";
    const xml::Document doc(text, "t.xml", kKind);
    const xml::Element top(doc, doc.root(), "plant");
    const xml::Element leaf = top.child(doc.root().child("leaf"));
    EXPECT_EQ(leaf.path(), "plant.leaf");
    EXPECT_EQ(leaf.attribute("kind"), "ovate");
    EXPECT_EQ(leaf.attribute("absent"), "");

    Error e = errorOf([&] { leaf.checkAttributes({"kind", "size"}); });
    EXPECT_EQ(e.line(), 2);
    EXPECT_EQ(e.parameter(), "plant.leaf.sizee");
    EXPECT_EQ(e.message(), "unknown attribute 'sizee' of <leaf>, did you mean 'size'?");
    EXPECT_EQ(e.validRange(), "one of: kind, size");
    EXPECT_EQ(e.value(), "3");

    e = errorOf([&] { leaf.requiredAttribute("shape"); });
    EXPECT_EQ(e.parameter(), "plant.leaf.shape");
    EXPECT_EQ(e.message(), "missing required attribute 'shape' of <leaf>");

    const xml::Element pitch = top.child(doc.root().child("pitch"));
    e = errorOf([&] { pitch.text(); });
    EXPECT_EQ(e.line(), 3);
    EXPECT_EQ(e.validRange(), "no attributes");
    EXPECT_EQ(pitch.content(), "30");

    // A child's path is its parent's and its own part, with an index when given.
    const xml::Element roll(top, doc.root().child("roll"), "roll", 2);
    EXPECT_EQ(roll.path(), "plant.roll[2]");
    EXPECT_EQ(roll.pathTo("x"), "plant.roll[2].x");
    e = errorOf([&] { roll.text(); });
    EXPECT_EQ(e.line(), 5);  // the line of <x/>
    EXPECT_EQ(e.parameter(), "plant.roll[2]");
    EXPECT_EQ(e.message(), "<roll> holds a value, not elements (found <x>)");

    // A conversion error keeps its message and value, and gains file, line and path.
    const xml::Element yaw = top.child(doc.root().child("yaw"));
    EXPECT_EQ(yaw.parse(text::parseFloat), 1500.0f);
    e = errorOf([&] { yaw.parse(text::parseInt); });
    EXPECT_EQ(std::string(e.what()),
              "t.xml:6: plant.yaw = 1.5e3: expected a whole number (valid: a whole number)");
}

TEST(XmlChildren, UnknownAndDuplicateChildrenAreReportedOnce) {
    const std::string text = R"(<top>
  <pitch>1</pitch>
  <roll>2</roll>
  <pitch>3</pitch>
  <wire/><wire/>
</top>)";
    const xml::Document doc(text, "t.xml", kKind);
    const xml::Element top(doc, doc.root(), "");

    {  // Taken once, then given again: the one not read is the duplicate.
        xml::Children c(top);
        EXPECT_EQ(doc.line(c.take("pitch")), 2);
        EXPECT_EQ(doc.line(c.take("roll")), 3);
        EXPECT_EQ(c.takeAll("wire").size(), 2u);
        const Error e = errorOf([&] { c.finish(); });
        EXPECT_EQ(e.line(), 4);
        EXPECT_EQ(e.parameter(), "pitch");
        EXPECT_EQ(e.message(), "duplicate element <pitch> (first at line 2)");
    }
    {  // Not declared: unknown, with the closest declared name and all of them.
        xml::Children c(top);
        c.take("pitch");
        c.take("rol");
        c.allow("wire", true);
        c.allow("pitch", false);  // declared twice: listed once
        const Error e = errorOf([&] { c.finish(); });
        EXPECT_EQ(e.line(), 3);
        EXPECT_EQ(e.message(), "unknown element <roll> in <top>, did you mean <rol>?");
        EXPECT_EQ(e.validRange(), "one of: pitch, rol, wire");
    }
    {  // Allowed without taking: the second of a name allowed once is the duplicate.
        xml::Children c(top);
        c.allow("pitch", false);
        c.allow("roll", false);
        c.allow("wire", false);
        const Error e = errorOf([&] { c.finish(); });
        EXPECT_EQ(e.line(), 4);
        EXPECT_EQ(e.message(), "duplicate element <pitch> (first at line 2)");
        EXPECT_EQ(c.elements().size(), 5u);
    }
    {  // Everything expected: no error.
        xml::Children c(top);
        c.take("roll");
        c.takeAll("pitch");
        c.allow("wire", true);
        EXPECT_NO_THROW(c.finish());
        EXPECT_FALSE(c.take("absent"));
    }
    const xml::Document texty("<top>\n<a/> stray   words </top>", "t.xml", kKind);
    const xml::Element root(texty, texty.root(), "");
    const Error e = errorOf([&] {
        xml::Children c(root);
        c.finish();
    });
    EXPECT_EQ(e.line(), 2);
    EXPECT_EQ(e.message(), "unexpected text inside <top>, expected elements");
    EXPECT_EQ(e.value(), "stray words");
}

// One implementation for every number type: the same text rules, each type's own range.
TEST(NumberReader, OneRuleForEveryNumberType) {
    float f = 0;
    double d = 0;
    int i = 0;
    unsigned u = 0;
    std::uint64_t w = 0;
    EXPECT_TRUE(text::readNumber("+2.5", f) && f == 2.5f);
    EXPECT_TRUE(text::readNumber("-1e-3", d) && d == -1e-3);
    EXPECT_TRUE(text::readNumber("+7", i) && i == 7);
    EXPECT_TRUE(text::readNumber("+7", u) && u == 7u);
    EXPECT_TRUE(text::readNumber("18446744073709551615", w) && w == ~std::uint64_t(0));
    for (const char* bad : {"", "+", "+-1", "1 ", " 1", "1x", "0x10", "nan", "inf", "1,5"}) {
        SCOPED_TRACE(bad);
        EXPECT_FALSE(text::readNumber(bad, f));
        EXPECT_FALSE(text::readNumber(bad, d));
        EXPECT_FALSE(text::readNumber(bad, i));
    }
    EXPECT_FALSE(text::readNumber("1e39", f));  // beyond float
    EXPECT_TRUE(text::readNumber("1e39", d));
    EXPECT_FALSE(text::readNumber("-1", u));
    EXPECT_FALSE(text::readNumber("2.0", i));
    EXPECT_FALSE(text::readNumber("4294967296", u));
    EXPECT_EQ(text::parseDouble(" 0.1 "), 0.1);
    EXPECT_EQ(text::parse<float>("0.1"), 0.1f);
    EXPECT_EQ(errorOf([] { text::parseDouble("1e400"); }).message(), "expected a number");
    EXPECT_EQ(errorOf([] { text::parseFloat("1e400"); }).message(), "expected a number");
}

TEST(ValueText, LabelsAndChoices) {
    EXPECT_TRUE(text::isLabel("main_2-b"));
    for (const char* bad : {"", "a.b", "a b", "a/b", "\xc3\xa9"}) EXPECT_FALSE(text::isLabel(bad));
    const std::vector<std::string> choices = {"ovate", "cordate"};
    EXPECT_EQ(text::parseChoice(" cordate ", choices), 1u);
    const Error e = errorOf([&] { text::parseChoice("cordat", choices); });
    EXPECT_EQ(e.message(), "unknown value 'cordat', did you mean 'cordate'?");
    EXPECT_EQ(e.validRange(), "one of: ovate, cordate");
    EXPECT_EQ(text::oneOf({}), "none");
}

// The species reader and the plant structure reader read shoot type parameters through one
// layer: the same misspelling gets the same message and valid list in both.
TEST(XmlReaders, SpeciesAndPlantFilesWordMistakesAlike) {
    const std::string species = readText(std::string(PLANTARCH_SOURCE_DIR) + "/species/bean.xml");
    Context ctx;
    PlantArchitecture arch(&ctx);
    arch.loadPlantModelFromLibrary("bean");
    const unsigned id = arch.buildPlantInstanceFromLibrary(vec3(0.0f), 10.0f);
    const std::string plants = arch.getPlantStructureXML({id});

    // The first <element> and </element> spelt with a 'z' at the end.
    auto misspelt = [](std::string xml, const std::string& element) {
        for (const std::string& tag : {"<" + element + ">", "</" + element + ">"}) {
            const auto at = xml.find(tag);
            EXPECT_NE(at, std::string::npos) << tag;
            if (at != std::string::npos) xml.insert(at + tag.size() - 1, "z");
        }
        return xml;
    };
    auto plantError = [](const std::string& xml) {
        Context c;
        PlantArchitecture a(&c);
        return errorOf([&] { a.readPlantStructureXMLString(xml); });
    };
    for (const std::string element : {"max_nodes", "internode_length_max", "evergreen"}) {
        SCOPED_TRACE(element);
        const Error s = errorOf([&] { readSpeciesString(misspelt(species, element), "b.xml"); });
        const Error p = plantError(misspelt(plants, element));
        EXPECT_NE(s.message().find("unknown element <" + element + "z>"), std::string::npos)
            << s.what();
        EXPECT_NE(s.message().find("did you mean <" + element + ">?"), std::string::npos)
            << s.what();
        EXPECT_EQ(s.message(), p.message()) << s.what() << "\n" << p.what();
        EXPECT_EQ(s.validRange(), p.validRange());
        EXPECT_EQ(p.parameter().rfind("plant_instance[0].", 0), 0u) << p.what();
    }
    // A value of the wrong form: the same message too.
    const auto bad = [](const std::string& xml) {
        const auto open = xml.find("<max_nodes>") + std::string("<max_nodes>").size();
        return xml.substr(0, open) + "many" + xml.substr(xml.find("</max_nodes>", open));
    };
    const Error s = errorOf([&] { readSpeciesString(bad(species), "b.xml"); });
    const Error p = plantError(bad(plants));
    EXPECT_EQ(s.message(), p.message());
    EXPECT_EQ(s.value(), "many");
    EXPECT_EQ(p.value(), "many");
}
