// The bending options of build and grow: --bend, --pull SHOOT:NODE:FX,FY,FZ and
// --displace SHOOT:NODE:DX,DY,DZ (docs/measured-plants.md, "Shoots bending under load").

#include "bend_options.h"

#include <fmt/format.h>

#include <charconv>
#include <cstdio>

#include "plantarch/Bending.h"
#include "plantarch/Error.h"
#include "plantarch/PlantArchitecture.h"

namespace plantarch::cli {

namespace {

struct NodeLoad {
    unsigned shoot = 0, node = 0;
    vec3 value{0.0f};
};

unsigned parseIndex(const std::string& text, const std::string& all, const char* option) {
    unsigned v = 0;
    const auto [p, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
    if (text.empty() || ec != std::errc() || p != text.data() + text.size())
        throw Error("not SHOOT:NODE:X,Y,Z",
                    {.parameter = option,
                     .value = all,
                     .validRange = "shoot ID and node index (whole numbers >= 0), then x,y,z"});
    return v;
}

NodeLoad parseNodeLoad(const std::string& text, const char* option) {
    const std::size_t a = text.find(':');
    const std::size_t b = a == std::string::npos ? a : text.find(':', a + 1);
    if (b == std::string::npos)
        throw Error("not SHOOT:NODE:X,Y,Z",
                    {.parameter = option, .value = text, .validRange = "e.g. 3:5:0,0,-10"});
    NodeLoad l;
    l.shoot = parseIndex(text.substr(0, a), text, option);
    l.node = parseIndex(text.substr(a + 1, b - a - 1), text, option);
    l.value = parseVec3(text.substr(b + 1), option);
    return l;
}

std::string shown(const vec3& v) {
    // (+ 0: no "-0")
    return fmt::format("({:.6g}, {:.6g}, {:.6g})", v.x + 0.0f, v.y + 0.0f, v.z + 0.0f);
}

}  // namespace

void addBendOptions(CLI::App& app, BendArgs& a) {
    app.add_flag("--bend", a.bend,
                 "Bend the shoots under their weight, leaves and fruit (the species' mechanics "
                 "parameters; docs/measured-plants.md)");
    app.add_option("--pull", a.pull,
                   "Pull node NODE of shoot SHOOT of the (first) plant with a force, "
                   "SHOOT:NODE:FX,FY,FZ in N, and print the reaction forces");
    app.add_option("--displace", a.displace,
                   "Move node NODE of shoot SHOOT by SHOOT:NODE:DX,DY,DZ in m and print the "
                   "force it takes")
        ->excludes("--pull");
}

bool bendOn(const BendArgs& a) {
    return a.bend || !a.pull.empty() || !a.displace.empty();
}

void checkBendOptions(const BendArgs& a) {
    if (!a.pull.empty()) parseNodeLoad(a.pull, "--pull");
    if (!a.displace.empty()) parseNodeLoad(a.displace, "--displace");
}

void enableBending(PlantArchitecture& arch, const std::vector<unsigned>& plants,
                   const BendArgs& a) {
    if (!a.bend) return;
    for (unsigned id : plants) {
        PhenologyParameters ph = arch.plant(id).phenology;
        if (ph.mechanics.enabled) continue;
        ph.mechanics.enabled = true;
        arch.setPlantPhenologicalThresholds(id, ph);
    }
}

void applyBending(PlantArchitecture& arch, const std::vector<unsigned>& plants, const BendArgs& a,
                  std::FILE* out) {
    if (plants.empty()) return;
    if (a.bend)
        for (unsigned id : plants) bendPlant(arch, id);
    if (a.pull.empty() && a.displace.empty()) return;
    const bool pull = !a.pull.empty();
    const NodeLoad l = parseNodeLoad(pull ? a.pull : a.displace, pull ? "--pull" : "--displace");
    const PullResult r = pull ? pullNode(arch, plants.front(), l.shoot, l.node, l.value)
                              : displaceNode(arch, plants.front(), l.shoot, l.node, l.value);
    std::fprintf(out, "%s",
                 fmt::format("plant {} shoot {} node {}: force {} N moved it {} m to {}; reaction "
                             "at the node {} N, at the shoot's base {} N and {} N m, at the "
                             "ground {} N and {} N m\n",
                             plants.front(), l.shoot, l.node, shown(r.force), shown(r.displacement),
                             shown(r.position), shown(r.nodeReaction), shown(r.baseForce),
                             shown(r.baseMoment), shown(r.groundForce), shown(r.groundMoment))
                     .c_str());
}

}  // namespace plantarch::cli
