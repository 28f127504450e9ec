// Progress reporting of every long library job: growth (one plant over years, many plants, a
// canopy, an animation's frames), each exporter, the OBJ reader, point sampling, rendering
// and scanning. Each job is checked for calls under its stage name, fractions increasing from
// above 0 to a last call of exactly 1, more than one call for a job of many parts, few calls
// however large the job, and no change to the bytes it writes.

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <stdexcept>
#include <string>
#include <vector>

#include "plantarch/Context.h"
#include "plantarch/Error.h"
#include "plantarch/Export.h"
#include "plantarch/ExportPlants.h"
#include "plantarch/PlantArchitecture.h"
#include "plantarch/Render.h"
#include "plantarch/Scan.h"

using namespace plantarch;
namespace fs = std::filesystem;

namespace {

struct Call {
    std::string stage;
    double fraction;
};

// Records the calls of one job.
struct Recorder {
    std::vector<Call> calls;
    ProgressCallback callback() {
        return [this](std::string_view stage, double f) {
            calls.push_back({std::string(stage), f});
        };
    }
    // The fractions reported under `stage`, in order.
    std::vector<double> of(const std::string& stage) const {
        std::vector<double> f;
        for (const Call& c : calls)
            if (c.stage == stage) f.push_back(c.fraction);
        return f;
    }
};

// Fractions increasing, within (0, 1], the last exactly 1; at least `least` calls; at most
// a hundred and one (one a hundredth, then 1), so a callback per part of the work is cheap.
void expectProgress(const std::vector<double>& f, std::size_t least, const std::string& what) {
    SCOPED_TRACE(what);
    ASSERT_FALSE(f.empty());
    EXPECT_GE(f.size(), least);
    EXPECT_LE(f.size(), 101u);
    EXPECT_EQ(f.back(), 1.0);
    EXPECT_GT(f.front(), 0.0);
    for (std::size_t i = 1; i < f.size(); ++i) EXPECT_LT(f[i - 1], f[i]) << "call " << i;
}

std::string readBytes(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

class Progress : public ::testing::Test {
protected:
    void SetUp() override {
        dir_ = fs::temp_directory_path() /
               ("progress_" +
                std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
        fs::remove_all(dir_);
        fs::create_directories(dir_);
    }
    void TearDown() override { fs::remove_all(dir_); }
    std::string path(const std::string& name) const { return (dir_ / name).string(); }

    fs::path dir_;
};

// A bean canopy of 3 x 3 plants at 40 days: some 270,000 triangles in a few thousand objects.
const Context& beans() {
    static Context ctx;
    static PlantArchitecture arch(&ctx);
    static bool built = false;
    if (!built) {
        arch.loadPlantModelFromLibrary("bean");
        arch.buildPlantCanopyFromLibrary(vec3(0.0f), vec2(0.3f), glm::ivec2(3, 3), 40.0f);
        built = true;
    }
    return ctx;
}

}  // namespace

TEST_F(Progress, GrowingOnePlantReportsWithinThePlant) {
    Context ctx;
    PlantArchitecture arch(&ctx);
    Recorder r;
    arch.setProgressCallback(r.callback());
    arch.loadPlantModelFromLibrary("bean");
    arch.buildPlantInstanceFromLibrary(vec3(0.0f), 60.0f);
    expectProgress(r.of("growing"), 10, "one plant, 60 days");
    EXPECT_EQ(r.of("growing").size(), r.calls.size());
}

TEST_F(Progress, CanopyBuildReportsItsBatches) {
    Context ctx;
    PlantArchitecture arch(&ctx);
    Recorder r;
    arch.setProgressCallback(r.callback());
    arch.loadPlantModelFromLibrary("bean");
    arch.buildPlantCanopyFromLibrary(vec3(0.0f), vec2(0.3f), glm::ivec2(4, 4), 30.0f);
    expectProgress(r.of("building"), 2, "canopy of 16 beans");
}

TEST_F(Progress, GrowthAnimationReportsFramesThenEachFile) {
    Context ctx;
    PlantArchitecture arch(&ctx);
    arch.loadPlantModelFromLibrary("bean");
    const unsigned plant = arch.buildPlantInstanceFromLibrary(vec3(0.0f), 0.0f);
    Recorder r;
    writeGrowthAnimation(arch, {plant}, {0.0, 30.0, 3.0}, {path("g.glb"), path("g.usda")},
                         {24.0, r.callback()});
    expectProgress(r.of("growing"), 10, "eleven frames");
    expectProgress(r.of("writing glTF"), 2, "animated glb");
    expectProgress(r.of("writing USD"), 2, "animated usda");
    // In that order: the frames grown first, then the files in the order given.
    ASSERT_FALSE(r.calls.empty());
    EXPECT_EQ(r.calls.front().stage, "growing");
    EXPECT_EQ(r.calls.back().stage, "writing USD");
}

TEST_F(Progress, EveryExporterReportsAndWritesTheSameBytes) {
    const Context& ctx = beans();
    struct Job {
        std::string stage, file;
        std::function<void(const std::string&, const ProgressCallback&)> write;
    };
    const std::vector<Job> jobs = {
        {"writing OBJ", "s.obj",
         [&](const std::string& p, const ProgressCallback& cb) {
             writeOBJ(ctx, p, {.progress = cb});
         }},
        {"writing PLY", "s.ply",
         [&](const std::string& p, const ProgressCallback& cb) {
             writePLY(ctx, p, {.progress = cb});
         }},
        {"writing PLY", "a.ply",
         [&](const std::string& p, const ProgressCallback& cb) {
             writePLY(ctx, p, {.format = PlyFormat::Ascii, .progress = cb});
         }},
        {"writing glTF", "s.glb",
         [&](const std::string& p, const ProgressCallback& cb) {
             GltfOptions o;
             o.progress = cb;
             writeGLTF(ctx, p, o);
         }},
        {"writing glTF", "s.gltf",
         [&](const std::string& p, const ProgressCallback& cb) {
             GltfOptions o;
             o.progress = cb;
             writeGLTF(ctx, p, o);
         }},
        {"writing USD", "s.usda",
         [&](const std::string& p, const ProgressCallback& cb) {
             UsdOptions o;
             o.progress = cb;
             writeUSDA(ctx, p, o);
         }},
        {"writing PLY", "points.ply",
         [&](const std::string& p, const ProgressCallback& cb) {
             writePointCloudPLY(samplePoints(ctx, {.points = 200000, .seed = 3}), p, cb);
         }},
        {"writing NPZ", "points.npz",
         [&](const std::string& p, const ProgressCallback& cb) {
             writePointCloudNPZ(samplePoints(ctx, {.points = 200000, .seed = 3}), p, cb);
         }},
    };
    fs::create_directories(dir_ / "with");
    fs::create_directories(dir_ / "without");
    for (const Job& job : jobs) {
        Recorder r;
        job.write(path("with/" + job.file), r.callback());
        expectProgress(r.of(job.stage), 2, job.file);
        EXPECT_EQ(r.of(job.stage).size(), r.calls.size()) << job.file;
        job.write(path("without/" + job.file), {});
        const std::string bytes = readBytes(path("with/" + job.file));
        EXPECT_GT(bytes.size(), 100000u) << job.file;
        EXPECT_TRUE(bytes == readBytes(path("without/" + job.file))) << job.file;
    }
}

TEST_F(Progress, SplitObjReportsOverTheObjects) {
    Recorder r;
    writeOBJ(beans(), path("split"), {.splitPerObject = true, .progress = r.callback()});
    expectProgress(r.of("writing OBJ"), 50, "one file per object");
}

TEST_F(Progress, ReadingSamplingRenderingAndScanningReport) {
    writeOBJ(beans(), path("s.obj"));
    Context read;
    Recorder reading;
    readOBJ(read, path("s.obj"), {.progress = reading.callback()});
    expectProgress(reading.of("reading OBJ"), 3, "readOBJ");
    // The parse itself (the first half) reports as the file is read, not only at its end.
    const std::vector<double> read_ = reading.of("reading OBJ");
    EXPECT_GE(std::count_if(read_.begin(), read_.end(), [](double f) { return f < 0.5; }), 3)
        << "calls during the parse";

    Recorder sampling;
    samplePoints(beans(), {.points = 500000, .seed = 1, .progress = sampling.callback()});
    expectProgress(sampling.of("sampling points"), 5, "samplePoints");

    Recorder rendering;
    RenderOptions o;
    o.width = 240;
    o.height = 200;  // bands of 64 rows: four calls
    o.samplesPerPixel = 1;
    o.progress = rendering.callback();
    o.scene.progress = rendering.callback();
    render(beans(), o);
    expectProgress(rendering.of("rendering"), 2, "render");
    // The scene (triangles copied, then the BVH) before the rows.
    expectProgress(rendering.of("building scene"), 2, "scene build");
    ASSERT_FALSE(rendering.calls.empty());
    EXPECT_EQ(rendering.calls.front().stage, "building scene");

    Recorder scanning;
    ScanOptions s;
    s.scanners.push_back({.origin = {2.0f, 2.0f, 1.5f}, .resolution = 0.5f});  // 240 rows
    s.progress = scanning.callback();
    scan(beans(), s);
    expectProgress(scanning.of("scanning"), 2, "scan");
}

// A callback that throws stops the job: the exception comes out, and no file, temporary or
// half written, is left (the OBJ body is written from several threads).
TEST_F(Progress, ThrowingCallbackStopsAWriteAndLeavesNothing) {
    int calls = 0;
    const ProgressCallback stop = [&](std::string_view, double f) {
        if (++calls == 2 && f < 1.0) throw std::runtime_error("stopped");
    };
    EXPECT_THROW(writeOBJ(beans(), path("s.obj"), {.progress = stop}), std::runtime_error);
    calls = 0;
    EXPECT_THROW(writePLY(beans(), path("s.ply"), {.progress = stop}), std::runtime_error);
    EXPECT_TRUE(fs::is_empty(dir_));
}
