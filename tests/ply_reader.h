#pragma once
// A small PLY reader for the tests: binary little-endian or ASCII, a vertex and a face element,
// scalar properties of types float, int and uchar, and one `list uchar int` face property.
// Every scalar property is read into a column of doubles (exact for these types).

#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace plantarch::testing {

struct PlyProperty {
    std::string type, name;  // type "list" for the vertex index list
};

struct PlyData {
    bool binary = false;
    std::vector<std::string> comments;
    std::vector<PlyProperty> vertexProperties, faceProperties;
    std::map<std::string, std::vector<double>> vertex, face;  // columns by property name
    std::vector<std::array<int, 3>> faces;
};

inline std::size_t plyTypeBytes(const std::string& type) {
    return type == "uchar" ? 1 : 4;
}

inline double plyBinaryValue(const char* p, const std::string& type) {
    if (type == "uchar") return double(static_cast<unsigned char>(*p));
    if (type == "int") {
        std::int32_t v;
        std::memcpy(&v, p, 4);
        return double(v);
    }
    float v;
    std::memcpy(&v, p, 4);
    return double(v);
}

/// Reads a PLY file; failures are gtest failures (the result is then incomplete).
inline PlyData readPlyFile(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    const std::string bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    PlyData ply;
    std::size_t pos = 0, vertexCount = 0, faceCount = 0;
    std::string element;
    while (pos < bytes.size()) {
        const std::size_t end = bytes.find('\n', pos);
        if (end == std::string::npos) break;
        const std::string line = bytes.substr(pos, end - pos);
        pos = end + 1;
        if (line == "end_header") break;
        std::istringstream words(line);
        std::string key;
        words >> key;
        if (key == "format") {
            std::string format;
            words >> format;
            ply.binary = format == "binary_little_endian";
        } else if (key == "comment") {
            ply.comments.push_back(line.substr(8));
        } else if (key == "element") {
            std::size_t n = 0;
            words >> element >> n;
            (element == "vertex" ? vertexCount : faceCount) = n;
        } else if (key == "property") {
            PlyProperty p;
            words >> p.type;
            if (p.type == "list") {
                std::string countType, itemType;
                words >> countType >> itemType;
                EXPECT_EQ(countType + " " + itemType, "uchar int");
            }
            words >> p.name;
            (element == "vertex" ? ply.vertexProperties : ply.faceProperties).push_back(p);
        }
    }
    for (const auto& p : ply.vertexProperties) ply.vertex[p.name].resize(vertexCount);
    for (const auto& p : ply.faceProperties)
        if (p.type != "list") ply.face[p.name].resize(faceCount);
    ply.faces.resize(faceCount);
    if (ply.binary) {
        const char* p = bytes.data() + pos;
        const char* end = bytes.data() + bytes.size();
        for (std::size_t v = 0; v < vertexCount; ++v)
            for (const auto& prop : ply.vertexProperties) {
                if (p + plyTypeBytes(prop.type) > end) {
                    ADD_FAILURE() << path << ": truncated vertex data";
                    return ply;
                }
                ply.vertex[prop.name][v] = plyBinaryValue(p, prop.type);
                p += plyTypeBytes(prop.type);
            }
        for (std::size_t f = 0; f < faceCount; ++f)
            for (const auto& prop : ply.faceProperties) {
                if (prop.type == "list") {
                    if (p + 13 > end || p[0] != 3) {
                        ADD_FAILURE() << path << ": bad face " << f;
                        return ply;
                    }
                    std::memcpy(ply.faces[f].data(), p + 1, 12);
                    p += 13;
                } else {
                    if (p + plyTypeBytes(prop.type) > end) {
                        ADD_FAILURE() << path << ": truncated face data";
                        return ply;
                    }
                    ply.face[prop.name][f] = plyBinaryValue(p, prop.type);
                    p += plyTypeBytes(prop.type);
                }
            }
        EXPECT_EQ(p, end) << path << ": trailing bytes";
    } else {
        std::istringstream body(bytes.substr(pos));
        // A float property's text is read as a float (as a binary file would hold it).
        auto number = [&](const std::string& type = "int") {
            std::string word;
            body >> word;
            return type == "float" ? double(std::strtof(word.c_str(), nullptr))
                                   : std::strtod(word.c_str(), nullptr);
        };
        for (std::size_t v = 0; v < vertexCount; ++v)
            for (const auto& prop : ply.vertexProperties)
                ply.vertex[prop.name][v] = number(prop.type);
        for (std::size_t f = 0; f < faceCount; ++f)
            for (const auto& prop : ply.faceProperties) {
                if (prop.type == "list") {
                    EXPECT_EQ(number(), 3.0);
                    for (int& i : ply.faces[f]) i = int(number());
                } else {
                    ply.face[prop.name][f] = number(prop.type);
                }
            }
        std::string rest;
        body >> rest;
        EXPECT_TRUE(rest.empty()) << path << ": trailing data " << rest;
    }
    return ply;
}

}  // namespace plantarch::testing
