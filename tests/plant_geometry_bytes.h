#pragma once
// Test helpers comparing plants' geometry across Contexts. Object IDs depend on the history
// of a Context (a grown plant's organs were created over time, a plant read from a file all at
// once), so geometry is compared organ by organ in the order of the plant's state.

#include <cstring>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

#include "plantarch/Export.h"
#include "plantarch/PlantArchitecture.h"

namespace plantarch::testing {

/// Calls f(objectID) for every object slot of the plant's organs, in state order (kNoObject
/// included, so a missing organ also shows up).
inline void forEachOrganObject(const PlantInstance& p, const std::function<void(ObjectID)>& f) {
    for (const Shoot& s : p.shoots) {
        if (s.removed) continue;
        auto floral = [&](const FloralBud& fb) {
            f(fb.peduncleObject);
            for (const FlowerOrgan& fl : fb.flowers)
                for (ObjectID id : fl.objects) f(id);
        };
        for (const Phytomer& ph : s.phytomers) {
            f(ph.internode.object);
            for (const Petiole& pt : ph.petioles) {
                f(pt.object);
                for (const LeafOrgan& l : pt.leaves)
                    for (ObjectID id : l.objects) f(id);
                for (const FloralBud& fb : pt.floralBuds) floral(fb);
            }
        }
        for (const FloralBud& fb : s.terminalFloralBuds) floral(fb);
    }
}

/// The plants' geometry as bytes: per organ object its vertex positions, UVs, triangle
/// indices, material and organ label, in state order.
inline std::string organBytes(const PlantArchitecture& arch, const std::vector<unsigned>& plants) {
    const Context& ctx = const_cast<PlantArchitecture&>(arch).context();
    std::string out;
    auto bytes = [&](const void* data, std::size_t n) {
        out.append(static_cast<const char*>(data), n);
    };
    for (unsigned id : plants)
        forEachOrganObject(arch.plant(id), [&](ObjectID o) {
            if (o == kNoObject || !ctx.doesObjectExist(o)) {
                out += "|none";
                return;
            }
            const ObjectView v = ctx.object(o);
            out += '|';
            out += ctx.objectDataString(o, "organ").value_or("?");
            out += ':';
            bytes(v.positions.data(), v.positions.size_bytes());
            bytes(v.uvs.data(), v.uvs.size_bytes());
            bytes(v.indices.data(), v.indices.size_bytes());
            const Material& m = ctx.material(v.material);
            bytes(&m.color, sizeof m.color);
            out += m.texture;
        });
    return out;
}

/// The plants' objects copied into a new Context in state order, with their data: what an
/// export of a plant built in one go would hold.
inline Context canonicalScene(const PlantArchitecture& arch, const std::vector<unsigned>& plants) {
    const Context& ctx = const_cast<PlantArchitecture&>(arch).context();
    Context out;
    for (unsigned id : plants)
        forEachOrganObject(arch.plant(id), [&](ObjectID o) {
            if (o == kNoObject || !ctx.doesObjectExist(o)) return;
            const ObjectView v = ctx.object(o);
            const ObjectID copy = out.addObject(v.positions, v.uvs, v.indices,
                                                out.addMaterial(ctx.material(v.material)));
            for (const std::string& label : ctx.objectDataLabels())
                if (auto value = ctx.objectData(o, label)) out.setObjectData(copy, label, *value);
        });
    return out;
}

/// "" when equal, else where the two first differ with some context (gtest's own diff of
/// megabyte strings needs gigabytes).
inline std::string firstDifference(const std::string& a, const std::string& b) {
    if (a == b) return "";
    std::size_t i = 0;
    while (i < a.size() && i < b.size() && a[i] == b[i]) ++i;
    const std::size_t from = i > 60 ? i - 60 : 0;
    auto around = [&](const std::string& s) {
        return from < s.size() ? s.substr(from, 120) : std::string("<end>");
    };
    return "sizes " + std::to_string(a.size()) + " and " + std::to_string(b.size()) +
           ", first difference at byte " + std::to_string(i) + ":\n[" + around(a) + "]\n[" +
           around(b) + "]";
}

inline std::string fileBytes(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

}  // namespace plantarch::testing
