#pragma once
// Species files: strict reading, complete writing, the species library on disk, and the
// values a species gives a plant (build parameters, attraction points, trellis); building a
// plant from a species is in plantarch/SpeciesBuild.h. The format is described in
// docs/species-format.md.
//
// Reading is strict: an unknown or misspelt element or attribute, a missing required value,
// a value of the wrong type, a value outside its declared range, a duplicate element, child
// shoot probabilities that do not sum to 1, or a reference to an undefined shoot type or
// build step is a plantarch::Error whose one-line message names the file, the line, the
// parameter path (e.g. `trifoliate.phytomer.petiole.pitch`), the value and what is valid.

#include <iosfwd>
#include <map>
#include <string>
#include <vector>

#include "plantarch/Collision.h"
#include "plantarch/Error.h"
#include "plantarch/Species.h"

namespace plantarch {

// ---- reading and writing ---------------------------------------------------------------

/// Reads a species file. Throws plantarch::Error (see above); a file that cannot be opened
/// is an Error naming it.
SpeciesModel readSpeciesFile(const std::string& path);
/// Reads a species from XML text; `nameForErrors` stands for the file in error messages and
/// becomes the model's sourceFile.
SpeciesModel readSpeciesString(const std::string& xml, const std::string& nameForErrors);
/// Every error of a species file rather than the first: a bad or out-of-range value, an
/// unknown element, each one line with its file and line (sorted by line); an error after
/// which the file cannot be read further (malformed XML) ends the list. Empty: the file
/// reads (readSpeciesFile then succeeds).
std::vector<Error> checkSpeciesFile(const std::string& path);
std::vector<Error> checkSpeciesString(const std::string& xml, const std::string& nameForErrors);

struct SpeciesWriteOptions {
    /// Put each field's unit, valid range and description in an XML comment after it.
    bool comments = true;
};

/// Writes every field of every shoot type (not only those that differ from the defaults),
/// numbers in their shortest round-trip form, so the text reads back to an identical model.
void writeSpecies(const SpeciesModel& model, std::ostream& out,
                  const SpeciesWriteOptions& options = {});
std::string writeSpeciesString(const SpeciesModel& model, const SpeciesWriteOptions& options = {});
/// Writes to `path` through a temporary file renamed into place (never half a file).
void writeSpeciesFile(const SpeciesModel& model, const std::string& path,
                      const SpeciesWriteOptions& options = {});

/// `base` with `changes` applied, read back through the species reader so that every value
/// gets the checks, and the messages, a species file gets. A change's key is
///   shoot_types.LABEL.PATH   a field of a shoot type
///   ("shoot_types.trifoliate.phytomer.leaf.pitch") phenology.PATH           a field of the
///   phenology ("phenology.max_age") build_parameters.NAME    the default of a build parameter
/// and its value is the text a species file holds there ("20", "uniform(10, 30)", "0.2 0.3
/// 0.1", "true"). Fields that hold lists or maps (child shoot types, node rules...) are not
/// edited this way. `name` (when not empty) becomes the species' name. Throws
/// plantarch::Error naming the key (and the nearest valid one for an unknown key) or, for a
/// bad value, the reader's own message with the key's parameter path (no file or line: the
/// text read is made here).
SpeciesModel editSpecies(const SpeciesModel& base,
                         const std::map<std::string, std::string>& changes,
                         const std::string& name = "");

// ---- the species library ---------------------------------------------------------------

/// The folder holding the library's species files, the first that exists of:
///  1. the environment variable PLANTARCH_SPECIES_DIR (used as given, even if missing);
///  2. when plantarch runs from a shared object (a shared library, the Python extension):
///     `species/` beside it (a wheel), then `share/plantarch/species` in each of the five
///     folders above it (an installed prefix);
///  3. `<dir of the running executable>/../share/plantarch/species` (an installed plantarch);
///  4. the `species/` folder of the source tree this library was compiled from;
///  5. `<dir of the running executable>/../species` and `<dir of the executable>/species`;
///  6. `species/` in the current directory.
/// Throws plantarch::Error listing the places searched when none exists.
std::string speciesLibraryDirectory();
/// Names of the library's species (the *.xml files of speciesLibraryDirectory() without the
/// extension), sorted.
std::vector<std::string> listSpecies();
/// A species by library name ("bean") or by path: an argument that contains '/' or ends in
/// ".xml" is a path. An unknown name is an Error listing the available names.
SpeciesModel loadSpecies(const std::string& nameOrPath);

// ---- files a species names ---------------------------------------------------------------

/// A file named in the species (a texture, an OBJ model) as it is opened: a relative path is
/// relative to the folder of the species file (the model's sourceFile); an absolute one, or
/// any path of a species that has no file, as written.
std::string speciesFilePath(const SpeciesModel& species, const std::string& file);

/// The species' shoot types as a PlantArchitecture uses them: every file they name (leaf
/// textures and OBJ models, stem textures, flower and fruit .obj models) resolved by
/// speciesFilePath. The model itself keeps the paths as written, so it writes back unchanged.
std::map<std::string, ShootParameters> speciesShootTypes(const SpeciesModel& species);

/// Every error of the files the species names (empty: all good), one per file, each naming
/// the species file, the line, the parameter and the file: a texture must be a PNG or JPEG
/// image (decoded, at most 16384 pixels a side, at most 256 MiB), an OBJ model a text file
/// (at most 4 GiB); either a regular file (no directory, FIFO or device).
/// PlantArchitecture::loadPlantModelFromLibrary and `plantarch validate` check them.
std::vector<Error> checkSpeciesFiles(const SpeciesModel& species);

// ---- a plant's values -------------------------------------------------------------

/// The species' build parameters with `overrides` applied: every name must be a build
/// parameter of the species (else an Error listing the valid names) and every value within
/// its declared range (else an Error giving the range).
std::map<std::string, float> resolveBuildParameters(
    const SpeciesModel& species, const std::map<std::string, float>& overrides = {});

/// The attraction points of a plant of the species at `base` (its <attraction_points>
/// evaluated with the build parameters, wires sampled at their spacing). Random expressions
/// draw from Rng::forPlant(seed, 3 * 2^61 + plantID), plantID being the plant's stream number
/// (PlantArchitecture::plantStream). Errors name the file and line. The
/// species must declare attraction points.
AttractionPoints speciesAttractionPoints(const SpeciesModel& species, std::uint64_t seed,
                                         unsigned plantID, const vec3& base,
                                         const std::map<std::string, float>& overrides = {});

/// One post or wire of a species' trellis, meshed (a closed tube) in world coordinates.
struct TrellisPart {
    enum class Kind { Post, Wire };
    Kind kind = Kind::Post;
    Mesh mesh;
};

/// The trellis of a plant of the species at `base` (its <trellis> evaluated with the build
/// parameters). Random expressions draw from Rng::forPlant(seed, 5 * 2^60 + plantID), plantID
/// being the plant's stream number (PlantArchitecture::plantStream). Errors
/// name the file, line and parameter. The species must declare a trellis.
std::vector<TrellisPart> speciesTrellis(const SpeciesModel& species, std::uint64_t seed,
                                        unsigned plantID, const vec3& base,
                                        const std::map<std::string, float>& overrides = {});

}  // namespace plantarch
