// The builder's web front end in the fuzz build (CMakeLists.txt): no files. fuzz_builder runs
// the server's routes, which then answer 404 for every page.

#include "builder/server/assets.h"

namespace plantarch::builder {

std::span<const Asset> assets() {
    return {};
}

}  // namespace plantarch::builder
