// MTG files (multiscale tree graphs, FORM-A): reading a plant's measured topology and node
// coordinates into a skeleton, and writing plants so OpenAlea and phenotyping tools take them
// on. docs/measured-plants.md says which parts of the format are read and written.

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <sstream>

#include "core/value_text.h"
#include "geometry/tessellate.h"
#include "plantarch/Error.h"
#include "plantarch/Skeleton.h"
#include "project/json_scan.h"
#include "project/skeleton_internal.h"

namespace plantarch {

namespace {

constexpr std::size_t kMaxVertices = 10'000'000;
constexpr std::size_t kMaxColumns = 4096;

struct Vertex {
    std::string cls;
    int scale = 0;
    int complex = -1;  ///< the vertex it is a component of (coarser scale)
    int parent = -1;   ///< its parent at its own scale
    char link = 0;     ///< '<' or '+' to its parent
    int bearer = -1;   ///< a coarser vertex reached from a finer one: that finer vertex
    char bearerLink = 0;
    std::map<int, int> lastComponent;  ///< scale -> the last component made at that scale
    std::map<std::string, std::string> features;
    int line = 0;
};

std::string lower(std::string s) {
    std::transform(s.begin(), s.end(), s.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    return s;
}

// Cells of a line: split at tabs, a '#' hiding the rest of its cell.
std::vector<std::string> cellsOf(const std::string& line) {
    std::vector<std::string> cells;
    std::string cell;
    bool comment = false;
    for (char ch : line) {
        if (ch == '\t') {
            cells.push_back(cell);
            cell.clear();
            comment = false;
        } else if (ch == '#') {
            comment = true;
        } else if (!comment && ch != '\r') {
            cell += ch;
        }
    }
    cells.push_back(cell);
    return cells;
}

class MTGReader {
public:
    MTGReader(const std::string& text, std::string name) : name_(std::move(name)) {
        std::istringstream in(text);
        std::string line;
        while (std::getline(in, line)) lines_.push_back(cellsOf(line));
    }

    Skeleton read() {
        std::string section;
        bool header = false;  // the MTG section's column line is read
        for (std::size_t i = 0; i < lines_.size(); ++i) {
            line_ = int(i) + 1;
            const std::vector<std::string>& cells = lines_[i];
            if (cells.size() > kMaxColumns) fail("too many columns", "", "at most 4096");
            const std::string first(text::trim(cells[0]));
            std::string key = first;
            key.erase(std::remove(key.begin(), key.end(), ' '), key.end());
            if (section != "MTG:" || !header) {
                if (key == "CODE:" || key == "CLASSES:" || key == "DESCRIPTION:" ||
                    key == "FEATURES:" || key == "MTG:") {
                    section = key;
                    if (key == "CODE:") code(cells);
                    continue;
                }
            }
            if (allEmpty(cells)) continue;
            if (section == "CLASSES:") {
                classRow(cells);
            } else if (section == "FEATURES:") {
                featureRow(cells);
            } else if (section == "MTG:") {
                if (!header) {
                    columnLine(cells);
                    header = true;
                } else {
                    topologyRow(cells);
                }
            } else if (section.empty()) {
                fail("expected the MTG header's CODE: line", first, "CODE: FORM-A");
            }
        }
        if (!formA_) fail0("not an MTG file: no CODE: FORM-A line", "CODE: FORM-A");
        if (!header) fail0("no MTG: section with a column line", "MTG: then TOPO or ENTITY-CODE");
        return skeleton();
    }

private:
    [[noreturn]] void fail(const std::string& message, const std::string& value,
                           const std::string& range, const std::string& parameter = "") const {
        throw Error(message, {.file = name_,
                              .line = line_,
                              .parameter = parameter,
                              .value = project::printable(value, 60),
                              .validRange = range});
    }
    [[noreturn]] void fail0(const std::string& message, const std::string& range) const {
        throw Error(message, {.file = name_, .validRange = range});
    }
    static bool allEmpty(const std::vector<std::string>& cells) {
        return std::all_of(cells.begin(), cells.end(),
                           [](const std::string& c) { return text::trim(c).empty(); });
    }

    void code(const std::vector<std::string>& cells) {
        std::string form;
        for (std::size_t k = 1; k < cells.size() && form.empty(); ++k)
            form = std::string(text::trim(cells[k]));
        if (form == "FORM-B") fail("FORM-B MTG files are not read", form, "CODE: FORM-A");
        if (form != "FORM-A") fail("unknown MTG code form", form, "FORM-A");
        formA_ = true;
    }

    void classRow(const std::vector<std::string>& cells) {
        const std::string symbol(text::trim(cells[0]));
        if (symbol == "SYMBOL") return;  // the column names
        if (symbol == "$") return;       // the whole database, scale 0
        if (cells.size() < 2)
            fail("a class needs a symbol and a scale", symbol, "SYMBOL<TAB>SCALE...");
        if (symbol.empty() || symbol.size() > 64 ||
            !std::all_of(symbol.begin(), symbol.end(),
                         [](unsigned char c) { return std::isalpha(c); }))
            fail("a class symbol is letters", symbol, "letters A-Z, a-z", "SYMBOL");
        int scale = 0;
        if (!text::readNumber(text::trim(cells[1]), scale) || scale < 1 || scale > 64)
            fail("class scale out of range", cells[1], "1 to 64", "SCALE");
        if (!classes_.emplace(symbol, scale).second)
            fail("class declared twice", symbol, "one line per class");
    }

    void featureRow(const std::vector<std::string>& cells) {
        const std::string feature(text::trim(cells[0]));
        if (feature == "NAME") return;
        if (feature.empty()) return;
        features_.push_back(feature);
    }

    // TOPO (or ENTITY-CODE) and the feature names: the topology spans the columns before the
    // first feature's.
    void columnLine(const std::vector<std::string>& cells) {
        const std::string first(text::trim(cells[0]));
        if (first != "TOPO" && first != "ENTITY-CODE")
            fail("the MTG section starts with its column line", first, "TOPO or ENTITY-CODE");
        topoColumns_ = cells.size();
        for (std::size_t k = 1; k < cells.size(); ++k) {
            const std::string nameK(text::trim(cells[k]));
            if (nameK.empty()) continue;
            if (std::find(features_.begin(), features_.end(), nameK) == features_.end())
                fail("a column names a feature the FEATURES section does not declare", nameK,
                     features_.empty() ? "none declared" : text::oneOf(features_));
            if (topoColumns_ == cells.size()) topoColumns_ = k;
            featureColumn_[k] = nameK;
        }
        lastInColumn_.assign(topoColumns_, -1);
    }

    int newVertex(const std::string& cls, int line) {
        if (vertices_.size() >= kMaxVertices) fail("too many vertices", "", "at most 10000000");
        const auto c = classes_.find(cls);
        if (c == classes_.end())
            fail("a class the CLASSES section does not declare", cls, classNames());
        Vertex v;
        v.cls = cls;
        v.scale = c->second;
        v.line = line;
        vertices_.push_back(std::move(v));
        return int(vertices_.size()) - 1;
    }
    std::string classNames() const {
        std::vector<std::string> names;
        for (const auto& [n, s] : classes_) names.push_back(n);
        return names.empty() ? "none declared" : text::oneOf(names);
    }

    // The ancestor of `v` (by complexes) at `scale`, or -1.
    int ancestorAt(int v, int scale) const {
        while (v >= 0 && vertices_[std::size_t(v)].scale > scale)
            v = vertices_[std::size_t(v)].complex;
        return v >= 0 && vertices_[std::size_t(v)].scale == scale ? v : -1;
    }

    // One more vertex of class `cls` reached from `from` by `rel`.
    int step(int from, char rel, const std::string& cls, const std::string& code) {
        const int x = newVertex(cls, line_);
        Vertex& X = vertices_[std::size_t(x)];
        if (from < 0) {
            if (rel != '/') fail("a plant's code starts with '/'", code, "/P1...");
            return x;
        }
        const Vertex& F = vertices_[std::size_t(from)];
        if (rel == '/') {
            if (X.scale <= F.scale)
                fail("'/' leads to a finer scale", code, "a class of a finer scale after '/'");
            X.complex = from;
            if (F.bearer >= 0 && vertices_[std::size_t(F.bearer)].scale == X.scale) {
                X.parent = F.bearer;
                X.link = F.bearerLink;
            } else if (F.parent >= 0) {
                const auto& lc = vertices_[std::size_t(F.parent)].lastComponent;
                if (const auto it = lc.find(X.scale); it != lc.end()) {
                    X.parent = it->second;
                    X.link = F.link;
                }
            }
        } else if (X.scale == F.scale) {
            X.parent = from;
            X.link = rel;
            X.complex = F.complex;
        } else if (X.scale < F.scale) {
            X.parent = ancestorAt(from, X.scale);
            X.link = rel;
            X.complex = X.parent >= 0 ? vertices_[std::size_t(X.parent)].complex : -1;
            X.bearer = from;
            X.bearerLink = rel;
        } else {
            fail("'<' or '+' cannot lead to a finer scale", code, "'/' to a finer scale");
        }
        if (X.complex >= 0) vertices_[std::size_t(X.complex)].lastComponent[X.scale] = x;
        return x;
    }

    // A label: class letters then an optional index.
    std::pair<std::string, long> label(const std::string& code, std::size_t& i) {
        std::string cls;
        while (i < code.size() && std::isalpha((unsigned char)code[i])) cls += code[i++];
        std::string digits;
        while (i < code.size() && std::isdigit((unsigned char)code[i])) digits += code[i++];
        if (cls.empty()) fail("expected a class symbol", code, classNames());
        if (digits.size() > 9) fail("entity index out of range", code, "0 to 999999999");
        return {cls, digits.empty() ? 0L : std::stol(digits)};
    }

    void topologyRow(const std::vector<std::string>& cells) {
        std::size_t column = 0;
        while (column < topoColumns_ && column < cells.size() && text::trim(cells[column]).empty())
            ++column;
        if (column >= topoColumns_ || column >= cells.size()) {
            fail("a row with features but no entity code", "", "a code in the topology columns");
        }
        std::string code(text::trim(cells[column]));
        int at = -1;
        if (code == "*") {  // a later observation of the same entity: its values replace
            at = lastInColumn_[column];
            if (at < 0) fail("'*' with no entity above it", code, "an entity code");
        } else {
            if (code.front() == '(') fail("aliases are not read", code, "codes without (alias)");
            std::size_t i = 0;
            if (code.front() == '^') {
                at = lastInColumn_[column];
                if (at < 0)
                    fail("'^' with no entity above it in its column", code, "an entity above");
                i = 1;
            } else if (column > 0) {
                at = lastInColumn_[column - 1];
                if (at < 0)
                    fail("an indented code with no entity in the column before", code, "an entity");
            }
            if (i >= code.size()) fail("expected an entity code", code, "/, < or + then a label");
            while (i < code.size()) {
                const char rel = code[i];
                if (rel != '/' && rel != '<' && rel != '+')
                    fail("expected '/', '<' or '+'", code, "/, <, +");
                ++i;
                bool range = false;
                if (i < code.size() && code[i] == rel && rel != '/') {  // U87<<U93
                    range = true;
                    ++i;
                } else if (i + 1 < code.size() && code[i] == '.' && code[i + 1] == rel &&
                           rel != '/') {
                    range = true;  // U87<.<U93: the same, values shared
                    i += 2;
                }
                const auto [cls, index] = label(code, i);
                if (range) {
                    if (at < 0 || vertices_[std::size_t(at)].cls != cls)
                        fail("a range of entities joins two labels of one class", code, "U1<<U9");
                    const long from = lastIndex_[at];
                    if (index <= from || index - from > 100000)
                        fail("a range's last index is after its first", code,
                             "at most 100000 entities");
                    for (long k = from + 1; k <= index; ++k) {
                        at = step(at, rel, cls, code);
                        lastIndex_[at] = k;
                    }
                } else {
                    at = step(at, rel, cls, code);
                    lastIndex_[at] = index;
                }
            }
        }
        lastInColumn_[column] = at;
        for (const auto& [k, feature] : featureColumn_)
            if (k < cells.size() && !text::trim(cells[k]).empty())
                vertices_[std::size_t(at)].features[feature] = std::string(text::trim(cells[k]));
    }

    // ---- from the graph to a skeleton ----------------------------------------------------

    std::optional<double> number(const Vertex& v, std::initializer_list<const char*> names) const {
        for (const auto& [key, value] : v.features)
            for (const char* n : names)
                if (lower(key) == n) {
                    double d = 0.0;
                    if (!text::readNumber(value, d) || !(std::fabs(d) <= 1e5))
                        throw Error("feature value not a number in range",
                                    {.file = name_,
                                     .line = v.line,
                                     .parameter = key,
                                     .value = project::printable(value, 40),
                                     .validRange = "a number -100000 to 100000"});
                    return d;
                }
        return std::nullopt;
    }
    std::optional<vec3> coordinates(const Vertex& v) const {
        const auto x = number(v, {"xx"}), y = number(v, {"yy"}), z = number(v, {"zz"});
        if (!x && !y && !z) return std::nullopt;
        if (!x || !y || !z)
            throw Error("a vertex with some but not all of XX, YY, ZZ",
                        {.file = name_, .line = v.line, .validRange = "all three, or none"});
        return vec3(float(*x), float(*y), float(*z));
    }

    Skeleton skeleton() {
        Skeleton sk;
        sk.source = name_;
        // The geometric scale: the finest scale at which a vertex has coordinates; the
        // classes of that scale that carry coordinates are the stems.
        int geometric = 0;
        for (const Vertex& v : vertices_)
            if (coordinates(v)) geometric = std::max(geometric, v.scale);
        if (geometric == 0)
            fail0(
                "the MTG has no vertex with XX, YY, ZZ: plantarch rebuilds a plant from its "
                "node coordinates",
                "features XX, YY, ZZ on the vertices of the finest scale");
        std::map<std::string, bool> stemClass;
        for (const Vertex& v : vertices_)
            if (v.scale == geometric && coordinates(v)) stemClass[v.cls] = true;
        auto isNode = [&](int i) {
            const Vertex& v = vertices_[std::size_t(i)];
            return v.scale == geometric && stemClass.count(v.cls);
        };
        std::vector<long> nodeOf(vertices_.size(), -1);
        long nextID = 0;
        for (std::size_t i = 0; i < vertices_.size(); ++i) {
            if (!isNode(int(i))) continue;
            const Vertex& v = vertices_[i];
            const auto c = coordinates(v);
            if (!c)
                throw Error("a stem vertex without XX, YY, ZZ",
                            {.file = name_,
                             .line = v.line,
                             .parameter = v.cls,
                             .validRange = "XX, YY, ZZ on every vertex of a class that has them"});
            // Its parent among the nodes (over vertices of other classes, a leaf, say).
            int p = v.parent;
            char link = v.link;
            while (p >= 0 && !isNode(p)) {
                if (vertices_[std::size_t(p)].link == '+') link = '+';
                p = vertices_[std::size_t(p)].parent;
            }
            SkeletonNode n;
            n.line = v.line;
            n.position = *c;
            if (const auto r = number(v, {"radius"}))
                n.radius = float(*r);
            else if (const auto d = number(v, {"diameter", "topdia", "topdiameter"}))
                n.radius = float(*d / 2.0);
            if (!(n.radius >= 0.0f))
                throw Error("radius out of range", {.file = name_,
                                                    .line = v.line,
                                                    .value = std::to_string(n.radius),
                                                    .validRange = ">= 0"});
            const auto nx = number(v, {"leaf_nx"}), ny = number(v, {"leaf_ny"}),
                       nz = number(v, {"leaf_nz"});
            if (nx || ny || nz) {
                if (!nx || !ny || !nz)
                    throw Error(
                        "a leaf normal needs leaf_nx, leaf_ny and leaf_nz",
                        {.file = name_, .line = v.line, .validRange = "all three, or none"});
                n.leafNormal = vec3(float(*nx), float(*ny), float(*nz));
            }
            if (const auto len = number(v, {"leaf_length"})) {
                if (!(*len >= 0.0))
                    throw Error("leaf length out of range", {.file = name_,
                                                             .line = v.line,
                                                             .parameter = "leaf_length",
                                                             .validRange = ">= 0"});
                n.leafLength = float(*len);
            }
            for (const auto& [key, value] : v.features) {
                const ErrorContext at{.file = name_, .line = v.line, .parameter = key};
                if (lower(key) == "shoot_type") n.shootType = skeleton::checkedShootType(value, at);
                if (lower(key) == "organs") n.organs = skeleton::parseOrgans(value, at);
            }
            if (p >= 0) {
                n.id = nextID++;
                n.parent = nodeOf[std::size_t(p)];
                n.link = link == '+' ? SkeletonLink::Branch : SkeletonLink::Continue;
            } else {
                // A first node: the plant's base is its nearest coarser vertex with
                // coordinates; without one, this node stands for the base.
                std::optional<vec3> base;
                for (int a = v.complex; a >= 0 && !base; a = vertices_[std::size_t(a)].complex)
                    base = coordinates(vertices_[std::size_t(a)]);
                if (base) {
                    SkeletonNode root;
                    root.id = nextID++;
                    root.position = *base;
                    root.line = v.line;
                    sk.nodes.push_back(root);
                    n.id = nextID++;
                    n.parent = root.id;
                    n.link = SkeletonLink::Continue;
                } else {
                    n.id = nextID++;
                    n.parent = -1;
                    if (!n.shootType.empty() || !n.organs.empty()) {
                        // A root is a point: its type goes to the axis its child starts.
                        n.shootType.clear();
                        n.organs.clear();
                    }
                }
            }
            nodeOf[i] = n.id;
            sk.nodes.push_back(std::move(n));
        }
        return sk;
    }

    std::string name_;
    std::vector<std::vector<std::string>> lines_;
    int line_ = 0;
    bool formA_ = false;
    std::map<std::string, int> classes_;
    std::vector<std::string> features_;
    std::size_t topoColumns_ = 1;
    std::map<std::size_t, std::string> featureColumn_;
    std::vector<int> lastInColumn_;
    std::vector<Vertex> vertices_;
    std::map<int, long> lastIndex_;
};

}  // namespace

namespace skeleton {

Skeleton readMTG(const std::string& text, const std::string& name) {
    return MTGReader(text, name).read();
}

}  // namespace skeleton

// ---- writing ---------------------------------------------------------------------------

std::string plantsMTG(const PlantArchitecture& arch, const std::vector<unsigned>& plantIDs) {
    std::vector<std::pair<const PlantInstance*, unsigned>> plants;
    unsigned columns = 1;
    for (unsigned id : plantIDs) {
        const PlantInstance& p = arch.plant(id);
        plants.emplace_back(&p, id);
        for (const Shoot& s : p.shoots) columns = std::max(columns, s.rank + 1);
    }
    // The topology takes one column per branching order.
    std::string out =
        "CODE:\tFORM-A\n\nCLASSES:\nSYMBOL\tSCALE\tDECOMPOSITION\tINDEXATION\tDEFINITION\n"
        "$\t0\tFREE\tFREE\tIMPLICIT\nP\t1\tFREE\tFREE\tEXPLICIT\nA\t2\tFREE\tFREE\tEXPLICIT\n"
        "I\t3\tFREE\tFREE\tEXPLICIT\n\nDESCRIPTION:\nLEFT\tRIGHT\tRELTYPE\tMAX\nA\tA\t+\t?\n"
        "A\tA\t<\t1\nI\tI\t<\t1\nI\tI\t+\t?\n\nFEATURES:\nNAME\tTYPE\nXX\tREAL\nYY\tREAL\n"
        "ZZ\tREAL\nRadius\tREAL\nLength\tREAL\nAge\tREAL\nLeaves\tINT\nshoot_type\tSTRING\n"
        "plant_name\tSTRING\n\nMTG:\nTOPO";
    out += std::string(columns, '\t');
    out += "XX\tYY\tZZ\tRadius\tLength\tAge\tLeaves\tshoot_type\tplant_name\n";
    char buf[512];
    auto row = [&](unsigned column, const std::string& code, const vec3* xyz, const Phytomer* ph,
                   const std::string& type, const std::string& plantName) {
        out += std::string(column, '\t') + code + std::string(columns - column, '\t');
        if (xyz) {
            std::snprintf(buf, sizeof buf, "%.9g\t%.9g\t%.9g", double(xyz->x), double(xyz->y),
                          double(xyz->z));
            out += buf;
        } else {
            out += "\t\t";
        }
        if (ph) {
            unsigned leaves = 0;
            for (const Petiole& pt : ph->petioles)
                for (const LeafOrgan& l : pt.leaves)
                    if (!l.removed && hasSize(currentLeafSize(*ph, l))) ++leaves;
            std::snprintf(buf, sizeof buf, "\t%.9g\t%.9g\t%.9g\t%u", double(ph->internode.radius),
                          double(ph->internode.length * ph->internodeFraction), double(ph->age),
                          leaves);
            out += buf;
        } else {
            out += "\t\t\t\t";
        }
        out += "\t" + type + "\t" + plantName + "\n";
    };
    unsigned plantNumber = 0;
    for (const auto& entry : plants) {
        // Not a structured binding: the lambda below uses it (clang 14 cannot capture those).
        const auto* p = entry.first;
        ++plantNumber;
        row(0, "/P" + std::to_string(plantNumber), &p->base, nullptr, "", p->name);
        if (p->shoots.empty() || p->shoots[0].removed) continue;
        std::vector<std::vector<vec3>> nodes(p->shoots.size());
        for (const Shoot& s : p->shoots)
            if (!s.removed) nodes[s.id] = shootNodePositions(*p, s.id);
        // Children of each (shoot, node), in ID order.
        std::map<std::pair<unsigned, int>, std::vector<unsigned>> children;
        for (const Shoot& s : p->shoots)
            if (!s.removed && s.parent >= 0)
                children[{unsigned(s.parent), s.parentNode}].push_back(s.id);
        // Each shoot: its first internode's row, the rest with '^<'; after each internode
        // the shoots it bears, one column further (or, continuing it, in its own column).
        auto writeShoot = [&](auto&& self, unsigned sid, unsigned column,
                              const std::string& first) -> void {
            const Shoot& s = p->shoots[sid];
            for (std::size_t k = 0; k < s.phytomers.size(); ++k) {
                const std::string code = k == 0 ? first + "A" + std::to_string(sid + 1) + "/I1"
                                                : "^<I" + std::to_string(k + 1);
                row(column, code, &nodes[sid][k + 1], &s.phytomers[k], k == 0 ? s.type : "", "");
                const auto c = children.find({sid, int(k)});
                if (c == children.end()) continue;
                // Branches first: a shoot continuing this one takes over its column, and
                // a branch's row is read against the last row of the column before it.
                for (const bool continuing : {false, true})
                    for (unsigned child : c->second) {
                        const Shoot& cs = p->shoots[child];
                        if (cs.phytomers.empty()) continue;
                        const bool continues = cs.rank == s.rank && k + 1 == s.phytomers.size();
                        if (continues != continuing) continue;
                        if (continues)
                            self(self, child, column, "^<");
                        else
                            self(self, child, column + 1, "+");
                    }
            }
        };
        if (!p->shoots[0].phytomers.empty()) writeShoot(writeShoot, 0, 0, "^/");
    }
    return out;
}

}  // namespace plantarch
