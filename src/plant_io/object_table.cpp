#include "plant_io/object_table.h"

#include <fmt/format.h>

#include <cmath>
#include <unordered_map>

#include "plant_io/plant_structure.h"
#include "plantarch/Export.h"
#include "scene_io/export_common.h"

namespace plantarch::io {

namespace {

// Where an organ's object ID stands in the plant structure file: the indices of the elements
// on the way (-1: not on the way), the element holding the ID and the ID's place in it.
struct Place {
    unsigned plant = 0, shoot = 0;
    int phytomer = -1, petiole = -1, leaf = -1, floralBud = -1, terminalBud = -1, flower = -1;
    const char* element = "";  // internode, petiole, leaf, peduncle or flower
    int part = -1;             // index in object_IDs (leaves and flowers)
};

void appendJsonString(std::string& out, std::string_view text) {
    out += '"';
    for (char c : text) {
        const auto byte = static_cast<unsigned char>(c);
        if (c == '"' || c == '\\') {
            out += '\\';
            out += c;
        } else if (c == '\n') {
            out += "\\n";
        } else if (byte < 0x20) {
            out += fmt::format("\\u{:04x}", byte);
        } else {
            out += c;
        }
    }
    out += '"';
}

// Shortest text that reads back as the same value (of its type: float or double).
template <class T>
void appendFloat(std::string& out, T value) {
    if (std::isfinite(value))
        out += fmt::format("{}", value);
    else
        out += "null";
}

// Every object ID of the plants' organs and its place.
std::unordered_map<ObjectID, Place> placesOf(const std::vector<const PlantInstance*>& plants) {
    std::unordered_map<ObjectID, Place> places;
    auto add = [&](ObjectID id, Place p) {
        if (id != kNoObject) places.emplace(id, p);
    };
    auto addParts = [&](const std::vector<ObjectID>& ids, Place p) {
        for (std::size_t k = 0; k < ids.size(); ++k) {
            p.part = int(k);
            add(ids[k], p);
        }
    };
    auto floral = [&](const FloralBud& bud, Place p) {
        p.element = "peduncle";
        add(bud.peduncleObject, p);
        p.element = "flower";
        for (std::size_t j = 0; j < bud.flowers.size(); ++j) {
            p.flower = int(j);
            addParts(bud.flowers[j].objects, p);
        }
    };
    for (const PlantInstance* plant : plants)
        for (const Shoot& s : plant->shoots) {
            Place shoot{.plant = plant->id, .shoot = s.id};
            for (std::size_t i = 0; i < s.phytomers.size(); ++i) {
                const Phytomer& ph = s.phytomers[i];
                Place p = shoot;
                p.phytomer = int(i);
                p.element = "internode";
                add(ph.internode.object, p);
                for (std::size_t k = 0; k < ph.petioles.size(); ++k) {
                    const Petiole& pt = ph.petioles[k];
                    Place q = p;
                    q.petiole = int(k);
                    q.element = "petiole";
                    add(pt.object, q);
                    q.element = "leaf";
                    for (std::size_t l = 0; l < pt.leaves.size(); ++l) {
                        q.leaf = int(l);
                        addParts(pt.leaves[l].objects, q);
                    }
                    q.leaf = -1;
                    for (std::size_t b = 0; b < pt.floralBuds.size(); ++b) {
                        q.floralBud = int(b);
                        floral(pt.floralBuds[b], q);
                    }
                }
            }
            for (std::size_t b = 0; b < s.terminalFloralBuds.size(); ++b) {
                Place p = shoot;
                p.terminalBud = int(b);
                floral(s.terminalFloralBuds[b], p);
            }
        }
    return places;
}

// "structure": {...} of one object: the indices, the element and its XPath in the file
// (positions in XPath count from 1).
void appendPlace(std::string& out, const Place& p) {
    std::string xpath = fmt::format("/{}/plant_instance[@ID='{}']/shoot[@ID='{}']", plant_io::kRoot,
                                    p.plant, p.shoot);
    out +=
        fmt::format(", \"structure\": {{\"plant_instance\": {}, \"shoot\": {}", p.plant, p.shoot);
    if (p.phytomer >= 0) {
        out += fmt::format(", \"phytomer\": {}", p.phytomer);
        xpath += fmt::format("/phytomer[{}]/internode", p.phytomer + 1);
    }
    if (p.petiole >= 0) {
        out += fmt::format(", \"petiole\": {}", p.petiole);
        xpath += fmt::format("/petiole[{}]", p.petiole + 1);
    }
    if (p.leaf >= 0) {
        out += fmt::format(", \"leaf\": {}", p.leaf);
        xpath += fmt::format("/leaf[{}]", p.leaf + 1);
    }
    if (p.floralBud >= 0) {
        out += fmt::format(", \"floral_bud\": {}", p.floralBud);
        xpath += fmt::format("/floral_bud[{}]/peduncle", p.floralBud + 1);
    }
    if (p.terminalBud >= 0) {
        out += fmt::format(", \"terminal_floral_bud\": {}", p.terminalBud);
        xpath += fmt::format("/terminal_floral_bud[{}]/peduncle", p.terminalBud + 1);
    }
    if (p.flower >= 0) {
        out += fmt::format(", \"flower\": {}", p.flower);
        xpath += fmt::format("/flower[{}]", p.flower + 1);
    }
    if (p.part >= 0) out += fmt::format(", \"part\": {}", p.part);
    out += fmt::format(", \"element\": \"{}\", \"xpath\": ", p.element);
    appendJsonString(out, xpath);
    out += '}';
}

}  // namespace

std::string objectTableJSON(const Context& context, const std::vector<const PlantInstance*>& plants,
                            bool includeHidden) {
    const std::vector<ObjectID> ids = exportedObjects(context, includeHidden);
    const std::vector<std::string> organs = organLabelTable(context, includeHidden);
    std::unordered_map<std::string_view, std::size_t> organIndex;
    for (std::size_t i = 0; i < organs.size(); ++i) organIndex.emplace(organs[i], i);
    const std::unordered_map<ObjectID, Place> places = placesOf(plants);
    const LabelReader labelsOf(context);
    const bool hasNames = context.objectDataType("plant_name") == DataType::String;
    const bool hasOrgans = context.objectDataType("organ") == DataType::String;

    std::string out = "{\n  \"format\": \"plantarch object table 1\",\n  \"organ_labels\": [";
    for (std::size_t i = 0; i < organs.size(); ++i) {
        if (i) out += ", ";
        appendJsonString(out, organs[i]);
    }
    out += "],\n  \"plants\": [";
    for (std::size_t i = 0; i < plants.size(); ++i) {
        const PlantInstance& p = *plants[i];
        out += fmt::format("{}\n    {{\"plant_id\": {}, \"plant_name\": ", i ? "," : "", p.id);
        appendJsonString(out, p.name);
        out += ", \"age\": ";
        appendFloat(out, p.age);
        out += ", \"base\": [";
        for (int k = 0; k < 3; ++k) {
            if (k) out += ", ";
            appendFloat(out, p.base[k]);
        }
        out += "]}";
    }
    out += plants.empty() ? "],\n  \"objects\": [" : "\n  ],\n  \"objects\": [";
    for (std::size_t i = 0; i < ids.size(); ++i) {
        const ObjectID id = ids[i];
        const ObjectLabels l = labelsOf(id);
        out +=
            fmt::format("{}\n    {{\"object_id\": {}, \"plant_id\": {}", i ? "," : "", id, l.plant);
        if (hasNames)
            if (const auto name = context.objectDataString(id, "plant_name")) {
                out += ", \"plant_name\": ";
                appendJsonString(out, *name);
            }
        const std::string organ = hasOrgans ? organOf(context, id) : std::string();
        out += ", \"organ\": ";
        appendJsonString(out, organ.empty() ? organs[0] : organ);
        const auto at = organIndex.find(organ);
        out += fmt::format(
            ", \"organ_label\": {}, \"shoot_id\": {}, \"rank\": {}, \"node\": {}, "
            "\"leaf_id\": {}, \"age\": ",
            at == organIndex.end() ? 0 : at->second, l.shoot, l.rank, l.node, l.leaf);
        appendFloat(out, l.age);
        const auto place = places.find(id);
        if (place != places.end()) appendPlace(out, place->second);
        out += '}';
    }
    out += ids.empty() ? "]\n}\n" : "\n  ]\n}\n";
    return out;
}

}  // namespace plantarch::io
