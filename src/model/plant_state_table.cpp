// What the plant state table (plantarch/PlantStateTable.h) needs beyond its declarations.

#include "core/value_text.h"
#include "plantarch/PlantStateTable.h"

namespace plantarch::state {

std::string rangeText(const FieldInfo& f) {
    const bool openMin = f.check == Check::ExclusiveMin || f.check == Check::Exclusive;
    const bool openMax = f.check == Check::Exclusive;
    if (!openMin) return text::formatDouble(f.min) + " to " + text::formatDouble(f.max);
    return "> " + text::formatDouble(f.min) + " and " + (openMax ? "< " : "<= ") +
           text::formatDouble(f.max);
}

}  // namespace plantarch::state
