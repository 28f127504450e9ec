#pragma once
// Writing plant structure files with options (docs/plant-xml.md). The methods
// PlantArchitecture::writePlantStructureXML / getPlantStructureXML write the defaults.

#include <string>
#include <vector>

namespace plantarch {

class PlantArchitecture;

/// How a plant structure file is written.
struct PlantStructureWriteOptions {
    /// Also write each organ's Context object IDs, so that reading the file into a Context
    /// where they are free gives the objects the same IDs (exports then list the same
    /// objects under the same names, in the same order). Off by default: the IDs record
    /// when the plant's geometry was made, so files of one plant made by different histories
    /// (built at 50 days, or built at 30 and grown 20) would differ.
    bool objectIDs = false;
};

std::string getPlantStructureXML(const PlantArchitecture& arch,
                                 const std::vector<unsigned>& plantIDs,
                                 const PlantStructureWriteOptions& options);
/// Writes through a temporary file: never half a file.
void writePlantStructureXML(const PlantArchitecture& arch, const std::vector<unsigned>& plantIDs,
                            const std::string& filename, const PlantStructureWriteOptions& options);

}  // namespace plantarch
