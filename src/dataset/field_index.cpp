// A field's index from its tiles' files: tileset.json (3D Tiles 1.1, one child per tile with
// its GLB) and plants.csv (every tile's rows in tile order).

#include <charconv>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/atomic_file.h"
#include "core/value_text.h"
#include "dataset/field_internal.h"
#include "plantarch/Error.h"

namespace plantarch {

namespace field {

namespace {

// The fields of one CSV line (quoted fields unquoted).
std::vector<std::string> csvFields(const std::string& line) {
    std::vector<std::string> out(1);
    bool quoted = false;
    for (std::size_t i = 0; i < line.size(); ++i) {
        const char c = line[i];
        if (quoted) {
            if (c == '"' && i + 1 < line.size() && line[i + 1] == '"') {
                out.back() += '"';
                ++i;
            } else if (c == '"') {
                quoted = false;
            } else {
                out.back() += c;
            }
        } else if (c == '"') {
            quoted = true;
        } else if (c == ',') {
            out.emplace_back();
        } else {
            out.back() += c;
        }
    }
    return out;
}

// What the index needs of a tile: its rows' text and the box around its plants.
struct TileRows {
    std::string text;  // the rows, each with its newline
    AABB bounds;
};

TileRows readTileRows(const std::string& path, const FieldTile& tile) {
    const auto bad = [&](const std::string& why) {
        return Error(why, {.file = path,
                           .validRange = "the CSV buildFieldTile writes for the tile's " +
                                         std::to_string(tile.plants.size()) +
                                         " plants: build the tile again"});
    };
    std::ifstream in(path, std::ios::binary);
    if (!in) throw bad("cannot read the tile's table");
    std::string line;
    if (!std::getline(in, line) || line != fieldPlantsHeader()) throw bad("not a tile's table");
    TileRows t;
    std::size_t n = 0;
    const std::size_t columns = csvFields(fieldPlantsHeader()).size();
    while (std::getline(in, line)) {
        const std::vector<std::string> f = csvFields(line);
        if (f.size() != columns || n >= tile.plants.size() ||
            f[0] != std::to_string(tile.plants[n].id))
            throw bad("row " + std::to_string(n + 1) + " is not the tile's plant");
        float v[6];
        for (std::size_t k = 0; k < 6; ++k) {
            const std::string& s = f[columns - 6 + k];
            const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v[k]);
            if (ec != std::errc() || end != s.data() + s.size() || !std::isfinite(v[k]))
                throw bad("row " + std::to_string(n + 1) + ": a bounding box value is no number");
        }
        t.bounds.add(vec3(v[0], v[1], v[2]));
        t.bounds.add(vec3(v[3], v[4], v[5]));
        t.text += line + "\n";
        ++n;
    }
    if (n != tile.plants.size())
        throw bad(std::to_string(n) + " rows for " + std::to_string(tile.plants.size()) +
                  " plants");
    return t;
}

// A JSON string.
std::string jsonText(const std::string& s) {
    std::string out = "\"";
    for (char c : s) {
        if (c == '"' || c == '\\') {
            out += '\\';
            out += c;
        } else if (static_cast<unsigned char>(c) < 0x20) {
            static const char* hex = "0123456789abcdef";
            out += "\\u00";
            out += hex[(c >> 4) & 0xf];
            out += hex[c & 0xf];
        } else {
            out += c;
        }
    }
    return out + "\"";
}

// A 3D Tiles box: centre, then the three half-axes (x, y, z aligned; z up, metres).
std::string boxText(const AABB& b) {
    const vec3 c = 0.5f * (b.min + b.max);
    // Half sizes never 0 (a box of no volume is not a bounding volume every viewer accepts),
    // and a tenth of a millimetre over, so that the rounded centre's box still holds it all.
    const vec3 h = glm::max(0.5f * (b.max - b.min), vec3(1e-3f)) + vec3(1e-4f);
    const auto f = [](float v) { return text::formatFloat(v); };
    return "[" + f(c.x) + ", " + f(c.y) + ", " + f(c.z) + ", " + f(h.x) + ", 0, 0, 0, " + f(h.y) +
           ", 0, 0, 0, " + f(h.z) + "]";
}

}  // namespace

}  // namespace field

void writeFieldIndex(const Project& project, const FieldOptions& options,
                     const std::string& outDir) {
    const FieldPlan plan = fieldTiles(project, options);
    field::requireFolder(outDir);
    const std::filesystem::path dir(outDir);
    std::vector<field::TileRows> tiles;
    AABB all;
    for (const FieldTile& t : plan.tiles) {
        const std::string glb = (dir / (t.name + ".glb")).string();
        std::error_code ec;
        if (!std::filesystem::is_regular_file(glb, ec)) {
            std::size_t missing = 0;
            for (const FieldTile& u : plan.tiles)
                missing += !std::filesystem::is_regular_file(dir / (u.name + ".glb"), ec);
            throw Error("tile missing: " + std::to_string(missing) + " of " +
                            std::to_string(plan.tiles.size()) + " tiles not built",
                        {.file = glb,
                         .validRange = "every tile built (plantarch field without --index-only, "
                                       "or every shard) before the index"});
        }
        tiles.push_back(field::readTileRows((dir / (t.name + ".csv")).string(), t));
        all.add(tiles.back().bounds.min);
        all.add(tiles.back().bounds.max);
    }
    const vec3 size = all.max - all.min;
    const std::string rootError = text::formatFloat(glm::length(size));
    std::string json =
        "{\n  \"asset\": {\"version\": \"1.1\", \"generator\": \"plantarch field\"},\n";
    json += "  \"extras\": {\"project\": " + field::jsonText(project.name) +
            ", \"plants\": " + std::to_string(plan.plants) +
            ", \"tile_size\": " + text::formatFloat(plan.tileSize) + "},\n";
    json += "  \"geometricError\": " + rootError + ",\n";
    json += "  \"root\": {\n    \"boundingVolume\": {\"box\": " + field::boxText(all) +
            "},\n    \"geometricError\": " + rootError +
            ",\n    \"refine\": \"ADD\",\n    \"children\": [";
    for (std::size_t i = 0; i < plan.tiles.size(); ++i) {
        json += std::string(i == 0 ? "" : ",") +
                "\n      {\"boundingVolume\": {\"box\": " + field::boxText(tiles[i].bounds) +
                "}, \"geometricError\": 0, \"content\": {\"uri\": \"" + plan.tiles[i].name +
                ".glb\"}, \"extras\": {\"plants\": " + std::to_string(plan.tiles[i].plants.size()) +
                "}}";
    }
    json += "\n    ]\n  }\n}\n";
    std::string csv = fieldPlantsHeader() + "\n";
    for (const field::TileRows& t : tiles) csv += t.text;
    io::AtomicFile table((dir / "plants.csv").string());
    table.write(csv);
    io::AtomicFile index((dir / "tileset.json").string());
    index.write(json);
    table.commit();
    index.commit();
}

}  // namespace plantarch
