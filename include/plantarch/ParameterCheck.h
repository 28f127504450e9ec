#pragma once
// Checks one field of the parameter table on its own, with the message validate() gives for
// it, for front ends that set parameters one at a time (the Python module).

#include <map>
#include <string>
#include <vector>

#include "plantarch/ParameterTable.h"

namespace plantarch::params {

/// Throws plantarch::Error when `value` is outside what field `f` accepts; the parameter
/// path in the message is `path` + "." + f.name (`path` may be empty).
void checkField(const FieldInfo& f, const std::string& path, const RandomFloat& value);
void checkField(const FieldInfo& f, const std::string& path, const RandomInt& value);
void checkField(const FieldInfo& f, const std::string& path, const float& value);
void checkField(const FieldInfo& f, const std::string& path, const unsigned& value);
void checkField(const FieldInfo& f, const std::string& path, const int& value);
void checkField(const FieldInfo& f, const std::string& path, const bool& value);
void checkField(const FieldInfo& f, const std::string& path, const vec3& value);
void checkField(const FieldInfo& f, const std::string& path, const std::string& value);
void checkField(const FieldInfo& f, const std::string& path, const LeafShape& value);
void checkField(const FieldInfo& f, const std::string& path, const FlowerArrangement& value);
void checkField(const FieldInfo& f, const std::string& path, const NodeRuleTime& value);
void checkField(const FieldInfo& f, const std::string& path,
                const LeafInclinationDistribution& value);
void checkField(const FieldInfo& f, const std::string& path, const LeafAzimuthDistribution& value);
void checkField(const FieldInfo& f, const std::string& path,
                const std::map<int, std::string>& value);
void checkField(const FieldInfo& f, const std::string& path,
                const std::map<std::string, float>& value);
void checkField(const FieldInfo& f, const std::string& path, const Formula& value);
/// A list of node rules: every field of every rule, and each rule as a whole.
void checkField(const FieldInfo& f, const std::string& path, const std::vector<NodeRule>& value);

}  // namespace plantarch::params
