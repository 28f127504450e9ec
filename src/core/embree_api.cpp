// Loading Embree on first use (embree_api.h).

#include "core/embree_api.h"

#include <dlfcn.h>

#include <atomic>
#include <cstdlib>
#include <mutex>
#include <string>

#include "plantarch/Error.h"

namespace plantarch::core {

namespace {

constexpr const char* kDefaultLibrary = "libembree3.so.3";

[[noreturn]] void cannotLoad(const std::string& library, const std::string& why) {
    throw Error(
        "cannot load the ray tracing library (Embree 3), which collision avoidance, "
        "pictures and scans need: " +
            why,
        {.parameter = "PLANTARCH_EMBREE_LIBRARY",
         .value = library,
         .validRange = "an Embree 3 shared library (Debian: libembree3-3)"});
}

}  // namespace

const EmbreeApi& embree() {
    // Called once per ray by the renderer: after the first load, one atomic read, no lock.
    static std::atomic<const EmbreeApi*> ready{nullptr};
    if (const EmbreeApi* api = ready.load(std::memory_order_acquire)) return *api;
    static std::mutex mutex;
    static EmbreeApi api;
    std::lock_guard<std::mutex> lock(mutex);
    if (ready.load(std::memory_order_relaxed)) return api;
    const char* named = std::getenv("PLANTARCH_EMBREE_LIBRARY");
    const std::string library = named && *named ? named : kDefaultLibrary;
    // Kept loaded for the life of the process (its devices may outlive any one user).
    void* handle = ::dlopen(library.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!handle) {
        const char* why = ::dlerror();
        cannotLoad(library, why ? why : "dlopen failed");
    }
    EmbreeApi found;
#define PLANTARCH_EMBREE_LOOKUP(name)                                            \
    found.name = reinterpret_cast<decltype(found.name)>(::dlsym(handle, #name)); \
    if (!found.name) {                                                           \
        ::dlclose(handle);                                                       \
        cannotLoad(library, std::string("it has no function ") + #name);         \
    }
    PLANTARCH_EMBREE_FUNCTIONS(PLANTARCH_EMBREE_LOOKUP)
#undef PLANTARCH_EMBREE_LOOKUP
    api = found;
    ready.store(&api, std::memory_order_release);
    return api;
}

}  // namespace plantarch::core
