#include "model/plant_move.h"

#include <algorithm>
#include <optional>
#include <type_traits>
#include <vector>

#include "plantarch/PlantStateTable.h"

namespace plantarch {

namespace {

// Visitor of the state table that turns directions and moves plant ages.
class Mover {
public:
    Mover(const glm::mat3& rotation, double shift) : rotation_(rotation), shift_(shift) {}

    template <class T>
    void field(const state::FieldInfo& f, T& member) {
        if constexpr (std::is_same_v<T, vec3>) {
            if (f.check == state::Check::UnitVector && glm::length(member) > 0.0f)
                member = glm::normalize(rotation_ * member);
        } else if constexpr (std::is_floating_point_v<T>) {
            if (f.clock == state::Clock::Age) member = T(double(member) + shift_);
            if (f.clock == state::Clock::Scheduled && member >= T(0))
                member = T(std::max(0.0, double(member) + shift_));
        }
    }
    template <class Fn>
    void group(const char*, Fn&& visit) {
        visit(*this);
    }
    template <class T>
    void list(const char*, std::vector<T>& items, bool = false) {
        for (T& item : items) state::describeState(item, *this);
    }
    template <class T>
    void optional(const char*, std::optional<T>& item) {
        if (item) state::describeState(*item, *this);
    }
    template <class T>
    void values(const state::FieldInfo&, T&) {}
    template <class T>
    void parameters(const char*, T&) {}
    template <class T>
    void objects(const char*, T&) {}
    void legacy(const char*) {}

private:
    glm::mat3 rotation_;
    double shift_;
};

}  // namespace

void movePlant(PlantInstance& plant, const PlantMove& move) {
    const vec3 from = plant.base;
    Mover mover(move.rotation, move.age - plant.age);
    state::describeState(plant, mover);  // plant_age is among the ages moved
    plant.age = move.age;
    plant.base = move.base;
    if (plant.attraction)
        for (vec3& p : plant.attraction->points) p = move.base + move.rotation * (p - from);
}

}  // namespace plantarch
