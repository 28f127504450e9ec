#pragma once
// A .glb file taken apart for the glTF tests: its JSON and binary chunk, and the values of
// its accessors and buffer views.

#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace plantarch::testing {

inline std::string readAll(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

struct Glb {
    nlohmann::json doc;
    std::string bin;
};

/// The chunks of a .glb, checking its header and chunk types on the way.
inline Glb parseGlb(const std::string& bytes) {
    std::uint32_t header[3], chunk[2];
    EXPECT_GE(bytes.size(), 20u);
    std::memcpy(header, bytes.data(), 12);
    EXPECT_EQ(header[0], 0x46546C67u);  // "glTF"
    EXPECT_EQ(header[1], 2u);
    EXPECT_EQ(header[2], bytes.size());
    std::memcpy(chunk, bytes.data() + 12, 8);
    EXPECT_EQ(chunk[1], 0x4E4F534Au);  // "JSON"
    EXPECT_EQ(chunk[0] % 4, 0u);
    Glb g;
    g.doc = nlohmann::json::parse(bytes.substr(20, chunk[0]));
    const std::size_t binAt = 20 + chunk[0];
    std::memcpy(chunk, bytes.data() + binAt, 8);
    EXPECT_EQ(chunk[1], 0x004E4942u);  // "BIN"
    g.bin = bytes.substr(binAt + 8, chunk[0]);
    return g;
}

/// The values of an accessor (tightly packed, as plantarch writes them, from the accessor's
/// byteOffset in its view; zeros with sparse values laid over them).
template <class T>
std::vector<T> accessorValues(const Glb& g, int accessorIndex) {
    const nlohmann::json& a = g.doc["accessors"][accessorIndex];
    const std::string type = a["type"];
    const std::size_t components = type == "VEC4" ? 4 : type == "VEC3" ? 3 : type == "VEC2" ? 2 : 1;
    std::vector<T> out(a["count"].get<std::size_t>() * components);
    if (a.contains("bufferView")) {
        const nlohmann::json& v = g.doc["bufferViews"][a["bufferView"].get<int>()];
        std::memcpy(out.data(),
                    g.bin.data() + v["byteOffset"].get<std::size_t>() +
                        a.value("byteOffset", std::size_t(0)),
                    out.size() * sizeof(T));
    }
    if (a.contains("sparse")) {
        const nlohmann::json& s = a["sparse"];
        const std::size_t n = s["count"];
        EXPECT_EQ(s["indices"]["componentType"], 5125);  // plantarch writes uint32 indices
        const nlohmann::json& iv = g.doc["bufferViews"][s["indices"]["bufferView"].get<int>()];
        const nlohmann::json& vv = g.doc["bufferViews"][s["values"]["bufferView"].get<int>()];
        std::vector<std::uint32_t> indices(n);
        std::memcpy(indices.data(), g.bin.data() + iv["byteOffset"].get<std::size_t>(), 4 * n);
        for (std::size_t k = 0; k < n; ++k)
            std::memcpy(
                out.data() + indices[k] * components,
                g.bin.data() + vv["byteOffset"].get<std::size_t>() + k * components * sizeof(T),
                components * sizeof(T));
    }
    return out;
}

/// The first `count` values of a buffer view.
template <class T>
std::vector<T> viewValues(const Glb& g, int view, std::size_t count) {
    const nlohmann::json& v = g.doc["bufferViews"][view];
    std::vector<T> out(count);
    std::memcpy(out.data(), g.bin.data() + v["byteOffset"].get<std::size_t>(), count * sizeof(T));
    return out;
}

}  // namespace plantarch::testing
