#include "geometry/prototype_cache.h"

#include <mutex>
#include <unordered_map>
#include <utility>

namespace plantarch {

namespace {

// The process's shapes made by library functions. Bounded, so a long-running process that
// meets ever new parameters (an editor, a parameter sweep) does not grow without end: past
// the bound, new shapes stay with the cache that made them.
class ProcessPrototypes {
public:
    std::shared_ptr<const OrganPrototype> find(const std::string& key) {
        std::lock_guard<std::mutex> lock(mutex_);
        auto it = entries_.find(key);
        return it == entries_.end() ? nullptr : it->second;
    }
    void insert(const std::string& key, const std::shared_ptr<const OrganPrototype>& proto) {
        std::size_t bytes = key.size();
        for (const PrototypePart& part : *proto)
            bytes += part.mesh.positions.size() * sizeof(vec3) +
                     part.mesh.uvs.size() * sizeof(vec2) +
                     part.mesh.indices.size() * sizeof(std::uint32_t);
        std::lock_guard<std::mutex> lock(mutex_);
        if (bytes_ + bytes > kMaxBytes) return;
        if (entries_.emplace(key, proto).second) bytes_ += bytes;
    }

private:
    static constexpr std::size_t kMaxBytes = std::size_t(64) << 20;
    std::mutex mutex_;
    std::unordered_map<std::string, std::shared_ptr<const OrganPrototype>> entries_;
    std::size_t bytes_ = 0;
};

ProcessPrototypes& processPrototypes() {
    static ProcessPrototypes shared;
    return shared;
}

}  // namespace

PrototypeCache PrototypeCache::share() const {
    PrototypeCache copy(*functions_);
    copy.entries_ = entries_;
    return copy;
}

std::shared_ptr<const OrganPrototype> PrototypeCache::find(const std::string& key, Scope scope) {
    auto it = entries_.find(key);
    if (it != entries_.end()) return it->second;
    if (scope != Scope::Process) return nullptr;
    std::shared_ptr<const OrganPrototype> shared = processPrototypes().find(key);
    if (shared) entries_.emplace(key, shared);
    return shared;
}

void PrototypeCache::insert(const std::string& key, std::shared_ptr<const OrganPrototype> p,
                            Scope scope) {
    if (scope == Scope::Process) processPrototypes().insert(key, p);
    entries_[key] = std::move(p);
}

}  // namespace plantarch
