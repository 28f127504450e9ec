#pragma once
// Progress reporting. The library never prints: long operations call a user-supplied callback
// with what they are doing and how far along they are, and the caller decides what a person
// sees (the plantarch command draws a bar on a terminal).

#include <functional>
#include <string_view>

namespace plantarch {

/// Called with a short stage name ("growing", "rendering") and the fraction done, 0 to 1.
/// Calls come from the calling thread, in increasing order of `fraction` per stage; the
/// last call of a stage has fraction 1. Keep it cheap: it may be called often.
using ProgressCallback = std::function<void(std::string_view stage, double fraction)>;

}  // namespace plantarch
