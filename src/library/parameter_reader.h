#pragma once
// One field of the parameter table (plantarch/ParameterTable.h) read from the element that holds
// it. Species files and plant structure files spell parameters alike: a value as the
// element's text (the forms of core/value_text.h), an enum-like field by the name of one of
// its declared choices, a formula as its text, a map as one child element per entry (spelled
// as the field declares). Errors name the element's line and path.

#include <map>
#include <string>

#include "core/value_text.h"
#include "core/xml_reader.h"
#include "plantarch/ParameterTable.h"

namespace plantarch::species_xml {

/// Lines of the map entries read, by parameter path ("main.child_shoot_types.lateral"), for
/// errors found after reading. Optional in every call below.
using EntryLines = std::map<std::string, int>;

/// A number, flag, vector or distribution: the element's text.
template <class T>
void readParameter(const xml::Element& e, const params::FieldInfo&, T& m, EntryLines* = nullptr) {
    m = e.parse(text::parse<T>);
}
/// Text.
void readParameter(const xml::Element& e, const params::FieldInfo& f, std::string& m,
                   EntryLines* lines = nullptr);
/// A node rule formula (empty text: none).
void readParameter(const xml::Element& e, const params::FieldInfo& f, Formula& m,
                   EntryLines* lines = nullptr);
/// An enum-like field: the name of one of its declared choices.
template <params::ChoiceType E>
void readParameter(const xml::Element& e, const params::FieldInfo&, E& m, EntryLines* = nullptr) {
    static const std::vector<std::string> names = params::choiceNames<E>();
    m = params::kChoices<E>[e.parse([](std::string_view s) { return text::parseChoice(s, names); })]
            .value;
}
/// Maps: one child element per entry. Keys of name -> number maps are names (letters,
/// digits, '_' and '-').
void readParameter(const xml::Element& e, const params::FieldInfo& f, std::map<int, std::string>& m,
                   EntryLines* lines = nullptr);
void readParameter(const xml::Element& e, const params::FieldInfo& f,
                   std::map<std::string, float>& m, EntryLines* lines = nullptr);

}  // namespace plantarch::species_xml
