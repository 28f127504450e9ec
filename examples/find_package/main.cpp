// Builds a tiny scene in a plantarch Context and prints what it holds.
#include <plantarch/Context.h>
#include <plantarch/Version.h>

#include <cstdio>

int main() {
    plantarch::Context context;
    plantarch::Mesh leaf;
    leaf.positions = {{0, 0, 0}, {0.1f, -0.02f, 0}, {0.1f, 0.02f, 0}};
    leaf.indices = {0, 1, 2};
    const auto id = context.addObject(leaf, plantarch::Material{.color = {0.2f, 0.6f, 0.2f}});
    context.setObjectData(id, "organ", std::string("leaf"));
    std::printf("plantarch %s: %zu object, %zu triangle, area %.4f m2\n", PLANTARCH_VERSION_STRING,
                context.objectCount(), context.triangleCount(), context.objectArea(id));
    return context.triangleCount() == 1 ? 0 : 1;
}
