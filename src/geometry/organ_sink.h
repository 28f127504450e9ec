#pragma once
// Where tessellation puts a plant's organs. The Context is one destination (the plant's
// geometry); collision avoidance is another (light proxies of the organs it treats as
// obstacles, and single organs placed on trial while turning them out of solid obstacles).
// Both run the same placement code, so an organ's proxy sits exactly where its mesh does.

#include <vector>

#include "model/architecture_impl.h"

namespace plantarch {

/// What an organ is, for labels and for sinks that keep only some kinds.
struct OrganLabels {
    OrganKind kind;
    const Shoot* shoot;
    int node;
    float age;
    int leafID = -1;
};

class OrganSink {
public:
    virtual ~OrganSink() = default;
    /// Whether organs of this kind are wanted; unwanted ones are not meshed at all.
    virtual bool wants(OrganKind kind) const = 0;
    /// One organ made of `mesh` (tubes: internodes, petioles, peduncles).
    virtual void write(ObjectID& object, const Mesh& mesh, const Material& material,
                       const OrganLabels& labels) = 0;
    /// One organ made of the parts of a prototype placed by `transform` (leaves, flowers, fruit).
    virtual void writeParts(std::vector<ObjectID>& objects, const OrganPrototype& prototype,
                            const mat4& transform, const OrganLabels& labels) = 0;
    /// An organ that has no geometry now (fallen, not yet visible, zero length).
    virtual void remove(ObjectID& object) { (void)object; }
    virtual void removeAll(std::vector<ObjectID>& objects) { (void)objects; }
};

/// Places every organ of the plant into `sink` (the plant's state as it stands).
void tessellatePlant(PlantArchitecture::Impl& impl, OrganSink& sink, PlantInstance& plant);

/// Places single organs of one plant, for trials (collision clearance). Node positions are
/// computed once when it is made: the plant's shape must not change while it is used.
class OrganPlacer {
public:
    OrganPlacer(PlantArchitecture::Impl& impl, PlantInstance& plant);
    ~OrganPlacer();
    OrganPlacer(const OrganPlacer&) = delete;
    OrganPlacer& operator=(const OrganPlacer&) = delete;

    /// The petiole `petiole` of node `node` on shoot `shoot`, with its leaves.
    void petiole(OrganSink& sink, unsigned shoot, unsigned node, unsigned petiole);
    /// Where that petiole starts (its organs move with this point when the plant below grows).
    vec3 petioleStart(unsigned shoot, unsigned node, unsigned petiole) const;
    /// A floral bud's peduncle, flowers or fruit: an axillary bud (petiole, bud) of a node, or
    /// the shoot's terminal bud `bud` when `terminal`.
    void floralBud(OrganSink& sink, unsigned shoot, unsigned node, unsigned petiole, unsigned bud,
                   bool terminal);

    struct State;

private:
    std::unique_ptr<State> state_;
};

}  // namespace plantarch
