// A small command-line driver of the reference system, for whole-process timings beside
// plantarch's own command (bench/scripts/user_speed.py). Each run does one job and prints
// the in-process time of its main step as JSON on stdout:
//
//   reference_driver empty
//   reference_driver build SPECIES AGE [SEED]
//   reference_driver canopy SPECIES NX NY SPACING AGE [ply|obj|soft]... [--out FILE]
//   reference_driver xml-write SPECIES AGE FILE
//   reference_driver xml-read SPECIES FILE   (the reference reads a file only with its
//                                             species loaded)
//
// Run it from its build folder: the reference finds its assets there.

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "PlantArchitecture.h"

using namespace helios;

namespace {

double since(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

int usage() {
    std::fprintf(stderr,
                 "usage: reference_driver empty | build SPECIES AGE [SEED] | canopy SPECIES NX NY "
                 "SPACING AGE [ply|obj|soft]... [--out FILE] | xml-write SPECIES AGE FILE | "
                 "xml-read SPECIES FILE\n");
    return 2;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 2) return usage();
    const std::string job = argv[1];
    Context context;
    if (job == "empty") {
        std::printf("{\"job\": \"empty\"}\n");
        return 0;
    }
    PlantArchitecture pa(&context);
    if (job == "build" && (argc == 4 || argc == 5)) {
        if (argc == 5) context.seedRandomGenerator(uint(std::atoi(argv[4])));
        const auto t0 = std::chrono::steady_clock::now();
        pa.loadPlantModelFromLibrary(argv[2]);
        pa.buildPlantInstanceFromLibrary(make_vec3(0, 0, 0), float(std::atof(argv[3])));
        std::printf("{\"job\": \"build\", \"ms\": %.3f, \"primitives\": %zu}\n", since(t0),
                    context.getPrimitiveCount());
        return 0;
    }
    if (job == "canopy" && argc >= 7) {
        bool ply = false, obj = false, soft = false;
        std::string out = "reference_canopy";
        for (int i = 7; i < argc; ++i) {
            const std::string a = argv[i];
            if (a == "ply")
                ply = true;
            else if (a == "obj")
                obj = true;
            else if (a == "soft")
                soft = true;
            else if (a == "--out" && i + 1 < argc)
                out = argv[++i];
            else
                return usage();
        }
        const auto t0 = std::chrono::steady_clock::now();
        pa.loadPlantModelFromLibrary(argv[2]);
        if (soft) pa.enableSoftCollisionAvoidance();
        const float spacing = float(std::atof(argv[5]));
        pa.buildPlantCanopyFromLibrary(make_vec3(0, 0, 0), make_vec2(spacing, spacing),
                                       make_int2(std::atoi(argv[3]), std::atoi(argv[4])),
                                       float(std::atof(argv[6])));
        const double build = since(t0);
        if (ply) context.writePLY((out + ".ply").c_str());
        if (obj) context.writeOBJ(out + ".obj", false, true);
        std::printf(
            "{\"job\": \"canopy\", \"build_ms\": %.3f, \"ms\": %.3f, \"primitives\": %zu}\n", build,
            since(t0), context.getPrimitiveCount());
        return 0;
    }
    if (job == "xml-write" && argc == 5) {
        pa.loadPlantModelFromLibrary(argv[2]);
        const uint id =
            pa.buildPlantInstanceFromLibrary(make_vec3(0, 0, 0), float(std::atof(argv[3])));
        const auto t0 = std::chrono::steady_clock::now();
        pa.writePlantStructureXML(id, argv[4]);
        std::printf("{\"job\": \"xml-write\", \"ms\": %.3f}\n", since(t0));
        return 0;
    }
    if (job == "xml-read" && argc == 4) {
        pa.loadPlantModelFromLibrary(argv[2]);
        const auto t0 = std::chrono::steady_clock::now();
        const std::vector<uint> ids = pa.readPlantStructureXML(argv[3], true);
        std::printf("{\"job\": \"xml-read\", \"ms\": %.3f, \"plants\": %zu}\n", since(t0),
                    ids.size());
        return 0;
    }
    return usage();
}
