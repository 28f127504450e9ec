#pragma once
// The fixture of the builder's server tests: a server started in-process on a free port, its
// output folder in the test's folder, used through cpp-httplib's client as the web page uses
// it (builder_server_test.cpp, builder_hostile_test.cpp).

#include <gtest/gtest.h>
#include <httplib.h>

#include <chrono>
#include <nlohmann/json.hpp>
#include <thread>

#include "builder/server/server.h"
#include "folder_test.h"

namespace fs = std::filesystem;
using json = nlohmann::json;

class BuilderServer : public FolderTest {
protected:
    BuilderServer() : FolderTest("plantarch-builder-server-") {}

    void SetUp() override {
        FolderTest::SetUp();
        start({});
    }
    void TearDown() override {
        stop();
        FolderTest::TearDown();
    }

    void start(plantarch::builder::ServerOptions o) {
        o.port = 0;
        o.output = at("out");
        server_ = std::make_unique<plantarch::builder::Server>(o);
        port_ = server_->bind();
        thread_ = std::thread([this] { server_->serve(); });
        client_ = std::make_unique<httplib::Client>("127.0.0.1", port_);
        client_->set_read_timeout(120, 0);
        for (int i = 0; i < 200 && !client_->Get("/api/config"); ++i)
            std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    void stop() {
        if (!server_) return;
        server_->stop();
        thread_.join();
        server_.reset();
    }

    std::string origin() const { return "http://127.0.0.1:" + std::to_string(port_); }
    httplib::Result post(const std::string& path, const json& body) {
        return client_->Post(path.c_str(), {{"Origin", origin()}}, body.dump(), "application/json");
    }
    static json body(const httplib::Result& r) { return json::parse(r->body); }

    // Polls a build until it is no longer queued or running.
    json waitFor(const std::string& id) {
        for (int i = 0; i < 6000; ++i) {
            auto r = client_->Get(("/api/builds/" + id).c_str());
            if (!r || r->status != 200) return json{{"state", "missing"}};
            json j = body(r);
            if (j["state"] != "queued" && j["state"] != "running") return j;
            std::this_thread::sleep_for(std::chrono::milliseconds(20));
        }
        return json{{"state", "timeout"}};
    }
    std::string build(const json& project, const std::string& from = "") {
        json request = {{"project", project}};
        if (!from.empty()) request["from"] = from;
        auto r = post("/api/builds", request);
        EXPECT_TRUE(r && r->status == 202) << (r ? r->body : "no answer");
        return r && r->status == 202 ? body(r)["id"].get<std::string>() : "";
    }

    std::unique_ptr<plantarch::builder::Server> server_;
    std::unique_ptr<httplib::Client> client_;
    std::thread thread_;
    int port_ = 0;
};

/// A project of one grid block of beans.
inline json beans(int nx, int ny, double age) {
    return {{"plantarch_project", 1},
            {"name", "beans"},
            {"seed", 5},
            {"blocks",
             {{{"name", "A"},
               {"species", "bean"},
               {"count", {nx, ny}},
               {"spacing", {0.3, 0.3}},
               {"age", age}}}}};
}
