// The builder's export variants (builder/server/export_options.cpp): materials and texture
// size, nodes and instancing, levels of detail, meshopt compression and skin, given to
// POST /api/export and GET /api/export/download as the command line's options are given to
// `plantarch project run`, with the same bytes; the view's textured scene.glb; and every bad
// value refused with one line naming its field, before any file is written.

#include <gtest/gtest.h>
#include <httplib.h>

#include <algorithm>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "builder_fixture.h"
#include "cli_run.h"
#include "glb_reader.h"

using plantarch::testing::parseGlb;

namespace {

// Nodes of a glTF document whose extras name an organ, by organ.
std::map<std::string, int> organNodes(const json& doc) {
    std::map<std::string, int> count;
    for (const json& n : doc["nodes"])
        if (n.contains("extras") && n["extras"].contains("organ") &&
            n["extras"].contains("objectID"))
            count[n["extras"]["organ"].get<std::string>()]++;
    return count;
}

bool uses(const json& doc, const char* extension) {
    const json& used = doc.value("extensionsUsed", json::array());
    return std::find(used.begin(), used.end(), extension) != used.end();
}

}  // namespace

// A textured GLB with a node per organ, downloaded, and the same file written into the output
// folder: the command line's file with --materials textured --texture-size 64 --nodes organ.
TEST_F(BuilderServer, ExportsTexturedOrganNodesAsTheCommandLine) {
    json project = beans(2, 1, 20);
    auto saved = post("/api/projects/save", {{"name", "v"}, {"project", project}});
    ASSERT_TRUE(saved && saved->status == 200) << saved->body;
    const std::string id = build(project);
    ASSERT_EQ(waitFor(id)["state"], "done");

    auto r = post("/api/export", {{"build", id},
                                  {"format", "glb"},
                                  {"name", "organs"},
                                  {"materials", "textured"},
                                  {"texture_size", 64},
                                  {"nodes", "organ"}});
    ASSERT_TRUE(r && r->status == 200) << r->body;
    EXPECT_EQ(body(r)["files"], json({"organs.glb"}));
    const std::string mine = at("cli/organs.glb");
    const auto run = cli::run("project run " + at("out/projects/v.json") +
                              " --materials textured --texture-size 64 --nodes organ -o " + mine);
    ASSERT_EQ(run.status, 0) << run.out;
    const std::string written = existingBytes(at("out/organs.glb"));
    EXPECT_TRUE(existingBytes(mine) == written);

    auto download = client_->Get(("/api/export/download?build=" + id +
                                  "&format=glb&materials=textured&texture_size=64&nodes=organ")
                                     .c_str());
    ASSERT_TRUE(download && download->status == 200) << download->body;
    EXPECT_TRUE(download->body == written);
    const json doc = parseGlb(written).doc;
    EXPECT_GT(doc["images"].size(), 0u);
    bool baseColorMap = false;
    for (const json& m : doc["materials"])
        baseColorMap |= m["pbrMetallicRoughness"].contains("baseColorTexture");
    EXPECT_TRUE(baseColorMap);
    const auto organs = organNodes(doc);
    EXPECT_GT(organs.count("leaf") ? organs.at("leaf") : 0, 10);
    EXPECT_GT(organs.count("internode") ? organs.at("internode") : 0, 2);
}

// A textured OBJ lists (and zips) its texture images beside its .mtl; a re-export lists
// them again, as written anew.
TEST_F(BuilderServer, ListsTheTextureImagesOfATexturedOBJ) {
    const std::string id = build(beans(1, 1, 20));
    ASSERT_EQ(waitFor(id)["state"], "done");
    const json request = {{"build", id},     {"format", "obj"},         {"name", "t"},
                          {"folder", "tex"}, {"materials", "textured"}, {"texture_size", 32}};
    for (int again = 0; again < 2; ++again) {
        auto r = post("/api/export", request);
        ASSERT_TRUE(r && r->status == 200) << r->body;
        const json files = body(r)["files"];
        ASSERT_GT(files.size(), 4u);
        EXPECT_EQ(files[0], "tex/t.obj");
        EXPECT_EQ(files[1], "tex/t.mtl");
        std::size_t pngs = 0;
        for (const auto& entry : fs::directory_iterator(at("out/tex")))
            pngs += entry.path().extension() == ".png";
        EXPECT_EQ(files.size(), pngs + 2);
        const std::string mtl = existingBytes(at("out/tex/t.mtl"));
        for (std::size_t i = 2; i < files.size(); ++i) {
            const std::string f = files[i].get<std::string>();
            EXPECT_TRUE(f.starts_with("tex/t_") && f.ends_with(".png")) << f;
            EXPECT_NE(mtl.find(fs::path(f).filename().string()), std::string::npos) << f;
        }
    }
    auto zip = client_->Get(("/api/export/download?build=" + id +
                             "&format=obj&name=t&materials=textured&texture_size=32")
                                .c_str());
    ASSERT_TRUE(zip && zip->status == 200);
    EXPECT_EQ(zip->get_header_value("Content-Type"), "application/zip");
    EXPECT_NE(zip->body.find("_basecolor.png"), std::string::npos);
}

// Levels of detail with meshopt compression, and a skin, reach the GLB.
TEST_F(BuilderServer, ExportsLevelsOfDetailMeshoptAndSkins) {
    const std::string id = build(beans(1, 1, 20));
    ASSERT_EQ(waitFor(id)["state"], "done");
    auto lod = client_->Get(
        ("/api/export/download?build=" + id + "&format=glb&lod=reduced,cards&meshopt=true")
            .c_str());
    ASSERT_TRUE(lod && lod->status == 200) << lod->body;
    const json doc = parseGlb(lod->body).doc;
    EXPECT_TRUE(uses(doc, "MSFT_lod"));
    EXPECT_TRUE(uses(doc, "EXT_meshopt_compression"));
    auto skin = post("/api/export", {{"build", id}, {"format", "glb"}, {"skin", true}});
    ASSERT_TRUE(skin && skin->status == 200) << skin->body;
    const json skinned = parseGlb(existingBytes(at("out/scene.glb"))).doc;
    EXPECT_EQ(skinned["skins"].size(), 1u);
    auto plant = post("/api/export", {{"build", id},
                                      {"format", "usda"},
                                      {"name", "p"},
                                      {"nodes", "plant"},
                                      {"instancing", "none"}});
    ASSERT_TRUE(plant && plant->status == 200) << plant->body;
    // GPU instances (EXT_mesh_gpu_instancing), as the query of a download.
    auto gpu = client_->Get(
        ("/api/export/download?build=" + id + "&format=glb&nodes=organ&instancing=gpu").c_str());
    ASSERT_TRUE(gpu && gpu->status == 200) << gpu->body;
    EXPECT_TRUE(uses(parseGlb(gpu->body).doc, "EXT_mesh_gpu_instancing"));
}

// The view's scene.glb with textured materials: embedded images, made once per texture size.
TEST_F(BuilderServer, ServesATexturedSceneForTheView) {
    const std::string id = build(beans(1, 1, 20));
    ASSERT_EQ(waitFor(id)["state"], "done");
    const std::string url = "/api/builds/" + id + "/scene.glb";
    auto flat = client_->Get(url.c_str());
    auto textured = client_->Get((url + "?materials=textured&texture_size=32").c_str());
    ASSERT_TRUE(flat && flat->status == 200 && textured && textured->status == 200);
    EXPECT_FALSE(parseGlb(flat->body).doc.contains("images"));
    EXPECT_GT(parseGlb(textured->body).doc["images"].size(), 0u);
    EXPECT_EQ(client_->Get(url.c_str())->body, flat->body);
    EXPECT_EQ(client_->Get((url + "?materials=textured&texture_size=32").c_str())->body,
              textured->body);
    for (const char* bad : {"?materials=shiny", "?texture_size=5000", "?nodes=organ"}) {
        auto r = client_->Get((url + bad).c_str());
        ASSERT_TRUE(r);
        EXPECT_EQ(r->status, 400) << bad;
    }
}

// Every bad value: 400, one line naming the field and its value, the command line's words,
// and no file written.
TEST_F(BuilderServer, RefusesBadExportVariants) {
    const std::string id = build(beans(1, 1, 10));
    ASSERT_EQ(waitFor(id)["state"], "done");
    const std::vector<std::pair<json, std::string>> posted = {
        {{{"materials", "shiny"}},
         "materials = shiny: unknown material style (valid: flat, textured)"},
        {{{"materials", 1}}, "materials = 1: expected a text in quotes"},
        {{{"texture_size", 5000}},
         "texture_size = 5000: texture size 5000 is not allowed (valid: a power of two from 16 "
         "to 4096)"},
        {{{"texture_size", 100}}, "texture_size = 100: texture size 100 is not allowed"},
        {{{"texture_size", -16}}, "texture_size = -16: texture size -16 is not allowed"},
        {{{"texture_size", 0}}, "texture_size = 0: texture size 0 is not allowed"},
        {{{"texture_size", 1e300}}, "texture_size = 1e+300: texture size is a whole number"},
        {{{"texture_size", 99999999999LL}},
         "texture_size = 99999999999: texture size 99999999999 is not allowed"},
        {{{"texture_size", 64.5}}, "texture_size = 64.5: texture size is a whole number"},
        {{{"texture_size", "512"}}, "texture_size = \"512\": texture size is a whole number"},
        {{{"nodes", "leaf"}}, "nodes = leaf: unknown node level (valid: plant, kind, organ)"},
        {{{"instancing", "no"}}, "instancing = no: unknown instancing (valid: none, shared, gpu)"},
        {{{"instancing", false}}, "instancing = false: expected a text in quotes"},
        {{{"instancing", "gpu"}}, "instancing = gpu: gpu instancing needs a node per organ"},
        {{{"lod", "foo"}}, "lod = foo: unknown level of detail (valid: none, or comma-separated"},
        {{{"lod", "reduced:nan"}}, "lod = reduced:nan: not a number"},
        {{{"lod", "reduced:1.5"}}, "lod = reduced:1.5"},
        {{{"lod", std::string(500, 'x')}}, "lod = xxxx"},
        {{{"meshopt", 1}}, "meshopt = 1: expected true or false"},
        {{{"skin", nullptr}, {"nodes", "organ"}, {"lod", "cards"}},
         "lod = cards: a node per organ cannot be written with levels of detail"},
        {{{"skin", true}, {"nodes", "organ"}},
         "skin = true: a node per organ cannot be written with a skin"},
        {{{"skin", true}, {"lod", "cards"}},
         "lod = cards: levels of detail are not written with skins"},
        {{{"format", "ply"}, {"nodes", "organ"}},
         "nodes = organ: node levels are written in glTF and USD only"},
        {{{"format", "ply"}, {"materials", "textured"}},
         "materials = textured: textured materials are written in OBJ, glTF and USD only"},
        {{{"format", "xml"}, {"skin", true}}, "skin = true: skins are written in glTF and USD"},
        {{{"format", "usda"}, {"lod", "cards"}},
         "lod = cards: levels of detail are written in glTF only"},
        {{{"format", "obj"}, {"meshopt", true}},
         "meshopt = true: meshopt compression is written in glTF only"},
        {{{"colour", "red"}},
         "colour: unknown field (valid: build, format, per_plant, folder, "
         "name, materials, texture_size, atlas, nodes, instancing, lod, meshopt, "
         "skin)"},
    };
    for (const auto& request : posted) {
        json fields = request.first;
        fields["build"] = id;
        fields["name"] = "refused";
        auto r = post("/api/export", fields);
        ASSERT_TRUE(r);
        EXPECT_EQ(r->status, 400) << fields.dump() << " " << r->body;
        const std::string error = body(r)["error"];
        EXPECT_TRUE(error.starts_with(request.second)) << error;
        EXPECT_EQ(error.find('\n'), std::string::npos);
        EXPECT_LE(error.size(), 300u) << error;
    }
    // Query text: NaN, huge, empty and unknown words.
    const std::vector<std::pair<std::string, std::string>> queried = {
        {"texture_size=nan", "texture_size = nan: texture size is a whole number of texels"},
        {"texture_size=1e9", "texture_size = 1e9: texture size is a whole number of texels"},
        {"texture_size=99999999999999999999",
         "texture_size = 99999999999999999999: texture size 99999999999999999999 is not "
         "allowed"},
        {"texture_size=", "texture_size: texture size is a whole number of texels"},
        {"materials=TEXTURED", "materials = TEXTURED: unknown material style"},
        {"nodes=", "nodes: unknown node level"},
        {"meshopt=maybe", "meshopt = maybe: not true or false (valid: true, false)"},
        {"lod=reduced:0.5@nan", "lod = reduced:0.5@nan"},
    };
    for (const auto& [query, expected] : queried) {
        auto r =
            client_->Get(("/api/export/download?build=" + id + "&format=glb&" + query).c_str());
        ASSERT_TRUE(r);
        EXPECT_EQ(r->status, 400) << query << " " << r->body;
        EXPECT_TRUE(body(r)["error"].get<std::string>().starts_with(expected)) << r->body;
    }
    // Nothing but the folders the server starts with.
    for (const auto& entry : fs::recursive_directory_iterator(at("out")))
        EXPECT_TRUE(entry.is_directory()) << entry.path();
}
