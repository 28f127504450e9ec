// The builder's web front end embedded in the binary (builder/server/assets.h): the bundle's
// pages with their content types, the page as written in builder/web, and nothing that loads
// code from the network.

#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <set>
#include <sstream>
#include <string>

#include "builder/server/assets.h"

namespace {

using plantarch::builder::Asset;
using plantarch::builder::assets;

const Asset* findAsset(std::string_view path) {
    for (const Asset& a : assets())
        if (a.path == path) return &a;
    return nullptr;
}

TEST(BuilderAssets, PageScriptAndStyleWithTheirContentTypes) {
    const Asset* page = findAsset("/index.html");
    ASSERT_NE(page, nullptr);
    EXPECT_EQ(page->contentType, "text/html; charset=utf-8");
    const Asset* app = findAsset("/app.js");
    ASSERT_NE(app, nullptr);
    EXPECT_EQ(app->contentType, "text/javascript; charset=utf-8");
    const Asset* css = findAsset("/app.css");
    ASSERT_NE(css, nullptr);
    EXPECT_EQ(css->contentType, "text/css; charset=utf-8");
    // The page loads the bundle's script and style by the paths they are served at.
    EXPECT_NE(page->bytes.find("src=\"/app.js\""), std::string_view::npos);
    EXPECT_NE(page->bytes.find("href=\"/app.css\""), std::string_view::npos);
    // three.js is inside the bundle (its WebGL renderer's messages), not fetched.
    EXPECT_NE(app->bytes.find("THREE.WebGLRenderer"), std::string_view::npos);
    EXPECT_EQ(findAsset("/"), nullptr);  // served as /index.html by the server
}

TEST(BuilderAssets, TheEmbeddedPageIsTheSourcePage) {
    std::ifstream in(PLANTARCH_SOURCE_DIR "/builder/web/index.html", std::ios::binary);
    ASSERT_TRUE(in) << "builder/web/index.html";
    std::ostringstream text;
    text << in.rdbuf();
    EXPECT_EQ(findAsset("/index.html")->bytes, text.str());
}

TEST(BuilderAssets, SortedUniqueAbsolutePathsWithKnownTypes) {
    const auto all = assets();
    ASSERT_GE(all.size(), 3u);
    std::set<std::string_view> types;
    for (std::size_t i = 0; i < all.size(); ++i) {
        EXPECT_EQ(all[i].path.substr(0, 1), "/") << all[i].path;
        EXPECT_EQ(all[i].path.find(".."), std::string_view::npos) << all[i].path;
        EXPECT_FALSE(all[i].bytes.empty()) << all[i].path;
        EXPECT_FALSE(all[i].contentType.empty()) << all[i].path;
        if (i > 0) {
            EXPECT_LT(all[i - 1].path, all[i].path);
        }
    }
}

// Whether an address at `at` is where code or style is loaded from: preceded (quotes and
// spaces aside) by an import, a script or link attribute or a CSS url().
bool loadsFrom(std::string_view text, std::size_t at) {
    std::size_t i = at;
    while (i > 0 && (text[i - 1] == '"' || text[i - 1] == '\'' || text[i - 1] == ' ')) --i;
    const std::string_view before = text.substr(i >= 8 ? i - 8 : 0, i >= 8 ? 8 : i);
    for (std::string_view cue : {"from", "import(", "src=", "href=", "url(", "@import"})
        if (before.ends_with(cue)) return true;
    return false;
}

TEST(BuilderAssets, NoCodeLoadedFromTheNetwork) {
    EXPECT_TRUE(loadsFrom(R"(import x from"https://cdn.example/three.js")", 14));
    EXPECT_FALSE(loadsFrom(R"(a="see https://threejs.org")", 7));
    for (const Asset& a : assets()) {
        if (!a.contentType.starts_with("text/")) continue;
        for (std::string_view scheme : {"http://", "https://", "\"//"}) {
            for (std::size_t at = a.bytes.find(scheme); at != std::string_view::npos;
                 at = a.bytes.find(scheme, at + 1)) {
                const std::size_t start = scheme[0] == '"' ? at + 1 : at;
                EXPECT_FALSE(loadsFrom(a.bytes, start))
                    << a.path << " loads from " << a.bytes.substr(start, 60);
            }
        }
    }
}

}  // namespace
