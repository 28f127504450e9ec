#pragma once
// ProgressSteps: reports a job's progress through a ProgressCallback at most about a hundred
// times, so a writer can call at() after every object without making the callback costly.

#include <string_view>

#include "plantarch/Progress.h"

namespace plantarch {

class ProgressSteps {
public:
    /// `total` units of work under `stage`; `callback` may be empty (then nothing is called)
    /// and must outlive this object.
    ProgressSteps(const ProgressCallback& callback, std::string_view stage, double total)
        : callback_(callback ? &callback : nullptr),
          stage_(stage),
          total_(total),
          next_(total / 100.0) {}

    /// `done` units are finished (never less than at the last call). Calls the callback when
    /// another hundredth is done; never with 1 (finish() does that).
    void at(double done) {
        if (callback_ && done >= next_ && done < total_) {
            (*callback_)(stage_, done / total_);
            next_ = done + total_ / 100.0;
        }
    }
    /// The job is done: the callback's last call, fraction 1.
    void finish() {
        if (callback_) (*callback_)(stage_, 1.0);
    }
    bool active() const { return callback_ != nullptr; }

private:
    const ProgressCallback* callback_;
    std::string_view stage_;
    double total_;
    double next_;
};

}  // namespace plantarch
