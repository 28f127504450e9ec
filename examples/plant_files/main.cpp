// Saving plants and reading them back (docs/plant-xml.md): a bean grown 30 days is saved,
// read into a fresh PlantArchitecture with nothing loaded, and both grow on for 20 days into
// the same plant. The plant string of the result is printed, and read back.
#include <cstdio>
#include <cstdlib>

#include "plantarch/PlantArchitecture.h"
using namespace plantarch;

int main() {
    Context context;
    PlantArchitecture arch(&context);
    arch.loadPlantModelFromLibrary("bean");
    const unsigned bean = arch.buildPlantInstanceFromLibrary(vec3(0, 0, 0), 30);
    arch.writePlantStructureXML(bean, "bean_30_days.xml");

    Context other;
    PlantArchitecture fresh(&other);  // no species loaded: the file carries its parameters
    PlantStructureReadOptions options;
    options.onWarning = [](const std::string& w) {
        std::fprintf(stderr, "warning: %s\n", w.c_str());
    };
    const unsigned copy = fresh.readPlantStructureXML("bean_30_days.xml", options).at(0);

    arch.advanceTime(20);
    fresh.advanceTime(20);
    const bool same = arch.getPlantStructureXML({bean}) == fresh.getPlantStructureXML({copy});
    std::printf("grown on after saving: %s (%u leaves, %.4f m^2)\n",
                same ? "same plant" : "DIFFERENT", fresh.getPlantLeafCount(copy),
                fresh.getPlantLeafArea(copy));

    const std::string text = fresh.getPlantString(copy);  // 4 significant digits
    std::printf("plant string: %zu characters, starts %.60s...\n", text.size(), text.c_str());
    fresh.loadPlantModelFromLibrary("bean");  // strings name shoot types: load the species
    const unsigned fromString = fresh.generatePlantFromString(text);
    const bool exact = fresh.getPlantString(fromString) == text;
    std::printf("string -> plant -> string: %s\n", exact ? "identical" : "DIFFERENT");
    return same && exact ? EXIT_SUCCESS : EXIT_FAILURE;
}
