// The model specification's "modify parameters of a plant loaded from the library" listing,
// with the include line and namespace changed and its variable name made consistent (the
// listing declares `plantarchitecture` but then calls `plantarch`).
#include <cstdio>

#include "plantarch/PlantArchitecture.h"
using namespace plantarch;

int main() {
    // define the Helios Context class (main model database)
    Context context;

    // define an instance of the plant architecture model
    PlantArchitecture plantarch(&context);

    // load "bean" model parameters from the library
    plantarch.loadPlantModelFromLibrary("bean");

    // modify the parameters
    // the "bean" model has shoot types of "unifoliate" and "trifoliate"
    ShootParameters params_uni = plantarch.getCurrentShootParameters("unifoliate");
    params_uni.max_nodes = 20;
    params_uni.phytomer_parameters.internode.pitch = 5.0;
    plantarch.updateCurrentShootParameters("unifoliate", params_uni);
    ShootParameters params_tri = plantarch.getCurrentShootParameters("trifoliate");
    params_tri.max_nodes = 25;
    plantarch.updateCurrentShootParameters("trifoliate", params_tri);

    // add the plant with its base at the origin
    // plant will be built based on updated parameters
    vec3 plant_origin(0, 0, 0);
    float age = 15;  // days
    uint plantID = plantarch.buildPlantInstanceFromLibrary(plant_origin, age);

    std::printf("plant %u: %u leaves, %.3f m tall\n", plantID, plantarch.getPlantLeafCount(plantID),
                plantarch.getPlantHeight(plantID));
    return plantarch.getPlantLeafCount(plantID) > 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}
