#pragma once
// Writing plant structure files with options (docs/plant-xml.md). The methods
// PlantArchitecture::writePlantStructureXML / getPlantStructureXML write the defaults.

#include <string>
#include <vector>

namespace plantarch {

class Context;
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

// ---- object table -----------------------------------------------------------------------
// The link between a mesh and the plant structure file (docs/formats.md, "Object table"):
// a JSON file listing each object an export writes (its object ID, as in the PLY object_id,
// the OBJ names and labels, the glTF and USD labels) with its labels and, for the organs of
// the plants given, the place of the organ in the plant structure file (shoot, phytomer,
// petiole, leaf, floral bud and flower indices, and an XPath to the element that holds the
// object's ID in a file written with object IDs). The command line writes it next to each
// mesh output with --object-ids (`field.obj` -> `field.objects.json`).

/// Options of the object table.
struct ObjectTableOptions {
    /// Also list hidden objects (as the exporters' includeHidden).
    bool includeHidden = false;
};

/// The table of the objects of `arch`'s Context; organs of `plantIDs` get their place.
std::string getObjectTableJSON(const PlantArchitecture& arch, const std::vector<unsigned>& plantIDs,
                               const ObjectTableOptions& options = {});
/// The table of a Context's objects with their labels only (no plant structure), for example
/// of a Context read from a labelled OBJ file.
std::string getObjectTableJSON(const Context& context, const ObjectTableOptions& options = {});
/// Write the tables above through a temporary file: never half a file.
void writeObjectTableJSON(const PlantArchitecture& arch, const std::vector<unsigned>& plantIDs,
                          const std::string& filename, const ObjectTableOptions& options = {});
void writeObjectTableJSON(const Context& context, const std::string& filename,
                          const ObjectTableOptions& options = {});

}  // namespace plantarch
