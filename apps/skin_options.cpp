// --skin: glTF and USD outputs of plants carry a wind-ready skeleton (a joint per internode,
// vertex weights), posed as the plant stands (bent under load where it bends).

#include "cli.h"

namespace plantarch::cli {

void addSkinOptions(CLI::App& app, GlobalOptions& global) {
    app.add_flag("--skin", global.skin,
                 "Skin the plants of .glb, .gltf and .usda outputs: a skeleton with a joint per "
                 "internode and per-vertex weights, so an engine can sway them (bind pose: the "
                 "plant as built, bent where it bends); other outputs are unchanged");
}

}  // namespace plantarch::cli
