#include "model/function_registry.h"

#include "plantarch/Error.h"

namespace plantarch {

namespace {

// The function registered as `name` in `registry`, or an error naming the shoot type's field.
template <class Map>
const typename Map::mapped_type& lookUp(const Map& registry, const std::string& name,
                                        const std::string& shootType, const char* kind) {
    auto fn = registry.find(name);
    if (fn == registry.end())
        throw Error(
            std::string("unknown phytomer ") + kind + " function",
            {.parameter = shootType + ".phytomer.phytomer_" + kind + "_function", .value = name});
    return fn->second;
}

}  // namespace

const PhytomerCreationFunction& FunctionRegistry::creation(const std::string& name,
                                                           const std::string& shootType) const {
    return lookUp(creationFunctions, name, shootType, "creation");
}

const PhytomerCallbackFunction& FunctionRegistry::callback(const std::string& name,
                                                           const std::string& shootType) const {
    return lookUp(callbackFunctions, name, shootType, "callback");
}

}  // namespace plantarch
