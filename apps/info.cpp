// plantarch info: a readable summary of a species (names, the parameters of each shoot type
// that differ from the defaults, phenology, build parameters, initial structure), with --xml
// the complete species file with every value, which reads back to the same species. With
// --parameters (or --parameters-markdown, the page docs/parameters.md) it lists every
// parameter a species file can set. Every parameter name, unit, range and description comes
// from the library's parameter table (plantarch/ParameterInfo.h).

#include <fmt/format.h>

#include <algorithm>
#include <cstdio>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "cli.h"
#include "plantarch/Error.h"
#include "plantarch/NumberRange.h"
#include "plantarch/ParameterInfo.h"
#include "plantarch/SpeciesIO.h"

namespace plantarch::cli {
namespace {

struct InfoArgs {
    std::string species;
    bool xml = false;
    bool all = false;
    bool parameters = false;
    bool markdown = false;
};

// Splits text into lines of at most `width` characters, each starting with `indent`.
std::string wrap(const std::string& text, std::size_t width, const std::string& indent) {
    std::string out, line;
    std::size_t start = 0;
    while (start < text.size()) {
        std::size_t end = text.find(' ', start);
        if (end == std::string::npos) end = text.size();
        const std::string word = text.substr(start, end - start);
        if (!line.empty() && line.size() + 1 + word.size() > width) {
            out += indent + line + "\n";
            line.clear();
        }
        line += (line.empty() ? "" : " ") + word;
        start = end + 1;
    }
    if (!line.empty()) out += indent + line + "\n";
    return out;
}

// "20 degrees", "uniform(0.1, 0.2) m", "-" for an empty text or map.
std::string valueWithUnit(const ParameterInfo& p) {
    if (p.value.empty()) return "-";
    return p.unit.empty() ? p.value : p.value + " " + p.unit;
}

// The group a field is in: its path without the last part ("" at the top).
std::string groupOf(const ParameterInfo& p) {
    const std::size_t dot = p.path.rfind('.');
    return dot == std::string::npos ? "" : p.path.substr(0, dot);
}

// One aligned line per parameter, name then value and unit, under a heading per group
// ("phytomer.leaf:") as a species file nests them.
void printRows(const std::vector<const ParameterInfo*>& rows, const std::string& indent) {
    auto label = [](const ParameterInfo& p) { return (groupOf(p).empty() ? "" : "  ") + p.name; };
    std::size_t width = 0;
    for (const ParameterInfo* p : rows) width = std::max(width, label(*p).size());
    std::string group;
    for (const ParameterInfo* p : rows) {
        if (groupOf(*p) != group) {
            group = groupOf(*p);
            std::printf("%s%s:\n", indent.c_str(), group.c_str());
        }
        if (p->kind == ParameterKind::List && !p->value.empty()) {
            // One numbered line per element: "1. rank_max 1, node_max 5, ...".
            std::printf("%s%s:\n", indent.c_str(), label(*p).c_str());
            std::size_t start = 0, n = 0;
            while (start <= p->value.size()) {
                std::size_t end = p->value.find("; ", start);
                if (end == std::string::npos) end = p->value.size();
                std::printf("%s    %zu. %s\n", indent.c_str(), ++n,
                            p->value.substr(start, end - start).c_str());
                start = end + 2;
            }
            continue;
        }
        std::printf(
            "%s\n",
            fmt::format("{}{:<{}}  {}", indent, label(*p), width, valueWithUnit(*p)).c_str());
    }
}

void printShootType(const std::string& label, const ShootParameters& s, bool all) {
    const std::vector<ParameterInfo> fields = parameterInfo(s);
    const std::vector<ParameterInfo> defaults = parameterInfo(ShootParameters{});
    std::vector<const ParameterInfo*> rows;
    for (std::size_t i = 0; i < fields.size(); ++i)
        if (all || fields[i].value != defaults[i].value) rows.push_back(&fields[i]);
    if (all)
        std::printf("  %s (%zu parameters)\n", label.c_str(), fields.size());
    else
        std::printf("  %s (%zu of %zu parameters set; the others at their defaults)\n",
                    label.c_str(), rows.size(), fields.size());
    printRows(rows, "    ");
}

void printSummary(const SpeciesModel& m, bool all) {
    std::string title = m.name;
    if (!m.commonName.empty()) title += ": " + m.commonName;
    if (!m.latinName.empty()) title += " (" + m.latinName + ")";
    if (!m.plantType.empty()) title += ", " + m.plantType;
    std::printf("%s\n", title.c_str());
    std::printf("  file: %s\n", m.sourceFile.c_str());
    if (!m.description.empty()) std::printf("%s", wrap(m.description, 90, "  ").c_str());
    std::printf("  recommended age: %s days (%s to %s)",
                fmt::format("{}", m.recommendedAge).c_str(),
                fmt::format("{}", m.recommendedAgeMin).c_str(),
                fmt::format("{}", m.recommendedAgeMax).c_str());
    if (m.maxHeight > 0.0f)
        std::printf("; height up to %s m", fmt::format("{}", m.maxHeight).c_str());
    std::printf("\n\nshoot types (%zu)%s:\n", m.shootTypes.size(),
                all ? "" : "; --all lists every parameter");
    for (const auto& [label, params] : m.shootTypes) printShootType(label, params, all);

    std::printf("\nphenology:\n");
    const std::vector<ParameterInfo> phenology = parameterInfo(m.phenology);
    std::vector<const ParameterInfo*> rows;
    for (const ParameterInfo& p : phenology) rows.push_back(&p);
    printRows(rows, "  ");

    if (m.buildParameters.empty()) {
        std::printf("\nbuild parameters: none\n");
    } else {
        std::printf("\nbuild parameters (plantarch build -D name=value):\n");
        for (const BuildParameter& p : m.buildParameters)
            std::printf("  %s\n",
                        fmt::format("{} = {}{} (valid {}){}", p.name, p.value,
                                    p.unit.empty() ? "" : " " + p.unit,
                                    rangeText({.min = p.min, .max = p.max, .single = true}),
                                    p.doc.empty() ? "" : ": " + p.doc)
                            .c_str());
    }

    std::printf("\ninitial structure (%zu step%s):\n", m.build.size(),
                m.build.size() == 1 ? "" : "s");
    for (const BuildStep& s : m.build) {
        const char* kind = s.kind == BuildStep::Kind::BaseStem ? "base stem"
                           : s.kind == BuildStep::Kind::Append ? "append"
                                                               : "child";
        std::string where;
        if (s.kind == BuildStep::Kind::Append) where = " on " + s.parent;
        if (s.kind == BuildStep::Kind::Child)
            where = " on " + s.parent + " node " + s.parentNode + " petiole " + s.petiole +
                    (s.repeat == "1" ? "" : ", " + s.repeat + " copies");
        std::printf("  %s %s%s%s: %s node(s), pitch %s, yaw %s, roll %s\n", kind,
                    s.shootType.c_str(), s.id.empty() ? "" : (" '" + s.id + "'").c_str(),
                    where.c_str(), s.nodes.c_str(), s.pitch.c_str(), s.yaw.c_str(), s.roll.c_str());
    }
}

// ---- the parameter list -------------------------------------------------------------------

struct Section {
    const char* title;
    const char* element;
    std::vector<ParameterInfo> fields;  // values: the defaults
};

std::vector<Section> sections() {
    return {{"Shoot type", "<shoot_type label=\"...\">", parameterInfo(ShootParameters{})},
            {"Phenology", "<phenology>", parameterInfo(PhenologyParameters{})}};
}

// The description, with how one entry of a map is written (in `quote` marks).
std::string describe(const ParameterInfo& p, const std::string& quote = "") {
    if (p.entry.empty()) return p.doc;
    return p.doc + ". One entry each: " + quote + p.entry + quote;
}

void printParameters() {
    for (const Section& s : sections()) {
        std::printf("%s parameters (%s):\n", s.title, s.element);
        for (const ParameterInfo& p : s.fields) {
            std::string line = p.path + ": " + parameterKindText(p.kind);
            if (!p.unit.empty()) line += ", " + p.unit;
            if (p.hasRange()) line += ", " + p.rangeText();
            line += ", default " + (p.value.empty() ? std::string("empty") : p.value);
            std::printf("  %s\n%s", line.c_str(), wrap(describe(p), 88, "      ").c_str());
            for (const ParameterChoice& c : p.choices)
                std::printf("%s", wrap(c.name + ": " + c.doc, 88, "        ").c_str());
        }
        std::printf("\n");
    }
}

// A table cell: no line breaks, '|' escaped.
std::string cell(const std::string& text) {
    std::string out;
    for (char c : text) {
        if (c == '|')
            out += "\\|";
        else
            out += c == '\n' ? ' ' : c;
    }
    return out;
}

std::string code(const std::string& text) {
    return text.empty() ? "" : "`" + cell(text) + "`";
}

void printMarkdown() {
    std::printf(
        "# Species parameters\n\n"
        "<!-- Generated by `plantarch info --parameters-markdown` from the parameter table;\n"
        "     change the table, then regenerate. A test fails when this page differs. -->\n\n"
        "Every field a species file can set: its element inside `<shoot_type>` or\n"
        "`<phenology>`, the kind of value it holds, its unit, valid range, default and meaning.\n"
        "This is the list the species reader accepts, the writer writes, validation checks and\n"
        "`plantarch info` prints. How each kind of value is written, and the rest of the file\n"
        "format, is in [species-format.md](species-format.md#values). Units: metres, degrees,\n"
        "days. A range bounds every value a distribution can take: a normal draw is limited to\n"
        "its mean plus and minus three standard deviations, a Weibull draw to its 99.9 %%\n"
        "quantile.\n");
    for (const Section& s : sections()) {
        std::printf("\n## %s: `%s`\n", s.title, s.element);
        std::string group = "-";
        std::vector<const ParameterInfo*> choiceFields;
        auto flushChoices = [&] {
            for (const ParameterInfo* p : choiceFields) {
                std::printf("\nValues of `%s`:\n\n| Value | Meaning |\n|---|---|\n",
                            p->path.c_str());
                for (const ParameterChoice& c : p->choices)
                    std::printf("| `%s` | %s |\n", c.name.c_str(), cell(c.doc).c_str());
            }
            choiceFields.clear();
        };
        for (const ParameterInfo& p : s.fields) {
            if (groupOf(p) != group) {
                flushChoices();
                group = groupOf(p);
                if (!group.empty()) std::printf("\n### `%s`\n", group.c_str());
                std::printf(
                    "\n| Field | Kind | Unit | Range | Default | Description |\n"
                    "|---|---|---|---|---|---|\n");
            }
            std::string doc = describe(p, "`");
            if (!p.choices.empty()) {
                doc += " (values below)";
                choiceFields.push_back(&p);
            }
            std::printf("| `%s` | %s | %s | %s | %s | %s |\n", p.name.c_str(),
                        parameterKindText(p.kind), cell(p.unit).c_str(),
                        cell(p.rangeText()).c_str(), code(p.value).c_str(), cell(doc).c_str());
        }
        flushChoices();
    }
}

int run(const InfoArgs& a) {
    if (a.parameters || a.markdown) {
        if (a.markdown)
            printMarkdown();
        else
            printParameters();
        return 0;
    }
    if (a.species.empty())
        throw Error("plantarch info needs a SPECIES (or --parameters)",
                    {.parameter = "SPECIES", .validRange = "see 'plantarch list'"});
    const SpeciesModel species = loadSpecies(a.species);
    if (a.xml) {
        writeSpecies(species, std::cout);
        std::cout.flush();
    } else {
        printSummary(species, a.all);
    }
    return 0;
}

std::function<int()> setupInfo(CLI::App& app, GlobalOptions&) {
    app.description("Describe a species: shoot types, phenology, build parameters");
    auto args = std::make_shared<InfoArgs>();
    app.add_option("SPECIES", args->species, "Library name (see 'plantarch list') or species file");
    app.add_flag("--xml", args->xml,
                 "Print the complete species file (every value), which reads back identically");
    app.add_flag("--all", args->all,
                 "List every parameter of each shoot type, not only those set differently "
                 "from the defaults");
    app.add_flag("--parameters", args->parameters,
                 "List every parameter a species file can set: unit, range, default, meaning");
    app.add_flag("--parameters-markdown", args->markdown,
                 "The same list as the Markdown page docs/parameters.md");
    return [args] { return run(*args); };
}

}  // namespace

PLANTARCH_REGISTER_COMMAND(info, "info", 70, setupInfo);

}  // namespace plantarch::cli
