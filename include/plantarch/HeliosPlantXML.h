#pragma once
// Plant structure files with the root element <helios>, in the layout the reference plant
// architecture system reads and writes (docs/plant-xml.md, "Files with the root <helios>").
// Reading them needs nothing new: PlantArchitecture::readPlantStructureXML reads either root.
// plantarch's own format (writePlantStructureXML) stays the exact, self-contained one; a
// <helios> file holds only what that layout has (no species parameters, no random state).

#include <string>
#include <vector>

namespace plantarch {

class PlantArchitecture;

/// The plants as a <helios> document: current sizes, angles in degrees, leaflets left to
/// right, floral buds with their peduncle and flowers or fruit. Removed shoots and shed
/// leaves are left out.
std::string getHeliosPlantStructureXML(const PlantArchitecture& arch,
                                       const std::vector<unsigned>& plantIDs);
/// The same, written to `filename` (through a temporary file: never half a file).
void writeHeliosPlantStructureXML(const PlantArchitecture& arch,
                                  const std::vector<unsigned>& plantIDs,
                                  const std::string& filename);

}  // namespace plantarch
