#pragma once
// The plantarch::Error a call throws (a test failure when it throws none).

#include <gtest/gtest.h>

#include "plantarch/Error.h"

namespace plantarch::testing {

template <class Fn>
Error errorOf(Fn&& fn) {
    try {
        fn();
    } catch (const Error& e) {
        return e;
    }
    ADD_FAILURE() << "no plantarch::Error was thrown";
    return Error("none");
}

}  // namespace plantarch::testing
