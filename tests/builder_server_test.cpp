// The project builder's server (builder/server/), started in-process on a free port and used
// through cpp-httplib's client as the web page uses it: every endpoint's answers and errors,
// the security checks (Host, Origin, body size, paths out of the output folder), cancelling,
// growing on, and a saved project that `plantarch project run` reproduces byte for byte.

#include <gtest/gtest.h>
#include <httplib.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <nlohmann/json.hpp>
#include <thread>

#include "builder_fixture.h"
#include "cli_run.h"
#include "plantarch/Export.h"
#include "plantarch/NumberRange.h"
#include "plantarch/OutputFormats.h"
#include "plantarch/Project.h"

TEST_F(BuilderServer, ServesThePageAndItsConfig) {
    auto page = client_->Get("/");
    ASSERT_TRUE(page);
    EXPECT_EQ(page->status, 200);
    EXPECT_EQ(page->get_header_value("Content-Type"), "text/html; charset=utf-8");
    EXPECT_NE(page->body.find("<"), std::string::npos);
    auto config = client_->Get("/api/config");
    ASSERT_TRUE(config && config->status == 200);
    EXPECT_EQ(body(config)["output"], fs::canonical(at("out")).string());
    auto missing = client_->Get("/api/nothing");
    ASSERT_TRUE(missing);
    EXPECT_EQ(missing->status, 404);
    EXPECT_NE(body(missing)["error"].get<std::string>().find("no such endpoint"),
              std::string::npos);
    EXPECT_EQ(client_->Get("/no-such-file.js")->status, 404);
}

// GET /api/defaults: what the page takes instead of restating it, equal to the C++ declarations
// (Project.h's defaults, the organ label colours, the builder's export formats).
TEST_F(BuilderServer, ServesTheDefaultsOfTheCppDeclarations) {
    using namespace plantarch;
    auto r = client_->Get("/api/defaults");
    ASSERT_TRUE(r && r->status == 200);
    const json d = body(r);
    const Project def;
    const Project served = readProjectString(d["project"].dump(), "defaults");
    EXPECT_EQ(served.seed, def.seed);
    EXPECT_EQ(served.meshDetail, def.meshDetail);
    EXPECT_FALSE(served.ground);
    EXPECT_EQ(served.softCollision, def.softCollision);
    EXPECT_EQ(served.softCone.halfAngle, def.softCone.halfAngle);
    EXPECT_EQ(served.softCone.lookAhead, def.softCone.lookAhead);
    EXPECT_EQ(served.softCone.rays, def.softCone.rays);
    EXPECT_EQ(served.softCone.inertia, def.softCone.inertia);
    EXPECT_EQ(served.avoidDistance, def.avoidDistance);
    EXPECT_EQ(served.fruitAdjustment, def.fruitAdjustment);
    EXPECT_EQ(served.attraction, def.attraction);
    EXPECT_EQ(served.attractionCone.halfAngle, def.attractionCone.halfAngle);
    EXPECT_EQ(served.attractionCone.lookAhead, def.attractionCone.lookAhead);
    EXPECT_EQ(served.attractionCone.inertia, def.attractionCone.inertia);
    EXPECT_TRUE(served.blocks.empty());
    const ProjectGround ground;
    EXPECT_EQ(d["ground"], json({{"size", {ground.size.x, ground.size.y}},
                                 {"center", {ground.center.x, ground.center.y}}}));
    const ProjectBlock block;
    for (const char* layout : {"grid", "scatter", "single"}) {
        json b = d["blocks"][layout];
        b["species"] = "bean";
        const json file = {{"plantarch_project", 1}, {"blocks", {b}}};
        const ProjectBlock read = readProjectString(file.dump(), layout).blocks.at(0);
        EXPECT_EQ(b["layout"], layout);
        EXPECT_EQ(read.origin, block.origin) << layout;
        EXPECT_EQ(read.count, block.count) << layout;
        EXPECT_EQ(read.spacing, block.spacing) << layout;
        EXPECT_EQ(read.area, block.area) << layout;
        EXPECT_EQ(read.plants, block.plants) << layout;
        EXPECT_EQ(read.germination, block.germination) << layout;
        EXPECT_EQ(read.age, block.age) << layout;
        EXPECT_EQ(read.seed, block.seed) << layout;
        EXPECT_EQ(read.parameters, block.parameters) << layout;
        EXPECT_EQ(read.trellis, block.trellis) << layout;
    }
    // A season's defaults: a project of it reads back as the default season.
    const ProjectPhysiology season;
    json readable = {
        {"plantarch_project", 1}, {"blocks", json::array()}, {"physiology", d["physiology"]}};
    readable["physiology"]["carbon"] = true;  // a season needs a model to be read
    const ProjectPhysiology read = readProjectString(readable.dump(), "season").physiology.value();
    EXPECT_FALSE(d["physiology"]["carbon"].get<bool>());
    EXPECT_EQ(d["physiology"]["nitrogen"].get<bool>(), season.season.nitrogen);
    EXPECT_EQ(read.days, season.days);
    EXPECT_EQ(read.season.clearness, season.season.clearness);
    EXPECT_EQ(read.season.lightEvery, season.season.lightEvery);
    EXPECT_TRUE(read.season.fertilise.empty());
    EXPECT_TRUE(read.weatherFile.empty());
    EXPECT_EQ(d["organ_colors"].size(), kOrganLabels.size());
    for (std::string_view organ : kOrganLabels)
        EXPECT_EQ(d["organ_colors"][std::string(organ)], json(organLabelColor(organ))) << organ;
    for (const OrganLabelColor& c : organLabelColors())
        EXPECT_EQ(d["organ_colors"][std::string(c.organ)], json(c.rgb)) << c.organ;
    std::vector<std::string> formats;
    for (const OutputFormat& f : outputFormats())
        if (f.uses & kBuilderExport) {
            formats.emplace_back(f.extension.substr(1));
            EXPECT_NE(std::find(d["export_formats"].begin(), d["export_formats"].end(),
                                json({{"format", formats.back()},
                                      {"description", std::string(f.description)}})),
                      d["export_formats"].end())
                << f.extension;
        }
    EXPECT_EQ(d["export_formats"].size(), formats.size());
    EXPECT_EQ(body(client_->Get("/api/config"))["formats"], json(formats));
}

TEST_F(BuilderServer, ListsSpeciesWithTheirParameters) {
    auto list = client_->Get("/api/species");
    ASSERT_TRUE(list && list->status == 200);
    bool bean = false, vine = false;
    for (const json& s : body(list)) {
        if (s["name"] == "bean") {
            bean = true;
            EXPECT_EQ(s["latin_name"], "Phaseolus vulgaris");
            EXPECT_EQ(s["recommended_age"]["default"], 45);
            EXPECT_EQ(s["user"], false);
            EXPECT_EQ(s["trellis"], false);
        }
        if (s["name"] == "grapevine_VSP") {
            vine = true;
            EXPECT_EQ(s["trellis"], true);
        }
    }
    EXPECT_TRUE(bean && vine);
    auto one = client_->Get("/api/species/bean");
    ASSERT_TRUE(one && one->status == 200);
    const json j = body(one);
    ASSERT_TRUE(j["shoot_types"].contains("trifoliate"));
    bool pitch = false;
    for (const json& p : j["shoot_types"]["trifoliate"])
        if (p["path"] == "phytomer.internode.pitch") {
            pitch = true;
            EXPECT_EQ(p["unit"], "degrees");
            EXPECT_EQ(p["min"], -180);
            EXPECT_EQ(p["range"], "-180 to 180");
            EXPECT_EQ(p["value"], "20");
        }
    EXPECT_TRUE(pitch);
    EXPECT_FALSE(j["phenology"].empty());
    EXPECT_EQ(client_->Get("/api/species/nosuch")->status, 404);
    EXPECT_EQ(client_->Get("/api/species/a.b")->status, 400);
    auto apple = body(client_->Get("/api/species/apple"));
    EXPECT_FALSE(apple["build_parameters"].empty());
    // A build parameter's range in the library's wording, from its float bounds.
    for (const json& b : apple["build_parameters"])
        EXPECT_EQ(b["range"],
                  plantarch::rangeText(
                      {.min = b["min"].get<float>(), .max = b["max"].get<float>(), .single = true}))
            << b["name"];
}

TEST_F(BuilderServer, DrawsAThumbnail) {
    auto png = client_->Get("/api/species/strawberry/thumbnail.png");
    ASSERT_TRUE(png && png->status == 200);
    EXPECT_EQ(png->get_header_value("Content-Type"), "image/png");
    EXPECT_EQ(png->body.substr(1, 3), "PNG");
    EXPECT_EQ(client_->Get("/api/species/strawberry/thumbnail.png")->body, png->body);
}

TEST_F(BuilderServer, ChecksAndSavesAnEditedSpecies) {
    const json good = {{"base", "bean"},
                       {"name", "my_bean"},
                       {"changes",
                        {{"shoot_types.trifoliate.phytomer.internode.pitch", "uniform(10, 30)"},
                         {"phenology.max_age", "200"}}}};
    auto ok = post("/api/species/check", good);
    ASSERT_TRUE(ok);
    EXPECT_EQ(ok->status, 200) << ok->body;
    auto bad = post("/api/species/check",
                    {{"base", "bean"},
                     {"changes", {{"shoot_types.trifoliate.phytomer.internode.pitch", "200"}}}});
    ASSERT_TRUE(bad);
    EXPECT_EQ(bad->status, 400);
    EXPECT_EQ(body(bad)["error"],
              "trifoliate.phytomer.internode.pitch = 200: out of range (valid: "
              "-180 to 180)");
    auto typo = post(
        "/api/species/check",
        {{"base", "bean"}, {"changes", {{"shoot_types.trifoliate.phytomer.internode.ptch", "2"}}}});
    EXPECT_EQ(typo->status, 400);
    EXPECT_NE(body(typo)["error"].get<std::string>().find("did you mean"), std::string::npos);
    auto word = post("/api/species/check",
                     {{"base", "bean"}, {"changes", {{"phenology.max_age", "long"}}}});
    EXPECT_EQ(word->status, 400) << word->body;

    auto saved = post("/api/species/save", good);
    ASSERT_TRUE(saved && saved->status == 200) << saved->body;
    EXPECT_EQ(body(saved)["path"], "species/my_bean.xml");
    const std::string file = at("out/species/my_bean.xml");
    ASSERT_TRUE(fs::exists(file));
    bool listed = false;
    for (const json& s : body(client_->Get("/api/species")))
        if (s["name"] == "my_bean") listed = s["user"] == true;
    EXPECT_TRUE(listed);
    auto mine = body(client_->Get("/api/species/my_bean"));
    bool pitchFound = false;
    for (const json& p : mine["shoot_types"]["trifoliate"])
        if (p["path"] == "phytomer.internode.pitch") {
            pitchFound = true;
            EXPECT_EQ(p["value"], "uniform(10, 30)");
        }
    EXPECT_TRUE(pitchFound) << "the saved species lists no phytomer.internode.pitch";
    const auto r = cli::run("build " + file + " --age 12 -o " + at("mine.obj"));
    EXPECT_EQ(r.status, 0) << r.out;
    // Usable by name in a project.
    json project = beans(1, 1, 12);
    project["blocks"][0]["species"] = "my_bean";
    EXPECT_EQ(waitFor(build(project))["state"], "done");

    auto library = post("/api/species/save", {{"base", "bean"}, {"name", "bean"}});
    EXPECT_EQ(library->status, 400);
    auto badName = post("/api/species/save", {{"base", "bean"}, {"name", "../x"}});
    EXPECT_EQ(badName->status, 400);
    EXPECT_FALSE(fs::exists(at("out/x.xml")));
}

TEST_F(BuilderServer, BuildsAProjectAndServesItsScene) {
    const std::string id = build(beans(2, 2, 20));
    const json done = waitFor(id);
    ASSERT_EQ(done["state"], "done") << done.dump();
    EXPECT_EQ(done["stats"]["plants"], 4);
    EXPECT_GT(done["stats"]["triangles"].get<int>(), 1000);
    EXPECT_EQ(done["blocks"][0]["plants"].size(), 4u);
    EXPECT_EQ(done["ages"][0], 20);
    auto glb = client_->Get(("/api/builds/" + id + "/scene.glb").c_str());
    ASSERT_TRUE(glb && glb->status == 200);
    EXPECT_EQ(glb->body.substr(0, 4), "glTF");
    EXPECT_NE(glb->body.find("\"plantID\""), std::string::npos);
    auto png = client_->Get(("/api/builds/" + id + "/render.png?w=64&h=48").c_str());
    ASSERT_TRUE(png && png->status == 200);
    EXPECT_EQ(png->body.substr(1, 3), "PNG");
    EXPECT_EQ(client_->Get(("/api/builds/" + id + "/render.png?w=5").c_str())->status, 400);
    EXPECT_EQ(client_->Get("/api/builds/b999")->status, 404);
    EXPECT_EQ(client_->Get("/api/builds/b999/scene.glb")->status, 404);

    json bad = beans(2, 2, 20);
    bad["blocks"][0]["count"] = {0, 2};
    auto refused = post("/api/builds", {{"project", bad}});
    ASSERT_TRUE(refused);
    EXPECT_EQ(refused->status, 400);
    EXPECT_EQ(body(refused)["error"],
              "project: blocks/0/count/0 = 0: out of range (valid: whole "
              "numbers 1 to 1000000)");
    auto noProject = post("/api/builds", {{"projekt", bad}});
    EXPECT_EQ(noProject->status, 400);
    auto notJSON =
        client_->Post("/api/builds", {{"Origin", origin()}}, "{nope", "application/json");
    EXPECT_EQ(notJSON->status, 400);

    // Forgotten on DELETE.
    EXPECT_EQ(body(client_->Delete(("/api/builds/" + id).c_str(), {{"Origin", origin()}}))["state"],
              "deleted");
    EXPECT_EQ(client_->Get(("/api/builds/" + id).c_str())->status, 404);
}

TEST_F(BuilderServer, GrowsAnEarlierBuildOnToTheSamePlantsAsAFreshBuild) {
    const std::string first = build(beans(2, 1, 20));
    ASSERT_EQ(waitFor(first)["state"], "done");
    const std::string grown = build(beans(2, 1, 27), first);
    const json g = waitFor(grown);
    ASSERT_EQ(g["state"], "done") << g.dump();
    EXPECT_EQ(g["from"], first);
    EXPECT_EQ(g["ages"][0], 27);
    const std::string freshID = build(beans(2, 1, 27));
    const json fresh = waitFor(freshID);
    EXPECT_EQ(g["stats"]["leaf_count"], fresh["stats"]["leaf_count"]);
    EXPECT_EQ(g["stats"]["triangles"], fresh["stats"]["triangles"]);
    // Its export is the fresh build's, byte for byte (the grown scene numbers its organs in
    // the order they grew; an export writes the project built anew, made once and kept).
    for (const std::string name : {"grown1", "fresh", "grown2"}) {
        const std::string id = name[0] == 'g' ? grown : freshID;
        auto r = post("/api/export", {{"build", id}, {"format", "glb"}, {"name", name}});
        ASSERT_TRUE(r && r->status == 200) << r->body;
    }
    EXPECT_TRUE(existingBytes(at("out/grown1.glb")) == existingBytes(at("out/fresh.glb")));
    EXPECT_TRUE(existingBytes(at("out/grown2.glb")) == existingBytes(at("out/fresh.glb")));
    EXPECT_EQ(client_->Get(("/api/builds/" + first + "/scene.glb").c_str())->status, 410);
    EXPECT_EQ(body(client_->Get(("/api/builds/" + first).c_str()))["taken_by"], grown);
    // Only ages may change, and only forward.
    json other = beans(3, 1, 30);
    const std::string refused = build(other, grown);
    const json r = waitFor(refused);
    EXPECT_EQ(r["state"], "failed");
    EXPECT_NE(r["error"].get<std::string>().find("only block ages"), std::string::npos);
    EXPECT_EQ(client_->Get(("/api/builds/" + grown + "/scene.glb").c_str())->status, 200);
    json younger = beans(2, 1, 21);
    EXPECT_EQ(waitFor(build(younger, grown))["state"], "failed");
    EXPECT_EQ(post("/api/builds", {{"project", beans(2, 1, 30)}, {"from", "b99"}})->status, 404);
}

TEST_F(BuilderServer, CancelsARunningBuildAndRefusesTooManyWaiting) {
    const std::string big = build(beans(12, 12, 45));
    const std::string queued = build(beans(1, 1, 10));
    auto cancel = client_->Delete(("/api/builds/" + big).c_str(), {{"Origin", origin()}});
    ASSERT_TRUE(cancel && cancel->status == 200);
    EXPECT_EQ(body(cancel)["state"], "cancelled");
    const json stopped = waitFor(big);
    EXPECT_EQ(stopped["state"], "cancelled");
    EXPECT_EQ(client_->Get(("/api/builds/" + big + "/scene.glb").c_str())->status, 409);
    EXPECT_EQ(waitFor(queued)["state"], "done");

    // Four may wait; a fifth is refused while one runs.
    const std::string running = build(beans(12, 12, 45));
    std::vector<std::string> waiting;
    for (int i = 0; i < 4; ++i) waiting.push_back(build(beans(1, 1, 5)));
    auto fifth = post("/api/builds", {{"project", beans(1, 1, 5)}});
    ASSERT_TRUE(fifth);
    EXPECT_EQ(fifth->status, 429);
    for (const std::string& id : waiting)
        client_->Delete(("/api/builds/" + id).c_str(), {{"Origin", origin()}});
    client_->Delete(("/api/builds/" + running).c_str(), {{"Origin", origin()}});
    EXPECT_EQ(waitFor(running)["state"], "cancelled");
    for (const std::string& id : waiting) EXPECT_EQ(waitFor(id)["state"], "cancelled");
}

TEST_F(BuilderServer, RefusesRequestsFromOtherSites) {
    const json request = {{"project", beans(1, 1, 5)}};
    auto evil = client_->Post("/api/builds", {{"Origin", "http://evil.example"}}, request.dump(),
                              "application/json");
    ASSERT_TRUE(evil);
    EXPECT_EQ(evil->status, 403);
    EXPECT_NE(body(evil)["error"].get<std::string>().find("Origin"), std::string::npos);
    auto otherPort = client_->Post("/api/builds", {{"Origin", "http://127.0.0.1:1"}},
                                   request.dump(), "application/json");
    EXPECT_EQ(otherPort->status, 403);
    auto nullOrigin =
        client_->Post("/api/builds", {{"Origin", "null"}}, request.dump(), "application/json");
    EXPECT_EQ(nullOrigin->status, 403);
    auto crossSite = client_->Post("/api/builds", {{"Sec-Fetch-Site", "cross-site"}},
                                   request.dump(), "application/json");
    EXPECT_EQ(crossSite->status, 403);
    auto del = client_->Delete("/api/builds/b1", {{"Origin", "http://evil.example"}});
    EXPECT_EQ(del->status, 403);
    // DNS rebinding: another name for this address.
    auto rebound = client_->Get("/api/config", {{"Host", "evil.example:" + std::to_string(port_)}});
    ASSERT_TRUE(rebound);
    EXPECT_EQ(rebound->status, 403);
    // The page's own origin (either name) and tools that send none are served.
    EXPECT_EQ(post("/api/builds", request)->status, 202);
    auto localhost =
        client_->Post("/api/builds", {{"Origin", "http://localhost:" + std::to_string(port_)}},
                      request.dump(), "application/json");
    EXPECT_EQ(localhost->status, 202);
    EXPECT_EQ(client_->Post("/api/builds", request.dump(), "application/json")->status, 202);
}

TEST_F(BuilderServer, RefusesAnOversizedBody) {
    const std::string big(5u << 20, ' ');
    auto r = client_->Post("/api/builds", {{"Origin", origin()}}, big, "application/json");
    ASSERT_TRUE(r);
    EXPECT_EQ(r->status, 413);
    EXPECT_NE(body(r)["error"].get<std::string>().find("too large"), std::string::npos);
    EXPECT_EQ(client_->Get("/api/config")->status, 200);  // still serving
}

TEST_F(BuilderServer, ExportsOnlyUnderTheOutputFolder) {
    const std::string id = build(beans(2, 1, 15));
    ASSERT_EQ(waitFor(id)["state"], "done");
    auto exported =
        post("/api/export",
             {{"build", id}, {"format", "obj"}, {"folder", "trial/day15"}, {"name", "field"}});
    ASSERT_TRUE(exported && exported->status == 200) << exported->body;
    EXPECT_EQ(body(exported)["files"], json({"trial/day15/field.obj", "trial/day15/field.mtl"}));
    EXPECT_TRUE(fs::exists(at("out/trial/day15/field.obj")));
    auto perPlant = post(
        "/api/export",
        {{"build", id}, {"format", "ply"}, {"per_plant", true}, {"folder", "pp"}, {"name", "p"}});
    ASSERT_TRUE(perPlant && perPlant->status == 200) << perPlant->body;
    EXPECT_EQ(body(perPlant)["files"], json({"pp/p_0000.ply", "pp/p_0001.ply", "pp/p_index.json"}));

    fs::create_directories(at("outside"));
    fs::create_directory_symlink(at("outside"), at("out/link"));
    const std::vector<std::pair<json, int>> refused = {
        {{{"build", id}, {"folder", "../escape"}}, 403},
        {{{"build", id}, {"folder", "a/../../escape"}}, 403},
        {{{"build", id}, {"folder", at("outside")}}, 403},
        {{{"build", id}, {"folder", "link"}}, 403},
        {{{"build", id}, {"folder", "link/deeper"}}, 403},
        {{{"build", id}, {"name", "../x"}}, 403},
        {{{"build", id}, {"name", "a b"}}, 400},
        {{{"build", id}, {"format", "stl"}}, 400},
        {{{"build", "b999"}}, 404},
    };
    for (const auto& [request, status] : refused) {
        auto r = post("/api/export", request);
        ASSERT_TRUE(r);
        EXPECT_EQ(r->status, status) << request.dump() << " " << r->body;
    }
    EXPECT_TRUE(fs::is_empty(at("outside")));
    EXPECT_FALSE(fs::exists(at("escape")));
    EXPECT_FALSE(fs::exists(at("x.glb")));
}

TEST_F(BuilderServer, DownloadsOneFileOrAZip) {
    const std::string id = build(beans(2, 1, 15));
    ASSERT_EQ(waitFor(id)["state"], "done");
    auto glb = client_->Get(("/api/export/download?build=" + id + "&format=glb").c_str());
    ASSERT_TRUE(glb && glb->status == 200);
    EXPECT_EQ(glb->body.substr(0, 4), "glTF");
    EXPECT_NE(glb->get_header_value("Content-Disposition").find("scene.glb"), std::string::npos);
    EXPECT_EQ(glb->body, client_->Get(("/api/builds/" + id + "/scene.glb").c_str())->body);
    auto zip = client_->Get(
        ("/api/export/download?build=" + id + "&format=obj&per_plant=true&name=f").c_str());
    ASSERT_TRUE(zip && zip->status == 200) << zip->body;
    EXPECT_EQ(zip->get_header_value("Content-Type"), "application/zip");
    EXPECT_EQ(zip->body.substr(0, 2), "PK");
    for (const char* name : {"f_0000.obj", "f_0000.mtl", "f_0001.obj", "f_index.json"})
        EXPECT_NE(zip->body.find(name), std::string::npos) << name;
    EXPECT_EQ(
        client_->Get(("/api/export/download?build=" + id + "&per_plant=maybe").c_str())->status,
        400);
}

TEST_F(BuilderServer, ASavedProjectRunFromTheCommandLineGivesTheExportsBytes) {
    json project = beans(2, 2, 18);
    project["ground"] = {{"size", {2, 2}}};
    project["blocks"].push_back({{"name", "T"},
                                 {"species", "tomato"},
                                 {"layout", "single"},
                                 {"origin", {1.5, 0, 0}},
                                 {"age", 15},
                                 {"seed", 4}});
    auto saved = post("/api/projects/save", {{"name", "trial"}, {"project", project}});
    ASSERT_TRUE(saved && saved->status == 200) << saved->body;
    EXPECT_EQ(body(saved)["path"], "projects/trial.json");
    EXPECT_EQ(body(client_->Get("/api/projects")), json({"trial"}));
    const json loaded = body(client_->Get("/api/projects/trial"));
    EXPECT_EQ(loaded["blocks"][1]["species"], "tomato");
    EXPECT_EQ(client_->Get("/api/projects/nosuch")->status, 404);
    EXPECT_EQ(post("/api/projects/save", {{"name", "../x"}, {"project", project}})->status, 400);

    const std::string id = build(loaded);
    ASSERT_EQ(waitFor(id)["state"], "done");
    for (const char* format : {"glb", "ply", "obj", "xml"}) {
        auto r = post("/api/export", {{"build", id}, {"format", format}, {"name", "field"}});
        ASSERT_TRUE(r && r->status == 200) << r->body;
        // The same name: an OBJ names its .mtl.
        const std::string mine = at(std::string("cli/field.") + format);
        const auto run = cli::run("project run " + at("out/projects/trial.json") + " -o " + mine);
        ASSERT_EQ(run.status, 0) << run.out;
        EXPECT_TRUE(existingBytes(mine) == existingBytes(at(std::string("out/field.") + format)))
            << format;
    }
    auto r = post("/api/export",
                  {{"build", id}, {"format", "glb"}, {"name", "sep"}, {"per_plant", true}});
    ASSERT_TRUE(r && r->status == 200);
    const auto run = cli::run("project run " + at("out/projects/trial.json") + " --separate -o " +
                              at("sep.glb"));
    ASSERT_EQ(run.status, 0) << run.out;
    EXPECT_TRUE(existingBytes(at("sep_0004.glb")) == existingBytes(at("out/sep_0004.glb")));
    EXPECT_TRUE(existingBytes(at("sep_index.json")) == existingBytes(at("out/sep_index.json")));
}

TEST_F(BuilderServer, ASavedUserSpeciesIsWrittenAsAPathAndReadBackByName) {
    ASSERT_EQ(post("/api/species/save", {{"base", "bean"}, {"name", "tall_bean"}})->status, 200);
    json project = beans(1, 1, 10);
    project["blocks"][0]["species"] = "tall_bean";
    ASSERT_EQ(post("/api/projects/save", {{"name", "mine"}, {"project", project}})->status, 200);
    const json file = json::parse(bytes(at("out/projects/mine.json")));
    EXPECT_EQ(file["blocks"][0]["species"], "../species/tall_bean.xml");
    EXPECT_EQ(body(client_->Get("/api/projects/mine"))["blocks"][0]["species"], "tall_bean");
    const auto run = cli::run("project run " + at("out/projects/mine.json") + " --stats");
    EXPECT_EQ(run.status, 0) << run.out;
    // A species file outside the output folder is not read.
    project["blocks"][0]["species"] = at("outside.xml");
    EXPECT_EQ(post("/api/builds", {{"project", project}})->status, 403);
    project["blocks"][0]["species"] = "../../x.xml";
    EXPECT_EQ(post("/api/builds", {{"project", project}})->status, 403);
}

// A measured skeleton (a file under OUTPUT, named relative to OUTPUT/projects/ as the page
// names it) rebuilt as a block of its own, next to a block of beans. Bending on for the beans
// bends them; on for the skeleton it leaves its measured internodes as measured (their shape
// is the loaded one).
TEST_F(BuilderServer, BuildsASkeletonBlockAndBendsItOnRequest) {
    fs::create_directories(at("out/skeletons"));
    fs::copy_file(std::string(PLANTARCH_SOURCE_DIR) + "/examples/skeletons/pepper_digitised.csv",
                  at("out/skeletons/pepper.csv"));
    json project = beans(1, 1, 20);
    project["blocks"].push_back(
        {{"name", "measured"},
         {"species", "capsicum"},
         {"layout", "skeleton"},
         {"origin", {0.5, 0, 0}},
         {"skeleton", {{"file", "../skeletons/pepper.csv"}, {"unit", 0.01}}},
         {"age", 60}});
    const json straight = waitFor(build(project));
    ASSERT_EQ(straight["state"], "done") << straight.dump();
    EXPECT_EQ(straight["blocks"][1]["name"], "measured");
    EXPECT_EQ(straight["blocks"][1]["plants"].size(), 1u);
    EXPECT_EQ(straight["stats"]["plants"], 2);
    const std::string straightGLB =
        client_->Get(("/api/builds/" + straight["id"].get<std::string>() + "/scene.glb").c_str())
            ->body;

    project["blocks"][1]["bend"] = true;
    project["blocks"][1]["elastic_modulus"] = 1e9;
    const json measured = waitFor(build(project));
    ASSERT_EQ(measured["state"], "done") << measured.dump();
    EXPECT_EQ(measured["stats"], straight["stats"]);
    project["blocks"][0]["bend"] = true;
    project["blocks"][0]["elastic_modulus"] = 2e8;
    const json bent = waitFor(build(project));
    ASSERT_EQ(bent["state"], "done") << bent.dump();
    const std::string bentGLB =
        client_->Get(("/api/builds/" + bent["id"].get<std::string>() + "/scene.glb").c_str())->body;
    EXPECT_EQ(bentGLB.substr(0, 4), "glTF");
    EXPECT_NE(bentGLB, straightGLB);

    // Exported like any build; the saved project holds the block as sent.
    auto exported = post("/api/export", {{"build", bent["id"]}, {"format", "glb"}});
    ASSERT_TRUE(exported && exported->status == 200) << (exported ? exported->body : "");
    auto saved = post("/api/projects/save", {{"name", "measured"}, {"project", project}});
    ASSERT_TRUE(saved && saved->status == 200) << (saved ? saved->body : "");
    const json back = body(client_->Get("/api/projects/measured"));
    EXPECT_EQ(back["blocks"][1]["skeleton"]["file"], "../skeletons/pepper.csv");
    EXPECT_EQ(back["blocks"][1]["bend"], true);
    EXPECT_EQ(back["blocks"][1]["elastic_modulus"], 1000000000);

    // A modulus out of the species' range: the one-line error.
    project["blocks"][1]["elastic_modulus"] = 10;
    auto refused = post("/api/builds", {{"project", project}});
    ASSERT_TRUE(refused);
    EXPECT_EQ(refused->status, 400);
    EXPECT_EQ(body(refused)["error"],
              "project: blocks/1/elastic_modulus = 10: out of range (valid: 1e5 to 1e12 Pa, or "
              "null for the species')");
}
