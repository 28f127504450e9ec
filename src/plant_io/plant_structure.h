#pragma once
// Plant structure files and plant strings (docs/plant-xml.md), the internal side: the
// readers produce PlantInstances that PlantArchitecture then adopts, the writers take them.
//
// Both readers note which values their input left out (a Presence), and completePlant()
// fills those the way a plant built by plantarch would have them (species parameters from
// the PlantArchitecture, realized values from the parameters' means, internode frames from
// the listed angles), so a file in the specification's listing form, or a plant string,
// becomes a whole plant that can be drawn and grown. checkPlant() then verifies that the
// plant is consistent (shoot references, node indices, shoot types), so what reaches growth
// and tessellation can never index out of range.

#include <cstdint>
#include <map>
#include <string>
#include <type_traits>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include "plantarch/PlantState.h"

namespace pugi {
class xml_node;
}

namespace plantarch::xml {
class Document;
}

namespace plantarch::plant_io {

inline constexpr const char* kRoot = "plantarch_plants";
/// Root element of the specification's sample listing, read as the listing form.
inline constexpr const char* kListingRoot = "helios";
inline constexpr int kFormatVersion = 1;

/// Which members of a plant being read were given by the input. Addresses of members
/// stay valid while a plant is read and completed (every vector is sized once, before its
/// items are read).
class Presence {
public:
    /// Records members that were absent (XML reader: most members are present) ...
    static Presence recordingMissing() { return Presence(false); }
    /// ... or members that were given (string reader: most members are absent).
    static Presence recordingPresent() { return Presence(true); }

    void note(const void* member) { set_.insert(member); }
    bool missing(const void* member) const {
        return recordsPresent_ ? set_.count(member) == 0 : set_.count(member) != 0;
    }
    /// True when nothing was absent (a complete file): completion has nothing to do.
    bool complete() const { return !recordsPresent_ && set_.empty(); }

private:
    explicit Presence(bool recordsPresent) : recordsPresent_(recordsPresent) {}
    bool recordsPresent_;
    std::unordered_set<const void*> set_;
};

/// What the PlantArchitecture provides for values an input leaves out.
struct Defaults {
    const std::map<std::string, ShootParameters>* shootTypes = nullptr;  ///< current types
    PhenologyParameters phenology;
    bool groundClearance = true;  ///< PlantInstance::groundClearance
    std::uint64_t seed = 0;
    unsigned firstStream = 0;  ///< random stream of the first plant read (PlantInstance::stream)
};

/// Plants read from a file or string, with one warning per plant that needed defaults.
struct ReadResult {
    std::vector<PlantInstance> plants;
    std::vector<std::string> warnings;
    /// Per plant: the Context material IDs its file gives (`<material_IDs>`), or none.
    std::vector<std::vector<unsigned>> materialIDs;
};

/// Fills the values `presence` reports missing; `notes` receives what was taken from where
/// (e.g. "shoot type unifoliate: the PlantArchitecture's"). Errors name paths below `where`.
/// The plant gets random stream `stream` (its generator from it, when the input has none).
void completePlant(PlantInstance& plant, const Presence& presence, const Defaults& defaults,
                   unsigned stream, std::vector<std::string>& notes, const std::string& where);

/// What completion derives for an internode after one with roll reference `previous`: that
/// reference carried to the shoot axis `guide` with the smallest rotation (no twist), as
/// growth carries it ...
vec3 carriedRollReference(vec3 previous, vec3 guide);
/// ... the internode's axis from its shoot axis, roll reference, azimuth and zig-zag pitch ...
vec3 internodeDirection(const Internode& in);
/// ... and the azimuth of petiole `j` of the `n` at a node of azimuth `internodeAzimuth`:
/// spread evenly.
float petioleAzimuth(float internodeAzimuth, std::size_t j, std::size_t n);

/// The shared check of every plant read (plant structure file, `<helios>` file, plant string),
/// after completion: every value in its declared range (plantarch/PlantStateTable.h) and
/// finite; shoot references (parents listed before, existing nodes and petioles); buds whose
/// shoot grows from them, no shoot claimed by two buds; unique leaf IDs below next_leaf_ID;
/// known shoot types and shape variants. Throws plantarch::Error (parameter path such as
/// "plant_instance[0].shoot[3].parent_shoot_ID", below `where`) at the first problem;
/// derives Shoot::children.
void checkPlant(PlantInstance& plant, const std::string& where);

/// The element that `path` ("shoot[2].phytomer[0].internode.petiole[1]", "shoot_type[main]")
/// names below `from`, as far as the path can be followed: where an error that checkPlant
/// found is placed in the file (plant_xml_reader.cpp).
pugi::xml_node locateElement(pugi::xml_node from, const std::string& path);

/// The values a file left out, for the one warning per plant: "path, path (3), ..." from the
/// count of each missing path (plant_xml_reader.cpp).
std::string missingReport(const std::map<std::string, int>& counts);

// ---- XML ---------------------------------------------------------------------------

/// A complete plant structure document holding `plants`, numbers in shortest round-trip form;
/// with `objectIDs`, each organ's Context object IDs too.
/// `materialIDs` (with objectIDs; one list per plant) are the Context material IDs of the
/// plant's objects, distinct, in the order of the objects' IDs.
std::string writePlantsXML(const std::vector<const PlantInstance*>& plants, bool objectIDs = false,
                           const std::vector<std::vector<unsigned>>* materialIDs = nullptr);

/// Reads a plant structure document (the complete form or the specification's listing
/// form). Throws plantarch::Error naming `fileName`, the line, the element path and the value.
ReadResult readPlantsXML(const std::string& xml, const std::string& fileName,
                         const Defaults& defaults);

/// Reads a document whose root is `<helios>`: the specification's listing and the files
/// of the reference system (helios_xml.cpp).
ReadResult readHeliosPlants(const xml::Document& doc, const std::string& fileName,
                            const Defaults& defaults);
/// The plants as a `<helios>` document in the reference system's layout.
std::string writeHeliosPlants(const std::vector<const PlantInstance*>& plants);

/// Writes the plants' internodes as cylinders, one CSV row each (qsm_writer.cpp).
void writeQSM(const std::vector<const PlantInstance*>& plants, const std::string& path);

// ---- object IDs ----------------------------------------------------------------------

/// Calls f(ObjectID&) or f(std::vector<ObjectID>&) for every object member of one shoot's
/// organs, in a fixed order (phytomers: internode, petioles with their leaves and floral buds;
/// then the shoot's terminal buds).
template <class ShootT, class F>
void forEachShootObjectMember(ShootT& s, F&& f) {
    auto floral = [&](auto& fb) {
        f(fb.peduncleObject);
        for (auto& fl : fb.flowers) f(fl.objects);
    };
    for (auto& ph : s.phytomers) {
        f(ph.internode.object);
        for (auto& pt : ph.petioles) {
            f(pt.object);
            for (auto& l : pt.leaves) f(l.objects);
            for (auto& fb : pt.floralBuds) floral(fb);
        }
    }
    for (auto& fb : s.terminalFloralBuds) floral(fb);
}

/// forEachShootObjectMember for every shoot of the plant, in shoot order.
template <class Plant, class F>
void forEachObjectMember(Plant& p, F&& f) {
    for (auto& s : p.shoots) forEachShootObjectMember(s, f);
}

/// Forgets every organ's Context object IDs: the plant gets new objects when drawn next.
template <class Plant>
void clearObjectIDs(Plant& p) {
    forEachObjectMember(p, [](auto& member) {
        if constexpr (std::is_same_v<std::decay_t<decltype(member)>, ObjectID>)
            member = kNoObject;
        else
            member.clear();
    });
}

// ---- plant strings -------------------------------------------------------------------

std::string writePlantString(const PlantInstance& plant, int significantDigits);
ReadResult readPlantString(const std::string& text, const Defaults& defaults);

}  // namespace plantarch::plant_io
