// Parameter table fields read from XML elements (parameter_reader.h).

#include "library/parameter_reader.h"

#include <type_traits>

#include "core/value_text.h"
#include "library/species_xml.h"
#include "plantarch/Error.h"

namespace plantarch::species_xml {

namespace {

std::string copyText(std::string_view s) {
    return std::string(s);
}

std::string nameKey(std::string_view s) {
    if (!text::isLabel(s))
        throw Error("expected a name of letters, digits, '_' or '-'",
                    {.value = std::string(s), .validRange = "a non-empty name"});
    return std::string(s);
}

// <field><entry key="k" [value="v"]>[v]</entry>...</field>
template <class Key, class Value, class ParseKey, class ParseValue>
void readMap(const xml::Element& e, const params::FieldInfo& f, std::map<Key, Value>& m,
             EntryLines* lines, ParseKey&& parseKey, ParseValue&& parseValue) {
    const params::MapEntries& spell = f.entries;
    e.checkAttributes({});
    xml::Children children(e);
    const std::vector<pugi::xml_node> entries = children.takeAll(spell.element);
    children.finish();
    const std::string path = e.path();
    m.clear();
    for (pugi::xml_node c : entries) {
        const xml::Element item(e.document(), c, path);
        if (spell.value)
            item.checkAttributes({spell.key, spell.value});
        else
            item.checkAttributes({spell.key});
        const std::string keyText = item.requiredAttribute(spell.key);
        const xml::Element entry(e.document(), c, path + "." + keyText);
        const Key key = entry.convert(keyText, parseKey);
        std::string valueText;
        if (spell.value) {
            if (c.first_child())
                entry.fail(std::string("<") + spell.element + "> takes no content");
            valueText = entry.requiredAttribute(spell.value);
        } else {
            valueText = entry.content();
        }
        const Value value = entry.convert(valueText, parseValue);
        if (!m.emplace(key, value).second)
            entry.fail("duplicate " + std::string(spell.key) + " '" + keyText + "' in <" + f.name +
                       ">");
        if (lines) (*lines)[entry.path()] = entry.line();
    }
}

}  // namespace

void readParameter(const xml::Element& e, const params::FieldInfo&, std::string& m, EntryLines*) {
    m = e.text();
}

void readParameter(const xml::Element& e, const params::FieldInfo&, Formula& m, EntryLines*) {
    const std::string s = e.text();
    m = s.empty() ? Formula() : e.convert(s, NodeRule::formula);
}

void readParameter(const xml::Element& e, const params::FieldInfo& f, std::map<int, std::string>& m,
                   EntryLines* lines) {
    readMap(e, f, m, lines, text::parseInt, copyText);
}

void readParameter(const xml::Element& e, const params::FieldInfo& f,
                   std::map<std::string, float>& m, EntryLines* lines) {
    readMap(e, f, m, lines, nameKey, text::parseFloat);
}

}  // namespace plantarch::species_xml
