#pragma once
// Exceptions out of OpenMP parallel regions. An exception that leaves the body of an OpenMP
// region calls std::terminate (the process aborts), so every worker runs its body through
// ParallelErrors::run, which catches whatever it throws; the calling thread then calls
// rethrow() after the region. When several iterations fail, the one with the lowest index is
// rethrown, so the error a user sees does not depend on the thread count or on timing.
//
//     ParallelErrors errors;
//     #pragma omp parallel for
//     for (long i = 0; i < n; ++i)
//         errors.run(i, [&] { work(i); });
//     errors.rethrow();

#include <omp.h>

#include <atomic>
#include <cstdint>
#include <exception>
#include <limits>
#include <utility>

namespace plantarch {

class ParallelErrors {
public:
    /// Runs f(); an exception it throws is kept (the lowest `index`'s) instead of escaping.
    template <class F>
    void run(std::int64_t index, F&& f) noexcept {
        try {
            std::forward<F>(f)();
        } catch (...) {
            keep(index, std::current_exception());
        }
    }

    /// Whether a worker has failed so far: long loops may skip the work left.
    bool failed() const noexcept { return failed_.load(std::memory_order_relaxed); }

    /// After the region: the index whose exception is kept (valid when failed()).
    std::int64_t index() const noexcept { return index_; }

    /// On the calling thread, after the region: throws the kept exception, if any.
    void rethrow() {
        if (!first_) return;
        std::exception_ptr e = std::exchange(first_, nullptr);
        failed_ = false;
        index_ = std::numeric_limits<std::int64_t>::max();
        std::rethrow_exception(e);
    }

private:
    void keep(std::int64_t index, std::exception_ptr e) noexcept {
#pragma omp critical(plantarch_parallel_errors)
        {
            if (index < index_) {
                index_ = index;
                first_ = std::move(e);
            }
        }
        failed_.store(true, std::memory_order_relaxed);
    }

    std::exception_ptr first_;
    std::int64_t index_ = std::numeric_limits<std::int64_t>::max();
    std::atomic<bool> failed_{false};
};

}  // namespace plantarch
