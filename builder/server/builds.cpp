// The build queue: one worker thread builds the queued projects in order. A build is stopped
// through its progress callback, which throws once the build is cancelled: buildProject then
// leaves nothing of it (and the worker drops the half-built scene).

#include "builder/server/builds.h"

#include <algorithm>

#include "plantarch/Error.h"

namespace plantarch::builder {

namespace {

// Thrown by a cancelled build's progress callback.
struct Cancelled {};

}  // namespace

const char* buildStateName(BuildState state) {
    switch (state) {
        case BuildState::Queued:
            return "queued";
        case BuildState::Running:
            return "running";
        case BuildState::Done:
            return "done";
        case BuildState::Failed:
            return "failed";
        case BuildState::Cancelled:
            return "cancelled";
    }
    return "failed";
}

BuildQueue::BuildQueue(Options options) : options_(options), worker_([this] { work(); }) {}

BuildQueue::~BuildQueue() {
    {
        std::lock_guard<std::mutex> lock(mutex_);
        stopping_ = true;
        for (auto& [id, b] : builds_) b->cancel = true;
    }
    wake_.notify_all();
    worker_.join();
}

std::variant<std::string, Refusal> BuildQueue::submit(Project project, const std::string& from) {
    std::lock_guard<std::mutex> lock(mutex_);
    if (queue_.size() >= options_.maxQueued)
        return Refusal{429, "too many builds waiting (" + std::to_string(queue_.size()) +
                                "): wait for one to finish or cancel one"};
    if (!from.empty()) {
        const auto it = builds_.find(from);
        if (it == builds_.end()) return Refusal{404, "from = " + from + ": no such build"};
        // A build still queued or running may finish before this one starts: the worker
        // checks again.
        if (it->second->state == BuildState::Failed || it->second->state == BuildState::Cancelled)
            return Refusal{409, "from = " + from + ": that build did not finish"};
        if (!it->second->takenBy.empty())
            return Refusal{410, "from = " + from + ": its plants were grown on by build " +
                                    it->second->takenBy};
    }
    auto b = std::make_shared<Build>();
    b->id = "b";  // appended, not "b" + ...: GCC 12 warns of a false overlap (-Wrestrict)
    b->id += std::to_string(next_++);
    b->project = std::move(project);
    b->from = from;
    builds_[b->id] = b;
    queue_.push_back(b);
    wake_.notify_all();
    return b->id;
}

std::optional<Build> BuildQueue::status(const std::string& id) const {
    std::lock_guard<std::mutex> lock(mutex_);
    const auto it = builds_.find(id);
    if (it == builds_.end()) return std::nullopt;
    Build copy;
    const Build& b = *it->second;
    copy.id = b.id;
    copy.project = b.project;
    copy.from = b.from;
    copy.state = b.state;
    copy.stage = b.stage;
    copy.progress = b.progress;
    copy.error = b.error;
    copy.takenBy = b.takenBy;
    copy.stats = b.stats;
    copy.ages = b.ages;
    if (b.scene) copy.scene = b.scene;  // for the plants' IDs; callers only read
    return copy;
}

std::variant<std::shared_ptr<Scene>, Refusal> BuildQueue::scene(const std::string& id) const {
    std::lock_guard<std::mutex> lock(mutex_);
    const auto it = builds_.find(id);
    if (it == builds_.end()) return Refusal{404, "no build " + id};
    const Build& b = *it->second;
    if (!b.takenBy.empty())
        return Refusal{410, "build " + id + "'s plants were grown on by build " + b.takenBy};
    if (b.state != BuildState::Done || !b.scene)
        return Refusal{409, "build " + id + " is " + buildStateName(b.state) + ", not done"};
    return b.scene;
}

std::variant<std::shared_ptr<Scene>, Refusal> BuildQueue::exportScene(const std::string& id) {
    auto own = scene(id);
    if (std::holds_alternative<Refusal>(own)) return own;
    Project project;
    {
        std::lock_guard<std::mutex> lock(mutex_);
        const auto it = builds_.find(id);
        if (it == builds_.end()) return Refusal{404, "no build " + id};
        const Build& b = *it->second;
        if (b.from.empty()) return own;
        if (b.freshScene) return b.freshScene;
        project = b.project;
    }
    // Built outside the lock (the queue goes on); two exports at once may both build it.
    auto fresh = std::make_shared<Scene>();
    try {
        fresh->built = buildProject(project, *fresh->arch, {.maxTriangles = options_.maxTriangles});
        if (options_.checkScene) options_.checkScene(fresh->context);
    } catch (const Error& e) {
        return Refusal{500, std::string("building build ") + id + " anew for export: " + e.what()};
    }
    std::lock_guard<std::mutex> lock(mutex_);
    if (const auto it = builds_.find(id); it != builds_.end()) it->second->freshScene = fresh;
    return fresh;
}

std::optional<bool> BuildQueue::cancel(const std::string& id) {
    std::lock_guard<std::mutex> lock(mutex_);
    const auto it = builds_.find(id);
    if (it == builds_.end()) return std::nullopt;
    const std::shared_ptr<Build> b = it->second;
    if (b->state == BuildState::Queued || b->state == BuildState::Running) {
        b->cancel = true;
        if (b->state == BuildState::Queued) {
            queue_.erase(std::remove(queue_.begin(), queue_.end(), b), queue_.end());
            b->state = BuildState::Cancelled;
            finished_.push_back(id);
        }
        return true;
    }
    builds_.erase(it);
    finished_.erase(std::remove(finished_.begin(), finished_.end(), id), finished_.end());
    return false;
}

std::variant<std::string, Refusal> BuildQueue::glb(const std::string& id, const std::string& key,
                                                   const std::function<std::string(Scene&)>& make) {
    std::shared_ptr<Build> b;
    std::shared_ptr<Scene> s;
    {
        std::lock_guard<std::mutex> lock(mutex_);
        const auto it = builds_.find(id);
        if (it != builds_.end() && it->second->glb.count(key) && it->second->takenBy.empty())
            return it->second->glb.at(key);
        if (it != builds_.end()) b = it->second;
    }
    auto found = scene(id);
    if (auto* r = std::get_if<Refusal>(&found)) return *r;
    s = std::get<std::shared_ptr<Scene>>(found);
    std::string bytes;
    {
        std::shared_lock<std::shared_mutex> read(s->lock);
        bytes = make(*s);
    }
    std::lock_guard<std::mutex> lock(mutex_);
    if (b && b->takenBy.empty()) {
        // The flat scene and the last variant asked for: a textured scene can weigh 100 MB.
        std::erase_if(b->glb, [&](const auto& kept) { return !kept.first.empty(); });
        b->glb[key] = bytes;
    }
    return bytes;
}

void BuildQueue::forgetOld() {
    while (finished_.size() > options_.keepFinished) {
        builds_.erase(finished_.front());
        finished_.pop_front();
    }
}

void BuildQueue::work() {
    for (;;) {
        std::shared_ptr<Build> b;
        {
            std::unique_lock<std::mutex> lock(mutex_);
            wake_.wait(lock, [&] { return stopping_ || !queue_.empty(); });
            if (stopping_) return;
            b = queue_.front();
            queue_.pop_front();
            b->state = BuildState::Running;
        }
        run(b);
        std::lock_guard<std::mutex> lock(mutex_);
        finished_.push_back(b->id);
        forgetOld();
    }
}

void BuildQueue::run(const std::shared_ptr<Build>& b) {
    const ProgressCallback progress = [this, b](std::string_view stage, double fraction) {
        std::lock_guard<std::mutex> lock(mutex_);
        if (b->cancel) throw Cancelled{};
        b->stage = std::string(stage);
        b->progress = fraction;
    };
    const ProjectBuildOptions options{.progress = progress, .maxTriangles = options_.maxTriangles};
    std::shared_ptr<Scene> scene;
    std::shared_ptr<Build> earlier;
    auto finish = [&](BuildState state, const std::string& error) {
        std::lock_guard<std::mutex> lock(mutex_);
        b->state = state;
        b->error = error;
        if (state == BuildState::Done) {
            b->scene = scene;
            b->stats = projectStats(*scene->arch, scene->built);
            b->progress = 1.0;
        }
    };
    try {
        if (!b->from.empty()) {
            {
                std::lock_guard<std::mutex> lock(mutex_);
                const auto it = builds_.find(b->from);
                if (it == builds_.end() || it->second->state != BuildState::Done ||
                    !it->second->scene || !it->second->takenBy.empty())
                    throw Error("no finished build to grow on",
                                {.parameter = "from",
                                 .value = b->from,
                                 .validRange = "a build that is done and not grown on yet"});
                earlier = it->second;
                scene = earlier->scene;
            }
            projectGrowth(earlier->project, b->project);  // refused: the earlier build stays
            std::unique_lock<std::shared_mutex> write(scene->lock);  // readers finish first
            {
                std::lock_guard<std::mutex> lock(mutex_);
                earlier->takenBy = b->id;  // from now on its scene is this build's
                earlier->glb.clear();
                earlier->scene.reset();
                earlier->freshScene.reset();
            }
            growProject(earlier->project, b->project, *scene->arch, scene->built, options);
        } else {
            scene = std::make_shared<Scene>();
            scene->built = buildProject(b->project, *scene->arch, options);
        }
        if (options_.checkScene) options_.checkScene(scene->context);
        {
            std::lock_guard<std::mutex> lock(mutex_);
            for (std::size_t i = 0; i < b->project.blocks.size(); ++i) {
                const auto& plants = scene->built.blockPlants[i];
                b->ages.push_back(plants.empty() ? b->project.blocks[i].age.value_or(0.0f)
                                                 : scene->arch->getPlantAge(plants.front()));
            }
        }
        finish(BuildState::Done, "");
    } catch (const Cancelled&) {
        finish(BuildState::Cancelled, "");
    } catch (const TriangleBudgetError& e) {
        finish(BuildState::Failed, std::string(e.what()) + " (--max-triangles)");
    } catch (const Error& e) {
        finish(BuildState::Failed, e.what());
    } catch (const std::bad_alloc&) {
        finish(BuildState::Failed, "out of memory: lower --max-triangles to be told before");
    } catch (const std::exception& e) {
        finish(BuildState::Failed, std::string("internal error: ") + e.what());
    }
}

}  // namespace plantarch::builder
