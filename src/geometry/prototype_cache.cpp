#include "geometry/prototype_cache.h"

#include <utility>

namespace plantarch {

PrototypeCache PrototypeCache::share() const {
    PrototypeCache copy(*functions_);
    copy.entries_ = entries_;
    return copy;
}

std::shared_ptr<const OrganPrototype> PrototypeCache::find(const std::string& key) const {
    auto it = entries_.find(key);
    return it == entries_.end() ? nullptr : it->second;
}

void PrototypeCache::insert(const std::string& key, std::shared_ptr<const OrganPrototype> p) {
    entries_[key] = std::move(p);
}

}  // namespace plantarch
