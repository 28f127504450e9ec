// The builder's dataset endpoints (builder/server/dataset_routes.cpp): a spec checked (its
// errors with their field), a sample previewed as pictures (the library's own sample, written
// nowhere under the output folder), a local run with progress, one at a time, cancelled
// before or during a sample with nothing half written left, and hostile values refused with
// one line.

#include <gtest/gtest.h>
#include <httplib.h>
#include <sys/stat.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <fstream>
#include <nlohmann/json.hpp>
#include <thread>

#include "builder_fixture.h"
#include "plantarch/Dataset.h"
#include "plantarch/Render.h"

namespace {

std::string readText(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

std::string tinySpec() {
    return readText(std::string(PLANTARCH_SOURCE_DIR) + "/examples/datasets/tiny.json");
}

// tiny.json with `samples` samples.
std::string tinyWith(std::size_t samples) {
    json j = json::parse(tinySpec());
    j["samples"] = samples;
    return j.dump();
}

// A spec whose one sample takes a while to build: a canopy of beans, small pictures.
std::string slowSpec() {
    return json({{"plantarch_dataset", 1},
                 {"name", "slow"},
                 {"samples", 3},
                 {"scene",
                  {{"species", {{{"species", "bean"}, {"age", 45}}}},
                   {"layouts",
                    {{{"layout", "rows"},
                      {"rows", 4},
                      {"plants_per_row", 6},
                      {"row_spacing", 0.4},
                      {"plant_spacing", 0.2}}}}}},
                 {"camera", {{"width", 32}, {"height", 24}, {"samples_per_pixel", 1}}},
                 {"points", {{"count", 100}}}})
        .dump();
}

// Width and height of PNG bytes (its IHDR).
std::pair<int, int> pngSize(const std::string& png) {
    auto word = [&](std::size_t at) {
        return int((std::uint8_t(png[at]) << 24) | (std::uint8_t(png[at + 1]) << 16) |
                   (std::uint8_t(png[at + 2]) << 8) | std::uint8_t(png[at + 3]));
    };
    if (png.size() < 24 || png.compare(1, 3, "PNG") != 0) return {0, 0};
    return {word(16), word(20)};
}

}  // namespace

class BuilderDataset : public BuilderServer {
protected:
    std::string errorOf(const httplib::Result& r) {
        if (!r) return "no answer";
        const json j = json::parse(r->body, nullptr, false);
        return j.is_object() && j.contains("error") ? j["error"].get<std::string>() : r->body;
    }
    httplib::Result cancel(const std::string& id) {
        return client_->Delete(("/api/dataset/runs/" + id).c_str(), {{"Origin", origin()}});
    }
    // Polls a run until it has stopped.
    json waitForRun(const std::string& id) {
        for (int i = 0; i < 6000; ++i) {
            auto r = client_->Get(("/api/dataset/runs/" + id).c_str());
            if (!r || r->status != 200) return json{{"state", "missing"}};
            json j = body(r);
            if (j["state"] != "running") return j;
            std::this_thread::sleep_for(std::chrono::milliseconds(20));
        }
        return json{{"state", "timeout"}};
    }
    std::string startRun(const json& request) {
        auto r = post("/api/dataset/runs", request);
        EXPECT_TRUE(r && r->status == 202) << (r ? r->body : "no answer");
        return r && r->status == 202 ? body(r)["id"].get<std::string>() : "";
    }
    fs::path out(const std::string& sub = "") const {
        return sub.empty() ? fs::path(at("out")) : fs::path(at("out")) / sub;
    }
};

TEST_F(BuilderDataset, ChecksASpecAndNamesTheFieldOfAnError) {
    auto r = post("/api/dataset/check", {{"text", tinySpec()}});
    ASSERT_TRUE(r && r->status == 200) << (r ? r->body : "");
    const json j = body(r);
    EXPECT_EQ(j["name"], "tiny");
    EXPECT_EQ(j["samples"], 4);
    EXPECT_EQ(j["seed"], 7);
    EXPECT_EQ(j["splits"].size(), 3u);
    EXPECT_NE(std::find(j["splits"].begin(), j["splits"].end(),
                        json({{"name", "train"}, {"fraction", 0.5}})),
              j["splits"].end())
        << j["splits"];
    EXPECT_EQ(j["species"], json({"bean", "strawberry"}));
    EXPECT_EQ(j["weeds"], json({"puncturevine"}));
    EXPECT_EQ(j["image"], json({160, 120}));

    // The library's one line, with its field and line.
    json bad = json::parse(tinySpec());
    bad["scene"]["species"][0]["age"] = -5;
    r = post("/api/dataset/check", {{"text", bad.dump(1)}});
    ASSERT_TRUE(r);
    EXPECT_EQ(r->status, 400);
    EXPECT_EQ(body(r)["field"], "scene/species/0/age");
    EXPECT_NE(errorOf(r).find("scene/species/0/age = -5"), std::string::npos) << errorOf(r);
    bad = json::parse(tinySpec());
    bad["scene"]["species"][0]["speces"] = "bean";
    EXPECT_NE(errorOf(post("/api/dataset/check", {{"text", bad.dump()}})).find("did you mean"),
              std::string::npos);
    r = post("/api/dataset/check", {{"text", "{\"plantarch_dataset\": 1,"}});
    EXPECT_EQ(r->status, 400);
    EXPECT_EQ(errorOf(r).find('\n'), std::string::npos);

    // A spec file under the output folder; anything else refused.
    fs::create_directories(out("datasets"));
    std::ofstream(out("datasets/tiny.json")) << tinySpec();
    r = post("/api/dataset/check", {{"path", "datasets/tiny.json"}});
    ASSERT_TRUE(r && r->status == 200) << (r ? r->body : "");
    EXPECT_EQ(body(r)["name"], "tiny");
    r = client_->Get("/api/dataset/spec?path=datasets/tiny.json");
    ASSERT_TRUE(r && r->status == 200);
    EXPECT_EQ(body(r)["text"], tinySpec());
    EXPECT_EQ(post("/api/dataset/check", {{"path", "../tiny.json"}})->status, 403);
    EXPECT_EQ(post("/api/dataset/check", {{"path", "/etc/passwd"}})->status, 403);
    EXPECT_EQ(client_->Get("/api/dataset/spec?path=/etc/passwd")->status, 403);
    EXPECT_EQ(client_->Get("/api/dataset/spec?path=../../x.json")->status, 403);
    EXPECT_EQ(post("/api/dataset/check", {{"path", "datasets"}})->status, 400);
    // A pipe is never opened (it would block), nor listed.
    ASSERT_EQ(mkfifo(out("datasets/pipe.json").c_str(), 0600), 0);
    EXPECT_EQ(post("/api/dataset/check", {{"path", "datasets/pipe.json"}})->status, 400);
    EXPECT_EQ(client_->Get("/api/dataset/spec?path=datasets/pipe.json")->status, 400);
    EXPECT_EQ(body(client_->Get("/api/dataset/specs")), json({"datasets/tiny.json"}));
    EXPECT_EQ(post("/api/dataset/check", {{"path", "datasets/none.json"}})->status, 404);
    EXPECT_EQ(post("/api/dataset/check", json::object())->status, 400);
    EXPECT_EQ(post("/api/dataset/check", {{"text", "{}"}, {"path", "x.json"}})->status, 400);
    EXPECT_EQ(post("/api/dataset/check", {{"text", 5}})->status, 400);
    EXPECT_EQ(post("/api/dataset/check", {{"text", "{}"}, {"extra", 1}})->status, 400);
    // A spec text over its limit (the request itself within the server's).
    r = post("/api/dataset/check", {{"text", std::string(1100000, ' ') + tinySpec()}});
    ASSERT_TRUE(r);
    EXPECT_EQ(r->status, 413);
    EXPECT_NE(errorOf(r).find("a spec too large (valid: at most 1048576 bytes)"),
              std::string::npos);
    // A species file outside the output folder, by absolute and by relative path.
    for (const std::string& species : {at("elsewhere/bean.xml"), std::string("../../bean.xml")}) {
        json outside = json::parse(tinySpec());
        outside["scene"]["weeds"]["species"][0]["species"] = species;
        r = post("/api/dataset/check", {{"text", outside.dump()}});
        ASSERT_TRUE(r);
        EXPECT_EQ(r->status, 403) << r->body;
        EXPECT_NE(errorOf(r).find("scene/weeds/species/0/species"), std::string::npos)
            << errorOf(r);
        EXPECT_EQ(post("/api/dataset/preview", {{"text", outside.dump()}})->status, 403);
    }
    // From another site: refused as every request that changes anything.
    auto foreign = client_->Post("/api/dataset/check", {{"Origin", "http://evil.example"}},
                                 json({{"text", tinySpec()}}).dump(), "application/json");
    EXPECT_EQ(foreign->status, 403);
}

TEST_F(BuilderDataset, PreviewsTheLibrarysSampleAsPicturesWrittenOutsideTheOutputFolder) {
    const auto before = names();
    auto r = post("/api/dataset/preview", {{"text", tinySpec()}, {"sample", 1}});
    ASSERT_TRUE(r && r->status == 200) << (r ? r->body : "");
    const json j = body(r);
    const json& s = j["summary"];
    EXPECT_EQ(s["sample"], 1);
    EXPECT_TRUE(s["split"] == "train" || s["split"] == "val" || s["split"] == "test");
    EXPECT_TRUE(s["species"] == "bean" || s["species"] == "strawberry") << s;
    EXPECT_GE(s["plants"].get<int>(), 1);
    EXPECT_GE(s["annotations"].get<int>(), 1);
    EXPECT_EQ(s["image"], json({160, 120}));

    // The sample is the library's own: its RGB the bytes writeDatasetSample writes.
    const plantarch::DatasetSpec spec = plantarch::readDatasetSpecString(tinySpec(), "tiny");
    const plantarch::DatasetSampleResult direct =
        plantarch::writeDatasetSample(spec, 1, at("direct"));
    EXPECT_EQ(s["plants"], direct.plants);
    EXPECT_EQ(s["split"], direct.split);
    for (const char* name : {"rgb", "semantic", "instances", "plants", "depth"}) {
        ASSERT_TRUE(j["images"].contains(name)) << name;
        auto picture = client_->Get(j["images"][name].get<std::string>().c_str());
        ASSERT_TRUE(picture && picture->status == 200) << name;
        EXPECT_EQ(picture->get_header_value("Content-Type"), "image/png");
        EXPECT_EQ(pngSize(picture->body), std::make_pair(160, 120)) << name;
        if (std::string(name) == "rgb") {
            EXPECT_EQ(picture->body, readText(at("direct/samples/000001/rgb.png")));
        }
    }
    // Coloured masks: the semantic picture holds the leaf's label colour.
    {
        auto png = client_->Get(j["images"]["semantic"].get<std::string>().c_str());
        std::ofstream(at("semantic.png"), std::ios::binary) << png->body;
        const plantarch::Image image = plantarch::readImage(at("semantic.png"));
        const auto leaf = plantarch::organLabelColor("leaf");
        bool found = false;
        for (int y = 0; y < image.height && !found; ++y)
            for (int x = 0; x < image.width && !found; ++x) found = image.pixel(x, y) == leaf;
        EXPECT_TRUE(found);
        fs::remove(at("semantic.png"));
    }
    fs::remove_all(at("direct"));
    // Nothing written under the output folder.
    EXPECT_EQ(names(), before);

    // Hostile values: one line each, and the server serves on.
    for (const json& sample :
         {json(-1), json(10000000), json(1e300), json(1.5), json("3"), json(true), json::array()}) {
        r = post("/api/dataset/preview", {{"text", tinySpec()}, {"sample", sample}});
        ASSERT_TRUE(r);
        EXPECT_EQ(r->status, 400) << sample;
        EXPECT_NE(errorOf(r).find("sample = "), std::string::npos) << errorOf(r);
        EXPECT_NE(errorOf(r).find("(valid: 0 to 9999999)"), std::string::npos) << errorOf(r);
    }
    // Previews asked for at once: each made or refused (429) with one line, one at a time.
    std::vector<int> statuses(3, 0);
    std::vector<std::thread> threads;
    for (std::size_t t = 0; t < statuses.size(); ++t)
        threads.emplace_back([&, t] {
            httplib::Client c("127.0.0.1", port_);
            c.set_read_timeout(60, 0);
            auto a = c.Post("/api/dataset/preview", {{"Origin", origin()}},
                            json({{"text", tinySpec()}, {"sample", t}}).dump(), "application/json");
            statuses[t] = a ? a->status : -1;
        });
    for (std::thread& t : threads) t.join();
    EXPECT_GE(std::count(statuses.begin(), statuses.end(), 200), 1);
    for (int status : statuses) EXPECT_TRUE(status == 200 || status == 429) << status;
    EXPECT_EQ(names(), before);
    EXPECT_EQ(client_->Get("/api/dataset/previews/p999/rgb.png")->status, 404);
    EXPECT_EQ(client_->Get("/api/dataset/previews/p1/secret.png")->status, 404);
    EXPECT_EQ(client_->Get("/api/dataset/previews/p1/../../etc/passwd")->status, 404);
}

TEST_F(BuilderDataset, RunsSamplesIntoAFolderUnderTheOutputFolder) {
    const std::string id =
        startRun({{"text", tinySpec()}, {"out", "datasets/run"}, {"samples", 2}});
    const json done = waitForRun(id);
    ASSERT_EQ(done["state"], "done") << done;
    EXPECT_EQ(done["done"], 2);
    EXPECT_EQ(done["total"], 2);
    EXPECT_EQ(done["out"], "datasets/run");
    EXPECT_GT(done["bytes"].get<double>(), 0.0);
    EXPECT_GT(done["per_minute"].get<double>(), 0.0);
    EXPECT_TRUE(fs::is_regular_file(out("datasets/run/dataset.json")));
    EXPECT_TRUE(fs::is_regular_file(out("datasets/run/manifest-0-of-1.json")));
    EXPECT_TRUE(fs::is_regular_file(out("datasets/run/samples/000001/rgb.png")));
    EXPECT_FALSE(fs::exists(out("datasets/run/samples/000002")));
    EXPECT_FALSE(fs::exists(out("datasets/run/.partial")));
    // The bytes of the command line's (the library's) run.
    const plantarch::DatasetSpec spec = plantarch::readDatasetSpecString(tinySpec(), "tiny");
    plantarch::writeDatasetSample(spec, 1, at("direct"));
    EXPECT_EQ(readText(out("datasets/run/samples/000001/semantic.png")),
              readText(at("direct/samples/000001/semantic.png")));

    // Into the same folder again: refused, unless resumed (the samples kept).
    auto r = post("/api/dataset/runs", {{"text", tinySpec()}, {"out", "datasets/run"}});
    ASSERT_TRUE(r);
    EXPECT_EQ(r->status, 409);
    EXPECT_NE(errorOf(r).find("holds samples already"), std::string::npos);
    const json resumed =
        waitForRun(startRun({{"text", tinySpec()}, {"out", "datasets/run"}, {"resume", true}}));
    EXPECT_EQ(resumed["state"], "done") << resumed;
    EXPECT_EQ(resumed["kept"], 2);
    EXPECT_EQ(resumed["done"], 4);
    EXPECT_TRUE(fs::is_regular_file(out("datasets/run/samples/000003/rgb.png")));

    // Hostile values: refused before anything is written.
    fs::remove_all(at("direct"));
    const auto before = names();
    const std::vector<std::pair<json, int>> refused = {
        {{{"text", tinySpec()}, {"out", "../escape"}}, 403},
        {{{"text", tinySpec()}, {"out", at("abs")}}, 403},
        {{{"text", tinySpec()}, {"out", ""}}, 400},
        {{{"text", tinySpec()}}, 400},
        {{{"text", tinySpec()}, {"out", "x"}, {"samples", 0}}, 400},
        {{{"text", tinySpec()}, {"out", "x"}, {"samples", -3}}, 400},
        {{{"text", tinySpec()}, {"out", "x"}, {"samples", 1e12}}, 400},
        {{{"text", tinySpec()}, {"out", "x"}, {"samples", 10000001}}, 400},
        {{{"text", tinySpec()}, {"out", "x"}, {"resume", "yes"}}, 400},
        {{{"text", "{\"plantarch_dataset\": 1}"}, {"out", "x"}}, 400},
        {{{"path", "/etc/passwd"}, {"out", "x"}}, 403},
    };
    for (const auto& [request, status] : refused) {
        r = post("/api/dataset/runs", request);
        ASSERT_TRUE(r);
        EXPECT_EQ(r->status, status) << request.dump().substr(0, 200) << ": " << r->body;
        EXPECT_EQ(errorOf(r).find('\n'), std::string::npos);
    }
    EXPECT_NE(
        errorOf(post("/api/dataset/runs", {{"text", tinySpec()}, {"out", "x"}, {"samples", 1e12}}))
            .find("samples = 1000000000000.0: out of range (valid: 1 to 10000000)"),
        std::string::npos);
    fs::remove_all(at("direct"));
    EXPECT_EQ(names(), before);
    // A file where the folder would be.
    std::ofstream(out("file")) << "x";
    r = post("/api/dataset/runs", {{"text", tinySpec()}, {"out", "file"}});
    EXPECT_EQ(r->status, 400);
    EXPECT_NE(errorOf(r).find("not a folder"), std::string::npos) << errorOf(r);
    // A symbolic link out of the output folder.
    fs::create_directories(at("elsewhere"));
    fs::create_directory_symlink(at("elsewhere"), out("link"));
    EXPECT_EQ(post("/api/dataset/runs", {{"text", tinySpec()}, {"out", "link/run"}})->status, 403);
    EXPECT_TRUE(fs::is_empty(at("elsewhere")));
}

TEST_F(BuilderDataset, OneRunAtATimeCancelledWithNothingHalfWritten) {
    // Parallel requests: one run starts, the others are refused.
    std::atomic<int> started{0}, busy{0};
    std::string id;
    std::mutex idLock;
    std::vector<std::thread> threads;
    for (int t = 0; t < 4; ++t)
        threads.emplace_back([&, t] {
            httplib::Client c("127.0.0.1", port_);
            c.set_read_timeout(60, 0);
            auto r = c.Post(
                "/api/dataset/runs", {{"Origin", origin()}},
                json({{"text", tinyWith(100000)}, {"out", "many" + std::to_string(t)}}).dump(),
                "application/json");
            if (r && r->status == 202) {
                ++started;
                std::lock_guard<std::mutex> lock(idLock);
                id = json::parse(r->body)["id"];
            } else if (r && r->status == 409) {
                ++busy;
            }
        });
    for (std::thread& t : threads) t.join();
    ASSERT_EQ(started, 1);
    EXPECT_EQ(busy, 3);
    // Progress, then cancel.
    json state;
    for (int i = 0; i < 3000; ++i) {
        state = body(client_->Get(("/api/dataset/runs/" + id).c_str()));
        if (state["done"].get<int>() >= 2) break;
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    EXPECT_EQ(state["state"], "running");
    EXPECT_EQ(state["total"], 100000);
    EXPECT_GE(state["done"].get<int>(), 2);
    EXPECT_TRUE(state["seconds_left"].is_number());
    EXPECT_EQ(body(cancel(id))["state"], "cancelling");
    const json end = waitForRun(id);
    EXPECT_EQ(end["state"], "cancelled") << end;
    EXPECT_TRUE(end["error"].is_null());
    // Only whole samples, nothing temporary, no index.
    fs::path folder;
    for (int t = 0; t < 4; ++t)
        if (fs::exists(out("many" + std::to_string(t)))) folder = out("many" + std::to_string(t));
    ASSERT_FALSE(folder.empty());
    EXPECT_FALSE(fs::exists(folder / ".partial"));
    EXPECT_FALSE(fs::exists(folder / "dataset.json"));
    std::size_t samples = 0;
    for (const auto& e : fs::directory_iterator(folder / "samples")) {
        ++samples;
        EXPECT_TRUE(fs::is_regular_file(e.path() / "metadata.json")) << e.path();
    }
    EXPECT_EQ(samples, end["done"].get<std::size_t>());
    // A finished run is forgotten on DELETE.
    EXPECT_EQ(body(cancel(id))["state"], "deleted");
    EXPECT_EQ(client_->Get(("/api/dataset/runs/" + id).c_str())->status, 404);
    EXPECT_EQ(cancel("d999")->status, 404);

    // Cancelled while its first sample is being built: the folder it made is gone.
    const std::string slow = startRun({{"text", slowSpec()}, {"out", "slow"}});
    std::this_thread::sleep_for(std::chrono::milliseconds(30));
    cancel(slow);
    const json stopped = waitForRun(slow);
    EXPECT_TRUE(stopped["state"] == "cancelled" || stopped["state"] == "done") << stopped;
    if (stopped["done"] == 0) {
        EXPECT_FALSE(fs::exists(out("slow")));
    }
    EXPECT_FALSE(fs::exists(out("slow/.partial")));

    // A run under way when the server stops: cancelled, its thread joined, nothing partial.
    startRun({{"text", tinyWith(100000)}, {"out", "stopped"}});
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    stop();
    EXPECT_FALSE(fs::exists(out("stopped/.partial")));
    EXPECT_FALSE(fs::exists(out("stopped/dataset.json")));
}
