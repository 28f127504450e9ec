// plantarch info: a readable summary of a species (names, shoot types with their key
// parameters, phenology, build parameters, initial structure), or with --xml the complete
// species file with every value, which reads back to the same species.

#include <fmt/format.h>

#include <cstdio>
#include <iostream>
#include <memory>
#include <string>

#include "cli.h"
#include "plantarch/SpeciesIO.h"

namespace plantarch::cli {
namespace {

struct InfoArgs {
    std::string species;
    bool xml = false;
};

std::string rgb(const vec3& c) {
    return fmt::format("{} {} {}", c.x, c.y, c.z);
}

std::string orNone(const std::string& s) {
    return s.empty() ? "-" : s;
}

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

void printShootType(const std::string& label, const ShootParameters& s) {
    const PhytomerParameters& p = s.phytomer_parameters;
    std::string children;
    for (const auto& [type, probability] : s.child_shoot_types)
        children += fmt::format("{}{} {}", children.empty() ? "" : ", ", type, probability);
    std::printf("  %s\n", label.c_str());
    std::printf(
        "    nodes: max %s (%s per season), phyllochron %s days, internode length "
        "%s m (min %s, change %s m per node)\n",
        s.max_nodes.describe().c_str(), s.max_nodes_per_season.describe().c_str(),
        s.phyllochron_min.describe().c_str(), s.internode_length_max.describe().c_str(),
        s.internode_length_min.describe().c_str(),
        s.internode_length_decay_rate.describe().c_str());
    std::printf(
        "    growth: elongation %s per day, gravitropic curvature %s deg/m, tortuosity %s, "
        "girth factor %s cm2/m2, %s growth\n",
        s.elongation_rate_max.describe().c_str(), s.gravitropic_curvature.describe().c_str(),
        s.tortuosity.describe().c_str(), s.girth_area_factor.describe().c_str(),
        s.determinate_shoot_growth ? "determinate" : "indeterminate");
    std::printf(
        "    branching: insertion angle %s deg, bud break probability %s to %s "
        "after %s days, child types: %s\n",
        s.insertion_angle_tip.describe().c_str(),
        s.vegetative_bud_break_probability_min.describe().c_str(),
        s.vegetative_bud_break_probability_max.describe().c_str(),
        s.vegetative_bud_break_time.describe().c_str(),
        children.empty() ? "same type" : children.c_str());
    std::printf(
        "    phytomer: internode pitch %s deg, phyllotactic angle %s deg, radius %s m; "
        "%u petiole%s of %s m at %s deg\n",
        p.internode.pitch.describe().c_str(), p.internode.phyllotactic_angle.describe().c_str(),
        p.internode.radius_initial.describe().c_str(), p.petiole.petioles_per_internode,
        p.petiole.petioles_per_internode == 1 ? "" : "s", p.petiole.length.describe().c_str(),
        p.petiole.pitch.describe().c_str());
    const LeafPrototype& leaf = p.leaf.prototype;
    std::printf("    leaves: %s per petiole, length %s m, %s outline (aspect %s)%s\n",
                p.leaf.leaves_per_petiole.describe().c_str(),
                p.leaf.prototype_scale.describe().c_str(), leaf.shape.c_str(),
                leaf.leaf_aspect_ratio.describe().c_str(),
                leaf.OBJ_model_file.empty() ? "" : (", OBJ " + leaf.OBJ_model_file).c_str());
    const InflorescenceParameters& f = p.inflorescence;
    std::printf(
        "    flowers: %s per peduncle, bud break probability %s, fruit set %s; "
        "flower %s (%s), fruit %s m (%s)\n",
        f.flowers_per_peduncle.describe().c_str(),
        s.flower_bud_break_probability.describe().c_str(),
        s.fruit_set_probability.describe().c_str(), orNone(f.flower_prototype_function).c_str(),
        rgb(f.flower_color).c_str(), f.fruit_prototype_scale.describe().c_str(),
        rgb(f.fruit_color).c_str());
    if (!p.phytomer_creation_function.empty() || !p.phytomer_callback_function.empty())
        std::printf("    functions: creation %s, callback %s\n",
                    orNone(p.phytomer_creation_function).c_str(),
                    orNone(p.phytomer_callback_function).c_str());
}

void printSummary(const SpeciesModel& m) {
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
    std::printf("\n\nshoot types (%zu):\n", m.shootTypes.size());
    for (const auto& [label, params] : m.shootTypes) printShootType(label, params);

    const PhenologyParameters& ph = m.phenology;
    std::printf(
        "\nphenology (days): dormancy break %s, flower initiation %s, flower opening %s, "
        "fruit set %s, fruit maturity %s, senescence %s, leaf lifespan %s, max age %s%s\n",
        fmt::format("{}", ph.time_to_dormancy_break).c_str(),
        fmt::format("{}", ph.time_to_flower_initiation).c_str(),
        fmt::format("{}", ph.time_to_flower_opening).c_str(),
        fmt::format("{}", ph.time_to_fruit_set).c_str(),
        fmt::format("{}", ph.time_to_fruit_maturity).c_str(),
        fmt::format("{}", ph.time_to_senescence).c_str(),
        fmt::format("{}", ph.max_leaf_lifespan).c_str(), fmt::format("{}", ph.max_age).c_str(),
        ph.evergreen ? ", evergreen" : "");

    if (m.buildParameters.empty()) {
        std::printf("\nbuild parameters: none\n");
    } else {
        std::printf("\nbuild parameters (plantarch build -D name=value):\n");
        for (const BuildParameter& p : m.buildParameters)
            std::printf("  %s\n", fmt::format("{} = {}{} (valid {} to {}){}", p.name, p.value,
                                              p.unit.empty() ? "" : " " + p.unit, p.min, p.max,
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

int run(const InfoArgs& a) {
    const SpeciesModel species = loadSpecies(a.species);
    if (a.xml) {
        writeSpecies(species, std::cout);
        std::cout.flush();
    } else {
        printSummary(species);
    }
    return 0;
}

std::function<int()> setup(CLI::App& app, GlobalOptions&) {
    app.description("Describe a species: shoot types, phenology, build parameters");
    auto args = std::make_shared<InfoArgs>();
    app.add_option("SPECIES", args->species, "Library name (see 'plantarch list') or species file")
        ->required();
    app.add_flag("--xml", args->xml,
                 "Print the complete species file (every value), which reads back identically");
    return [args] { return run(*args); };
}

}  // namespace

PLANTARCH_REGISTER_COMMAND(info, "info", 70, setup);

}  // namespace plantarch::cli
