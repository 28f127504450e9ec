// Plant strings: a compact, bracketed text form of a plant's visible structure (shoots,
// internodes, petioles, leaves, flowers and fruit with their realized sizes and angles), for
// machine learning. The grammar is in docs/plant-xml.md. Every number in a string is one
// stored value printed with a chosen number of significant digits, and the reader stores
// exactly the number it reads, so string -> plant -> string gives the same string.

#include <algorithm>
#include <array>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "geometry/tessellate.h"
#include "plant_io/plant_structure.h"
#include "plantarch/Error.h"

namespace plantarch::plant_io {

namespace {

bool isLabelChar(char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' ||
           c == '-';
}

bool isLabel(const std::string& s) {
    return !s.empty() && std::all_of(s.begin(), s.end(), isLabelChar);
}

// Whether two values are the same to the bit (-0 and 0 differ: their sines do).
bool sameBits(float a, float b) {
    return std::bit_cast<std::uint32_t>(a) == std::bit_cast<std::uint32_t>(b);
}
bool sameBits(vec3 a, vec3 b) {
    return sameBits(a.x, b.x) && sameBits(a.y, b.y) && sameBits(a.z, b.z);
}

char stageLetter(FloralStage s) {
    switch (s) {
        case FloralStage::FlowerClosed:
            return 'c';
        case FloralStage::FlowerOpen:
            return 'o';
        case FloralStage::Fruit:
            return 'f';
        default:
            return 0;
    }
}

constexpr int kMaxDepth = 1000;  // shoots nested in shoots (appended chains count too)
constexpr int kMaxLeafID = 1 << 30;
constexpr double kMaxPlantAge = 1e9;  // days, as plant_age in plant structure files
constexpr double kMaxFloat = std::numeric_limits<float>::max();
// A value a string may leave out, until completion fills it.
constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

// ---- writing -------------------------------------------------------------------------

class StringWriter {
public:
    StringWriter(const PlantInstance& p, int digits) : p_(p), digits_(digits) {}

    std::string run() {
        out_ += '@';
        if (isLabel(p_.name)) out_ += p_.name;
        out_ += '(';
        numbers({p_.base.x, p_.base.y, p_.base.z});
        out_ += ',';
        number(p_.age);
        out_ += ')';
        if (drawn(0)) shoot(0, 0);
        return std::move(out_);
    }

private:
    template <class T>
    void number(T v) {
        char buf[64];
        const auto r = digits_ == 0 ? std::to_chars(buf, buf + sizeof buf, v)
                                    : std::to_chars(buf, buf + sizeof buf, v,
                                                    std::chars_format::general, digits_);
        out_.append(buf, r.ptr);
    }
    void numbers(std::initializer_list<float> values) {
        bool first = true;
        for (float v : values) {
            if (!first) out_ += ',';
            first = false;
            number(v);
        }
    }

    // Shoots without phytomers (pruned to nothing) have no geometry and are left out.
    bool drawn(unsigned id) const {
        return id < p_.shoots.size() && !p_.shoots[id].removed && !p_.shoots[id].phytomers.empty();
    }

    void shoot(unsigned id, int depth) {
        if (depth >= kMaxDepth)
            throw Error(
                "the plant's shoots nest too deep for a plant string",
                {.parameter = "shoot " + std::to_string(id), .validRange = "at most 1000 levels"});
        const Shoot& s = p_.shoots[id];
        out_ += 'S';
        out_ += s.type;
        out_ += '(';
        const vec3 r = s.phytomers.front().internode.rollReference;
        numbers({r.x, r.y, r.z});
        out_ += "){";
        for (std::size_t k = 0; k < s.phytomers.size(); ++k) node(s, k, depth);
        for (const FloralBud& fb : s.terminalFloralBuds) floral(fb, true);
        for (unsigned c : s.children) {
            if (drawn(c) && p_.shoots[c].rank == s.rank)
                shoot(c, depth + 1);  // appended at the tip
        }
        out_ += '}';
    }

    void node(const Shoot& s, std::size_t k, int depth) {
        const Phytomer& ph = s.phytomers[k];
        const Internode& in = ph.internode;
        out_ += 'I';
        if (ph.parametersLabel != s.type) out_ += ph.parametersLabel;  // built by another type
        out_ += '(';
        const float current = in.length * ph.internodeFraction;
        numbers({current, in.radius, in.pitch, in.azimuth, in.guide.x, in.guide.y, in.guide.z});
        out_ += ')';
        if (digits_ == 0) exactInternode(s, k);
        for (std::size_t j = 0; j < ph.petioles.size(); ++j) {
            const Petiole& pt = ph.petioles[j];
            const float f = ph.leafFraction;
            out_ += "[P(";
            // A petiole whose leaves have all fallen is not drawn: it is written with length 0.
            const bool bare =
                !pt.leaves.empty() && std::all_of(pt.leaves.begin(), pt.leaves.end(),
                                                  [](const LeafOrgan& l) { return l.removed; });
            // Its length and bend rate now (a growing petiole keeps its full-grown bend).
            numbers({bare ? 0.0f : pt.length * f, pt.radius * f, pt.pitch, petioleBendRate(pt, f),
                     pt.taper});
            out_ += ')';
            // Exact strings: an azimuth steered away from the even spread, a clearance turn.
            if (digits_ == 0 &&
                !sameBits(pt.azimuth, petioleAzimuth(in.azimuth, j, ph.petioles.size()))) {
                out_ += "a(";
                number(pt.azimuth);
                out_ += ')';
            }
            clearance(pt.clearance);
            const bool ownShapes = digits_ == 0 && ownLeafShapes(ph);
            for (const LeafOrgan& l : pt.leaves) {
                if (l.removed) continue;
                out_ += 'L';
                out_ += std::to_string(l.leafletIndex);
                out_ += '(';
                numbers({l.scale * f, l.pitch, l.yaw, l.roll, l.position});
                out_ += ',';
                out_ += std::to_string(l.variant);
                out_ += ')';
                if (ownShapes && l.leafID >= 0) out_ += "i(" + std::to_string(l.leafID) + ')';
            }
            for (const FloralBud& fb : pt.floralBuds) floral(fb, false);
            for (unsigned c : s.children) {
                const Shoot& child = p_.shoots[c];
                if (drawn(c) && child.rank != s.rank && child.parentNode == int(k) &&
                    child.parentPetiole == int(j))
                    shoot(c, depth + 1);
            }
            out_ += ']';
        }
    }

    // What an exact string adds to an internode: the values the reader would not derive to
    // the bit. An internode still elongating gives its full length and the fraction grown
    // (its nodes lie at direction x full length x fraction, which differs in the last bit
    // from direction x current length). An internode whose shoot axis was steered (attraction
    // points, obstacles) gives its roll reference, which steering carried in two turns where
    // the reader carries it in one; one turned along a solid obstacle gives its axis.
    void exactInternode(const Shoot& s, std::size_t k) {
        const Phytomer& ph = s.phytomers[k];
        const Internode& in = ph.internode;
        if (ph.internodeFraction != 1.0f) {
            out_ += "e(";
            numbers({in.length, ph.internodeFraction});
            out_ += ')';
        }
        if (k > 0 &&
            !sameBits(in.rollReference,
                      carriedRollReference(s.phytomers[k - 1].internode.rollReference, in.guide))) {
            out_ += "r(";
            numbers({in.rollReference.x, in.rollReference.y, in.rollReference.z});
            out_ += ')';
        }
        if (!sameBits(in.direction, internodeDirection(in))) {
            out_ += "d(";
            numbers({in.direction.x, in.direction.y, in.direction.z});
            out_ += ')';
        }
    }

    // Whether the leaves of a phytomer each have their own shape, drawn from their leaf ID (a
    // shoot type with unique_prototypes 0).
    bool ownLeafShapes(const Phytomer& ph) const {
        const auto t = p_.shootTypes.find(ph.parametersLabel);
        return t != p_.shootTypes.end() &&
               t->second.phytomer_parameters.leaf.prototype.unique_prototypes == 0;
    }

    // A turn out of solid obstacles (exact strings; none: nothing written).
    void clearance(const OrganTurn& t) {
        if (digits_ != 0 || t.angle == 0.0f) return;
        out_ += "c(";
        numbers({t.axis.x, t.axis.y, t.axis.z, t.angle});
        out_ += ')';
    }

    // Terminal buds also give their place around the shoot tip (dead buds keep theirs).
    void floral(const FloralBud& fb, bool terminal) {
        const char letter = stageLetter(fb.stage);
        if (!letter) return;  // buds and removed organs are not drawn
        out_ += 'F';
        out_ += letter;
        out_ += fb.parametersLabel;  // drawn from another shoot type's template (an ear)
        out_ += '(';
        numbers({fb.peduncleLength, fb.peduncleRadius, fb.pedunclePitch, fb.peduncleRoll,
                 fb.peduncleCurvature});
        if (terminal) {
            out_ += ',';
            numbers({fb.terminalAzimuth});
        }
        out_ += ')';
        // Exact strings: a peduncle's side that soft collision avoidance turned.
        if (digits_ == 0 && fb.peduncleAzimuth != 0.0f) {
            out_ += "a(";
            number(fb.peduncleAzimuth);
            out_ += ')';
        }
        clearance(fb.peduncleClearance);
        const bool fruit = fb.stage == FloralStage::Fruit;
        const float m = fruit ? std::clamp(fb.fruitGrowth, 0.0f, 1.0f) : 1.0f;
        for (const FlowerOrgan& fl : fb.flowers) {
            out_ += "f(";
            numbers({fl.position, fl.azimuth, fl.pitch, fl.roll,
                     fruit ? fl.fruitScale * m : fl.flowerScale, fl.gravityFactor * m});
            out_ += ',';
            out_ += std::to_string(fl.variant);
            out_ += ')';
            clearance(fl.clearance);
        }
    }

    const PlantInstance& p_;
    int digits_;
    std::string out_;
};

// ---- reading -------------------------------------------------------------------------

class StringParser {
public:
    explicit StringParser(std::string_view text) : s_(text) {}

    PlantInstance run() {
        // Shoots are created while their children are parsed: reserve so that indices into
        // p_.shoots stay the only references needed.
        expect('@');
        p_.name = label(false);
        expect('(');
        p_.base.x = number<float>();
        expect(',');
        p_.base.y = number<float>();
        expect(',');
        p_.base.z = number<float>();
        expect(',');
        p_.age = number<double>(kMaxPlantAge, "-1e9 to 1e9");
        if (p_.age < 0.0) fail("negative plant age", "an age >= 0 days");
        expect(')');
        if (peek() == 'S') shoot(-1, 0, 0, false, 0);
        skipSpace();
        if (pos_ != s_.size()) fail("text after the plant's base stem", "the end of the string");
        return std::move(p_);
    }

private:
    [[noreturn]] void fail(const std::string& message, const std::string& expected) const {
        const std::size_t from = pos_ > 12 ? pos_ - 12 : 0;
        std::string near(s_.substr(from, std::min<std::size_t>(24, s_.size() - from)));
        for (char& c : near)
            if (static_cast<unsigned char>(c) < 32) c = ' ';
        throw Error(message, {.parameter = "plant string, character " + std::to_string(pos_ + 1),
                              .value = near,
                              .validRange = expected});
    }

    void skipSpace() {
        while (pos_ < s_.size() &&
               (s_[pos_] == ' ' || s_[pos_] == '\n' || s_[pos_] == '\r' || s_[pos_] == '\t'))
            ++pos_;
    }
    char peek() {
        skipSpace();
        return pos_ < s_.size() ? s_[pos_] : '\0';
    }
    void expect(char c) {
        if (peek() != c) fail(std::string("expected '") + c + "'", std::string("'") + c + "'");
        ++pos_;
    }

    std::string label(bool required) {
        skipSpace();
        const std::size_t start = pos_;
        while (pos_ < s_.size() && isLabelChar(s_[pos_])) ++pos_;
        if (required && pos_ == start)
            fail("expected a shoot type label", "letters, digits, '_' or '-'");
        return std::string(s_.substr(start, pos_ - start));
    }

    // A number of at most `limit` in size (the plant's age may reach a plant structure
    // file's plant_age limit, 1e9 days; a petiole's bend rate any finite number; everything
    // else 1e6).
    template <class T>
    T number(double limit = 1e6, const char* range = "-1e6 to 1e6") {
        skipSpace();
        const std::size_t start = pos_;
        while (pos_ < s_.size() && s_[pos_] != ',' && s_[pos_] != ')' && s_[pos_] != ' ') ++pos_;
        const std::string_view text = s_.substr(start, pos_ - start);
        T v{};
        const auto r = std::from_chars(text.data(), text.data() + text.size(), v);
        if (text.empty() || r.ec != std::errc() || r.ptr != text.data() + text.size() ||
            !std::isfinite(v)) {
            pos_ = start;
            fail("expected a number", "a finite number such as 0.012 or -1.5e-3");
        }
        if (std::abs(double(v)) > limit) {
            pos_ = start;
            fail("number out of range", range);
        }
        return v;
    }

    // n numbers separated by commas, inside parentheses.
    template <std::size_t N>
    std::array<float, N> tuple(std::size_t unbounded = N) {
        std::array<float, N> v{};
        expect('(');
        for (std::size_t i = 0; i < N; ++i) {
            if (i) expect(',');
            v[i] = i == unbounded ? number<float>(kMaxFloat, "a finite number") : number<float>();
        }
        expect(')');
        return v;
    }

    // N numbers, each followed by a comma (a whole number comes next).
    template <std::size_t N>
    std::array<float, N> numbersThen() {
        std::array<float, N> v{};
        for (std::size_t i = 0; i < N; ++i) {
            v[i] = number<float>();
            expect(',');
        }
        return v;
    }

    // A prototype variant and the closing parenthesis.
    unsigned variant() {
        const double v = number<double>();
        if (v < 0.0 || v > 1e6 || v != std::floor(v))
            fail("expected a variant number", "a whole number >= 0");
        expect(')');
        return unsigned(v);
    }

    vec3 direction(float x, float y, float z) {
        const vec3 v(x, y, z);
        const float l = glm::length(v);
        if (!(l > 0.5f && l < 1.5f))
            fail("a direction must have length close to 1", "a unit vector");
        return v;
    }

    void shoot(int parent, int node, int petiole, bool appended, int depth) {
        if (depth >= kMaxDepth) fail("shoots nested too deep", "at most 1000 levels");
        const unsigned id = unsigned(p_.shoots.size());
        mark("shoot[" + std::to_string(id) + "]");
        expect('S');
        {
            Shoot s;
            s.id = id;
            s.type = label(true);
            s.parent = parent;
            s.parentNode = parent < 0 ? -1 : node;
            s.parentPetiole = petiole;
            s.rank = parent < 0 ? 0 : p_.shoots[unsigned(parent)].rank + (appended ? 0 : 1);
            p_.shoots.push_back(std::move(s));
        }
        const auto roll = tuple<3>();
        expect('{');
        while (peek() == 'I') internode(id, depth);
        if (p_.shoots[id].phytomers.empty()) fail("a shoot needs at least one internode", "'I('");
        p_.shoots[id].phytomers.front().internode.rollReference =
            direction(roll[0], roll[1], roll[2]);
        while (peek() == 'F') {
            mark("shoot[" + std::to_string(id) + "].terminal_floral_bud[" +
                 std::to_string(p_.shoots[id].terminalFloralBuds.size()) + "]");
            FloralBud fb = floral(true);
            fb.terminal = true;
            p_.shoots[id].terminalFloralBuds.push_back(std::move(fb));
        }
        while (peek() == 'S')
            shoot(int(id), int(p_.shoots[id].phytomers.size()) - 1, 0, true, depth + 1);
        expect('}');
    }

    void internode(unsigned shootID, int depth) {
        const std::string at = "shoot[" + std::to_string(shootID) + "].phytomer[" +
                               std::to_string(p_.shoots[shootID].phytomers.size()) + "]";
        mark(at);
        expect('I');
        Phytomer ph;
        ph.parametersLabel = label(false);
        if (ph.parametersLabel.empty()) ph.parametersLabel = p_.shoots[shootID].type;
        const auto v = tuple<7>();
        ph.internode.length = v[0];
        ph.internode.radius = v[1];
        ph.internode.pitch = v[2];
        ph.internode.azimuth = v[3];
        ph.internode.guide = direction(v[4], v[5], v[6]);
        exactInternode(ph, p_.shoots[shootID].phytomers.empty());
        p_.shoots[shootID].phytomers.push_back(std::move(ph));
        const int node = int(p_.shoots[shootID].phytomers.size()) - 1;
        int petiole = 0;
        while (peek() == '[') {
            const std::string ptAt = at + ".internode.petiole[" + std::to_string(petiole) + "]";
            mark(ptAt);
            ++pos_;
            expect('P');
            // The bend rate (degrees per m) is the full-grown curvature over the petiole's
            // growth fraction: any finite number (a young petiole's is large).
            const auto q = tuple<5>(3);
            Petiole pt;
            pt.length = q[0];
            pt.radius = q[1];
            pt.pitch = q[2];
            pt.curvature = q[3];
            pt.taper = q[4];
            pt.azimuth = kNaN;  // not given: NaN until completed (spread evenly)
            if (peek() == 'a') {
                ++pos_;
                pt.azimuth = tuple<1>()[0];
            }
            clearance(pt.clearance);
            while (peek() == 'L') {
                mark(ptAt + ".leaf[" + std::to_string(pt.leaves.size()) + "]");
                pt.leaves.push_back(leaf());
            }
            while (peek() == 'F') {
                mark(ptAt + ".floral_bud[" + std::to_string(pt.floralBuds.size()) + "]");
                pt.floralBuds.push_back(floral(false));
            }
            p_.shoots[shootID].phytomers[std::size_t(node)].petioles.push_back(std::move(pt));
            while (peek() == 'S') shoot(int(shootID), node, petiole, false, depth + 1);
            expect(']');
            ++petiole;
        }
    }

    // The values an exact string adds to an internode (StringWriter::exactInternode).
    void exactInternode(Phytomer& ph, bool first) {
        if (peek() == 'e') {
            const std::size_t at = pos_;
            ++pos_;
            const auto v = tuple<2>();
            if (v[0] * v[1] != ph.internode.length) {
                pos_ = at;
                fail(
                    "an elongating internode's length must be its full length times the "
                    "fraction grown",
                    "e(full length, fraction) with full length x fraction = the length given");
            }
            ph.internode.length = v[0];
            ph.internodeFraction = v[1];
        }
        if (peek() == 'r') {
            if (first)
                fail("a shoot's first internode has the shoot's roll reference",
                     "r(...) after a later internode");
            ++pos_;
            const auto v = tuple<3>();
            ph.internode.rollReference = direction(v[0], v[1], v[2]);
        } else if (!first) {
            // Not given: NaN until completed (carried from the internode before).
            ph.internode.rollReference = vec3(kNaN);
        }
        // Not given: NaN until completed (from the shoot axis, pitch and azimuth).
        ph.internode.direction = vec3(kNaN);
        if (peek() == 'd') {
            ++pos_;
            const auto v = tuple<3>();
            ph.internode.direction = direction(v[0], v[1], v[2]);
        }
    }

    // A turn out of solid obstacles, if one follows: "c(" axis "," angle ")".
    void clearance(OrganTurn& t) {
        if (peek() != 'c') return;
        ++pos_;
        const auto v = tuple<4>();
        t.axis = direction(v[0], v[1], v[2]);
        t.angle = v[3];
    }

    LeafOrgan leaf() {
        expect('L');
        skipSpace();
        const std::size_t start = pos_;
        const bool plus = pos_ < s_.size() && s_[pos_] == '+';
        if (pos_ < s_.size() && (s_[pos_] == '-' || plus)) ++pos_;
        const std::size_t digits = pos_;
        while (pos_ < s_.size() && s_[pos_] >= '0' && s_[pos_] <= '9') ++pos_;
        int index = 0;
        const auto r = std::from_chars(s_.data() + start + (plus ? 1 : 0), s_.data() + pos_, index);
        if (pos_ == digits || r.ec != std::errc() || r.ptr != s_.data() + pos_ || index < -1000 ||
            index > 1000) {
            pos_ = start;
            fail("expected a leaflet index", "a whole number from -1000 to 1000");
        }
        expect('(');
        const auto v = numbersThen<5>();
        LeafOrgan l;
        l.variant = variant();
        l.leafletIndex = index;
        l.scale = v[0];
        l.pitch = v[1];
        l.yaw = v[2];
        l.roll = v[3];
        l.position = v[4];
        if (peek() == 'i') l.leafID = leafID();
        return l;
    }

    // "i(" id ")": a leaf's ID, a whole number unique within the plant.
    int leafID() {
        ++pos_;
        expect('(');
        skipSpace();
        const std::size_t start = pos_;
        while (pos_ < s_.size() && s_[pos_] >= '0' && s_[pos_] <= '9') ++pos_;
        int id = -1;
        const auto r = std::from_chars(s_.data() + start, s_.data() + pos_, id);
        if (pos_ == start || r.ec != std::errc() || id > kMaxLeafID) {
            pos_ = start;
            fail("expected a leaf ID", "a whole number from 0 to " + std::to_string(kMaxLeafID));
        }
        if (!leafIDs_.insert(id).second) {
            pos_ = start;
            fail("a leaf ID given twice", "IDs unique within the plant");
        }
        expect(')');
        return id;
    }

    // A terminal bud may give its place around the tip as a sixth number.
    FloralBud floral(bool terminal) {
        const std::string budAt = marks_.back().first;  // marked by the caller
        expect('F');
        FloralBud fb;
        const char letter = pos_ < s_.size() ? s_[pos_] : '\0';
        if (letter == 'c')
            fb.stage = FloralStage::FlowerClosed;
        else if (letter == 'o')
            fb.stage = FloralStage::FlowerOpen;
        else if (letter == 'f')
            fb.stage = FloralStage::Fruit;
        else
            fail("expected a flower stage letter", "c (closed flower), o (open flower), f (fruit)");
        ++pos_;
        fb.parametersLabel = label(false);
        expect('(');
        const auto v = numbersThen<4>();
        fb.peduncleLength = v[0];
        fb.peduncleRadius = v[1];
        fb.pedunclePitch = v[2];
        fb.peduncleRoll = v[3];
        fb.peduncleCurvature = number<float>();
        // Not given (a string written before terminal places were): NaN until completed.
        if (terminal) fb.terminalAzimuth = kNaN;
        if (terminal && peek() == ',') {
            expect(',');
            fb.terminalAzimuth = number<float>();
        }
        expect(')');
        if (peek() == 'a') {
            ++pos_;
            fb.peduncleAzimuth = tuple<1>()[0];
        }
        clearance(fb.peduncleClearance);
        const bool fruit = fb.stage == FloralStage::Fruit;
        while (peek() == 'f') {
            mark(budAt + ".peduncle.flower[" + std::to_string(fb.flowers.size()) + "]");
            ++pos_;
            expect('(');
            const auto q = numbersThen<6>();
            FlowerOrgan fl;
            fl.variant = variant();
            fl.position = q[0];
            fl.azimuth = q[1];
            fl.pitch = q[2];
            fl.roll = q[3];
            (fruit ? fl.fruitScale : fl.flowerScale) = q[4];
            fl.gravityFactor = q[5];
            clearance(fl.clearance);
            fb.flowers.push_back(fl);
        }
        return fb;
    }

    // Where the organ at `path` ("shoot[1].phytomer[0].internode.petiole[0].leaf[2]", as
    // plant structure files name it) starts in the string (at the next token).
    void mark(std::string path) {
        peek();
        marks_.emplace_back(std::move(path), pos_);
    }

    std::string_view s_;
    std::size_t pos_ = 0;
    PlantInstance p_;
    std::set<int> leafIDs_;                                   // given so far
    std::vector<std::pair<std::string, std::size_t>> marks_;  // in string order

public:
    /// An error of the check after reading (a path below "plant string"), placed at the
    /// character where the organ it names starts.
    Error located(const Error& e) const {
        const std::string prefix = "plant string.";
        if (e.parameter().compare(0, prefix.size(), prefix) != 0) return e;
        const std::string path = e.parameter().substr(prefix.size());
        const std::pair<std::string, std::size_t>* best = nullptr;
        for (const auto& m : marks_) {
            const bool within = path.compare(0, m.first.size(), m.first) == 0 &&
                                (path.size() == m.first.size() || path[m.first.size()] == '.');
            if (within && (!best || m.first.size() > best->first.size())) best = &m;
        }
        if (!best) return e;
        ErrorContext c = e.context();
        c.parameter = "plant string, character " + std::to_string(best->second + 1) + ": " + path;
        return Error(e.message(), c);
    }
};

// The members a plant string gives; everything else is completed.
void notePresent(PlantInstance& p, Presence& m) {
    for (const void* v : {(const void*)&p.name, (const void*)&p.base, (const void*)&p.age})
        m.note(v);
    for (Shoot& s : p.shoots) {
        for (const void* v :
             {(const void*)&s.type, (const void*)&s.parent, (const void*)&s.parentNode,
              (const void*)&s.parentPetiole, (const void*)&s.rank})
            m.note(v);
        auto floral = [&](FloralBud& fb) {
            for (const void* v : {(const void*)&fb.stage, (const void*)&fb.terminal,
                                  (const void*)&fb.parametersLabel, (const void*)&fb.peduncleLength,
                                  (const void*)&fb.peduncleRadius, (const void*)&fb.pedunclePitch,
                                  (const void*)&fb.peduncleRoll, (const void*)&fb.peduncleCurvature,
                                  (const void*)&fb.fruitGrowth})
                m.note(v);
        };
        for (std::size_t k = 0; k < s.phytomers.size(); ++k) {
            Phytomer& ph = s.phytomers[k];
            Internode& in = ph.internode;
            for (const void* v :
                 {(const void*)&ph.parametersLabel, (const void*)&ph.internodeFraction,
                  (const void*)&ph.leafFraction, (const void*)&in.length, (const void*)&in.radius,
                  (const void*)&in.pitch, (const void*)&in.azimuth, (const void*)&in.guide})
                m.note(v);
            if (k == 0 || !std::isnan(in.rollReference.x)) m.note(&in.rollReference);
            if (!std::isnan(in.direction.x)) m.note(&in.direction);
            for (Petiole& pt : ph.petioles) {
                for (const void* v :
                     {(const void*)&pt.length, (const void*)&pt.radius, (const void*)&pt.pitch,
                      (const void*)&pt.curvature, (const void*)&pt.taper})
                    m.note(v);
                if (!std::isnan(pt.azimuth)) m.note(&pt.azimuth);
                for (LeafOrgan& l : pt.leaves) {
                    for (const void* v :
                         {(const void*)&l.leafletIndex, (const void*)&l.scale,
                          (const void*)&l.pitch, (const void*)&l.yaw, (const void*)&l.roll,
                          (const void*)&l.position, (const void*)&l.variant})
                        m.note(v);
                    if (l.leafID >= 0) m.note(&l.leafID);  // given (else -1)
                }
                for (FloralBud& fb : pt.floralBuds) floral(fb);
            }
        }
        for (FloralBud& fb : s.terminalFloralBuds) {
            floral(fb);
            if (!std::isnan(fb.terminalAzimuth)) m.note(&fb.terminalAzimuth);
        }
    }
}

}  // namespace

std::string writePlantString(const PlantInstance& plant, int significantDigits) {
    return StringWriter(plant, significantDigits).run();
}

ReadResult readPlantString(const std::string& text, const Defaults& defaults) {
    ReadResult result;
    StringParser parser(text);
    PlantInstance plant = parser.run();
    Presence present = Presence::recordingPresent();
    notePresent(plant, present);
    std::vector<std::string> notes;
    try {
        completePlant(plant, present, defaults, defaults.firstStream, notes, "plant string");
        checkPlant(plant, "plant string");
    } catch (const Error& e) {
        throw parser.located(e);
    }
    for (const std::string& n : notes)
        if (n.find("default parameters") != std::string::npos)
            result.warnings.push_back("plant string: " + n);
    result.plants.push_back(std::move(plant));
    return result;
}

}  // namespace plantarch::plant_io
