// Skeleton node tables (.csv) and JSON skeletons: reading with every value checked (one
// error line naming the file, line, column and range), the tree checks, and the table writer.

#include <algorithm>
#include <cmath>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "core/value_text.h"
#include "plantarch/Error.h"
#include "plantarch/InputFiles.h"
#include "plantarch/OutputFormats.h"
#include "plantarch/Skeleton.h"
#include "project/json_document.h"
#include "project/json_scan.h"
#include "project/skeleton_internal.h"

namespace plantarch {

namespace skeleton {

const std::vector<std::string>& organTags() {
    static const std::vector<std::string> tags{"bare", "flower", "fruit"};
    return tags;
}

SkeletonLink parseLink(std::string_view text, const ErrorContext& at) {
    const std::string_view t = text::trim(text);
    if (t.empty()) return SkeletonLink::Auto;
    if (t == "<" || t == "continue") return SkeletonLink::Continue;
    if (t == "+" || t == "branch") return SkeletonLink::Branch;
    ErrorContext c = at;
    c.value = project::printable(t, 40);
    c.validRange = "<, +, continue, branch, or empty";
    throw Error("unknown link", c);
}

std::string checkedShootType(std::string_view text, const ErrorContext& at) {
    const std::string_view t = text::trim(text);
    const bool ok = t.size() <= 64 && std::all_of(t.begin(), t.end(), [](char ch) {
                        return std::isalnum((unsigned char)ch) || ch == '_' || ch == '-';
                    });
    if (!ok) {
        ErrorContext c = at;
        c.value = project::printable(t, 40);
        c.validRange = "a shoot type label: up to 64 letters, digits, '_' or '-'";
        throw Error("not a shoot type label", c);
    }
    return std::string(t);
}

std::vector<std::string> parseOrgans(std::string_view text, const ErrorContext& at) {
    std::vector<std::string> organs;
    std::string word;
    auto flush = [&] {
        if (word.empty()) return;
        if (std::find(organTags().begin(), organTags().end(), word) == organTags().end()) {
            ErrorContext c = at;
            c.value = project::printable(word, 40);
            c.validRange = text::oneOf(organTags()) + ", separated by ';' or spaces";
            throw Error("unknown organ tag", c);
        }
        if (std::find(organs.begin(), organs.end(), word) == organs.end()) organs.push_back(word);
        word.clear();
    };
    for (char ch : text) {
        if (ch == ';' || ch == ' ' || ch == '\t')
            flush();
        else
            word += ch;
    }
    flush();
    return organs;
}

}  // namespace skeleton

namespace {

using json = nlohmann::json;

constexpr std::size_t kMaxNodes = 10'000'000;
constexpr double kMaxCoordinate = 1e5;  // m (or the file's unit): 100 km

// ---- node tables ------------------------------------------------------------------------

const std::vector<std::string>& csvColumns() {
    static const std::vector<std::string> c{"id",      "parent",  "x",          "y",      "z",
                                            "radius",  "link",    "shoot_type", "organs", "leaf_nx",
                                            "leaf_ny", "leaf_nz", "leaf_length"};
    return c;
}

std::vector<std::string> splitRow(const std::string& line, char sep) {
    std::vector<std::string> cells;
    std::string cell;
    for (char ch : line) {
        if (ch == sep) {
            cells.push_back(cell);
            cell.clear();
        } else if (ch != '\r') {
            cell += ch;
        }
    }
    cells.push_back(cell);
    return cells;
}

Skeleton readCSV(const std::string& textIn, const std::string& name) {
    Skeleton sk;
    sk.source = name;
    std::istringstream in(textIn);
    std::string line;
    std::map<std::string, std::size_t> column;  // name -> index
    std::size_t columns = 0;
    char sep = ',';
    for (int number = 1; std::getline(in, line); ++number) {
        const std::string_view t = text::trim(line);
        if (t.empty() || t.front() == '#') continue;
        const ErrorContext at{.file = name, .line = number};
        if (column.empty()) {  // the header
            sep = (line.find(',') == std::string::npos && line.find('\t') != std::string::npos)
                      ? '\t'
                      : ',';
            const std::vector<std::string> cells = splitRow(line, sep);
            for (std::size_t i = 0; i < cells.size(); ++i) {
                std::string key(text::trim(cells[i]));
                std::transform(key.begin(), key.end(), key.begin(),
                               [](unsigned char ch) { return char(std::tolower(ch)); });
                const auto& known = csvColumns();
                if (std::find(known.begin(), known.end(), key) == known.end()) {
                    ErrorContext c = at;
                    c.parameter = "column " + std::to_string(i + 1);
                    c.value = project::printable(key, 40);
                    const std::string near = text::closestMatch(key, known);
                    c.validRange = text::oneOf(known);
                    throw Error(near.empty() ? "unknown column"
                                             : "unknown column, did you mean '" + near + "'?",
                                c);
                }
                if (!column.emplace(key, i).second) {
                    ErrorContext c = at;
                    c.parameter = key;
                    throw Error("column given twice", c);
                }
            }
            for (const char* need : {"id", "parent", "x", "y", "z"})
                if (!column.count(need)) {
                    ErrorContext c = at;
                    c.parameter = need;
                    c.validRange = "a header naming at least id, parent, x, y, z";
                    throw Error("the node table has no '" + std::string(need) + "' column", c);
                }
            columns = cells.size();
            continue;
        }
        const std::vector<std::string> cells = splitRow(line, sep);
        if (cells.size() != columns) {
            ErrorContext c = at;
            c.value = std::to_string(cells.size()) + " columns";
            c.validRange = std::to_string(columns) + " columns, as the header";
            throw Error("row has the wrong number of columns", c);
        }
        if (sk.nodes.size() >= kMaxNodes) {
            ErrorContext c = at;
            c.validRange = "at most 10000000 nodes";
            throw Error("too many nodes", c);
        }
        auto cell = [&](const char* key) -> std::string_view {
            const auto it = column.find(key);
            return it == column.end() ? std::string_view() : text::trim(cells[it->second]);
        };
        auto where = [&](const char* key) {
            ErrorContext c = at;
            c.parameter = key;
            return c;
        };
        auto integer = [&](const char* key, bool allowEmpty) -> long {
            const std::string_view v = cell(key);
            if (v.empty() && allowEmpty) return -1;
            double d = 0.0;
            if (!text::readNumber(v, d) || d != std::floor(d) || d < -1 || d > 9.0e15) {
                ErrorContext c = where(key);
                c.value = project::printable(v, 40);
                c.validRange = std::string("a whole number 0 to 9e15") +
                               (allowEmpty ? " (-1 or empty: none)" : "");
                throw Error("expected a node id", c);
            }
            if (d < 0 && !allowEmpty) {
                ErrorContext c = where(key);
                c.value = project::printable(v, 40);
                c.validRange = "a whole number 0 to 9e15";
                throw Error("expected a node id", c);
            }
            return long(d);
        };
        auto real = [&](const char* key, double lo, const char* range) -> float {
            const std::string_view v = cell(key);
            double d = 0.0;
            if (!text::readNumber(v, d) || d < lo || d > kMaxCoordinate) {
                ErrorContext c = where(key);
                c.value = project::printable(v, 40);
                c.validRange = range;
                throw Error(v.empty() ? "value missing" : "expected a number in range", c);
            }
            return float(d);
        };
        SkeletonNode n;
        n.line = number;
        n.id = integer("id", false);
        n.parent = integer("parent", true);
        const char* coord = "a number -100000 to 100000";
        n.position = vec3(real("x", -kMaxCoordinate, coord), real("y", -kMaxCoordinate, coord),
                          real("z", -kMaxCoordinate, coord));
        if (column.count("radius") && !cell("radius").empty())
            n.radius = real("radius", 0.0, "a number 0 to 100000 (0 or empty: not measured)");
        n.link = skeleton::parseLink(cell("link"), where("link"));
        n.shootType = skeleton::checkedShootType(cell("shoot_type"), where("shoot_type"));
        n.organs = skeleton::parseOrgans(cell("organs"), where("organs"));
        const bool anyNormal =
            !cell("leaf_nx").empty() || !cell("leaf_ny").empty() || !cell("leaf_nz").empty();
        if (anyNormal)
            n.leafNormal =
                vec3(real("leaf_nx", -kMaxCoordinate, "a number, with leaf_ny and leaf_nz"),
                     real("leaf_ny", -kMaxCoordinate, "a number, with leaf_nx and leaf_nz"),
                     real("leaf_nz", -kMaxCoordinate, "a number, with leaf_nx and leaf_ny"));
        if (!cell("leaf_length").empty())
            n.leafLength =
                real("leaf_length", 0.0, "a number 0 to 100000 (0 or empty: the species')");
        sk.nodes.push_back(std::move(n));
    }
    if (column.empty())
        throw Error("the node table has no header",
                    {.file = name, .line = 1, .validRange = "a header line: id,parent,x,y,z,..."});
    return sk;
}

// ---- JSON -------------------------------------------------------------------------------

// The line of each element of the top-level "nodes" array, in order (a scan of the text that
// nlohmann's parser does not report positions for).
std::vector<int> nodeLines(std::string_view t) {
    std::vector<int> lines;
    int line = 1, depth = 0;
    bool inString = false, escape = false, inNodes = false;
    std::string lastKey, current;
    for (std::size_t i = 0; i < t.size(); ++i) {
        const char ch = t[i];
        if (ch == '\n') ++line;
        if (inString) {
            if (escape)
                escape = false;
            else if (ch == '\\')
                escape = true;
            else if (ch == '"')
                inString = false;
            else if (depth == 1)
                current += ch;
            continue;
        }
        if (ch == '"') {
            inString = true;
            current.clear();
        } else if (ch == ':' && depth == 1) {
            lastKey = current;
        } else if (ch == '[' || ch == '{') {
            if (depth == 1 && ch == '[') inNodes = lastKey == "nodes";
            if (depth == 2 && inNodes) lines.push_back(line);
            ++depth;
        } else if (ch == ']' || ch == '}') {
            --depth;
            if (depth == 1) inNodes = false;
        } else if (depth == 2 && inNodes && ch != ',' && !std::isspace((unsigned char)ch) &&
                   (i == 0 || t[i - 1] == ',' || t[i - 1] == '[' ||
                    std::isspace((unsigned char)t[i - 1]))) {
            lines.push_back(line);  // a scalar element (an error the reader reports)
        }
    }
    return lines;
}

Skeleton readJSON(const std::string& text, const std::string& name) {
    const json doc = project::parseJSONDocument(text, name, 8, nullptr);
    const std::vector<int> lines = nodeLines(text);
    if (!doc.is_object())
        throw Error("expected an object {\"nodes\": [...]}", {.file = name, .line = 1});
    for (const auto& [key, value] : doc.items())
        if (key != "nodes") {
            // The line of the key as written (its first appearance in quotes).
            const std::size_t at =
                text.find(json(key).dump(-1, ' ', false, json::error_handler_t::replace));
            const int line =
                at == std::string::npos
                    ? 1
                    : 1 + int(std::count(text.begin(), text.begin() + std::ptrdiff_t(at), '\n'));
            throw Error("unknown field", {.file = name,
                                          .line = line,
                                          .parameter = project::printable(key, 40),
                                          .validRange = "nodes"});
        }
    if (!doc.contains("nodes") || !doc["nodes"].is_array())
        throw Error("expected \"nodes\": [...]", {.file = name, .line = 1, .parameter = "nodes"});
    const json& nodes = doc["nodes"];
    if (nodes.size() > kMaxNodes)
        throw Error("too many nodes",
                    {.file = name, .parameter = "nodes", .validRange = "at most 10000000 nodes"});
    Skeleton sk;
    sk.source = name;
    const std::vector<std::string> keys{"id",         "parent", "position",    "radius",     "link",
                                        "shoot_type", "organs", "leaf_normal", "leaf_length"};
    for (std::size_t i = 0; i < nodes.size(); ++i) {
        const json& j = nodes[i];
        const int line = i < lines.size() ? lines[i] : 0;
        const std::string path = "nodes/" + std::to_string(i);
        auto at = [&](const std::string& key) {
            return ErrorContext{.file = name, .line = line, .parameter = path + "/" + key};
        };
        auto fail = [&](const std::string& key, const std::string& message, const json& v,
                        const std::string& range) {
            ErrorContext c = at(key);
            c.value =
                project::printable(v.dump(-1, ' ', false, json::error_handler_t::replace), 40);
            c.validRange = range;
            throw Error(message, c);
        };
        if (!j.is_object()) fail("", "expected a node object {...}", j, "an object");
        for (const auto& [key, value] : j.items())
            if (std::find(keys.begin(), keys.end(), key) == keys.end()) {
                ErrorContext c = at(project::printable(key, 40));
                const std::string near = text::closestMatch(key, keys);
                c.validRange = text::oneOf(keys);
                throw Error(
                    near.empty() ? "unknown field" : "unknown field, did you mean '" + near + "'?",
                    c);
            }
        auto id = [&](const char* key, bool allowNone) -> long {
            if (!j.contains(key)) {
                if (allowNone) return -1;
                fail(key, "missing", json(nullptr), "a whole number 0 to 9e15");
            }
            const json& v = j[key];
            if (allowNone && v.is_null()) return -1;
            const double d = v.is_number() ? v.get<double>() : NAN;
            if (!(d == std::floor(d) && d >= (allowNone ? -1 : 0) && d <= 9.0e15))
                fail(key, "expected a node id", v,
                     allowNone ? "a whole number 0 to 9e15, or -1 or null: none"
                               : "a whole number 0 to 9e15");
            return long(d);
        };
        SkeletonNode n;
        n.line = line;
        n.id = id("id", false);
        n.parent = id("parent", true);
        if (!j.contains("position")) fail("position", "missing", json(nullptr), "[x, y, z]");
        const json& pos = j["position"];
        if (!pos.is_array() || pos.size() != 3)
            fail("position", "expected [x, y, z]", pos, "three numbers");
        for (int k = 0; k < 3; ++k) {
            const double d = pos[k].is_number() ? pos[k].get<double>() : NAN;
            if (!(std::fabs(d) <= kMaxCoordinate))
                fail("position/" + std::to_string(k), "expected a number in range", pos[k],
                     "a number -100000 to 100000");
            n.position[k] = float(d);
        }
        if (j.contains("radius")) {
            const double d = j["radius"].is_number() ? j["radius"].get<double>() : NAN;
            if (!(d >= 0.0 && d <= kMaxCoordinate))
                fail("radius", "expected a number in range", j["radius"],
                     "a number 0 to 100000 (0: not measured)");
            n.radius = float(d);
        }
        if (j.contains("link")) {
            if (!j["link"].is_string())
                fail("link", "expected a text", j["link"], "\"continue\" or \"branch\"");
            n.link = skeleton::parseLink(j["link"].get<std::string>(), at("link"));
        }
        if (j.contains("shoot_type")) {
            if (!j["shoot_type"].is_string())
                fail("shoot_type", "expected a text", j["shoot_type"], "a shoot type label");
            n.shootType =
                skeleton::checkedShootType(j["shoot_type"].get<std::string>(), at("shoot_type"));
        }
        if (j.contains("organs")) {
            const json& o = j["organs"];
            if (!o.is_array())
                fail("organs", "expected a list", o, "[\"bare\", \"flower\", \"fruit\"]");
            std::string joined;
            for (const json& t : o) {
                if (!t.is_string())
                    fail("organs", "expected texts", t, text::oneOf(skeleton::organTags()));
                joined += t.get<std::string>() + ";";
            }
            n.organs = skeleton::parseOrgans(joined, at("organs"));
        }
        if (j.contains("leaf_normal")) {
            const json& v = j["leaf_normal"];
            if (!v.is_array() || v.size() != 3)
                fail("leaf_normal", "expected [x, y, z]", v, "three numbers");
            vec3 normal{0.0f};
            for (int k = 0; k < 3; ++k) {
                const double d = v[k].is_number() ? v[k].get<double>() : NAN;
                if (!(std::fabs(d) <= kMaxCoordinate))
                    fail("leaf_normal/" + std::to_string(k), "expected a number in range", v[k],
                         "a number -100000 to 100000");
                normal[k] = float(d);
            }
            n.leafNormal = normal;
        }
        if (j.contains("leaf_length")) {
            const double d = j["leaf_length"].is_number() ? j["leaf_length"].get<double>() : NAN;
            if (!(d >= 0.0 && d <= kMaxCoordinate))
                fail("leaf_length", "expected a number in range", j["leaf_length"],
                     "a number 0 to 100000 (0: the species')");
            n.leafLength = float(d);
        }
        sk.nodes.push_back(std::move(n));
    }
    return sk;
}

std::string formatOf(const std::string& path) {
    std::string ext = lowerExtension(path);
    if (ext == ".csv" || ext == ".json" || ext == ".mtg") return ext.substr(1);
    throw Error("unknown skeleton file format",
                {.file = path, .value = ext, .validRange = ".csv, .json, .mtg"});
}

}  // namespace

Skeleton readSkeletonString(const std::string& text, const std::string& format,
                            const std::string& name) {
    Skeleton sk;
    if (format == "csv")
        sk = readCSV(text, name);
    else if (format == "json")
        sk = readJSON(text, name);
    else if (format == "mtg")
        sk = skeleton::readMTG(text, name);
    else
        throw Error("unknown skeleton format",
                    {.file = name, .value = format, .validRange = "csv, json, mtg"});
    checkSkeleton(sk);
    return sk;
}

Skeleton readSkeletonFile(const std::string& path) {
    const std::string format = formatOf(path);
    return readSkeletonString(readInputFile(path, InputFileKind::PlantStructure, "skeleton file"),
                              format, path);
}

void checkSkeleton(const Skeleton& sk) {
    auto fail = [&](const SkeletonNode& n, const std::string& message, const std::string& value,
                    const std::string& range) {
        throw Error(message, {.file = sk.source,
                              .line = n.line,
                              .parameter = "node " + std::to_string(n.id),
                              .value = value,
                              .validRange = range});
    };
    if (sk.nodes.empty())
        throw Error("the skeleton has no nodes",
                    {.file = sk.source, .validRange = "a root and at least one node"});
    std::map<long, std::size_t> index;
    for (std::size_t i = 0; i < sk.nodes.size(); ++i) {
        const SkeletonNode& n = sk.nodes[i];
        if (!(std::isfinite(n.position.x) && std::isfinite(n.position.y) &&
              std::isfinite(n.position.z)))
            fail(n, "position not finite", "", "finite coordinates");
        if (n.leafNormal && !(glm::length(*n.leafNormal) > 0.0f))
            fail(n, "leaf normal of length 0", "", "a direction: a vector of length > 0");
        if (!(n.radius >= 0.0f && std::isfinite(n.radius)))
            fail(n, "radius out of range", std::to_string(n.radius), ">= 0");
        if (n.id < 0) fail(n, "node id out of range", std::to_string(n.id), "0 or more");
        if (!index.emplace(n.id, i).second)
            fail(n, "node id given twice", std::to_string(n.id), "unique ids");
    }
    std::map<long, int> continuing;  // explicit continuing children per node
    std::size_t roots = 0;
    for (const SkeletonNode& n : sk.nodes) {
        if (n.parent < 0) {
            ++roots;
            if (n.link != SkeletonLink::Auto) fail(n, "a root has no link", "", "an empty link");
            continue;
        }
        if (!index.count(n.parent))
            fail(n, "parent not in the skeleton", std::to_string(n.parent),
                 "the id of another node, or -1");
        if (n.parent == n.id)
            fail(n, "a node is its own parent", std::to_string(n.parent), "another node's id");
        if (n.link == SkeletonLink::Continue && ++continuing[n.parent] > 1)
            fail(n, "a second node continuing the same parent", std::to_string(n.parent),
                 "one continuing child per node (others: link +)");
    }
    if (roots == 0)
        throw Error("the skeleton has no root",
                    {.file = sk.source, .validRange = "one node with parent -1 per plant"});
    // No cycle: every node reaches a root within the node count.
    std::vector<int> state(sk.nodes.size(), 0);  // 0 unseen, 1 on the path, 2 reaches a root
    for (std::size_t start = 0; start < sk.nodes.size(); ++start) {
        std::vector<std::size_t> path;
        std::size_t i = start;
        while (state[i] == 0) {
            state[i] = 1;
            path.push_back(i);
            if (sk.nodes[i].parent < 0) break;
            i = index.at(sk.nodes[i].parent);
            if (state[i] == 1)
                fail(sk.nodes[i], "the parents form a cycle", std::to_string(sk.nodes[i].id),
                     "a tree");
        }
        for (std::size_t k : path) state[k] = 2;
    }
}

std::string skeletonCSV(const Skeleton& sk) {
    const bool leaves = std::any_of(sk.nodes.begin(), sk.nodes.end(), [](const SkeletonNode& n) {
        return n.leafNormal || n.leafLength > 0.0f;
    });
    std::string out = "id,parent,x,y,z,radius,link,shoot_type,organs";
    out += leaves ? ",leaf_nx,leaf_ny,leaf_nz,leaf_length\n" : "\n";
    char buf[256];
    for (const SkeletonNode& n : sk.nodes) {
        const char* link = n.link == SkeletonLink::Continue ? "<"
                           : n.link == SkeletonLink::Branch ? "+"
                                                            : "";
        std::string organs;
        for (const std::string& o : n.organs) organs += (organs.empty() ? "" : ";") + o;
        std::snprintf(buf, sizeof buf, "%ld,%ld,%.9g,%.9g,%.9g,%.9g,%s,", n.id, n.parent,
                      double(n.position.x), double(n.position.y), double(n.position.z),
                      double(n.radius), link);
        out += buf;
        out += n.shootType + "," + organs;
        if (leaves) {
            if (n.leafNormal) {
                std::snprintf(buf, sizeof buf, ",%.9g,%.9g,%.9g", double(n.leafNormal->x),
                              double(n.leafNormal->y), double(n.leafNormal->z));
                out += buf;
            } else {
                out += ",,,";
            }
            if (n.leafLength > 0.0f) {
                std::snprintf(buf, sizeof buf, ",%.9g", double(n.leafLength));
                out += buf;
            } else {
                out += ",";
            }
        }
        out += "\n";
    }
    return out;
}

}  // namespace plantarch
