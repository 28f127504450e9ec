// Species files: the bean, round trips, the strict reader against a corpus of broken files,
// build steps and their expressions, the library folder, and the list/info/validate commands.

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <memory>
#include <sstream>

#include "core/value_text.h"
#include "error_of.h"
#include "library/expression.h"
#include "plantarch/Error.h"
#include "plantarch/PlantArchitecture.h"
#include "plantarch/SpeciesBuild.h"
#include "plantarch/SpeciesIO.h"

using namespace plantarch;
using plantarch::testing::errorOf;

namespace {

const std::string kSourceDir = PLANTARCH_SOURCE_DIR;
const std::string kBeanPath = kSourceDir + "/species/bean.xml";

// A small valid species. Each @MARK@ sits at the end of a line, so a corpus case can insert
// one line of XML there without moving the lines below it.
const std::string kTemplate = R"(<?xml version="1.0" encoding="UTF-8"?>
<plantarch_species format="1">
  <name>mini</name>
  <!-- comments are allowed anywhere -->
  <phenology>
    <max_age>100</max_age>@PHENOLOGY@
  </phenology>
  <build_parameters>
    <parameter name="angle" default="30" min="0" max="90" unit="degrees" doc="tilt"/>@PARAMS@
  </build_parameters>
  <shoot_type label="main">
    <max_nodes>5</max_nodes>@SHOOT@
    <child_shoot_types>
      <type label="main" probability="1"/>@CHILD@
    </child_shoot_types>
    <phytomer>
      <petiole>
        <pitch>30</pitch>@PETIOLE@
      </petiole>
      <leaf>
        <prototype>
          <shape>ovate</shape>@PROTOTYPE@
        </prototype>
      </leaf>
    </phytomer>
  </shoot_type>@TYPES@
  <build>
    <base_stem id="stem" type="main" nodes="3" pitch="angle / 2"/>@STEPS@
  </build>
</plantarch_species>
)";

std::string replaceAll(std::string s, const std::string& from, const std::string& to) {
    for (std::size_t i = 0; (i = s.find(from, i)) != std::string::npos; i += to.size())
        s.replace(i, from.size(), to);
    return s;
}

// The template with `edits` applied (each a literal replacement) and the marks removed.
std::string species(const std::vector<std::pair<std::string, std::string>>& edits = {}) {
    std::string s = kTemplate;
    for (const auto& [from, to] : edits) {
        const std::size_t at = s.find(from);
        EXPECT_NE(at, std::string::npos) << from;
        if (at != std::string::npos) s.replace(at, from.size(), to);
    }
    for (const char* mark : {"@PHENOLOGY@", "@PARAMS@", "@SHOOT@", "@CHILD@", "@PETIOLE@",
                             "@PROTOTYPE@", "@TYPES@", "@STEPS@"})
        s = replaceAll(s, mark, "");
    return s;
}

std::string run(const std::string& command, int* status) {
    std::string out;
    FILE* pipe = popen((command + " 2>&1").c_str(), "r");
    if (!pipe) return out;
    char buffer[4096];
    std::size_t n;
    while ((n = std::fread(buffer, 1, sizeof buffer, pipe)) > 0) out.append(buffer, n);
    const int raw = pclose(pipe);
    *status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
    return out;
}

std::string cli(const std::string& args, int* status) {
    return run("PLANTARCH_SPECIES_DIR='" + kSourceDir + "/species' '" + PLANTARCH_CLI + "' " + args,
               status);
}

std::string tempPath(const std::string& name) {
    return (std::filesystem::temp_directory_path() /
            ("plantarch_species_test_" + std::to_string(::getpid()) + "_" + name))
        .string();
}

void writeFile(const std::string& path, const std::string& text) {
    std::ofstream(path, std::ios::binary) << text;
}

}  // namespace

// ---- the bean ---------------------------------------------------------------------------

TEST(SpeciesBean, LoadsWithTheReferenceNumbers) {
    const SpeciesModel bean = readSpeciesFile(kBeanPath);
    EXPECT_EQ(bean.name, "bean");
    EXPECT_EQ(bean.latinName, "Phaseolus vulgaris");
    EXPECT_EQ(bean.plantType, "herbaceous");
    EXPECT_EQ(bean.recommendedAge, 45.0f);
    EXPECT_EQ(bean.recommendedAgeMin, 10.0f);
    EXPECT_EQ(bean.recommendedAgeMax, 100.0f);
    ASSERT_EQ(bean.shootTypes.size(), 2u);
    const ShootParameters& uni = bean.shootTypes.at("unifoliate");
    const ShootParameters& tri = bean.shootTypes.at("trifoliate");
    EXPECT_EQ(uni.max_nodes, RandomInt(1));
    EXPECT_EQ(tri.max_nodes, RandomInt(25));
    EXPECT_EQ(tri.insertion_angle_tip, RandomFloat::uniform(40, 60));
    EXPECT_EQ(uni.insertion_angle_tip, RandomFloat(50));
    EXPECT_EQ(uni.phytomer_parameters.petiole.petioles_per_internode, 2u);
    EXPECT_EQ(tri.phytomer_parameters.leaf.leaves_per_petiole, RandomInt(3));
    EXPECT_EQ(tri.phytomer_parameters.leaf.pitch, RandomFloat::normal(0, 20));
    EXPECT_EQ(tri.phytomer_parameters.inflorescence.flowers_per_peduncle, RandomInt::uniform(1, 4));
    EXPECT_EQ(tri.phytomer_parameters.internode.color, vec3(0.2f, 0.25f, 0.05f));
    // Inherited from the trifoliate type, which the unifoliate one does not override.
    EXPECT_EQ(uni.phytomer_parameters.peduncle.curvature, RandomFloat::uniform(-500, 500));
    EXPECT_EQ(uni.phytomer_parameters.leaf.prototype.shape, LeafShape::Cordate);
    EXPECT_EQ(tri.phytomer_parameters.leaf.prototype.shape, LeafShape::Ovate);
    EXPECT_EQ(uni.child_shoot_types, (std::map<std::string, float>{{"trifoliate", 1.0f}}));
    EXPECT_EQ(tri.phytomer_parameters.inflorescence.flower_prototype_function,
              "papilionaceous_flower");
    EXPECT_EQ(tri.phytomer_parameters.inflorescence.fruit_prototype_function, "legume_pod");
    EXPECT_EQ(tri.phytomer_parameters.inflorescence.fruit_prototype_parameters.at("seed_count"),
              6.0f);
    EXPECT_EQ(bean.phenology.time_to_flower_initiation, 40.0f);
    EXPECT_EQ(bean.phenology.max_age, 365.0f);
    ASSERT_EQ(bean.build.size(), 2u);
    EXPECT_EQ(bean.build[0].kind, BuildStep::Kind::BaseStem);
    EXPECT_EQ(bean.build[1].kind, BuildStep::Kind::Append);
    EXPECT_EQ(bean.build[1].parent, "stem");
}

TEST(SpeciesBean, BuildsTheSeedling) {
    const SpeciesModel bean = loadSpecies(kBeanPath);
    Context ctx;
    PlantArchitecture arch(&ctx);
    defineSpeciesShootTypes(arch, bean);
    const unsigned plant = arch.addPlantInstance(vec3(0.0f), 0.0f);
    const std::vector<unsigned> shoots = buildInitialStructure(arch, plant, bean);
    ASSERT_EQ(shoots, (std::vector<unsigned>{0, 1}));
    const PlantInstance& p = arch.plant(plant);
    ASSERT_EQ(p.shoots.size(), 2u);
    EXPECT_EQ(p.shoots[0].type, "unifoliate");
    ASSERT_EQ(p.shoots[0].phytomers.size(), 1u);
    EXPECT_EQ(p.shoots[0].phytomers[0].petioles.size(), 2u);  // the opposite primary leaves
    EXPECT_EQ(p.shoots[1].type, "trifoliate");
    EXPECT_EQ(p.shoots[1].parent, 0);
    ASSERT_EQ(p.shoots[1].phytomers.size(), 1u);
    ASSERT_EQ(p.shoots[1].phytomers[0].petioles.size(), 1u);
    EXPECT_EQ(p.shoots[1].phytomers[0].petioles[0].leaves.size(), 3u);
    EXPECT_EQ(arch.getPlantLeafCount(plant), 5u);
    // The base stem: radius 0.0005, internode 0.03 m, emerging at scale 0.01, tilted at most
    // 9 degrees from vertical.
    EXPECT_FLOAT_EQ(p.shoots[0].phytomers[0].internode.radius, 0.0005f);
    EXPECT_FLOAT_EQ(p.shoots[0].phytomers[0].internode.length, 0.03f);
    EXPECT_FLOAT_EQ(p.shoots[0].phytomers[0].internodeFraction, 0.01f);
    EXPECT_GT(p.shoots[0].phytomers[0].internode.guide.z, std::cos(9.01f * 3.14159265f / 180));
    // The appended shoot takes the trifoliate type's radius and internode length.
    EXPECT_FLOAT_EQ(p.shoots[1].phytomers[0].internode.radius, 0.001f);
    // The node rules shorten main-stem internodes made at emergence to 20 % of 0.025 m.
    EXPECT_FLOAT_EQ(p.shoots[1].phytomers[0].internode.length, 0.025f * 0.2f);
    EXPECT_FLOAT_EQ(p.shoots[1].phytomers[0].leafFraction, 0.1f);
    EXPECT_GT(ctx.objectCount(), 0u);
}

TEST(SpeciesBean, SameSeedSameSeedlingOtherSeedOther) {
    const SpeciesModel bean = loadSpecies(kBeanPath);
    auto build = [&](std::uint64_t seed) {
        Context ctx;
        PlantArchitecture arch(&ctx);
        arch.setSeed(seed);
        defineSpeciesShootTypes(arch, bean);
        const unsigned plant = arch.addPlantInstance(vec3(0.0f), 0.0f);
        buildInitialStructure(arch, plant, bean);
        return arch.plant(plant).shoots[0].phytomers[0].internode.guide;
    };
    EXPECT_EQ(build(7), build(7));
    EXPECT_NE(build(7), build(8));
}

TEST(SpeciesBean, LibraryFilesAreNamedAfterTheirSpecies) {
    setenv("PLANTARCH_SPECIES_DIR", (kSourceDir + "/species").c_str(), 1);
    const std::vector<std::string> names = listSpecies();
    ASSERT_FALSE(names.empty());
    for (const std::string& name : names) EXPECT_EQ(loadSpecies(name).name, name);
}

// The library's files are XML that any XML tool reads: no comment holds "--", which the XML
// specification forbids there (plantarch's reader lets it pass; xmllint does not).
TEST(SpeciesBean, LibraryFilesHoldNoDoubleHyphenInAComment) {
    for (const auto& entry : std::filesystem::directory_iterator(kSourceDir + "/species")) {
        if (entry.path().extension() != ".xml") continue;
        std::ifstream in(entry.path());
        const std::string text((std::istreambuf_iterator<char>(in)), {});
        for (std::size_t open = text.find("<!--"); open != std::string::npos;
             open = text.find("<!--", open + 4)) {
            const std::size_t close = text.find("-->", open + 4);
            ASSERT_NE(close, std::string::npos) << entry.path() << ": a comment never closed";
            const std::string body = text.substr(open + 4, close - open - 4);
            const auto line = 1 + std::count(text.begin(), text.begin() + open, '\n');
            EXPECT_EQ(body.find("--"), std::string::npos)
                << entry.path() << ":" << line << ": the comment starting here holds \"--\"";
        }
    }
}

// ---- round trips ------------------------------------------------------------------------

TEST(SpeciesRoundTrip, BeanWritesAndReadsBackIdentically) {
    const SpeciesModel bean = readSpeciesFile(kBeanPath);
    for (bool comments : {true, false}) {
        const std::string first = writeSpeciesString(bean, {.comments = comments});
        const SpeciesModel again = readSpeciesString(first, "written.xml");
        EXPECT_EQ(writeSpeciesString(again, {.comments = comments}), first);
        EXPECT_EQ(again.shootTypes.at("trifoliate").phytomer_parameters.leaf.pitch,
                  bean.shootTypes.at("trifoliate").phytomer_parameters.leaf.pitch);
    }
}

TEST(SpeciesRoundTrip, EveryKindOfValue) {
    const std::string rich = species(
        {{"@SHOOT@",
          "<max_nodes_per_season>discrete(2, 3, 5)</max_nodes_per_season>"
          "<tortuosity>normal(2, 0.5)</tortuosity>"},
         {"@PETIOLE@", "<curvature>normal(0.1, 1e-07)</curvature><color>1 0 0.333333343</color>"},
         {"@PROTOTYPE@",
          "<leaf_texture_file><image leaflet=\"-1\">left &amp; right.png</image>"
          "<image leaflet=\"0\">tip.png</image></leaf_texture_file>"
          "<lobes>uniform(0, 3)</lobes><build_petiolule>true</build_petiolule>"},
         {"@TYPES@",
          "<shoot_type label=\"side\" inherits=\"main\"><phytomer><inflorescence>"
          "<flower_prototype_parameters><param name=\"petals\">5</param>"
          "<param name=\"cup\">0.25</param></flower_prototype_parameters>"
          "</inflorescence></phytomer></shoot_type>"},
         {"<type label=\"main\" probability=\"1\"/>",
          "<type label=\"main\" probability=\"0.25\"/><type label=\"side\" probability=\"0.75\"/>"},
         {"@STEPS@",
          "<child id=\"b\" parent=\"stem\" node=\"i\" petiole=\"0\" repeat=\"2\" type=\"side\" "
          "nodes=\"1 + i\" yaw=\"uniform(0, 360)\" radius=\"0.002 * (1 - i / 4)\"/>"}});
    const SpeciesModel m = readSpeciesString(rich, "rich.xml");
    const ShootParameters& side = m.shootTypes.at("side");
    EXPECT_EQ(side.max_nodes_per_season, RandomInt::discrete({2, 3, 5}));
    EXPECT_EQ(side.tortuosity, RandomFloat::normal(2.0f, 0.5f));
    EXPECT_EQ(side.phytomer_parameters.leaf.prototype.leaf_texture_file.at(-1), "left & right.png");
    EXPECT_EQ(side.phytomer_parameters.inflorescence.flower_prototype_parameters.at("cup"), 0.25f);
    EXPECT_TRUE(m.shootTypes.at("main")
                    .phytomer_parameters.inflorescence.flower_prototype_parameters.empty());
    const std::string first = writeSpeciesString(m);
    const SpeciesModel again = readSpeciesString(first, "again.xml");
    EXPECT_EQ(writeSpeciesString(again), first);
    EXPECT_EQ(again.shootTypes.at("side").phytomer_parameters.petiole.curvature,
              RandomFloat::normal(0.1f, 1e-7f));
    EXPECT_EQ(again.buildParameters.size(), 1u);
    EXPECT_EQ(again.buildParameters[0].doc, "tilt");
}

TEST(SpeciesRoundTrip, DefaultsMadeInCodeAreWrittenCompletely) {
    SpeciesModel m;
    m.name = "defaults";
    m.shootTypes["stem"] = ShootParameters{};
    BuildStep step;
    step.shootType = "stem";
    m.build.push_back(step);
    const std::string text = writeSpeciesString(m);
    EXPECT_NE(text.find("<radial_subdivisions>7</radial_subdivisions>"), std::string::npos);
    EXPECT_NE(text.find("<serration_depth>0</serration_depth>"), std::string::npos);
    EXPECT_NE(text.find("<time_to_fruit_set>-1</time_to_fruit_set>"), std::string::npos);
    const SpeciesModel back = readSpeciesString(text, "defaults.xml");
    EXPECT_EQ(writeSpeciesString(back), text);
}

TEST(SpeciesRoundTrip, NumbersInShortestPlainForm) {
    EXPECT_EQ(text::formatFloat(0.0001f), "0.0001");
    EXPECT_EQ(text::formatFloat(1e6f), "1000000");
    EXPECT_EQ(text::formatFloat(0.1f), "0.1");
    EXPECT_EQ(text::formatFloat(1e-9f), "1e-09");
    for (float v : {0.1f, 1.0f / 3.0f, 3.4028235e38f, 1.17549435e-38f, -2.5e-7f, 123456.79f})
        EXPECT_EQ(text::parseFloat(text::formatFloat(v)), v);
}

TEST(SpeciesRoundTrip, RandomValuesAsText) {
    for (const char* t : {"20", "uniform(10, 30)", "normal(0, 5)", "weibull(1.5, 2)",
                          "uniform(-0.3, -0.2)", "0.0001"})
        EXPECT_EQ(text::formatRandomFloat(text::parseRandomFloat(t)), t);
    EXPECT_EQ(text::parseRandomFloat(" uniform( 1,2 ) "), RandomFloat::uniform(1, 2));
    for (const char* t : {"3", "-2", "uniform(1, 4)", "discrete(2, 5, 11)"})
        EXPECT_EQ(text::parseRandomInt(t).describe(), t);
}

// ---- the strict reader: a corpus of broken files ---------------------------------------

struct BrokenCase {
    std::string name;
    std::string xml;
    int line;
    std::vector<std::string> mentions;
};

std::vector<BrokenCase> brokenCorpus() {
    return {
        // Unknown and misspelt keys at every level: the path, and the valid names nearby.
        {"unknown top level",
         species({{"<name>mini</name>", "<name>mini</name><nmae/>"}}),
         3,
         {"nmae", "did you mean <name>", "shoot_type", "build_parameters"}},
        {"unknown phenology key",
         species({{"@PHENOLOGY@", "<max_ag>3</max_ag>"}}),
         6,
         {"phenology.max_ag", "did you mean <max_age>", "time_to_fruit_set"}},
        {"unknown shoot key",
         species({{"@SHOOT@", "<max_node>3</max_node>"}}),
         12,
         {"main.max_node", "did you mean <max_nodes>", "phyllochron_min"}},
        {"unknown phytomer group",
         species({{"<petiole>", "<petiol>"}, {"</petiole>", "</petiol>"}}),
         17,
         {"main.phytomer.petiol", "did you mean <petiole>", "internode", "inflorescence"}},
        {"misspelt petiole key",
         species({{"@PETIOLE@", "<pitchh>3</pitchh>"}}),
         18,
         {"main.phytomer.petiole.pitchh", "did you mean <pitch>", "petioles_per_internode",
          "radial_subdivisions"}},
        {"unknown key, nothing close",
         species({{"@PETIOLE@", "<zzzzzzzz>3</zzzzzzzz>"}}),
         18,
         {"main.phytomer.petiole.zzzzzzzz", "unknown element", "petioles_per_internode"}},
        {"unknown prototype key",
         species({{"@PROTOTYPE@", "<shap>ovate</shap>"}}),
         22,
         {"main.phytomer.leaf.prototype.shap", "did you mean <shape>", "leaf_aspect_ratio"}},
        {"unknown attribute on a value",
         species({{"<pitch>30</pitch>", "<pitch unit=\"deg\">30</pitch>"}}),
         18,
         {"main.phytomer.petiole.pitch.unit", "unknown attribute 'unit'", "no attributes"}},
        {"unknown shoot type attribute",
         species({{"<shoot_type label=\"main\">", "<shoot_type label=\"main\" lable=\"x\">"}}),
         11,
         {"lable", "did you mean 'label'"}},
        {"unknown build step attribute",
         species({{"@STEPS@", "<append parent=\"stem\" type=\"main\" pich=\"3\"/>"}}),
         28,
         {"build.append[2].pich", "did you mean 'pitch'", "internode_scale"}},
        {"unknown build step kind",
         species({{"@STEPS@", "<branch/>"}}),
         28,
         {"build.branch", "one of: base_stem, append, child"}},
        {"unknown map element",
         species({{"<type label=\"main\" probability=\"1\"/>",
                   "<child label=\"main\" probability=\"1\"/>"}}),
         14,
         {"main.child_shoot_types.child", "one of: type"}},
        {"unknown root attribute",
         species({{"<plantarch_species format=\"1\">",
                   "<plantarch_species format=\"1\" version=\"2\">"}}),
         2,
         {"version", "unknown attribute"}},
        // Missing required values.
        {"missing name",
         species({{"<name>mini</name>", ""}}),
         2,
         {"missing required element <name>"}},
        {"missing label",
         species({{"<shoot_type label=\"main\">", "<shoot_type>"}}),
         11,
         {"missing required attribute 'label'"}},
        {"empty label",
         species({{"<shoot_type label=\"main\">", "<shoot_type label=\"\">"}}),
         11,
         {"shoot type label"}},
        {"missing step type",
         species({{"@STEPS@", "<append parent=\"stem\"/>"}}),
         28,
         {"missing required attribute 'type'"}},
        {"missing step parent",
         species({{"@STEPS@", "<append type=\"main\"/>"}}),
         28,
         {"missing required attribute 'parent'"}},
        {"missing child node",
         species({{"@STEPS@", "<child parent=\"stem\" type=\"main\"/>"}}),
         28,
         {"missing required attribute 'node'"}},
        {"missing format",
         species({{" format=\"1\"", ""}}),
         2,
         {"missing required attribute 'format'"}},
        {"unsupported format",
         species({{"format=\"1\"", "format=\"7\""}}),
         2,
         {"unsupported species file format", "7"}},
        {"missing build",
         species({{"<build>", "<!--"}, {"</build>", "-->"}}),
         2,
         {"missing required element <build>"}},
        {"first step not a base stem",
         species({{"<base_stem id=\"stem\" type=\"main\" nodes=\"3\" pitch=\"angle / 2\"/>",
                   "<append parent=\"x\" type=\"main\"/>"}}),
         28,
         {"first build step must be a <base_stem>"}},
        {"no shoot type",
         species({{"<shoot_type label=\"main\">", "<!--"}, {"</shoot_type>", "-->"}}),
         2,
         {"at least one <shoot_type>"}},
        // Wrong types and malformed distributions.
        {"text for a float",
         species({{"@SHOOT@", "<internode_length_max>abc</internode_length_max>"}}),
         12,
         {"main.internode_length_max = abc", "expected a number or a distribution"}},
        {"bool for a number",
         species({{"<max_nodes>5</max_nodes>", "<max_nodes>true</max_nodes>"}}),
         12,
         {"main.max_nodes = true", "expected a whole number"}},
        {"fraction for an integer",
         species({{"<max_nodes>5</max_nodes>", "<max_nodes>5.5</max_nodes>"}}),
         12,
         {"main.max_nodes = 5.5", "whole number"}},
        {"negative unsigned",
         species({{"@PETIOLE@", "<radial_subdivisions>-3</radial_subdivisions>"}}),
         18,
         {"radial_subdivisions = -3", "expected a whole number >= 0"}},
        {"number for a bool",
         species({{"@PROTOTYPE@", "<build_petiolule>1</build_petiolule>"}}),
         22,
         {"build_petiolule = 1", "expected true or false"}},
        {"two numbers for a colour",
         species({{"@PETIOLE@", "<color>0.2 0.3</color>"}}),
         18,
         {"main.phytomer.petiole.color = 0.2 0.3", "expected three numbers"}},
        {"uniform with one argument",
         species({{"<pitch>30</pitch>", "<pitch>uniform(3)</pitch>"}}),
         18,
         {"main.phytomer.petiole.pitch = uniform(3)",
          "uniform takes 2 arguments (min, max), got 1"}},
        {"misspelt distribution",
         species({{"<pitch>30</pitch>", "<pitch>unifrom(1, 2)</pitch>"}}),
         18,
         {"unknown distribution 'unifrom'", "did you mean 'uniform'"}},
        {"distribution without closing parenthesis",
         species({{"<pitch>30</pitch>", "<pitch>normal(0, 5</pitch>"}}),
         18,
         {"missing ')'"}},
        {"distribution argument not a number",
         species({{"<pitch>30</pitch>", "<pitch>normal(0, x)</pitch>"}}),
         18,
         {"argument 2 of normal is not a number"}},
        {"uniform min above max",
         species({{"<pitch>30</pitch>", "<pitch>uniform(5, 1)</pitch>"}}),
         18,
         {"min must not exceed max"}},
        {"integer distribution with fractions",
         species({{"<max_nodes>5</max_nodes>", "<max_nodes>uniform(1.5, 4)</max_nodes>"}}),
         12,
         {"argument 1 of uniform is not a whole number"}},
        {"elements inside a value",
         species({{"<pitch>30</pitch>", "<pitch><a/></pitch>"}}),
         18,
         {"holds a value, not elements"}},
        {"text inside a group",
         species({{"<petiole>", "<petiole>5"}}),
         17,
         {"unexpected text inside <petiole>"}},
        // Out of range: the declared range is in the message.
        {"out of range",
         species({{"<pitch>30</pitch>", "<pitch>200</pitch>"}}),
         18,
         {"main.phytomer.petiole.pitch = 200", "out of range", "-180 to 180"}},
        {"distribution out of range",
         species({{"<pitch>30</pitch>", "<pitch>uniform(0, 500)</pitch>"}}),
         18,
         {"main.phytomer.petiole.pitch = uniform(0, 500)", "-180 to 180"}},
        {"unsigned out of range",
         species({{"@PETIOLE@", "<radial_subdivisions>2</radial_subdivisions>"}}),
         18,
         {"radial_subdivisions = 2", "3 to 100"}},
        {"phenology out of range",
         species({{"@PHENOLOGY@", "<time_to_fruit_set>-5</time_to_fruit_set>"}}),
         6,
         {"phenology.time_to_fruit_set = -5", "out of range (valid: -1 to "}},
        {"unknown choice",
         species({{"<shape>ovate</shape>", "<shape>cordat</shape>"}}),
         22,
         {"main.phytomer.leaf.prototype.shape = cordat", "did you mean 'cordate'", "elliptic"}},
        {"unknown plant type",
         species({{"<name>mini</name>", "<name>mini</name><plant_type>bush</plant_type>"}}),
         3,
         {"plant_type = bush", "herbaceous, weed, tree"}},
        {"minimum above maximum",
         species({{"@SHOOT@", "<internode_length_min>0.5</internode_length_min>"}}),
         12,
         {"main.internode_length_min", "exceeds internode_length_max"}},
        {"recommended age default outside its range",
         species({{"<name>mini</name>",
                   "<name>mini</name><recommended_age min=\"10\" max=\"20\" default=\"30\"/>"}}),
         3,
         {"recommended_age.default = 30", "10 to 20 days"}},
        {"build parameter default outside its range",
         species({{"default=\"30\" min=\"0\" max=\"90\"", "default=\"100\" min=\"0\" max=\"90\""}}),
         9,
         {"build_parameters.angle.default = 100", "0 to 90"}},
        {"reserved build parameter name",
         species({{"@PARAMS@", "<parameter name=\"pi\" default=\"1\" min=\"0\" max=\"2\"/>"}}),
         9,
         {"build_parameters.pi", "reserved name"}},
        // Child shoot probabilities and references.
        {"probabilities not summing to 1",
         species({{"<type label=\"main\" probability=\"1\"/>",
                   "<type label=\"main\" probability=\"0.5\"/>"}}),
         13,
         {"main.child_shoot_types", "sum to 1"}},
        {"probability above 1",
         species({{"<type label=\"main\" probability=\"1\"/>",
                   "<type label=\"main\" probability=\"1.5\"/>"}}),
         14,
         {"main.child_shoot_types.main = 1.5", "0 to 1"}},
        {"unknown child type",
         species({{"<type label=\"main\" probability=\"1\"/>",
                   "<type label=\"mian\" probability=\"1\"/>"}}),
         14,
         {"main.child_shoot_types.mian", "unknown shoot type 'mian'", "did you mean 'main'"}},
        {"unknown inherited type",
         species({{"@TYPES@", "<shoot_type label=\"side\" inherits=\"stem\"/>"}}),
         26,
         {"side.inherits = stem", "unknown shoot type 'stem'", "one of: main"}},
        {"unknown build shoot type",
         species({{"@STEPS@", "<append parent=\"stem\" type=\"side\"/>"}}),
         28,
         {"build.append[2].type = side", "unknown shoot type", "one of: main"}},
        {"unknown build parent",
         species({{"@STEPS@", "<append parent=\"stme\" type=\"main\"/>"}}),
         28,
         {"build.append[2].parent = stme", "did you mean 'stem'"}},
        {"bad expression",
         species({{"pitch=\"angle / 2\"", "pitch=\"angle / (2 +\""}}),
         28,
         {"build.stem.pitch = angle / (2 +", "bad expression", "column"}},
        {"unknown name in an expression",
         species({{"pitch=\"angle / 2\"", "pitch=\"angel / 2\""}}),
         28,
         {"build.stem.pitch", "unknown name 'angel'", "did you mean 'angle'"}},
        {"unknown function in an expression",
         species({{"pitch=\"angle / 2\"", "pitch=\"unifrom(0, 1)\""}}),
         28,
         {"unknown function 'unifrom'", "did you mean 'uniform'"}},
        // Duplicates.
        {"duplicate element",
         species({{"@SHOOT@", "<max_nodes>7</max_nodes>"}}),
         12,
         {"main.max_nodes", "duplicate element <max_nodes> (first at line 12)"}},
        {"duplicate group",
         species({{"</phytomer>", "<petiole/></phytomer>"}}),
         25,
         {"main.phytomer.petiole", "duplicate element <petiole> (first at line 17)"}},
        {"duplicate shoot type",
         species({{"@TYPES@", "<shoot_type label=\"main\"/>"}}),
         26,
         {"duplicate shoot type 'main' (first at line 11)"}},
        {"duplicate step id",
         species({{"@STEPS@", "<append id=\"stem\" parent=\"stem\" type=\"main\"/>"}}),
         28,
         {"duplicate step id 'stem'"}},
        {"duplicate map key",
         species({{"@PROTOTYPE@",
                   "<leaf_texture_file><image leaflet=\"0\">a.png</image>"
                   "<image leaflet=\"0\">b.png</image></leaf_texture_file>"}}),
         22,
         {"leaf_texture_file.0", "duplicate leaflet '0'"}},
        {"duplicate build parameter",
         species({{"@PARAMS@", "<parameter name=\"angle\" default=\"1\" min=\"0\" max=\"2\"/>"}}),
         9,
         {"duplicate build parameter 'angle' (first at line 9)"}},
        {"duplicate attribute",
         species({{"nodes=\"3\"", "nodes=\"3\" nodes=\"4\""}}),
         28,
         {"duplicate attribute 'nodes'"}},
        // Not a species file at all.
        {"truncated XML",
         species().substr(0, species().find("</phytomer>")),
         25,
         {"malformed XML", "ends too early"}},
        {"mismatched tags", species({{"</petiole>", "</petioles>"}}), 19, {"malformed XML"}},
        {"empty file", "", 1, {"empty file"}},
        {"blank file", "  \n\n  ", 1, {"empty file"}},
        {"not XML", "name = bean\nshoot types: unifoliate, trifoliate\n", 1, {"not an XML file"}},
        {"another XML document",
         "<?xml version=\"1.0\"?>\n<svg width=\"3\"/>\n",
         2,
         {"not a species file", "<svg>", "<plantarch_species>"}},
        {"two root elements", species() + "<plantarch_species/>\n", 31, {"second root element"}},
    };
}

TEST(SpeciesReader, CorpusOfBrokenFiles) {
    for (const BrokenCase& c : brokenCorpus()) {
        SCOPED_TRACE(c.name);
        const Error e = errorOf([&] { readSpeciesString(c.xml, "broken.xml"); });
        const std::string what = e.what();
        EXPECT_EQ(what.find('\n'), std::string::npos) << what;
        EXPECT_EQ(what.rfind("broken.xml:" + std::to_string(c.line) + ": ", 0), 0u) << what;
        EXPECT_EQ(e.file(), "broken.xml");
        EXPECT_EQ(e.line(), c.line) << what;
        for (const std::string& m : c.mentions)
            EXPECT_NE(what.find(m), std::string::npos) << "missing '" << m << "' in: " << what;
    }
}

// Random damage to a valid file gives a clean one-line error (or a valid file), never a crash
// or another exception.
TEST(SpeciesReader, DamagedFilesGiveCleanErrors) {
    std::ifstream in(kBeanPath);
    std::stringstream buffer;
    buffer << in.rdbuf();
    const std::string bean = buffer.str();
    const std::string alphabet = "<>/=\"' \n()-,.0123456789abcdefghijklmnopqrstuvwxyz_&!?";
    Rng rng(2024);
    for (int k = 0; k < 400; ++k) {
        std::string damaged = bean;
        const int edits = 1 + rng.uniformInt(0, 3);
        for (int e = 0; e < edits; ++e) {
            const auto at = std::size_t(rng.uniformInt(0, int(damaged.size()) - 1));
            const char c = alphabet[std::size_t(rng.uniformInt(0, int(alphabet.size()) - 1))];
            switch (rng.uniformInt(0, 2)) {
                case 0:
                    damaged.erase(at, std::size_t(rng.uniformInt(1, 8)));
                    break;
                case 1:
                    damaged.insert(at, 1, c);
                    break;
                default:
                    damaged[at] = c;
            }
        }
        try {
            // What still reads must also define and build, or fail cleanly.
            const SpeciesModel m = readSpeciesString(damaged, "damaged.xml");
            Context ctx;
            PlantArchitecture arch(&ctx);
            defineSpeciesShootTypes(arch, m);
            buildInitialStructure(arch, arch.addPlantInstance(vec3(0.0f), 0.0f), m);
        } catch (const Error& e) {
            const std::string what = e.what();
            EXPECT_EQ(what.rfind("damaged.xml:", 0), 0u) << what;
            EXPECT_GT(e.line(), 0) << what;
            EXPECT_EQ(what.find('\n'), std::string::npos) << what;
        } catch (const std::exception& e) {
            ADD_FAILURE() << "not a plantarch::Error: " << e.what();
        }
    }
}

TEST(SpeciesReader, TheTemplateItselfIsValid) {
    const SpeciesModel m = readSpeciesString(species(), "mini.xml");
    EXPECT_EQ(m.name, "mini");
    EXPECT_EQ(m.shootTypes.at("main").max_nodes, RandomInt(5));
    EXPECT_EQ(m.shootTypes.at("main").phytomer_parameters.petiole.pitch, RandomFloat(30));
    // Fields not given keep the struct defaults.
    EXPECT_EQ(m.shootTypes.at("main").phyllochron_min, ShootParameters{}.phyllochron_min);
    EXPECT_EQ(m.lines.at("main.phytomer.petiole.pitch"), 18);
}

TEST(SpeciesReader, ErrorsNameTheFile) {
    const Error missing = errorOf([] { readSpeciesFile("/nonexistent/dir/x.xml"); });
    EXPECT_EQ(missing.file(), "/nonexistent/dir/x.xml");
    const std::string path = tempPath("broken.xml");
    writeFile(path, species({{"<pitch>30</pitch>", "<pitch>300</pitch>"}}));
    const Error e = errorOf([&] { readSpeciesFile(path); });
    EXPECT_EQ(std::string(e.what()).rfind(path + ":18: ", 0), 0u) << e.what();
    std::filesystem::remove(path);
}

TEST(SpeciesReader, WindowsLineEndingsKeepLineNumbers) {
    const std::string crlf =
        replaceAll(species({{"@PETIOLE@", "<pitchh>3</pitchh>"}}), "\n", "\r\n");
    EXPECT_EQ(errorOf([&] { readSpeciesString(crlf, "crlf.xml"); }).line(), 18);
    EXPECT_EQ(readSpeciesString(replaceAll(species(), "\n", "\r\n"), "crlf.xml").name, "mini");
}

TEST(SpeciesReader, ValuesAreTrimmedAndCommentsIgnored) {
    const SpeciesModel m = readSpeciesString(
        species({{"<pitch>30</pitch>", "<pitch>\n  uniform( 10 ,20 ) <!-- why --> \n</pitch>"}}),
        "x.xml");
    EXPECT_EQ(m.shootTypes.at("main").phytomer_parameters.petiole.pitch,
              RandomFloat::uniform(10, 20));
}

// ---- building from steps ----------------------------------------------------------------

namespace {

// A straight species whose build makes branches with repeat and fan-out.
std::string branchingSpecies() {
    return species(
        {{"@PARAMS@", "<parameter name=\"branches\" default=\"2\" min=\"0\" max=\"4\"/>"},
         {"@SHOOT@", "<phytomer><internode><pitch>0</pitch></internode></phytomer>"},
         {"<phytomer>\n      <petiole>", "<!--"},
         {"</leaf>\n    </phytomer>", "-->"},
         {"@STEPS@",
          "<child id=\"branch\" parent=\"stem\" node=\"i\" repeat=\"branches\" type=\"main\" "
          "nodes=\"2\" internode_scale=\"0.5\"/>"
          "<child id=\"twig\" parent=\"branch\" node=\"min(parent_i, 1)\" type=\"main\" "
          "nodes=\"1\"/>"}});
}

struct Built {
    std::unique_ptr<Context> ctx = std::make_unique<Context>();
    std::unique_ptr<PlantArchitecture> arch = std::make_unique<PlantArchitecture>(ctx.get());
    unsigned plant = 0;
    std::vector<unsigned> shoots;
};

Built buildFrom(const SpeciesModel& m, const std::map<std::string, float>& overrides = {}) {
    Built b;
    defineSpeciesShootTypes(*b.arch, m);
    b.plant = b.arch->addPlantInstance(vec3(0.0f), 0.0f);
    b.shoots = buildInitialStructure(*b.arch, b.plant, m, overrides);
    return b;
}

}  // namespace

TEST(SpeciesBuild, RepeatAndFanOut) {
    const SpeciesModel m = readSpeciesString(branchingSpecies(), "branching.xml");
    const Built b = buildFrom(m);
    // stem, 2 branches at nodes 0 and 1, one twig on each branch at node parent_i.
    ASSERT_EQ(b.shoots.size(), 5u);
    const PlantInstance& p = b.arch->plant(b.plant);
    EXPECT_EQ(p.shoots[1].parent, 0);
    EXPECT_EQ(p.shoots[1].parentNode, 0);
    EXPECT_EQ(p.shoots[2].parentNode, 1);
    EXPECT_EQ(p.shoots[1].phytomers.size(), 2u);
    EXPECT_FLOAT_EQ(p.shoots[1].phytomers[0].internodeFraction, 0.5f);
    EXPECT_EQ(p.shoots[3].parent, 1);
    EXPECT_EQ(p.shoots[3].parentNode, 0);
    EXPECT_EQ(p.shoots[4].parent, 2);
    EXPECT_EQ(p.shoots[4].parentNode, 1);
    // The base stem's pitch is angle / 2 = 15 degrees.
    EXPECT_NEAR(p.shoots[0].phytomers[0].internode.guide.z, std::cos(15.0f * 3.14159265f / 180),
                1e-5f);
}

TEST(SpeciesBuild, OverridesAreValidatedAndHonoured) {
    const SpeciesModel m = readSpeciesString(branchingSpecies(), "branching.xml");
    EXPECT_EQ(buildFrom(m, {{"branches", 3}}).shoots.size(), 7u);
    EXPECT_EQ(buildFrom(m, {{"branches", 0}}).shoots.size(), 1u);
    const Error unknown = errorOf([&] { buildFrom(m, {{"branch", 3}}); });
    EXPECT_EQ(unknown.parameter(), "branch");
    EXPECT_NE(std::string(unknown.what()).find("did you mean 'branches'"), std::string::npos);
    EXPECT_EQ(unknown.validRange(), "one of: angle, branches");
    const Error range = errorOf([&] { buildFrom(m, {{"angle", 120}}); });
    EXPECT_EQ(range.parameter(), "angle");
    EXPECT_EQ(range.value(), "120");
    EXPECT_EQ(range.validRange(), "0 to 90 degrees");
    const Error none = errorOf([&] { buildFrom(loadSpecies(kBeanPath), {{"trunk_height", 1}}); });
    EXPECT_EQ(none.validRange(), "the species has no build parameters");
}

TEST(SpeciesBuild, StepFlagsStripLeavesBudsAndApex) {
    // A trained trunk: bare, without buds, headed; a branch on it keeps everything.
    const SpeciesModel m = readSpeciesString(
        species({{"<base_stem id=\"stem\" type=\"main\" nodes=\"3\" pitch=\"angle / 2\"/>",
                  "<base_stem id=\"stem\" type=\"main\" nodes=\"3\" leaves=\"false\" "
                  "vegetative_buds=\"false\" floral_buds=\"false\" apex=\"false\"/>"
                  "<child parent=\"stem\" node=\"2\" type=\"main\" nodes=\"1\"/>"}}),
        "trunk.xml");
    EXPECT_FALSE(m.build[0].leaves);
    EXPECT_TRUE(m.build[1].apex);
    Built b = buildFrom(m);
    const PlantInstance& p = b.arch->plant(b.plant);
    const Shoot& trunk = p.shoots[0];
    for (const Phytomer& ph : trunk.phytomers)
        for (const Petiole& pt : ph.petioles) {
            EXPECT_EQ(pt.object, kNoObject);  // no petiole drawn
            for (const LeafOrgan& l : pt.leaves) {
                EXPECT_TRUE(l.removed);
                EXPECT_TRUE(l.objects.empty());
            }
            for (const VegetativeBud& vb : pt.vegetativeBuds)
                EXPECT_TRUE(vb.state == BudState::Dead || vb.state == BudState::Broken);
            for (const FloralBud& fb : pt.floralBuds) EXPECT_EQ(fb.state, BudState::Dead);
        }
    EXPECT_EQ(trunk.apicalBud.state, BudState::Dead);
    const Shoot& branch = p.shoots[1];
    EXPECT_NE(branch.phytomers[0].petioles[0].object, kNoObject);
    EXPECT_FALSE(branch.phytomers[0].petioles[0].leaves[0].removed);
    b.arch->advanceTime(40.0);
    const PlantInstance& grown = b.arch->plant(b.plant);
    EXPECT_EQ(grown.shoots[0].phytomers.size(), 3u);  // headed: no new trunk nodes
    EXPECT_GT(grown.shoots[1].phytomers.size(), 1u);  // the branch grows on
    for (const Shoot& s : grown.shoots) EXPECT_TRUE(s.parent != 0 || s.parentNode == 2);
    // The flags are written back by the writer and must be true or false.
    std::ostringstream out;
    writeSpecies(m, out);
    EXPECT_NE(out.str().find("leaves=\"false\""), std::string::npos);
    const Error bad = errorOf([&] {
        readSpeciesString(species({{"nodes=\"3\" pitch", "nodes=\"3\" apex=\"no\" pitch"}}),
                          "bad.xml");
    });
    EXPECT_EQ(bad.parameter(), "build.stem.apex");
    EXPECT_EQ(bad.validRange(), "true, false");
}

TEST(SpeciesBuild, BuildTimeErrorsPointAtTheStep) {
    // Node 9 does not exist on a 3-node stem: found when building, reported at the step.
    const SpeciesModel m = readSpeciesString(
        species({{"@STEPS@", "<child id=\"c\" parent=\"stem\" node=\"9\" type=\"main\"/>"}}),
        "steps.xml");
    const Error e = errorOf([&] { buildFrom(m); });
    EXPECT_EQ(e.file(), "steps.xml");
    EXPECT_EQ(e.line(), 28);
    EXPECT_EQ(e.parameter(), "build.c.node");
    EXPECT_NE(std::string(e.what()).find("0 to 2"), std::string::npos) << e.what();

    const SpeciesModel zero = readSpeciesString(
        species({{"pitch=\"angle / 2\"", "pitch=\"1 / (angle - 30)\""}}), "zero.xml");
    const Error div = errorOf([&] { buildFrom(zero); });
    EXPECT_EQ(div.parameter(), "build.stem.pitch");
    EXPECT_NE(std::string(div.what()).find("division by zero"), std::string::npos);

    const SpeciesModel scale =
        readSpeciesString(species({{"pitch=\"angle / 2\"", "leaf_scale=\"2\""}}), "scale.xml");
    const Error s = errorOf([&] { buildFrom(scale); });
    EXPECT_EQ(s.parameter(), "build.stem.leaf_scale");
    EXPECT_EQ(s.line(), 28);
}

TEST(SpeciesBuild, UnregisteredFunctionsNameTheFile) {
    const SpeciesModel m = readSpeciesString(
        species({{"@PROTOTYPE@", "<prototype_function>fancy</prototype_function>"}}), "fn.xml");
    Context ctx;
    PlantArchitecture arch(&ctx);
    const Error e = errorOf([&] { defineSpeciesShootTypes(arch, m); });
    EXPECT_EQ(e.file(), "fn.xml");
    EXPECT_EQ(e.line(), 22);
    EXPECT_EQ(e.parameter(), "main.phytomer.leaf.prototype.prototype_function");
}

TEST(SpeciesExpression, Arithmetic) {
    Rng rng(1);
    const std::map<std::string, double> vars = {{"h", 1.5}, {"i", 2}};
    EXPECT_DOUBLE_EQ(expr::evaluate("1 + 2 * 3", vars, rng), 7);
    EXPECT_DOUBLE_EQ(expr::evaluate("(1 + 2) * 3", vars, rng), 9);
    EXPECT_DOUBLE_EQ(expr::evaluate("-h / 0.5 - -1", vars, rng), -2);
    EXPECT_DOUBLE_EQ(expr::evaluate("8 / 4 / 2", vars, rng), 1);
    EXPECT_DOUBLE_EQ(expr::evaluate("10 - 4 - 3", vars, rng), 3);
    EXPECT_DOUBLE_EQ(expr::evaluate("90 + i * 360 / 4", vars, rng), 270);
    EXPECT_DOUBLE_EQ(expr::evaluate("max(1, h, 0) + min(3, 2) + floor(2.7) + ceil(0.2)", vars, rng),
                     6.5);
    EXPECT_DOUBLE_EQ(expr::evaluate("round(2.5) + abs(-1) + 1e-1", vars, rng), 4.1);
    EXPECT_NEAR(expr::evaluate("2 * pi", vars, rng), 6.283185307, 1e-9);
    for (int k = 0; k < 100; ++k) {
        const double u = expr::evaluate("uniform(h, 2 * h)", vars, rng);
        EXPECT_GE(u, 1.5);
        EXPECT_LT(u, 3.0);
    }
    Rng a(5), b(5);
    EXPECT_EQ(expr::evaluate("normal(0, 1) + uniform(0, 1)", vars, a),
              expr::evaluate("normal(0, 1) + uniform(0, 1)", vars, b));
}

TEST(SpeciesExpression, Errors) {
    Rng rng(1);
    const std::map<std::string, double> vars = {{"height", 1.5}};
    auto message = [&](const std::string& text) {
        return std::string(errorOf([&] { expr::evaluate(text, vars, rng); }).what());
    };
    EXPECT_NE(message("").find("empty expression"), std::string::npos);
    EXPECT_NE(message("1 +").find("text ended"), std::string::npos);
    EXPECT_NE(message("(1 + 2").find("expected ')'"), std::string::npos);
    EXPECT_NE(message("2 3").find("unexpected '3'"), std::string::npos);
    EXPECT_NE(message("hieght").find("did you mean 'height'"), std::string::npos);
    EXPECT_NE(message("uniform(1)").find("uniform takes 2 arguments"), std::string::npos);
    EXPECT_NE(message("uniform(2, 1)").find("min exceeds max"), std::string::npos);
    EXPECT_NE(message("1 / 0").find("division by zero at column 5"), std::string::npos);
    EXPECT_NE(message("sqrt(4)").find("unknown function 'sqrt'"), std::string::npos);
    EXPECT_NE(message("max").find("needs arguments"), std::string::npos);
    EXPECT_NO_THROW(expr::check("1 / (i - i) + uniform(0, 1)", {"i"}));
    EXPECT_THROW(expr::check("j", {"i"}), Error);
}

// ---- the library --------------------------------------------------------------------------

TEST(SpeciesLibrary, FindsAndListsTheLibrary) {
    setenv("PLANTARCH_SPECIES_DIR", (kSourceDir + "/species").c_str(), 1);
    EXPECT_EQ(speciesLibraryDirectory(), kSourceDir + "/species");
    const std::vector<std::string> names = listSpecies();
    EXPECT_NE(std::find(names.begin(), names.end(), "bean"), names.end());
    EXPECT_TRUE(std::is_sorted(names.begin(), names.end()));
    EXPECT_EQ(loadSpecies("bean").sourceFile, kSourceDir + "/species/bean.xml");
    EXPECT_EQ(loadSpecies(kBeanPath).name, "bean");

    const Error e = errorOf([] { loadSpecies("been"); });
    EXPECT_EQ(e.parameter(), "species");
    EXPECT_EQ(e.value(), "been");
    EXPECT_NE(e.validRange().find("bean"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("did you mean 'bean'"), std::string::npos);

    // Without the variable, the source tree's species folder is found (the tests run from
    // a build directory outside it).
    unsetenv("PLANTARCH_SPECIES_DIR");
    EXPECT_TRUE(std::filesystem::equivalent(speciesLibraryDirectory(), kSourceDir + "/species"));
    setenv("PLANTARCH_SPECIES_DIR", (kSourceDir + "/species").c_str(), 1);
}

TEST(SpeciesLibrary, OwnFilesLoadByPath) {
    const std::string path = tempPath("mine.xml");
    writeFile(path, species());
    EXPECT_EQ(loadSpecies(path).name, "mini");
    std::filesystem::remove(path);
    const Error e = errorOf([&] { loadSpecies(path); });
    EXPECT_EQ(e.file(), path);
}

TEST(SpeciesLibrary, WriteSpeciesFileIsAtomicAndReadable) {
    const std::string path = tempPath("written.xml");
    const SpeciesModel bean = loadSpecies(kBeanPath);
    writeSpeciesFile(bean, path);
    EXPECT_EQ(writeSpeciesString(readSpeciesFile(path)), writeSpeciesString(bean));
    std::filesystem::remove(path);
}

TEST(SpeciesLibrary, TheDocumentedExampleReadsAndBuilds) {
    std::ifstream in(kSourceDir + "/docs/species-format.md");
    std::stringstream doc;
    doc << in.rdbuf();
    const std::string text = doc.str();
    const std::size_t start = text.find("```xml\n<?xml");
    ASSERT_NE(start, std::string::npos);
    const std::size_t end = text.find("```", start + 6);
    const std::string xml = text.substr(start + 7, end - start - 7);
    const SpeciesModel m = readSpeciesString(xml, "species-format.md");
    EXPECT_EQ(m.shootTypes.size(), 3u);
    EXPECT_EQ(m.shootTypes.at("twig").insertion_angle_tip, RandomFloat::uniform(40, 60));
    EXPECT_EQ(writeSpeciesString(readSpeciesString(writeSpeciesString(m), "again.xml")),
              writeSpeciesString(m));
    // A trunk, three scaffolds and one twig on each.
    EXPECT_EQ(buildFrom(m).shoots.size(), 7u);
    EXPECT_EQ(buildFrom(m, {{"scaffolds", 6}, {"trunk_height", 0.3f}}).shoots.size(), 13u);
}

TEST(SpeciesReader, CheckFindsEveryIndependentError) {
    EXPECT_TRUE(checkSpeciesString(species(), "ok.xml").empty());
    // Three bad values and an unknown element in three groups: four errors, by line.
    const std::string xml = species({{"<max_age>100</max_age>", "<max_age>-5</max_age>"},
                                     {"<max_nodes>5</max_nodes>", "<max_nodes>five</max_nodes>"},
                                     {"@SHOOT@", "<tortuosityy>1</tortuosityy>"},
                                     {"<pitch>30</pitch>", "<pitch>400</pitch>"}});
    const std::vector<Error> errors = checkSpeciesString(xml, "bad.xml");
    ASSERT_EQ(errors.size(), 4u);
    EXPECT_EQ(errors[0].line(), 6);
    EXPECT_EQ(errors[0].parameter(), "phenology.max_age");
    EXPECT_EQ(errors[1].line(), 12);
    EXPECT_EQ(errors[1].parameter(), "main.max_nodes");
    EXPECT_EQ(errors[2].line(), 12);
    EXPECT_NE(errors[2].message().find("unknown element <tortuosityy>"), std::string::npos);
    EXPECT_EQ(errors[3].line(), 18);
    EXPECT_EQ(errors[3].parameter(), "main.phytomer.petiole.pitch");
    // The first of them is the one readSpeciesString throws.
    EXPECT_EQ(std::string(errorOf([&] { readSpeciesString(xml, "bad.xml"); }).what()),
              std::string(errors[0].what()));
    // Malformed XML ends the list.
    const std::vector<Error> cut = checkSpeciesString(xml.substr(0, 200), "cut.xml");
    ASSERT_EQ(cut.size(), 1u);
    EXPECT_NE(cut[0].message().find("malformed XML"), std::string::npos);
}

// ---- command line -----------------------------------------------------------------------

TEST(SpeciesCli, ValidateOkAndBroken) {
    int status = -1;
    std::string out = cli("validate '" + kBeanPath + "'", &status);
    EXPECT_EQ(status, 0) << out;
    EXPECT_EQ(out, kBeanPath + ": ok (2 shoot types)\n");

    const std::string broken = tempPath("broken_cli.xml");
    writeFile(broken, species({{"@PETIOLE@", "<pitchh>3</pitchh>"}}));
    out = cli("validate '" + broken + "'", &status);
    EXPECT_EQ(status, 2) << out;
    EXPECT_EQ(std::count(out.begin(), out.end(), '\n'), 1) << out;
    EXPECT_NE(out.find(broken + ":18: main.phytomer.petiole.pitchh"), std::string::npos) << out;
    std::filesystem::remove(broken);

    out = cli("validate /nonexistent.xml", &status);
    EXPECT_EQ(status, 2) << out;
}

TEST(SpeciesCli, InfoSummarizesAndXmlReadsBack) {
    int status = -1;
    const std::string summary = cli("info bean", &status);
    EXPECT_EQ(status, 0) << summary;
    EXPECT_NE(summary.find("unifoliate"), std::string::npos);
    EXPECT_NE(summary.find("trifoliate"), std::string::npos);
    EXPECT_NE(summary.find("Phaseolus vulgaris"), std::string::npos);

    const std::string xml = cli("info bean --xml", &status);
    EXPECT_EQ(status, 0);
    const SpeciesModel back = readSpeciesString(xml, "info.xml");
    EXPECT_EQ(writeSpeciesString(back), xml);
    EXPECT_EQ(xml, writeSpeciesString(loadSpecies(kBeanPath)));

    const std::string unknown = cli("info been", &status);
    EXPECT_EQ(status, 2);
    EXPECT_NE(unknown.find("did you mean 'bean'"), std::string::npos) << unknown;
}

TEST(SpeciesCli, ListShowsTheLibrary) {
    int status = -1;
    const std::string out = cli("list", &status);
    EXPECT_EQ(status, 0) << out;
    EXPECT_NE(out.find("bean"), std::string::npos);
    EXPECT_NE(out.find("Common Bean (Phaseolus vulgaris)"), std::string::npos) << out;
}
