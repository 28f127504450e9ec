// --skin: glTF and USD outputs of plants carry a wind-ready skeleton (a joint per internode,
// vertex weights), posed as the plant stands (bent under load where it bends); --wind adds a
// looping animation swaying it to glTF outputs.

#include "cli.h"
#include "plantarch/Error.h"

namespace plantarch::cli {

void addSkinOptions(CLI::App& app, GlobalOptions& global) {
    app.add_flag("--skin", global.skin,
                 "Skin the plants of .glb, .gltf and .usda outputs: a skeleton with a joint per "
                 "internode and per-vertex weights, so an engine can sway them (bind pose: the "
                 "plant as built, bent where it bends); other outputs are unchanged");
    app.add_option_function<float>(
           "--wind",
           [&global](float degrees) {
               global.wind = degrees;
               global.skin = global.skin || degrees > 0.0f;
           },
           "With --skin (implied): a looping 2 s animation \"wind\" in .glb and .gltf outputs "
           "swaying each plant toward +x, its deepest tip by about DEGREES (0 to 90)")
        ->type_name("DEGREES")
        ->check(numberCheck("--wind", "an angle in degrees", 0.0, 90.0, false, "0 to 90"));
}

void checkSkinOutputs(const GlobalOptions& global, bool frames, bool separate) {
    if (!global.skin) return;
    const char* option = global.wind > 0.0f ? "--wind" : "--skin";
    if (frames)
        throw Error("a growth animation is not skinned (its organs are keyed per frame)",
                    {.parameter = option, .validRange = "without --frames"});
    if (separate)
        throw Error("files of one plant each are not skinned",
                    {.parameter = option, .validRange = "without --separate"});
}

}  // namespace plantarch::cli
