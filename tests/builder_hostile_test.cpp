// The builder's server against hostile requests (issue 41): JSON nested 100,000 deep in any
// field, numbers beyond a double's range, species whose files are /etc/passwd, a directory or a
// FIFO (refused, and the file's bytes never served in any export), textures reaching the scene
// through an obstacle's materials, a second server on a port in use; requests handled in
// process without sockets (Server::handle, as fuzz/fuzz_builder.cpp runs them).

#include <sys/stat.h>

#include "builder_fixture.h"
#include "cli_run.h"
#include "plantarch/Error.h"
#include "plantarch/Render.h"
#include "plantarch/SpeciesIO.h"

namespace {

using BuilderHostile = BuilderServer;

// `depth` '[' then as many ']'.
std::string nested(std::size_t depth) {
    return std::string(depth, '[') + std::string(depth, ']');
}

std::string errorOf(const httplib::Result& r) {
    if (!r) return "no answer";
    const json j = json::parse(r->body, nullptr, false);
    return j.is_object() && j.contains("error") ? j["error"].get<std::string>() : r->body;
}

// The first line of /etc/passwd, the file a hostile species names.
std::string passwdLine() {
    std::ifstream in("/etc/passwd");
    std::string line;
    std::getline(in, line);
    return line;
}

}  // namespace

TEST_F(BuilderHostile, JSONNestedDeepInAnyFieldIsRefusedAndTheServerServesOn) {
    const std::string deep = nested(100000);  // 200 KB
    const std::vector<std::pair<std::string, std::string>> requests = {
        {"/api/species/check", "{\"base\": \"bean\", \"changes\": " + deep + "}"},
        {"/api/species/check", "{\"base\": " + deep + "}"},
        {"/api/builds", "{\"project\": " + deep + "}"},
        {"/api/builds", "{\"project\": {\"plantarch_project\": 1, \"name\": " + deep + "}}"},
        {"/api/builds", "{\"from\": " + deep + ", \"project\": {}}"},
        {"/api/export", "{\"build\": " + deep + "}"},
        {"/api/projects/save", "{\"name\": \"x\", \"project\": {\"blocks\": [" + deep + "]}}"},
        {"/api/builds", deep},
    };
    for (const auto& [path, text] : requests) {
        auto r = client_->Post(path.c_str(), {{"Origin", origin()}}, text, "application/json");
        ASSERT_TRUE(r) << path << ": the server did not answer";
        EXPECT_EQ(r->status, 400) << path;
        EXPECT_NE(errorOf(r).find("nested too deep (valid: arrays and objects nested at most 64"),
                  std::string::npos)
            << errorOf(r);
        EXPECT_EQ(client_->Get("/api/config")->status, 200);
    }
    EXPECT_EQ(
        errorOf(client_->Post("/api/builds", {{"Origin", origin()}},
                              "{\"project\": {\"blocks\": [" + deep + "]}}", "application/json")),
        "project/blocks/0/0/0/0/0/0/...: JSON nested too deep (valid: arrays and objects "
        "nested at most 64 deep)");
    // 64 deep is read (and refused as a project for what it is).
    const std::string ok =
        "{\"project\": {\"plantarch_project\": 1, \"name\": " + nested(62) + "}}";
    auto r = client_->Post("/api/builds", {{"Origin", origin()}}, ok, "application/json");
    ASSERT_TRUE(r);
    EXPECT_EQ(r->status, 400);
    EXPECT_NE(errorOf(r).find("project: name = [[[["), std::string::npos) << errorOf(r);
    // And builds as before.
    EXPECT_EQ(waitFor(build(beans(1, 1, 8)))["state"], "done");
}

TEST_F(BuilderHostile, ANumberBeyondADoublesRangeIsNamedWithItsField) {
    json project = beans(1, 1, 8);
    std::string text = json({{"project", project}}).dump();
    text.replace(text.find("\"age\":8"), 7, "\"age\":1e400");
    auto r = client_->Post("/api/builds", {{"Origin", origin()}}, text, "application/json");
    ASSERT_TRUE(r);
    EXPECT_EQ(r->status, 400);
    EXPECT_EQ(errorOf(r),
              "project/blocks/0/age = 1e400: a number beyond the range of numbers (valid: "
              "numbers of at most about 1.8e308 in size; each field's own range is smaller)");
    auto bad = client_->Post("/api/builds", {{"Origin", origin()}}, "{\"project\": [1, -1e999]}",
                             "application/json");
    EXPECT_NE(errorOf(bad).find("project/1 = -1e999: a number beyond"), std::string::npos)
        << errorOf(bad);
    // Not JSON at all: the parser's reason, cut short, and the line.
    auto broken =
        client_->Post("/api/builds", {{"Origin", origin()}},
                      "{\n\"project\": \"" + std::string(100000, 'x'), "application/json");
    EXPECT_EQ(broken->status, 400);
    EXPECT_LT(errorOf(broken).size(), 300u) << errorOf(broken);
    EXPECT_NE(errorOf(broken).find("(line 2)"), std::string::npos) << errorOf(broken);
}

TEST_F(BuilderHostile, ASpeciesNamingAFileOutsideItsFoldersIsRefused) {
    const std::string texture = "shoot_types.trifoliate.phytomer.internode.image_texture";
    const std::string model = "shoot_types.trifoliate.phytomer.leaf.prototype.OBJ_model_file";
    fs::create_directories(at("out/textures/folder"));
    ASSERT_EQ(mkfifo(at("out/textures/pipe").c_str(), 0600), 0);
    fs::create_directory_symlink("/etc", at("out/textures/etc"));
    const std::string output = fs::canonical(at("out")).string();
    struct Case {
        std::string key, value;
        int status;
        std::string error;
    };
    const std::vector<Case> cases = {
        {texture, "/etc/passwd", 403,
         ": a file outside the builder's folders (valid: a file under " + output},
        {model, "/etc/passwd", 403, ": a file outside the builder's folders"},
        {texture, at("out/textures/etc/passwd"), 403, ": a file outside the builder's folders"},
        {texture, "../../../../../../../../etc/passwd", 403, ": a file outside"},
        {texture, at("out/textures/folder"), 400, ": a directory (valid: a file under"},
        {texture, at("out/textures/pipe"), 400, ": not a regular file (a pipe, socket or device)"},
        {texture, at("out/textures/none.png"), 400, ": no such file (valid: a file under"},
        {"shoot_types.trifoliate.phytomer.inflorescence.flower_prototype_function",
         "/etc/x/flower.obj", 400, ": no such file"},
    };
    for (const char* route : {"/api/species/check", "/api/species/save"})
        for (const Case& c : cases) {
            auto r =
                post(route, {{"base", "bean"}, {"name", "evil"}, {"changes", {{c.key, c.value}}}});
            ASSERT_TRUE(r);
            EXPECT_EQ(r->status, c.status) << route << " " << c.value << ": " << r->body;
            // The parameter, the value (cut at 80 bytes), what is wrong, the folders.
            EXPECT_EQ(errorOf(r).rfind(c.key + " = \"" + c.value.substr(0, 60), 0), 0u)
                << errorOf(r);
            EXPECT_NE(errorOf(r).find(c.error), std::string::npos) << errorOf(r);
        }
    EXPECT_FALSE(fs::exists(at("out/species/evil.xml")));

    // A texture under the output folder is fine; the scene embeds it.
    plantarch::Image image(4, 4);
    put(at("out/textures/bark.png"), plantarch::encodePNG(image));
    auto fine = post("/api/species/save", {{"base", "bean"},
                                           {"name", "barked"},
                                           {"changes", {{texture, at("out/textures/bark.png")}}}});
    ASSERT_TRUE(fine);
    EXPECT_EQ(fine->status, 200) << fine->body;
}

TEST_F(BuilderHostile, ASpeciesFileNamingPasswdIsNeitherBuiltNorServed) {
    const std::string secret = passwdLine();
    ASSERT_FALSE(secret.empty());
    // Written by hand (not through the builder) into its species folder.
    const plantarch::SpeciesModel evil = plantarch::editSpecies(
        plantarch::loadSpecies("bean"),
        {{"shoot_types.trifoliate.phytomer.internode.image_texture", "/etc/passwd"}}, "evil");
    plantarch::writeSpeciesFile(evil, at("out/species/evil.xml"));
    json project = beans(1, 1, 12);
    project["blocks"][0]["species"] = "evil";
    auto r = post("/api/builds", {{"project", project}});
    ASSERT_TRUE(r);
    EXPECT_EQ(r->status, 403) << r->body;
    EXPECT_EQ(errorOf(r),
              "project: blocks/0/species = \"evil\": "
              "shoot_types.trifoliate.phytomer.internode.image_texture = \"/etc/passwd\": a file "
              "outside the builder's folders (valid: a file under " +
                  fs::canonical(at("out")).string() + " or " +
                  fs::canonical(plantarch::speciesLibraryDirectory()).string() + ")");
    project["blocks"][0]["species"] = "../species/evil.xml";
    EXPECT_EQ(post("/api/builds", {{"project", project}})->status, 403);
    EXPECT_EQ(post("/api/projects/save", {{"name", "p"}, {"project", project}})->status, 403);
    auto thumb = client_->Get("/api/species/evil/thumbnail.png");
    ASSERT_TRUE(thumb);
    EXPECT_EQ(thumb->status, 403);
    EXPECT_EQ(thumb->body.find(secret), std::string::npos);
    // The species itself is listed and shown (its parameters name the file, nothing reads it).
    EXPECT_EQ(client_->Get("/api/species/evil")->status, 200);
    // No build holds it: no export of any build serves the file.
    const std::string id = build(beans(1, 1, 8));
    ASSERT_EQ(waitFor(id)["state"], "done");
    for (const char* format : {"glb", "gltf", "obj", "usda"}) {
        auto d = client_->Get(
            ("/api/export/download?build=" + id + "&format=" + format + "&per_plant=true").c_str());
        ASSERT_TRUE(d && d->status == 200) << format;
        EXPECT_EQ(d->body.find(secret), std::string::npos) << format;
    }
    EXPECT_EQ(client_->Get(("/api/builds/" + id + "/scene.glb").c_str())->body.find(secret),
              std::string::npos);
}

TEST_F(BuilderHostile, ATextureReachingTheSceneThroughAnObstacleFailsTheBuild) {
    // An obstacle under the output folder whose material names /etc/passwd as its texture.
    put(at("out/wall.obj"),
        "mtllib wall.mtl\nusemtl m\nv 0 0 0\nv 1 0 0\nv 1 0 1\nvt 0 0\nvt 1 0\nvt 1 1\n"
        "f 1/1 2/2 3/3\n");
    put(at("out/wall.mtl"), "newmtl m\nKd 0.5 0.5 0.5\nmap_Kd /etc/passwd\n");
    json project = beans(1, 1, 8);
    project["obstacles"] = {{"files", {"../wall.obj"}}};
    auto r = post("/api/builds", {{"project", project}});
    ASSERT_TRUE(r);
    if (r->status != 202) {  // the OBJ reader refused the texture itself: as good
        EXPECT_EQ(r->status, 400) << r->body;
        return;
    }
    const std::string id = body(r)["id"].get<std::string>();
    const json state = waitFor(id);
    EXPECT_EQ(state["state"], "failed");
    EXPECT_NE(state["error"].get<std::string>().find("texture = /etc/passwd"), std::string::npos)
        << state.dump();
    EXPECT_NE(client_->Get(("/api/builds/" + id + "/scene.glb").c_str())->status, 200);
}

TEST_F(BuilderHostile, RequestsAreHandledInProcessWithoutSockets) {
    using Server = plantarch::builder::Server;
    const std::vector<std::pair<std::string, std::string>> host = {
        {"Host", "127.0.0.1:" + std::to_string(port_)}};
    Server::Reply config = server_->handle("GET", "/api/config", host);
    EXPECT_EQ(config.status, 200);
    EXPECT_EQ(config.contentType, "application/json");
    EXPECT_EQ(json::parse(config.body)["max_json_depth"], 64);
    EXPECT_EQ(server_->handle("GET", "/api/config", {{"Host", "evil.example"}}).status, 403);
    EXPECT_EQ(server_->handle("GET", "/api/species/a.b", host).status, 400);
    EXPECT_EQ(server_->handle("GET", "/api/species/bean", host).status, 200);
    EXPECT_EQ(server_->handle("PATCH", "/api/config", host).status, 404);
    // A path with an encoded line break (cpp-httplib decodes it) is quoted on one line (the
    // fuzzer's second finding).
    const Server::Reply newline = server_->handle("GET", "/0%0api/x", host);
    EXPECT_EQ(newline.status, 404);
    EXPECT_EQ(json::parse(newline.body)["error"], "no such endpoint: GET /0\\npi/x");
    auto viaSocket = client_->Get("/api/x%0ay");
    ASSERT_TRUE(viaSocket);
    EXPECT_EQ(errorOf(viaSocket), "no such endpoint: GET /api/x\\ny");
    const Server::Reply deep =
        server_->handle("POST", "/api/species/check", host, "{\"base\": " + nested(100000) + "}");
    EXPECT_EQ(deep.status, 400);
    EXPECT_EQ(server_->handle("POST", "/api/builds", host, std::string(5u << 20, ' ')).status, 413);
    const Server::Reply download =
        server_->handle("GET", "/api/export/download?build=b9&per_plant=maybe", host);
    EXPECT_EQ(download.status, 400);
    EXPECT_NE(download.body.find("per_plant = maybe"), std::string::npos) << download.body;
    // A handler that sets only the content answers 200, as through cpp-httplib (the fuzzer's
    // first finding: a zip download answered -1).
    const std::string id = build(beans(2, 1, 8));
    ASSERT_EQ(waitFor(id)["state"], "done");
    const Server::Reply zip = server_->handle(
        "GET", "/api/export/download?build=" + id + "&format=ply&per_plant=true&name=f", host);
    EXPECT_EQ(zip.status, 200);
    EXPECT_EQ(zip.contentType, "application/zip");
    EXPECT_EQ(zip.body.substr(0, 2), "PK");
}

TEST_F(BuilderHostile, APortInUseIsRefused) {
    plantarch::builder::ServerOptions o;
    o.port = port_;
    o.output = at("second");
    plantarch::builder::Server second(o);
    try {
        second.bind();
        FAIL() << "a second server bound port " << port_;
    } catch (const plantarch::Error& e) {
        EXPECT_EQ(std::string(e.what()),
                  "--port = " + std::to_string(port_) +
                      ": cannot listen on 127.0.0.1:" + std::to_string(port_) +
                      ": the port is in use (another program listens on it) (valid: a free port, "
                      "or 0 for any free port)");
    }
    // The command: one line, exit 2 (timeout stops one that would serve).
    const auto r = cli::runShell("timeout 20 " + std::string(PLANTARCH_CLI) + " builder --port " +
                                 std::to_string(port_) + " --output " + at("third") + " 2>&1");
    EXPECT_EQ(r.status, 2) << r.out;
    EXPECT_EQ(r.out, "plantarch: --port = " + std::to_string(port_) +
                         ": cannot listen on 127.0.0.1:" + std::to_string(port_) +
                         ": the port is in use (another program listens on it) (valid: a free "
                         "port, or 0 for any free port)\n");
    EXPECT_EQ(client_->Get("/api/config")->status, 200);  // the first serves on
}

// A skeleton block's file: bad text, outside the output folder, a FIFO, a directory, missing:
// each refused before it is queued with one line naming the field, and the server serves on.
TEST_F(BuilderHostile, ABadSkeletonFileIsOneLineAndNeverACrash) {
    fs::create_directories(at("out/skeletons/folder.csv"));
    put(at("out/skeletons/bad.csv"), "id,parent,x,y,z\n0,,0,0,0\n1,0,nan,0,1\n");
    put(at("out/skeletons/cycle.csv"), "id,parent,x,y,z\n0,1,0,0,0\n1,0,0,0,1\n");
    put(at("out/skeletons/bad.json"), "{\"nodes\": [[[[\n");
    put(at("out/skeletons/bad.mtg"), "MTG:\nnothing here\n");
    put(at("outside.csv"), "id,parent,x,y,z\n0,,0,0,0\n1,0,0,0,0.1\n");
    ASSERT_EQ(mkfifo(at("out/skeletons/pipe.csv").c_str(), 0600), 0);
    const std::string field = "project: blocks/0/skeleton/file";
    const struct {
        std::string file;
        int status;
        std::string expected;  // in the error
    } cases[] = {
        {"../skeletons/bad.csv", 400, "bad.csv:3"},
        {"../skeletons/cycle.csv", 400, "cycle.csv"},
        {"../skeletons/bad.json", 400, "bad.json"},
        {"../skeletons/bad.mtg", 400, "bad.mtg"},
        {"../skeletons/pipe.csv", 400, field + " = "},
        {"../skeletons/folder.csv", 400, field + " = "},
        {"../skeletons/missing.csv", 400, field + " = "},
        {"../../outside.csv", 403, field + " = \"../../outside.csv\": outside the output folder"},
        {"/etc/passwd", 403, field + " = \"/etc/passwd\": outside the output folder"},
        {"../skeletons/notes.txt", 400, ""},
    };
    for (const auto& c : cases) {
        json project = {{"plantarch_project", 1},
                        {"blocks",
                         {{{"species", "capsicum"},
                           {"layout", "skeleton"},
                           {"skeleton", {{"file", c.file}}}}}}};
        auto r = post("/api/builds", {{"project", project}});
        ASSERT_TRUE(r) << c.file;
        EXPECT_EQ(r->status, c.status) << c.file << ": " << r->body;
        const std::string error = errorOf(r);
        EXPECT_NE(error.find(c.expected), std::string::npos) << c.file << ": " << error;
        EXPECT_EQ(error.find('\n'), std::string::npos) << error;
    }
    // A skeleton block without its file, and a field of another layout.
    auto r =
        post("/api/builds", {{"project",
                              {{"plantarch_project", 1},
                               {"blocks", {{{"species", "capsicum"}, {"layout", "skeleton"}}}}}}});
    EXPECT_EQ(errorOf(r),
              "project: blocks/0/skeleton: missing (valid: {\"file\": \"plant.csv\", "
              "\"unit\": 1, \"spacing\": 0})");
    EXPECT_EQ(client_->Get("/api/config")->status, 200);
}
