#include "model/function_registry.h"

#include "plantarch/Error.h"

namespace plantarch {

const PhytomerCreationFunction& FunctionRegistry::creation(const std::string& name,
                                                           const std::string& shootType) const {
    auto fn = creationFunctions.find(name);
    if (fn == creationFunctions.end())
        throw Error(
            "unknown phytomer creation function",
            {.parameter = shootType + ".phytomer.phytomer_creation_function", .value = name});
    return fn->second;
}

const PhytomerCallbackFunction& FunctionRegistry::callback(const std::string& name,
                                                           const std::string& shootType) const {
    auto fn = callbackFunctions.find(name);
    if (fn == callbackFunctions.end())
        throw Error(
            "unknown phytomer callback function",
            {.parameter = shootType + ".phytomer.phytomer_callback_function", .value = name});
    return fn->second;
}

}  // namespace plantarch
