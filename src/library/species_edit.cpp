// Editing a species field by field (the project builder's species form): the species is
// written out whole, the changed values put into that text, and the text read back, so that
// each value meets the reader's own checks and messages.

#include <pugixml.hpp>
#include <sstream>

#include "core/value_text.h"
#include "plantarch/Error.h"
#include "plantarch/ParameterInfo.h"
#include "plantarch/SpeciesIO.h"

namespace plantarch {

namespace {

bool editable(ParameterKind kind) {
    return kind != ParameterKind::NumberMap && kind != ParameterKind::TextMap &&
           kind != ParameterKind::List;
}

std::vector<std::string> split(const std::string& path) {
    std::vector<std::string> parts;
    std::stringstream ss(path);
    for (std::string part; std::getline(ss, part, '.');) parts.push_back(part);
    return parts;
}

// The field `path` of `fields` (with the kind it holds), or an Error naming `key` and the
// nearest valid field.
void requireField(const std::vector<ParameterInfo>& fields, const std::string& path,
                  const std::string& key, const std::string& prefix) {
    std::vector<std::string> paths;
    for (const ParameterInfo& f : fields) {
        if (f.path == path) {
            if (!editable(f.kind))
                throw Error("a list or map: edit it in the species file",
                            {.parameter = key, .validRange = "fields of single values"});
            return;
        }
        paths.push_back(prefix + f.path);
    }
    throw Error(text::unknownMessage("parameter", key, paths), {.parameter = key});
}

pugi::xml_node child(pugi::xml_node node, const std::string& name, const std::string& key) {
    pugi::xml_node c = node.child(name.c_str());
    if (!c) throw Error("not in the species as written", {.parameter = key});
    return c;
}

void setText(pugi::xml_node node, const std::string& value) {
    while (node.first_child()) node.remove_child(node.first_child());
    node.append_child(pugi::node_pcdata).set_value(value.c_str());
}

void applyChange(pugi::xml_node root, const SpeciesModel& base, const std::string& key,
                 const std::string& value) {
    const std::vector<std::string> parts = split(key);
    const std::string group = parts.empty() ? "" : parts[0];
    if (group == "shoot_types" && parts.size() >= 3) {
        const std::string& label = parts[1];
        const auto type = base.shootTypes.find(label);
        if (type == base.shootTypes.end()) {
            std::vector<std::string> labels;
            for (const auto& [l, p] : base.shootTypes) labels.push_back(l);
            throw Error(text::unknownMessage("shoot type", label, labels), {.parameter = key});
        }
        const std::string path = key.substr(group.size() + label.size() + 2);
        requireField(parameterInfo(type->second), path, key, "shoot_types." + label + ".");
        pugi::xml_node node = root.find_child_by_attribute("shoot_type", "label", label.c_str());
        if (!node) throw Error("not in the species as written", {.parameter = key});
        for (std::size_t i = 2; i < parts.size(); ++i) node = child(node, parts[i], key);
        setText(node, value);
        return;
    }
    if (group == "phenology" && parts.size() >= 2) {
        requireField(parameterInfo(base.phenology), key.substr(group.size() + 1), key,
                     "phenology.");
        pugi::xml_node node = child(root, "phenology", key);
        for (std::size_t i = 1; i < parts.size(); ++i) node = child(node, parts[i], key);
        setText(node, value);
        return;
    }
    if (group == "build_parameters" && parts.size() == 2) {
        std::vector<std::string> names;
        for (const BuildParameter& p : base.buildParameters) names.push_back(p.name);
        pugi::xml_node node = root.child("build_parameters")
                                  .find_child_by_attribute("parameter", "name", parts[1].c_str());
        if (!node)
            throw Error(text::unknownMessage("build parameter", parts[1], names),
                        {.parameter = key});
        node.attribute("default").set_value(value.c_str());
        return;
    }
    throw Error("unknown parameter group",
                {.parameter = key,
                 .validRange = "shoot_types.LABEL.PATH, phenology.PATH, build_parameters.NAME"});
}

}  // namespace

SpeciesModel editSpecies(const SpeciesModel& base,
                         const std::map<std::string, std::string>& changes,
                         const std::string& name) {
    const std::string written = writeSpeciesString(base, {.comments = false});
    pugi::xml_document doc;
    if (!doc.load_string(written.c_str(), pugi::parse_default | pugi::parse_comments))
        throw Error("the species could not be written for editing", {.file = base.sourceFile});
    pugi::xml_node root = doc.document_element();
    if (!name.empty()) setText(child(root, "name", "name"), name);
    for (const auto& [key, value] : changes) {
        if (value.find_first_of("<>&") != std::string::npos)
            throw Error("markup characters in a value",
                        {.parameter = key, .value = value, .validRange = "no <, > or &"});
        applyChange(root, base, key, value);
    }
    std::ostringstream out;
    doc.save(out, "  ");
    const std::string nameForErrors = name.empty() ? base.name : name;
    try {
        SpeciesModel model = readSpeciesString(out.str(), nameForErrors);
        model.sourceFile = base.sourceFile;
        return model;
    } catch (const Error& e) {
        // The reader's own message; its line is in the text made here, so it is left out.
        throw Error(e.message(),
                    {.parameter = e.parameter(), .value = e.value(), .validRange = e.validRange()});
    }
}

}  // namespace plantarch
