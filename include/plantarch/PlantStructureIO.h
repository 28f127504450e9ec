#pragma once
// Options of the plant structure file and plant string methods of PlantArchitecture
// (writePlantStructureXML, readPlantStructureXML, getPlantString, generatePlantFromString).
// The formats are described in docs/plant-xml.md.

#include <functional>
#include <string>

namespace plantarch {

/// How plant structure files and plant strings are read.
struct PlantStructureReadOptions {
    /// Receives one line per plant whose input left values out, listing them and the
    /// defaults used (a file in the specification's listing form, an older format). Empty:
    /// warnings are dropped.
    std::function<void(const std::string& warning)> onWarning;
    /// Stands for the file in messages when reading from a string.
    std::string nameForErrors = "plant structure string";
};

/// How a plant string is written.
struct PlantStringOptions {
    /// Significant digits of every number, 1 to 6 (reading the string back and writing it
    /// again then gives the same string); 0 writes every value exactly (shortest text that
    /// reads back to the same float).
    int significantDigits = 4;
};

}  // namespace plantarch
