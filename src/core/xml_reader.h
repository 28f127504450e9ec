#pragma once
// Strict reading of plantarch's XML files (species files, plant structure files) on pugixml.
// This is the one place that decides how a document, an element, its attributes and its
// children are checked, and how an error names the file, the line and the parameter path:
//
//   Document  parses the text, finds the root element, maps nodes to lines.
//   Element   one element and the parameter path that errors about it name; its attributes
//             (unknown ones are errors, with the closest valid name) and the value it holds.
//   Children  the child elements of an element, taken by name; finish() reports any child
//             that was not expected (unknown, with the closest valid name and the list of
//             valid ones) or a second one of a name expected once (with the line of the one
//             that was read).
//
// Every check throws plantarch::Error: "file:line: path = value: message (valid: range)".

#include <cstddef>
#include <initializer_list>
#include <pugixml.hpp>
#include <string>
#include <string_view>
#include <vector>

#include "plantarch/Error.h"

namespace plantarch::xml {

inline bool isElement(pugi::xml_node n) {
    return n.type() == pugi::node_element;
}
inline bool isText(pugi::xml_node n) {
    return n.type() == pugi::node_pcdata || n.type() == pugi::node_cdata;
}

/// What a document must be: its name in messages ("species file") and its root element.
struct DocumentKind {
    const char* description;
    const char* root;
    const char* otherRoot = nullptr;  ///< a second accepted root element, or none
};

/// A parsed document. `text` must outlive it. Not thread-safe (line starts are found on
/// first use).
class Document {
public:
    /// Throws for an empty text, malformed XML (with the line pugixml stopped at), no root
    /// element, a second root element, text outside the root, or a root of another name.
    Document(std::string_view text, std::string file, const DocumentKind& kind);
    Document(const Document&) = delete;
    Document& operator=(const Document&) = delete;

    pugi::xml_node root() const { return root_; }
    const std::string& file() const { return file_; }

    /// Line (from 1) of a byte offset into the text.
    int lineAt(std::ptrdiff_t offset) const;
    int line(pugi::xml_node n) const { return lineAt(n.offset_debug()); }

    /// An error at node `n` about the value at `path`.
    [[noreturn]] void fail(pugi::xml_node n, const std::string& path, const std::string& message,
                           std::string value = "", std::string validRange = "") const;
    /// `e` (raised while converting or checking a value) located at node `n` and, unless
    /// `path` is empty, the parameter path.
    [[noreturn]] void relocate(const Error& e, pugi::xml_node n, const std::string& path) const;

private:
    std::string_view text_;
    std::string file_;
    pugi::xml_document doc_;
    pugi::xml_node root_;
    mutable std::vector<std::ptrdiff_t> lineStarts_;
};

/// One element being read, and the parameter path of what it holds. The path of a child
/// element is built only when an error needs it, from its parent's and its own part.
class Element {
public:
    /// An element with its whole path ("" for the document's root).
    Element(const Document& doc, pugi::xml_node node, std::string path)
        : doc_(&doc), node_(node), path_(std::move(path)) {}
    /// A child of `parent`, at path "parent.part" or, with `index` >= 0, "parent.part[index]".
    /// `parent` and the text `part` views must outlive this Element.
    Element(const Element& parent, pugi::xml_node node, std::string_view part, int index = -1)
        : doc_(parent.doc_), node_(node), parent_(&parent), part_(part), index_(index) {}
    /// The child `node` of this element, its path part the element's name.
    Element child(pugi::xml_node node) const { return Element(*this, node, node.name()); }

    const Document& document() const { return *doc_; }
    pugi::xml_node node() const { return node_; }
    const char* name() const { return node_.name(); }
    int line() const { return doc_->line(node_); }
    std::string path() const;
    /// "path.part" ("part" when the path is empty).
    std::string pathTo(std::string_view part) const;

    /// An error at this element about its path, or about "path.part".
    [[noreturn]] void fail(const std::string& message, std::string value = "",
                           std::string validRange = "") const;
    [[noreturn]] void failAt(std::string_view part, const std::string& message,
                             std::string value = "", std::string validRange = "") const;

    // ---- attributes ----------------------------------------------------------------------

    /// Every attribute must be one of `allowed`, and none may appear twice.
    template <class Names = std::initializer_list<std::string_view>>
    void checkAttributes(const Names& allowed) const {
        if (!node_.first_attribute()) return;
        checkAttributeNames(std::vector<std::string>(allowed.begin(), allowed.end()));
    }
    bool hasAttribute(const char* name) const { return bool(node_.attribute(name)); }
    /// The attribute's value without surrounding white space; "" when it is absent.
    std::string attribute(const char* name) const;
    /// As attribute(), but its absence is an error ("missing required attribute").
    std::string requiredAttribute(const char* name, std::string validRange = "") const;

    // ---- content -------------------------------------------------------------------------

    /// The value this element holds: its text without surrounding white space. It may have
    /// no attributes and no child elements.
    std::string text() const;
    /// As text(), leaving the attributes to the caller.
    std::string content() const;

    /// `parse(text)`; an Error it raises is located at this element and its path.
    template <class Parse>
    auto convert(std::string_view text, Parse&& parse) const -> decltype(parse(text)) {
        try {
            return parse(text);
        } catch (const Error& e) {
            doc_->relocate(e, node_, path());
        }
    }
    /// The value this element holds, converted by `parse`.
    template <class Parse>
    auto parse(Parse&& p) const {
        return convert(text(), p);
    }
    /// A required attribute converted by `parse`; errors name "path.name".
    template <class Parse>
    auto parseAttribute(const char* name, Parse&& parse) const {
        return Element(*this, node_, name).convert(requiredAttribute(name), parse);
    }

private:
    void checkAttributeNames(const std::vector<std::string>& allowed) const;

    const Document* doc_;
    pugi::xml_node node_;
    const Element* parent_ = nullptr;  ///< null: path_ is the whole path
    std::string_view part_;
    int index_ = -1;
    std::string path_;
};

/// The child elements of an element. Each is taken by name, or allowed without being taken;
/// finish() then rejects the others. Text other than white space between them is an error.
/// The names given must outlive the Children.
class Children {
public:
    explicit Children(const Element& parent);

    /// A child called `name` not taken yet, or a null node; `name` is allowed once. The
    /// search starts after the last child taken and wraps around (children usually come in
    /// the order they are taken in).
    pugi::xml_node take(std::string_view name);
    /// Every child called `name`, in file order; `name` is allowed any number of times.
    std::vector<pugi::xml_node> takeAll(std::string_view name);
    /// Allows children called `name` without taking them (read in file order through
    /// elements()).
    void allow(std::string_view name, bool repeatable);
    /// Every child element, in file order.
    std::vector<pugi::xml_node> elements() const;

    /// Throws for the first child that was neither taken nor allowed ("unknown element"),
    /// or is a second one of a name allowed once ("duplicate element", reported at the one
    /// that was not read).
    void finish() const;

private:
    struct Kid {
        pugi::xml_node node;
        bool taken;
    };
    struct Name {
        std::string_view name;
        bool repeatable;
    };
    const Name* declared(std::string_view name) const;

    const Element& parent_;
    std::vector<Kid> kids_;
    std::vector<Name> names_;
    std::size_t cursor_ = 0;
};

}  // namespace plantarch::xml
