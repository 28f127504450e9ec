#pragma once
// The builds of the project builder's server: a queue run by one worker thread, one build at a
// time. Each build holds its project, its state and progress, and once done its scene (the
// Context and PlantArchitecture the project was built into).

#include <condition_variable>
#include <cstdint>
#include <deque>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <shared_mutex>
#include <string>
#include <thread>
#include <variant>
#include <vector>

#include "plantarch/Context.h"
#include "plantarch/PlantArchitecture.h"
#include "plantarch/Project.h"

namespace plantarch::builder {

/// A built scene. Readers (GLB, render, export) hold `lock` shared; growing it on holds it
/// alone.
struct Scene {
    Context context;
    std::unique_ptr<PlantArchitecture> arch;
    BuiltProject built;
    std::shared_mutex lock;
    Scene() : arch(std::make_unique<PlantArchitecture>(&context)) {}
};

enum class BuildState { Queued, Running, Done, Failed, Cancelled };
const char* buildStateName(BuildState state);

/// One build. Its fields are read and written under BuildQueue's mutex.
struct Build {
    std::string id;
    Project project;
    std::string from;  ///< the build whose plants this one grows on ("" for none)
    BuildState state = BuildState::Queued;
    std::string stage;
    double progress = 0.0;
    std::string error;
    bool cancel = false;
    std::string takenBy;           ///< the build that grew this one's plants on ("" for none)
    std::shared_ptr<Scene> scene;  ///< set once done
    ProjectStats stats;
    std::vector<float> ages;  ///< each block's age as built
    /// scene.glb by its variant ("" flat, "textured:512" ...), each made on first request;
    /// the flat one and the last other one kept
    std::map<std::string, std::string> glb;
    /// For a build grown on from another: its project built anew, for export (exportScene).
    std::shared_ptr<Scene> freshScene;
};

/// Why a request for a build was refused, as an HTTP status and one line.
struct Refusal {
    int status;
    std::string message;
};

class BuildQueue {
public:
    struct Options {
        std::size_t maxTriangles = 0;
        std::size_t maxQueued = 4;     ///< builds waiting (not running) at most
        std::size_t keepFinished = 8;  ///< finished builds kept (older ones forgotten)
        /// Called on each scene built or grown (before it is done) and on each scene built
        /// anew for export; a plantarch::Error it throws fails the build (the server checks
        /// the files the scene's materials name).
        std::function<void(const Context&)> checkScene;
    };
    explicit BuildQueue(Options options);
    /// Cancels every build and joins the worker.
    ~BuildQueue();
    BuildQueue(const BuildQueue&) = delete;
    BuildQueue& operator=(const BuildQueue&) = delete;

    /// Queues a build of `project` (grown on from build `from` when not empty); returns its ID
    /// or a refusal (429 queue full, 404 unknown `from`, 409 `from` not done).
    std::variant<std::string, Refusal> submit(Project project, const std::string& from);
    /// A copy of the build's fields (without its scene), or nullopt for an unknown ID.
    std::optional<Build> status(const std::string& id) const;
    /// The build's scene, or a refusal (404 unknown, 409 not done, 410 taken on by another).
    std::variant<std::shared_ptr<Scene>, Refusal> scene(const std::string& id) const;
    /// The scene whose files an export writes: the build's own when it was built anew; for
    /// a build grown on from another, the same project built anew (once, then kept), so that
    /// its files are the bytes `plantarch project run` writes (the grown scene holds the same
    /// plants, but numbers their organs in the order they grew). Refusals as scene()'s, or
    /// 500 with the one-line error should the build anew fail.
    std::variant<std::shared_ptr<Scene>, Refusal> exportScene(const std::string& id);
    /// Cancels a queued or running build (true), or forgets a finished one (false); nullopt
    /// for an unknown ID.
    std::optional<bool> cancel(const std::string& id);
    /// The build's GLB bytes of variant `key` if made already; else stores `make()`'s (made
    /// outside the lock).
    std::variant<std::string, Refusal> glb(const std::string& id, const std::string& key,
                                           const std::function<std::string(Scene&)>& make);

private:
    void work();
    void run(const std::shared_ptr<Build>& build);
    void forgetOld();

    Options options_;
    mutable std::mutex mutex_;
    std::condition_variable wake_;
    std::map<std::string, std::shared_ptr<Build>> builds_;
    std::deque<std::shared_ptr<Build>> queue_;
    std::deque<std::string> finished_;  ///< IDs of finished builds, oldest first
    std::uint64_t next_ = 1;
    bool stopping_ = false;
    std::thread worker_;
};

}  // namespace plantarch::builder
