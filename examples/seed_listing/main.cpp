// The model specification's "manually building a plant structure" listing, compiled as
// written there with only the include line and the namespace changed.
#include "plantarch/PlantArchitecture.h"
using namespace plantarch;

int main() {
    // define the Helios Context class (main model database)
    Context context;

    // define an instance of the plant architecture model
    PlantArchitecture plantarchitecture(&context);

    // Load an existing set of shoot parameters from the library
    // Alternatively, we could manually define a fresh set ourselves
    plantarchitecture.loadPlantModelFromLibrary("bean");

    // add the plant with its base at the origin
    vec3 base_position(0, 0, 0);
    float age = 15;  // days
    uint plantID = plantarchitecture.addPlantInstance(base_position, age);

    return EXIT_SUCCESS;
}
