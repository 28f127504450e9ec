// Strict XML reading: documents, elements, attributes and children (xml_reader.h).

#include "core/xml_reader.h"

#include <algorithm>
#include <set>
#include <utility>

#include "core/input_file.h"
#include "core/value_text.h"

namespace plantarch::xml {

namespace {

std::string excerpt(std::string_view text) {
    return text::collapseSpaces(text).substr(0, 40);
}

// Whether XML 1.0 allows the character `c` (its Char production).
bool isXmlChar(unsigned long c) {
    return c == 0x9 || c == 0xA || c == 0xD || (c >= 0x20 && c <= 0xD7FF) ||
           (c >= 0xE000 && c <= 0xFFFD) || (c >= 0x10000 && c <= 0x10FFFF);
}

// The offset of the first character reference (&#...;) outside comments and CDATA that names
// a character XML does not allow, such as &#0; (pugixml would decode it and cut the value
// short there), with the reference; npos when there is none.
std::pair<std::size_t, std::string_view> badCharacterReference(std::string_view text) {
    for (std::size_t at = 0; (at = text.find_first_of("<&", at)) != std::string_view::npos;) {
        const std::string_view rest = text.substr(at);
        if (rest.starts_with("<!--") || rest.starts_with("<![CDATA[")) {
            const std::string_view end = rest[2] == '-' ? "-->" : "]]>";
            const std::size_t close = text.find(end, at + 4);
            if (close == std::string_view::npos) break;  // the parser reports it
            at = close + end.size();
            continue;
        }
        ++at;
        if (!rest.starts_with("&#")) continue;
        const bool hex = rest.size() > 2 && (rest[2] == 'x' || rest[2] == 'X');
        const std::size_t first = hex ? 3 : 2;
        const std::size_t semicolon = rest.find(';', first);
        if (semicolon == std::string_view::npos || semicolon > first + 12) continue;
        unsigned long value = 0;
        bool digits = semicolon > first;
        for (std::size_t i = first; i < semicolon && digits; ++i) {
            const char c = rest[i];
            const int d = c >= '0' && c <= '9'          ? c - '0'
                          : hex && c >= 'a' && c <= 'f' ? c - 'a' + 10
                          : hex && c >= 'A' && c <= 'F' ? c - 'A' + 10
                                                        : -1;
            digits = d >= 0;
            value = std::min(value * (hex ? 16 : 10) + unsigned(d >= 0 ? d : 0), 0x110000ul);
        }
        if (digits && !isXmlChar(value)) return {at - 1, rest.substr(0, semicolon + 1)};
    }
    return {std::string_view::npos, {}};
}

}  // namespace

// ---- Document ------------------------------------------------------------------------------

Document::Document(std::string_view text, std::string file, const DocumentKind& kind)
    : text_(text), file_(std::move(file)) {
    const std::string expected = std::string("<") + kind.root + ">";
    // Not UTF-16 or binary: pugixml would stop at the first NUL byte, and read the rest as
    // if it were not there.
    io::checkText(text, file_, io::InputKind{kind.description, 0});
    if (text::trim(text).empty())
        throw Error("empty file, expected a " + expected + " document", {.file = file_, .line = 1});
    if (const auto [at, reference] = badCharacterReference(text); at != std::string_view::npos)
        throw Error(
            "a character reference to a character XML does not allow (a NUL or control "
            "character)",
            {.file = file_,
             .line = lineAt(std::ptrdiff_t(at)),
             .value = std::string(reference),
             .validRange = "&#9;, &#10;, &#13; or &#32; and above"});
    // As a fragment, so that text outside the root element is kept (and refused below)
    // instead of dropped without a word.
    const pugi::xml_parse_result parsed = doc_.load_buffer(
        text.data(), text.size(), pugi::parse_default | pugi::parse_fragment, pugi::encoding_utf8);
    if (!parsed) {
        if (parsed.status == pugi::status_no_document_element)
            throw Error("not an XML file: no root element, expected " + expected,
                        {.file = file_, .line = 1});
        std::string message = std::string("malformed XML: ") + parsed.description();
        const std::size_t end = text.find_last_not_of(" \t\r\n");
        if (parsed.offset >= std::ptrdiff_t(end)) message += " (the file ends too early)";
        throw Error(message, {.file = file_, .line = lineAt(parsed.offset)});
    }
    if (!doc_.find_child([](pugi::xml_node n) { return isElement(n); }))
        throw Error("not an XML file: no root element, expected " + expected,
                    {.file = file_, .line = 1});
    for (pugi::xml_node n : doc_.children()) {
        if (isText(n) && !text::trim(n.value()).empty()) {
            // At the line where the text itself starts, after the line break before it.
            const std::string_view value = n.value();
            const std::size_t skip = value.find_first_not_of(" \t\r\n");
            throw Error("text outside the root element",
                        {.file = file_,
                         .line = lineAt(n.offset_debug() + std::ptrdiff_t(skip)),
                         .value = excerpt(value)});
        }
        if (!isElement(n)) continue;
        if (root_)
            fail(n, "",
                 std::string("a second root element <") + n.name() + "> after <" + root_.name() +
                     ">");
        root_ = n;
    }
    const std::string_view name = root_.name();
    if (name != kind.root && !(kind.otherRoot && name == kind.otherRoot))
        fail(root_, "",
             std::string("not a ") + kind.description + ": root element <" + root_.name() + ">", "",
             expected);
}

int Document::lineAt(std::ptrdiff_t offset) const {
    if (offset < 0) return 1;
    if (lineStarts_.empty()) {
        lineStarts_.push_back(0);
        for (std::size_t i = 0; i < text_.size(); ++i)
            if (text_[i] == '\n') lineStarts_.push_back(std::ptrdiff_t(i + 1));
    }
    const auto it = std::upper_bound(lineStarts_.begin(), lineStarts_.end(), offset);
    return int(it - lineStarts_.begin());
}

void Document::fail(pugi::xml_node n, const std::string& path, const std::string& message,
                    std::string value, std::string validRange) const {
    throw Error(message, {.file = file_,
                          .line = line(n),
                          .parameter = path,
                          .value = std::move(value),
                          .validRange = std::move(validRange)});
}

void Document::relocate(const Error& e, pugi::xml_node n, const std::string& path) const {
    ErrorContext c = e.context();
    c.file = file_;
    c.line = line(n);
    if (!path.empty()) c.parameter = path;
    throw Error(e.message(), c);
}

// ---- Element -------------------------------------------------------------------------------

std::string Element::path() const {
    if (!parent_) return path_;
    std::string out = parent_->pathTo(part_);
    if (index_ >= 0) out.append("[").append(std::to_string(index_)).append("]");
    return out;
}

std::string Element::pathTo(std::string_view part) const {
    std::string out = path();
    if (!out.empty()) out += '.';
    out += part;
    return out;
}

void Element::fail(const std::string& message, std::string value, std::string validRange) const {
    doc_->fail(node_, path(), message, std::move(value), std::move(validRange));
}

void Element::failAt(std::string_view part, const std::string& message, std::string value,
                     std::string validRange) const {
    doc_->fail(node_, pathTo(part), message, std::move(value), std::move(validRange));
}

void Element::checkAttributeNames(const std::vector<std::string>& allowed) const {
    std::set<std::string_view> seen;
    for (pugi::xml_attribute a : node_.attributes()) {
        const std::string name = a.name();
        if (std::find(allowed.begin(), allowed.end(), name) == allowed.end())
            failAt(name,
                   text::unknownMessage("attribute", name, allowed,
                                        std::string(" of <") + node_.name() + ">"),
                   a.value(), allowed.empty() ? "no attributes" : text::oneOf(allowed));
        if (!seen.insert(a.name()).second)
            failAt(name, "duplicate attribute '" + name + "'", a.value());
    }
}

std::string Element::attribute(const char* name) const {
    return std::string(text::trim(node_.attribute(name).value()));
}

std::string Element::requiredAttribute(const char* name, std::string validRange) const {
    const pugi::xml_attribute a = node_.attribute(name);
    if (!a)
        failAt(name,
               std::string("missing required attribute '") + name + "' of <" + node_.name() + ">",
               "", std::move(validRange));
    return std::string(text::trim(a.value()));
}

std::string Element::text() const {
    checkAttributes({});
    return content();
}

std::string Element::content() const {
    const pugi::xml_node first = node_.first_child();
    if (first && isText(first) && !first.next_sibling())
        return std::string(text::trim(first.value()));
    std::string out;
    for (pugi::xml_node c : node_.children()) {
        if (isText(c))
            out += c.value();
        else if (isElement(c))
            doc_->fail(c, path(),
                       std::string("<") + node_.name() + "> holds a value, not elements (found <" +
                           c.name() + ">)");
    }
    return std::string(text::trim(out));
}

// ---- Children ------------------------------------------------------------------------------

Children::Children(const Element& parent) : parent_(parent) {
    for (pugi::xml_node c : parent.node().children()) {
        if (isElement(c))
            kids_.push_back({c, false});
        else if (isText(c) && !text::trim(c.value()).empty())
            parent.document().fail(
                c, parent.path(),
                std::string("unexpected text inside <") + parent.name() + ">, expected elements",
                excerpt(c.value()));
    }
}

pugi::xml_node Children::take(std::string_view name) {
    names_.push_back({name, false});
    // Children usually come in the order they are taken: search on from the last one.
    const std::size_t n = kids_.size();
    for (std::size_t j = 0; j < n; ++j) {
        Kid& k = kids_[(cursor_ + j) % n];
        if (!k.taken && name == k.node.name()) {
            k.taken = true;
            cursor_ = (cursor_ + j + 1) % n;
            return k.node;
        }
    }
    return {};
}

std::vector<pugi::xml_node> Children::takeAll(std::string_view name) {
    names_.push_back({name, true});
    std::vector<pugi::xml_node> out;
    for (Kid& k : kids_)
        if (name == k.node.name()) {
            k.taken = true;
            out.push_back(k.node);
        }
    return out;
}

void Children::allow(std::string_view name, bool repeatable) {
    names_.push_back({name, repeatable});
}

std::vector<pugi::xml_node> Children::elements() const {
    std::vector<pugi::xml_node> out;
    out.reserve(kids_.size());
    for (const Kid& k : kids_) out.push_back(k.node);
    return out;
}

const Children::Name* Children::declared(std::string_view name) const {
    for (const Name& n : names_)
        if (n.name == name) return &n;
    return nullptr;
}

void Children::finish() const {
    // A child taken is expected; every problem is among those that were not.
    for (const Kid& k : kids_) {
        if (k.taken) continue;
        const std::string_view name = k.node.name();
        if (const Name* n = declared(name)) {
            if (n->repeatable) continue;
            // A second one: reported where it stands, with the line of the one that was
            // read (the first in file order when none was taken).
            const Kid* first = nullptr;
            for (const Kid& o : kids_)
                if (name == o.node.name() && (o.taken || !first)) {
                    first = &o;
                    if (o.taken) break;
                }
            if (first != &k)
                parent_.document().fail(
                    k.node, parent_.pathTo(name),
                    "duplicate element <" + std::string(name) + "> (first at line " +
                        std::to_string(parent_.document().line(first->node)) + ")");
            continue;
        }
        std::vector<std::string> valid;
        for (const Name& d : names_)
            if (std::find(valid.begin(), valid.end(), d.name) == valid.end())
                valid.emplace_back(d.name);
        const std::string near = text::closestMatch(name, valid);
        parent_.document().fail(k.node, parent_.pathTo(name),
                                "unknown element <" + std::string(name) + "> in <" +
                                    parent_.name() + ">" +
                                    (near.empty() ? "" : ", did you mean <" + near + ">?"),
                                "", text::oneOf(valid));
    }
}

}  // namespace plantarch::xml
