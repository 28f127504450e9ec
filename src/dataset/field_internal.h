#pragma once
// What the field's files (src/dataset/field_*.cpp) share: the CSV rows of plants and the
// checks of the output folder.

#include <string>

#include "plantarch/Field.h"

namespace plantarch::field {

/// The project file's name for errors ("project" when it was not read from a file).
std::string projectFile(const Project& project);
/// A CSV field: as it is, or quoted (its quotes doubled) when it holds a comma, quote or newline.
std::string csvText(const std::string& s);
/// A plant's row of plants.csv (fieldPlantsHeader()'s columns), without its newline.
std::string rowText(const FieldPlantRow& row);
/// Throws plantarch::Error naming `outDir` when it is empty, or exists and is not a folder.
void requireFolder(const std::string& outDir);
/// requireFolder, then makes `outDir` and its parents if missing; an Error naming it when that
/// fails.
void makeFolder(const std::string& outDir);

}  // namespace plantarch::field
