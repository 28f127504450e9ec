// Node rules (NodeRule, docs/species-format.md "Node rules"): formulas evaluate as the same
// float arithmetic written in C++, each condition and action does what the format says on
// plants whose expected counts and areas follow from the rule by hand, a species with rules
// is a file and nothing else, and rules survive species and plant structure files.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "cli_run.h"
#include "plantarch/Error.h"
#include "plantarch/Formula.h"
#include "plantarch/PhytomerActions.h"
#include "plantarch/PlantArchitecture.h"
#include "plantarch/SpeciesIO.h"

using namespace plantarch;

namespace {

const std::string kSourceDir = PLANTARCH_SOURCE_DIR;

std::string tempPath(const std::string& name) {
    return (std::filesystem::temp_directory_path() /
            ("plantarch_node_rules_test_" + std::to_string(::getpid()) + "_" + name))
        .string();
}

// The example of docs/species-format.md's "Node rules" section.
std::string documentedExample() {
    std::ifstream in(kSourceDir + "/docs/species-format.md");
    std::stringstream doc;
    doc << in.rdbuf();
    const std::string text = doc.str();
    const std::size_t section = text.find("## Node rules");
    EXPECT_NE(section, std::string::npos);
    const std::size_t start = text.find("```xml\n<?xml", section);
    const std::size_t end = text.find("```\n", start + 7);
    return text.substr(start + 7, end - start - 7);
}

// The <node_rules> snippets of the same section, in order.
std::vector<std::string> documentedSnippets() {
    std::ifstream in(kSourceDir + "/docs/species-format.md");
    std::stringstream doc;
    doc << in.rdbuf();
    const std::string text = doc.str();
    const std::size_t section = text.find("## Node rules");
    const std::size_t next = text.find("\n## ", section + 1);
    std::vector<std::string> out;
    for (std::size_t at = text.find("```xml\n<node_rules>", section);
         at != std::string::npos && at < next; at = text.find("```xml\n<node_rules>", at + 1)) {
        const std::size_t end = text.find("```\n", at + 7);
        out.push_back(text.substr(at + 7, end - at - 7));
    }
    return out;
}

// A stem of `nodes` nodes, one leaf each (0.1 m), no branches, with the given rules.
std::string stemSpecies(const std::string& rules, int nodes = 10) {
    return R"(<?xml version="1.0"?>
<plantarch_species format="1">
  <name>stem</name>
  <shoot_type label="stem">
    <max_nodes>)" +
           std::to_string(nodes) + R"(</max_nodes>
    <phyllochron_min>1</phyllochron_min>
    <internode_length_max>0.1</internode_length_max>
    <vegetative_bud_break_probability_min>0</vegetative_bud_break_probability_min>
    <vegetative_bud_break_probability_max>0</vegetative_bud_break_probability_max>
    <phytomer>
      <leaf><prototype_scale>0.1</prototype_scale></leaf>
      )" + rules +
           R"(
    </phytomer>
  </shoot_type>
  <build><base_stem type="stem" nodes="1"/></build>
</plantarch_species>
)";
}

struct Grown {
    std::unique_ptr<Context> ctx = std::make_unique<Context>();
    std::unique_ptr<PlantArchitecture> arch = std::make_unique<PlantArchitecture>(ctx.get());
    unsigned plant = 0;
};

Grown grow(const std::string& xml, float age) {
    const std::string path = tempPath("species.xml");
    std::ofstream(path) << xml;
    Grown g;
    g.arch->loadPlantModelFromLibrary(path);
    std::filesystem::remove(path);
    g.plant = g.arch->buildPlantInstanceFromLibrary(vec3(0.0f), age);
    return g;
}

// Leaves per node of the base stem (removed leaves not counted).
std::vector<int> leavesPerNode(const Grown& g) {
    std::vector<int> out;
    for (const Phytomer& ph : g.arch->plant(g.plant).shoots[0].phytomers) {
        int n = 0;
        for (const Petiole& p : ph.petioles)
            for (const LeafOrgan& l : p.leaves) n += l.removed ? 0 : 1;
        out.push_back(n);
    }
    return out;
}

std::string errorOf(const std::function<void()>& f) {
    try {
        f();
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

}  // namespace

// ---- formulas ---------------------------------------------------------------------------

TEST(NodeRuleFormula, FloatEvaluationIsTheCppFloatExpressionToTheBit) {
    const Formula f = NodeRule::formula("min(1, 0.6 + 0.4 * age / 8)");
    const Formula g = NodeRule::formula("-(60 * ((max_nodes - node) / max_nodes))");
    for (float age : {0.0f, 0.3f, 1.0f, 2.7f, 5.0f, 7.9f, 8.0f, 13.0f}) {
        const float expected = std::min(1.0f, 0.6f + 0.4f * age / 8.0f);
        const float got = f.evaluateFloat(std::vector<float>{age, 0, 0, 0, 0});
        EXPECT_EQ(std::memcmp(&got, &expected, sizeof got), 0) << age;
    }
    for (int node = 0; node < 13; ++node) {
        const float fact = float(13 - node) / float(13);
        const float expected = -(60.0f * fact);
        const float got = g.evaluateFloat(std::vector<float>{0, float(node), 0, 13, 0});
        EXPECT_EQ(std::memcmp(&got, &expected, sizeof got), 0) << node;
    }
    // A literal beyond float's range is not silently zero in float precision.
    EXPECT_NE(
        errorOf([] {
            NodeRule::formula("1e39 * node").evaluateFloat(std::vector<float>{0, 1, 0, 10, 0});
        }).find("result is not a finite number"),
        std::string::npos);
    EXPECT_EQ(Formula("1e39 * 2", {}).evaluate(std::vector<double>{}), 2e39);
    // Double precision keeps double literals: 0.1 * 3 is not the float product.
    EXPECT_EQ(Formula("0.1 * 3", {}).evaluate(std::vector<double>{}), 0.1 * 3);
}

TEST(NodeRuleFormula, BadFormulasNameTheProblemAndTheColumn) {
    EXPECT_EQ(errorOf([] { NodeRule::formula("min(1, 0.5 + nod / 5)"); }),
              "'min(1, 0.5 + nod / 5)': bad expression: unknown name 'nod' at column 14, did you "
              "mean 'node'? (valid: one of: age, node, rank, max_nodes, nodes_from_tip, pi)");
    EXPECT_NE(errorOf([] {
                  NodeRule::formula("uniform(0, 1)");
              }).find("random function 'uniform' is not allowed here at column 1"),
              std::string::npos);
    EXPECT_NE(errorOf([] {
                  NodeRule::formula("node / (age - age)")
                      .evaluateFloat(std::vector<float>{2, 1, 0, 10, 0});
              }).find("division by zero at column 8"),
              std::string::npos);
}

// fuzz_species: a formula nested thousands of parentheses deep overflowed the parser's stack.
// Nesting is bounded: 200 levels read, 201 are one clear error, however the levels are made.
TEST(NodeRuleFormula, NestingIsBoundedWithAClearError) {
    const auto nested = [](const std::string& open, const std::string& close, int levels) {
        std::string text;
        for (int i = 0; i < levels; ++i) text += open;
        text += "node";
        for (int i = 0; i < levels; ++i) text += close;
        return text;
    };
    // 199 parentheses and the sign of the innermost term: 200 levels.
    EXPECT_EQ(
        NodeRule::formula(nested("(", ")", 199)).evaluateFloat(std::vector<float>{0, 7, 0, 10, 0}),
        7.0f);
    for (const auto& [open, close] : std::vector<std::pair<std::string, std::string>>{
             {"(", ")"}, {"-", ""}, {"abs(", ")"}, {"min(1, ", ")"}}) {
        SCOPED_TRACE(open);
        const std::string error = errorOf([&] { NodeRule::formula(nested(open, close, 5000)); });
        EXPECT_NE(error.find("bad expression: nested deeper than 200 levels at column "),
                  std::string::npos)
            << error;
        EXPECT_NE(error.find("(valid: at most 200 nested parentheses, calls and signs)"),
                  std::string::npos)
            << error;
        // The 5000-level text is shown by its start and its length.
        EXPECT_NE(error.find(" characters)': bad expression"), std::string::npos) << error;
        EXPECT_LT(error.size(), 400u) << error;
    }
}

// ---- the documented example: a species with rules is a file alone ------------------------

TEST(NodeRules, TheDocumentedExampleBuildsWhatItSays) {
    const std::string xml = documentedExample();
    const Grown g = grow(xml, 40.0f);
    // Nodes 0 to 2 bare, 3 to 9 with their leaf.
    EXPECT_EQ(leavesPerNode(g), (std::vector<int>{0, 0, 0, 1, 1, 1, 1, 1, 1, 1}));
    EXPECT_EQ(g.arch->getPlantLeafCount(g.plant), 7u);
    for (unsigned k = 0; k < 3; ++k)
        for (const Petiole& p : g.arch->plant(g.plant).shoots[0].phytomers[k].petioles) {
            for (const VegetativeBud& b : p.vegetativeBuds) EXPECT_EQ(b.state, BudState::Dead);
            for (const FloralBud& b : p.floralBuds) EXPECT_EQ(b.stage, FloralStage::Removed);
        }
    // Full sizes: c = half size at node 3, +10 % per node, full from node 8. A leaf made
    // smaller than its type's nominal size levels off (docs/growth.md, elongation) at the
    // fraction min(1, c r step / (1 - c)), here rate r 0.2 (the default) and step 1 day (the
    // phyllochron); at 40 days the leaves (31 to 40 days old) are there within 0.1 %. Area
    // scales with the square of the current size: sum of (c f)^2 over nodes 3 to 9, / 10 full
    // leaves.
    std::string plain = xml;
    const std::size_t from = plain.find("<node_rules>");
    const std::size_t to = plain.find("</node_rules>") + std::strlen("</node_rules>");
    plain.replace(from, to - from, "");
    const Grown full = grow(plain, 40.0f);
    EXPECT_EQ(full.arch->getPlantLeafCount(full.plant), 10u);
    double expected = 0.0;
    for (const double c : {0.5, 0.6, 0.7, 0.8, 0.9, 1.0, 1.0}) {
        const double f = c < 1.0 ? std::min(1.0, c * 0.2 * 1.0 / (1.0 - c)) : 1.0;
        expected += c * f * c * f / 10.0;
    }
    // (0.1^2 + 0.18^2 + 0.327^2 + 0.64^2 + 0.9^2 + 1 + 1) / 10
    EXPECT_NEAR(expected, 0.3369, 1e-4);
    EXPECT_NEAR(g.arch->getPlantLeafArea(g.plant) / full.arch->getPlantLeafArea(full.plant),
                expected, 1e-3 * expected);
}

TEST(NodeRules, EveryDocumentedSnippetReadsAndBuilds) {
    const std::vector<std::string> snippets = documentedSnippets();
    ASSERT_EQ(snippets.size(), 6u);
    for (const std::string& rules : snippets) {
        SCOPED_TRACE(rules);
        // The ears of the grass example come from a shoot type of their own.
        std::string xml = stemSpecies(rules, 14);
        xml.replace(xml.find("  <build>"), 0,
                    "  <shoot_type label=\"ear\"><max_nodes>1</max_nodes></shoot_type>\n");
        const SpeciesModel m = readSpeciesString(xml, "snippet.xml");
        EXPECT_FALSE(m.shootTypes.at("stem").phytomer_parameters.node_rules.empty());
        const Grown g = grow(xml, 120);
        EXPECT_GT(g.ctx->triangleCount(), 0u);
    }
}

// ---- conditions and actions -------------------------------------------------------------

TEST(NodeRules, NodeRangesCountFromTheBaseTheTipAndTheLastNode) {
    const std::string remove = "<remove_leaves>true</remove_leaves>";
    // Nodes 3 to 5 from the base.
    EXPECT_EQ(leavesPerNode(grow(stemSpecies("<node_rules><rule><node_min>3</node_min><node_max>5"
                                             "</node_max>" +
                                             remove + "</rule></node_rules>"),
                                 30)),
              (std::vector<int>{1, 1, 1, 0, 0, 0, 1, 1, 1, 1}));
    // The last two nodes of max_nodes (at creation, known before they are made).
    EXPECT_EQ(leavesPerNode(grow(stemSpecies("<node_rules><rule><nodes_before_last_max>1</"
                                             "nodes_before_last_max>" +
                                             remove + "</rule></node_rules>"),
                                 30)),
              (std::vector<int>{1, 1, 1, 1, 1, 1, 1, 1, 0, 0}));
    // Daily, nodes at least 7 below the tip: on a full stem of 10, nodes 0 to 2.
    EXPECT_EQ(leavesPerNode(grow(stemSpecies("<node_rules><rule><when>daily</when>"
                                             "<nodes_from_tip_min>7</nodes_from_tip_min>" +
                                             remove + "</rule></node_rules>"),
                                 30)),
              (std::vector<int>{0, 0, 0, 1, 1, 1, 1, 1, 1, 1}));
}

TEST(NodeRules, AgeAndHeightConditionsFollowThePlant) {
    // Creation at age 0 to 4.5: the nodes made on days 0 to 4 (phyllochron 1 day).
    const auto early = leavesPerNode(grow(stemSpecies("<node_rules><rule><age_max>4.5</age_max>"
                                                      "<remove_leaves>true</remove_leaves>"
                                                      "</rule></node_rules>"),
                                          30));
    EXPECT_EQ(early, (std::vector<int>{0, 0, 0, 0, 0, 1, 1, 1, 1, 1}));
    // Daily from day 20: strip nodes whose base is below 0.35 m. Internodes are 0.1 m when
    // grown, so nodes 0 to 3 (bases at 0, 0.1, 0.2, 0.3 m) lose their leaves.
    const std::string daily =
        "<node_rules><rule><when>daily</when><age_min>20</age_min>"
        "<height_below>0.35</height_below>"
        "<remove_leaves>true</remove_leaves></rule></node_rules>";
    EXPECT_EQ(leavesPerNode(grow(stemSpecies(daily), 19)), std::vector<int>(10, 1));
    EXPECT_EQ(leavesPerNode(grow(stemSpecies(daily), 25)),
              (std::vector<int>{0, 0, 0, 0, 1, 1, 1, 1, 1, 1}));
}

TEST(NodeRules, ScaleAndPitchActionsChangeTheOrgansBySetAmounts) {
    const Grown plain = grow(stemSpecies(""), 30);
    const Grown ruled = grow(stemSpecies("<node_rules><rule><node_min>5</node_min>"
                                         "<internode_scale>0.5</internode_scale>"
                                         "<petiole_pitch_change>10 + node</petiole_pitch_change>"
                                         "<leaf_pitch_change>-5</leaf_pitch_change>"
                                         "</rule></node_rules>"),
                             30);
    const auto& a = plain.arch->plant(plain.plant).shoots[0].phytomers;
    const auto& b = ruled.arch->plant(ruled.plant).shoots[0].phytomers;
    ASSERT_EQ(a.size(), 10u);
    ASSERT_EQ(b.size(), 10u);
    for (unsigned k = 0; k < 10; ++k) {
        const bool ruledNode = k >= 5;
        EXPECT_FLOAT_EQ(b[k].internode.length, a[k].internode.length * (ruledNode ? 0.5f : 1.0f));
        EXPECT_FLOAT_EQ(b[k].petioles[0].pitch,
                        a[k].petioles[0].pitch + (ruledNode ? 10.0f + float(k) : 0.0f));
        EXPECT_FLOAT_EQ(b[k].petioles[0].leaves[0].pitch,
                        a[k].petioles[0].leaves[0].pitch + (ruledNode ? -5.0f : 0.0f));
    }
    // Five internodes at half length: the stem is 7.5 internodes tall instead of 10.
    EXPECT_NEAR(
        ruled.arch->getPlantStemHeight(ruled.plant) / plain.arch->getPlantStemHeight(plain.plant),
        0.75, 0.02);
}

TEST(NodeRules, ShortInternodesAreSpursWithFewNodesASeason) {
    // Spurs: phytomers with full internodes shorter than 0.02 m make no branch, and their
    // shoot makes at most 3 nodes a season. A stem of 0.01 m internodes stops at 4 nodes: the
    // one planted, then 3 in the season that begins when dormancy breaks on day 0. One of
    // 0.05 m internodes makes all 8, with its buds alive (they break after 1000 days).
    auto species = [](const char* internode) {
        return std::string(R"(<?xml version="1.0"?>
<plantarch_species format="1">
  <name>spurs</name>
  <shoot_type label="stem">
    <max_nodes>8</max_nodes>
    <phyllochron_min>1</phyllochron_min>
    <internode_length_max>)") +
               internode + R"(</internode_length_max>
    <vegetative_bud_break_time>1000</vegetative_bud_break_time>
    <phytomer>
      <node_rules>
        <rule>
          <internode_length_below>0.02</internode_length_below>
          <remove_vegetative_buds>true</remove_vegetative_buds>
          <max_nodes_per_season>3</max_nodes_per_season>
        </rule>
      </node_rules>
    </phytomer>
  </shoot_type>
  <build><base_stem type="stem" nodes="1"/></build>
</plantarch_species>
)";
    };
    auto budsDead = [](const Shoot& s) {
        std::vector<bool> out;
        for (const Phytomer& ph : s.phytomers)
            for (const Petiole& p : ph.petioles)
                for (const VegetativeBud& b : p.vegetativeBuds)
                    out.push_back(b.state == BudState::Dead);
        return out;
    };
    const Grown spur = grow(species("0.01"), 20);
    const Shoot& short_ = spur.arch->plant(spur.plant).shoots[0];
    EXPECT_EQ(short_.phytomers.size(), 4u);
    EXPECT_EQ(short_.maxNodesPerSeason, 3);
    EXPECT_EQ(budsDead(short_), std::vector<bool>(4, true));
    const Grown longer = grow(species("0.05"), 20);
    const Shoot& long_ = longer.arch->plant(longer.plant).shoots[0];
    EXPECT_EQ(long_.phytomers.size(), 8u);
    EXPECT_GT(long_.maxNodesPerSeason, 8);
    EXPECT_EQ(budsDead(long_), std::vector<bool>(8, false));
}

// ---- files ------------------------------------------------------------------------------

TEST(NodeRules, InheritedListsAreReplacedWholeOrRemoved) {
    const std::string xml = R"(<?xml version="1.0"?>
<plantarch_species format="1">
  <name>inherit</name>
  <shoot_type label="a">
    <phytomer><node_rules>
      <rule><node_max>1</node_max><remove_leaves>true</remove_leaves></rule>
      <rule><leaf_scale>0.5</leaf_scale></rule>
    </node_rules></phytomer>
  </shoot_type>
  <shoot_type label="b" inherits="a"/>
  <shoot_type label="c" inherits="a">
    <phytomer><node_rules><rule><when>daily</when></rule></node_rules></phytomer>
  </shoot_type>
  <shoot_type label="d" inherits="a"><phytomer><node_rules/></phytomer></shoot_type>
  <build><base_stem type="a" nodes="1"/></build>
</plantarch_species>
)";
    const SpeciesModel m = readSpeciesString(xml, "inherit.xml");
    const auto& rules = [&](const char* t) -> const std::vector<NodeRule>& {
        return m.shootTypes.at(t).phytomer_parameters.node_rules;
    };
    ASSERT_EQ(rules("a").size(), 2u);
    EXPECT_EQ(rules("a")[0].node_max, 1);
    EXPECT_TRUE(rules("a")[0].remove_leaves);
    EXPECT_EQ(rules("a")[1].leaf_scale.text(), "0.5");
    EXPECT_EQ(rules("b"), rules("a"));
    ASSERT_EQ(rules("c").size(), 1u);
    EXPECT_EQ(rules("c")[0].when, NodeRuleTime::Daily);
    EXPECT_TRUE(rules("d").empty());
    // Written out and read back: the same rules.
    const SpeciesModel back = readSpeciesString(writeSpeciesString(m), "again.xml");
    for (const char* t : {"a", "b", "c", "d"})
        EXPECT_EQ(back.shootTypes.at(t).phytomer_parameters.node_rules, rules(t)) << t;
}

TEST(NodeRules, BadRulesGiveOneLineWithFileLineAndValidValues) {
    auto readError = [](const std::string& rule) {
        return errorOf([&] { readSpeciesString(stemSpecies(rule), "rules.xml"); });
    };
    EXPECT_EQ(readError("<node_rules><rule><when>weekly</when></rule></node_rules>"),
              "rules.xml:12: stem.phytomer.node_rules[1].when = weekly: unknown value 'weekly' "
              "(valid: one of: creation, daily, winter)");
    const std::string formula =
        readError("<node_rules><rule><leaf_scale>0.5 * nodes</leaf_scale></rule></node_rules>");
    EXPECT_EQ(formula,
              "rules.xml:12: stem.phytomer.node_rules[1].leaf_scale = 0.5 * nodes: bad "
              "expression: unknown name 'nodes' at column 7, did you mean 'node'? (valid: one "
              "of: age, node, rank, max_nodes, nodes_from_tip, pi)");
    const std::string unknown =
        readError("<node_rules><rule><node_maxx>3</node_maxx></rule></node_rules>");
    EXPECT_NE(unknown.find("rules.xml:12: stem.phytomer.node_rules[1].node_maxx"),
              std::string::npos)
        << unknown;
    EXPECT_NE(unknown.find("unknown element <node_maxx> in <rule>, did you mean <node_max>?"),
              std::string::npos)
        << unknown;
    const std::string range = readError(
        "<node_rules><rule><max_nodes_per_season>0</max_nodes_per_season></rule>"
        "</node_rules>");
    EXPECT_EQ(range,
              "rules.xml:12: stem.phytomer.node_rules[1].max_nodes_per_season = 0: out of range "
              "(valid: 1 to 1000000)");
    EXPECT_NE(readError("<node_rules><other/></node_rules>").find("rules.xml:12"),
              std::string::npos);
    // Checks across a rule's fields.
    EXPECT_EQ(readError("<node_rules><rule><node_min>5</node_min><node_max>2</node_max></rule>"
                        "</node_rules>"),
              "rules.xml:12: stem.phytomer.node_rules[1].node_min = 5: the rule can never hold: "
              "node_min exceeds node_max (valid: at most node_max = 2)");
    EXPECT_EQ(readError("<node_rules><rule><height_below>1</height_below></rule></node_rules>"),
              "rules.xml:12: stem.phytomer.node_rules[1].height_below = 1: height_below needs a "
              "daily or winter rule (a node has no height as it is made) (valid: "
              "<when>daily</when> or <when>winter</when>)");
    EXPECT_EQ(readError("<node_rules><rule><flowering_shoot_type>an ear</flowering_shoot_type>"
                        "</rule></node_rules>"),
              "rules.xml:12: stem.phytomer.node_rules[1].flowering_shoot_type = an ear: a shoot "
              "type label is letters, digits, '_' or '-' (valid: a shoot type label)");
}

TEST(NodeRules, APlantStructureFileKeepsTheRulesAndGrowsOnTheSame) {
    const std::string xml = stemSpecies(
        "<node_rules><rule><when>daily</when><age_min>12</age_min>"
        "<nodes_from_tip_min>4</nodes_from_tip_min><remove_leaves>true</remove_leaves>"
        "</rule><rule><leaf_scale>min(1, 0.5 + age / 20)</leaf_scale></rule>"
        "</node_rules>");
    Grown g = grow(xml, 8);
    const std::string saved = g.arch->getPlantStructureXML({g.plant});
    Context ctx;
    PlantArchitecture arch(&ctx);
    const unsigned back = arch.readPlantStructureXMLString(saved).at(0);
    EXPECT_EQ(arch.plant(back).shootTypes.at("stem").phytomer_parameters.node_rules,
              g.arch->plant(g.plant).shootTypes.at("stem").phytomer_parameters.node_rules);
    g.arch->advanceTime(g.plant, 12);
    arch.advanceTime(back, 12);
    EXPECT_EQ(arch.getPlantStructureXML({back}), g.arch->getPlantStructureXML({g.plant}));
    EXPECT_EQ(arch.getPlantLeafCount(back), 4u);  // 10 nodes, the 6 lowest stripped
}

TEST(NodeRules, InfoListsASpeciesRulesOnePerLine) {
    const cli::Result r = cli::run("info bean");
    ASSERT_EQ(r.status, 0) << r.out;
    EXPECT_NE(r.out.find("      node_rules:\n"
                         "        1. rank_max 1, node_max 5, remove_floral_buds true\n"
                         "        2. node_min 6, remove_vegetative_buds true\n"
                         "        3. rank_min 2, remove_vegetative_buds true\n"
                         "        4. leaf_scale min(1, 0.6 + 0.4 * age / 8)\n"
                         "        5. rank_max 0, internode_scale min(1, 0.2 + 0.8 * age / 10)\n"),
              std::string::npos)
        << r.out;
}

// A rule's result is held to the range of the state field it sets (plantarch/PlantStateTable.h):
// a leaf 1e30 times its size, or a negative one, is refused at the formula's own line (a
// rule running as a build step makes the node, or as the plant grows), naming the rule, the
// formula's value, the range and where it ran; nothing is added.
TEST(NodeRules, ResultsAreHeldToTheirFieldsRangesAtTheFormulasLine) {
    auto buildError = [](const std::string& rules, float age) {
        const std::string path = tempPath("range.xml");
        std::ofstream(path) << stemSpecies(rules);
        Context ctx;
        PlantArchitecture arch(&ctx);
        arch.loadPlantModelFromLibrary(path);
        const std::string e = errorOf([&] { arch.buildPlantInstanceFromLibrary(vec3(0.0f), age); });
        std::filesystem::remove(path);
        EXPECT_TRUE(arch.getAllPlantIDs().empty()) << "nothing is added";
        EXPECT_EQ(e.find(path + ":12: stem.phytomer.node_rules[1]."), 0u) << e;
        return e;
    };
    // At node 0, made by the build step (line 19): the formula's line all the same.
    std::string e = buildError(
        "<node_rules><rule><node_max>0</node_max>"
        "<leaf_scale>1e30</leaf_scale></rule></node_rules>",
        5.0f);
    EXPECT_NE(e.find("leaf_scale = 1e+30 (from '1e30'): makes leaf_scale 1e+29 from 0.1, out of "
                     "its range, at node 0 of shoot 0 (stem) at plant age 0 days (valid: "
                     "results keeping leaf_scale within 0 to 1000000)"),
              std::string::npos)
        << e;
    // As the plant grows.
    e = buildError(
        "<node_rules><rule><node_min>1</node_min>"
        "<leaf_scale>-0.5</leaf_scale></rule></node_rules>",
        5.0f);
    EXPECT_NE(e.find("leaf_scale = -0.5: makes leaf_scale -0.05 from 0.1, out of its range, at "
                     "node 1 of shoot 0 (stem) at plant age 1 days"),
              std::string::npos)
        << e;
    e = buildError(
        "<node_rules><rule><internode_scale>1e20 * (node + 1)</internode_scale></rule>"
        "</node_rules>",
        5.0f);
    EXPECT_NE(e.find("internode_scale = 1e+20 (from '1e20 * (node + 1)'): makes "
                     "internode_length 1e+19 from 0.1"),
              std::string::npos)
        << e;
    EXPECT_NE(e.find("(valid: results keeping internode_length within 0 to 1000000)"),
              std::string::npos)
        << e;
    e = buildError(
        "<node_rules><rule><petiole_pitch_change>3e38 * node</petiole_pitch_change>"
        "</rule></node_rules>",
        5.0f);
    EXPECT_NE(e.find("petiole_pitch_change = 3e+38 (from '3e38 * node'): makes "
                     "petiole_pitch 3e+38 from 90"),
              std::string::npos)
        << e;
    // A formula error: at its line, with where it ran.
    e = buildError(
        "<node_rules><rule><leaf_scale>1 + 1 / (node - 2)</leaf_scale></rule></node_rules>", 5.0f);
    EXPECT_NE(
        e.find("leaf_scale = 1 + 1 / (node - 2): bad expression: division by zero at column 9, "
               "at node 2 of shoot 0 (stem) at plant age 2 days"),
        std::string::npos)
        << e;
}

// ---- the rules' actions as functions (plantarch/PhytomerActions.h) ---------------------------

TEST(PhytomerActions, ScaleLeavesScalesEveryLeafOrRefusesChangingNothing) {
    Phytomer ph;
    ph.petioles.resize(2);
    ph.petioles[0].leaves.resize(3);
    ph.petioles[1].leaves.resize(1);
    for (Petiole& p : ph.petioles)
        for (LeafOrgan& l : p.leaves) l.scale = 0.1f;
    ph.petioles[1].leaves[0].scale = 2.0f;
    scaleLeaves(ph, 0.5f);
    EXPECT_FLOAT_EQ(ph.petioles[0].leaves[2].scale, 0.05f);
    EXPECT_FLOAT_EQ(ph.petioles[1].leaves[0].scale, 1.0f);
    const Phytomer before = ph;
    for (float factor : {NAN, INFINITY, -1.0f, 2e6f}) {
        try {
            scaleLeaves(ph, factor);
            ADD_FAILURE() << "factor " << factor << " accepted";
        } catch (const Error& e) {
            EXPECT_EQ(e.context().parameter, "factor");
            EXPECT_NE(std::string(e.what()).find("leaf_scale within 0 to 1000000"),
                      std::string::npos)
                << e.what();
        }
        // all or nothing: the first leaf would have stayed in range for 2e6
        EXPECT_EQ(ph.petioles[0].leaves[0].scale, before.petioles[0].leaves[0].scale);
        EXPECT_EQ(ph.petioles[1].leaves[0].scale, before.petioles[1].leaves[0].scale);
    }
    Phytomer bare;  // no leaves: any finite factor, nothing to change
    EXPECT_NO_THROW(scaleLeaves(bare, -3.0f));
    EXPECT_THROW(scaleLeaves(bare, NAN), Error);
}

// A smaller leaf has a petiole as much shorter and thinner that bends by the same angle.
TEST(PhytomerActions, ScaleLeavesScalesTheirPetiolesKeepingTheirBend) {
    Phytomer ph;
    ph.petioles.resize(1);
    Petiole& p = ph.petioles[0];
    p.leaves.resize(2);
    for (LeafOrgan& l : p.leaves) l.scale = 0.1f;
    p.length = 0.2f;
    p.radius = 0.002f;
    p.curvature = -140.0f;
    scaleLeaves(ph, 0.7f);
    EXPECT_FLOAT_EQ(p.leaves[1].scale, 0.07f);
    EXPECT_FLOAT_EQ(p.length, 0.14f);
    EXPECT_FLOAT_EQ(p.radius, 0.0014f);
    EXPECT_FLOAT_EQ(p.curvature, -200.0f);
    EXPECT_FLOAT_EQ(p.curvature * p.length, -140.0f * 0.2f);  // the same bend, in degrees
    // A factor that would take the curvature past the largest float changes nothing.
    const Phytomer before = ph;
    try {
        scaleLeaves(ph, 1e-37f);
        ADD_FAILURE() << "a curvature of -2e39 degrees per metre accepted";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("makes petiole_curvature"), std::string::npos)
            << e.what();
        EXPECT_NE(e.context().validRange.find("petiole_curvature within"), std::string::npos)
            << e.context().validRange;
    }
    EXPECT_EQ(p.length, before.petioles[0].length);
    EXPECT_EQ(p.curvature, before.petioles[0].curvature);
    EXPECT_EQ(p.leaves[0].scale, before.petioles[0].leaves[0].scale);
}
