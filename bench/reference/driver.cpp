// A small command-line driver of the reference system, for whole-process timings beside
// plantarch's own command (bench/scripts/user_speed.py) and for the reference plants of
// tests/data/reference_plants/. Each run does one job and prints the in-process time of its
// main step (and the box of what it drew) as JSON on stdout:
//
//   reference_driver empty
//   reference_driver build SPECIES AGE [SEED]
//   reference_driver canopy SPECIES NX NY SPACING AGE [ply|obj|soft]... [--out FILE]
//   reference_driver xml-write SPECIES AGE FILE [SEED [DUMP]]
//   reference_driver xml-read SPECIES FILE [DUMP]
//   reference_driver stats SPECIES AGE FIRST_SEED LAST_SEED
//   reference_driver shoots SPECIES AGE SEED
//
// (the reference reads a file only with its species loaded). stats prints, instead, one JSON
// line per seed with the plant statistics bench/scripts/fidelity.py compares: each seed's
// plant grown in a Context of its own. shoots prints one line per shoot: its ID, type, rank,
// parent shoot and node, node count, and each floral bud as node:state:inflorescence objects. DUMP:
// a text file listing every primitive drawn, one per line: its object label, object ID and
// vertices.
//
// Run it from its build folder: the reference finds its assets there.

#include <algorithm>
#include <chrono>
#include <cmath>
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

// The bounding box of every primitive's vertices, as JSON members.
std::string boxJson(Context& context) {
    float lo[3] = {1e30f, 1e30f, 1e30f}, hi[3] = {-1e30f, -1e30f, -1e30f};
    for (const uint uuid : context.getAllUUIDs()) {
        for (const vec3& v : context.getPrimitiveVertices(uuid)) {
            const float c[3] = {v.x, v.y, v.z};
            for (int k = 0; k < 3; ++k) {
                lo[k] = std::min(lo[k], c[k]);
                hi[k] = std::max(hi[k], c[k]);
            }
        }
    }
    char text[256];
    std::snprintf(text, sizeof text, "\"min\": [%.5f, %.5f, %.5f], \"max\": [%.5f, %.5f, %.5f]",
                  lo[0], lo[1], lo[2], hi[0], hi[1], hi[2]);
    return text;
}

// Every primitive as one line: its object_label (or "-") and its vertices.
void dumpPrimitives(Context& context, const char* path) {
    FILE* f = std::fopen(path, "w");
    if (!f) return;
    for (const uint uuid : context.getAllUUIDs()) {
        std::string label = "-";
        if (context.doesPrimitiveDataExist(uuid, "object_label"))
            context.getPrimitiveData(uuid, "object_label", label);
        std::fprintf(f, "%s %u", label.c_str(), context.getPrimitiveParentObjectID(uuid));
        for (const vec3& v : context.getPrimitiveVertices(uuid))
            std::fprintf(f, " %.6f %.6f %.6f", v.x, v.y, v.z);
        std::fprintf(f, "\n");
    }
    std::fclose(f);
}

// The horizontal extents of a point set along its own axes: the largest over every degree of
// direction, and the extent square to that direction. The same measure as plantarch's
// summarizePlant, written again here because this driver is built against the reference alone.
void ownAxes(const std::vector<vec3>& points, double& longest, double& across) {
    longest = -1.0;
    across = 0.0;
    for (int degree = 0; degree < 180; ++degree) {
        const double a = degree * 3.14159265358979 / 180.0, c = std::cos(a), s = std::sin(a);
        double l0 = 1e30, l1 = -1e30, w0 = 1e30, w1 = -1e30;
        for (const vec3& q : points) {
            const double along = c * q.x + s * q.y, square = c * q.y - s * q.x;
            l0 = std::min(l0, along);
            l1 = std::max(l1, along);
            w0 = std::min(w0, square);
            w1 = std::max(w1, square);
        }
        if (l1 - l0 > longest) {
            longest = l1 - l0;
            across = w1 - w0;
        }
    }
}

// One plant's statistics as a JSON line: the box of its primitives, leaf area (one-sided) and
// count, flower and fruit objects, shoots and phytomers by rank, and the leaf area's
// inclination histogram in 9 bins of 10 degrees.
std::string statsJson(Context& context, PlantArchitecture& pa, uint plant) {
    std::vector<vec3> points;
    float lo[3] = {1e30f, 1e30f, 1e30f}, hi[3] = {-1e30f, -1e30f, -1e30f};
    for (const uint uuid : context.getObjectPrimitiveUUIDs(pa.getAllPlantObjectIDs(plant))) {
        for (const vec3& v : context.getPrimitiveVertices(uuid)) {
            points.push_back(v);
            const float c[3] = {v.x, v.y, v.z};
            for (int k = 0; k < 3; ++k) {
                lo[k] = std::min(lo[k], c[k]);
                hi[k] = std::max(hi[k], c[k]);
            }
        }
    }
    double longest = 0.0, across = 0.0;
    ownAxes(points, longest, across);
    std::vector<unsigned> shoots, phytomers;
    for (const uint id : pa.getAllShootIDs(plant)) {
        const auto& shoot = pa.getPlantShoot(plant, id);
        if (shoots.size() <= shoot->rank) {
            shoots.resize(shoot->rank + 1, 0);
            phytomers.resize(shoot->rank + 1, 0);
        }
        ++shoots[shoot->rank];
        phytomers[shoot->rank] += unsigned(shoot->phytomers.size());
    }
    const auto list = [](const auto& values, const char* format) {
        std::string text = "[";
        char cell[32];
        for (std::size_t i = 0; i < values.size(); ++i) {
            std::snprintf(cell, sizeof cell, format, values[i]);
            text += (i ? ", " : "") + std::string(cell);
        }
        return text + "]";
    };
    const std::vector<float> inclination =
        pa.getPlantLeafInclinationAngleDistribution(plant, 9, true);
    char text[1024];
    std::snprintf(text, sizeof text,
                  "\"height\": %.5f, \"leaf_area\": %.6f, \"leaf_count\": %u, \"width_x\": %.5f, "
                  "\"width_y\": %.5f, \"width_long\": %.5f, \"width_short\": %.5f, "
                  "\"flowers\": %zu, \"fruit\": %zu, \"shoots_by_rank\": %s, "
                  "\"phytomers_by_rank\": %s, \"main_nodes\": %u, \"leaf_inclination\": %s",
                  hi[2], pa.sumPlantLeafArea(plant), pa.getPlantLeafCount(plant), hi[0] - lo[0],
                  hi[1] - lo[1], longest, across, pa.getPlantFlowerObjectIDs(plant).size(),
                  pa.getPlantFruitObjectIDs(plant).size(), list(shoots, "%u").c_str(),
                  list(phytomers, "%u").c_str(), pa.getShootNodeCount(plant, 0),
                  list(inclination, "%.4f").c_str());
    return text;
}

int usage() {
    std::fprintf(
        stderr,
        "usage: reference_driver empty | build SPECIES AGE [SEED] | canopy SPECIES NX NY "
        "SPACING AGE [ply|obj|soft]... [--out FILE] | xml-write SPECIES AGE FILE [SEED [DUMP]] | "
        "xml-read SPECIES FILE [DUMP] | stats SPECIES AGE FIRST_SEED LAST_SEED | shoots SPECIES "
        "AGE SEED\n");
    return 2;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 2) return usage();
    const std::string job = argv[1];
    if (job == "shoots" && argc == 5) {
        Context context;
        PlantArchitecture pa(&context);
        context.seedRandomGenerator(uint(std::atoi(argv[4])));
        pa.loadPlantModelFromLibrary(argv[2]);
        const uint plant =
            pa.buildPlantInstanceFromLibrary(make_vec3(0, 0, 0), float(std::atof(argv[3])));
        for (const uint id : pa.getAllShootIDs(plant)) {
            const auto& shoot = pa.getPlantShoot(plant, id);
            std::printf("shoot %u %s rank %u parent %d@%u nodes %zu:", id,
                        shoot->shoot_type_label.c_str(), shoot->rank, shoot->parent_shoot_ID,
                        shoot->parent_node_index, shoot->phytomers.size());
            for (std::size_t n = 0; n < shoot->phytomers.size(); ++n)
                for (const auto& buds : shoot->phytomers[n]->floral_buds)
                    for (const FloralBud& fb : buds)
                        std::printf(" %zu:%d:%zu", n, int(fb.state),
                                    fb.inflorescence_objIDs.size());
            std::printf("\n");
        }
        return 0;
    }
    if (job == "stats" && argc == 6) {
        for (int seed = std::atoi(argv[4]); seed <= std::atoi(argv[5]); ++seed) {
            Context context;
            PlantArchitecture pa(&context);
            context.seedRandomGenerator(uint(seed));
            pa.loadPlantModelFromLibrary(argv[2]);
            const uint plant =
                pa.buildPlantInstanceFromLibrary(make_vec3(0, 0, 0), float(std::atof(argv[3])));
            std::printf("{\"species\": \"%s\", \"age\": %s, \"seed\": %d, %s}\n", argv[2], argv[3],
                        seed, statsJson(context, pa, plant).c_str());
            std::fflush(stdout);
        }
        return 0;
    }
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
        const double ms = since(t0);
        std::printf("{\"job\": \"build\", \"ms\": %.3f, \"primitives\": %zu, %s}\n", ms,
                    context.getPrimitiveCount(), boxJson(context).c_str());
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
    if (job == "xml-write" && (argc >= 5 && argc <= 7)) {
        if (argc >= 6) context.seedRandomGenerator(uint(std::atoi(argv[5])));
        pa.loadPlantModelFromLibrary(argv[2]);
        const uint id =
            pa.buildPlantInstanceFromLibrary(make_vec3(0, 0, 0), float(std::atof(argv[3])));
        const auto t0 = std::chrono::steady_clock::now();
        pa.writePlantStructureXML(id, argv[4]);
        const double ms = since(t0);
        std::printf("{\"job\": \"xml-write\", \"ms\": %.3f, \"primitives\": %zu, %s}\n", ms,
                    context.getPrimitiveCount(), boxJson(context).c_str());
        if (argc == 7) dumpPrimitives(context, argv[6]);
        return 0;
    }
    if (job == "xml-read" && (argc == 4 || argc == 5)) {
        pa.loadPlantModelFromLibrary(argv[2]);
        const auto t0 = std::chrono::steady_clock::now();
        const std::vector<uint> ids = pa.readPlantStructureXML(argv[3], true);
        const double ms = since(t0);
        std::printf(
            "{\"job\": \"xml-read\", \"ms\": %.3f, \"plants\": %zu, \"primitives\": "
            "%zu, %s}\n",
            ms, ids.size(), context.getPrimitiveCount(), boxJson(context).c_str());
        if (argc == 5) dumpPrimitives(context, argv[4]);
        return 0;
    }
    return usage();
}
