// ParallelErrors: an exception thrown inside an OpenMP worker reaches the calling thread
// (instead of terminating the process), and which one does not depend on the threads.

#include <gtest/gtest.h>
#include <omp.h>

#include <stdexcept>
#include <string>

#include "core/parallel.h"
#include "plantarch/Error.h"

using namespace plantarch;

TEST(ParallelErrors, ExceptionInAWorkerArrivesAtTheCaller) {
    ParallelErrors errors;
    int ran = 0;
#pragma omp parallel for num_threads(4) reduction(+ : ran)
    for (int i = 0; i < 64; ++i)
        errors.run(i, [&] {
            ++ran;
            if (i == 37) throw Error("plant 37 failed", {.parameter = "plant", .value = "37"});
        });
    EXPECT_EQ(ran, 64);  // the other iterations ran to the end
    EXPECT_TRUE(errors.failed());
    EXPECT_EQ(errors.index(), 37);
    try {
        errors.rethrow();
        FAIL() << "rethrow threw nothing";
    } catch (const Error& e) {  // the same type and text as thrown in the worker
        EXPECT_EQ(e.message(), "plant 37 failed");
        EXPECT_EQ(e.value(), "37");
    }
    EXPECT_NO_THROW(errors.rethrow());  // given once
}

TEST(ParallelErrors, TheLowestIndexWinsWhateverTheThreads) {
    for (int threads : {1, 2, 3, 8}) {
        ParallelErrors errors;
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads)
        for (int i = 0; i < 100; ++i)
            errors.run(i, [&] {
                if (i % 10 == 3) throw std::runtime_error("iteration " + std::to_string(i));
            });
        try {
            errors.rethrow();
            FAIL() << "rethrow threw nothing with " << threads << " threads";
        } catch (const std::runtime_error& e) {
            EXPECT_STREQ(e.what(), "iteration 3") << threads << " threads";
        }
    }
}

TEST(ParallelErrors, AnyTypeAndBadAllocToo) {
    ParallelErrors errors;
#pragma omp parallel for num_threads(2)
    for (int i = 0; i < 4; ++i)
        errors.run(i, [&] {
            if (i == 1) throw std::bad_alloc();
            if (i == 2) throw 42;  // not even an exception class
        });
    EXPECT_THROW(errors.rethrow(), std::bad_alloc);
    ParallelErrors none;
#pragma omp parallel for num_threads(2)
    for (int i = 0; i < 4; ++i) none.run(i, [] {});
    EXPECT_FALSE(none.failed());
    EXPECT_NO_THROW(none.rethrow());
}
