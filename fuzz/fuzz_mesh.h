#pragma once
// What the mesh-reader fuzz targets (fuzz_obj, fuzz_ply, fuzz_gltf) share: a scratch file of
// the process's own, a failure that stops the run, and a Context summarized as text (objects,
// triangles and every object's labels) for write -> read comparisons.

#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>
#include <type_traits>
#include <variant>

#include "plantarch/Context.h"
#include "plantarch/Error.h"

namespace plantarch::fuzz {

// A file of this process's own on a memory file system when there is one.
inline std::string scratch(const char* target, const char* name) {
    const char* dir = ::access("/dev/shm", W_OK) == 0 ? "/dev/shm" : "/tmp";
    return std::string(dir) + "/plantarch-fuzz-" + target + "-" + std::to_string(::getpid()) + "-" +
           name;
}

inline void writeInput(const std::string& path, const std::uint8_t* data, std::size_t size) {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), std::streamsize(size));
}

[[noreturn]] inline void fail(const char* target, const std::string& why) {
    std::fprintf(stderr, "fuzz_%s: %s\n", target, why.c_str());
    std::abort();
}

// Objects, triangles and every object's labels, as text. `keep(label, id)` says which labels
// count (a name an OBJ gives an object only where the first Context had one, say).
template <class Keep>
std::string summary(const Context& ctx, Keep&& keep) {
    std::string s = std::to_string(ctx.objectCount()) + " objects, " +
                    std::to_string(ctx.triangleCount()) + " triangles\n";
    for (ObjectID id : ctx.objectIDs())
        for (const std::string& label : ctx.objectDataLabels())
            if (auto v = ctx.objectData(id, label); v && keep(label, id))
                std::visit(
                    [&](const auto& x) {
                        using T = std::decay_t<decltype(x)>;
                        s += label + "=";
                        if constexpr (std::is_same_v<T, std::string>)
                            s += x;
                        else if constexpr (std::is_same_v<T, vec3>)
                            s += std::to_string(x.x) + "," + std::to_string(x.y) + "," +
                                 std::to_string(x.z);
                        else
                            s += std::to_string(x);
                        s += ";";
                    },
                    *v);
    return s;
}

/// Every label counts.
inline std::string summary(const Context& ctx) {
    return summary(ctx, [](const std::string&, ObjectID) { return true; });
}

/// read(ctx) for an input: whether it read. A read that throws plantarch::Error must leave
/// the Context empty; anything else thrown is a crash.
template <class Read>
bool readsOrAddsNothing(const char* target, Context& ctx, Read&& read) {
    try {
        read(ctx);
        return true;
    } catch (const Error&) {
        if (ctx.objectCount() != 0) fail(target, "a failed read left objects in the Context");
        return false;
    }
}

/// write(ctx) then read(again) must give the same summary (`what` names the written file).
template <class Write, class Read>
void roundTrips(const char* target, const char* what, const Context& ctx, Write&& write,
                Read&& read) {
    try {
        write(ctx);
        Context again;
        read(again);
        if (summary(again) != summary(ctx))
            fail(target, "write -> read changed the objects or labels:\n" + summary(ctx) +
                             "-- became --\n" + summary(again));
    } catch (const Error& e) {
        fail(target, std::string("a written ") + what + " does not read back: " + e.what());
    }
}

}  // namespace plantarch::fuzz
