// Every library species at its youngest, usual and oldest recommended ages (seeds 42 and 7)
// keeps its geometry to the byte: a
// checksum of each plant's organ geometry (positions, UVs, triangles, materials and organ
// labels, organ by organ in state order) against the value recorded when the species' rules
// moved from C++ into the species files. A change to growth, tessellation or a species file
// that alters a library plant fails here; update a value only for a change made on purpose,
// and say in the commit which species changed and why.

#include <gtest/gtest.h>

#include <cinttypes>
#include <cstdint>
#include <cstdio>
#include <map>
#include <set>
#include <string>

#include "plant_geometry_bytes.h"
#include "plantarch/PlantArchitecture.h"
#include "plantarch/SpeciesIO.h"

using namespace plantarch;

namespace {

// FNV-1a, 64 bits: a checksum that any reader can recompute from the bytes.
std::uint64_t fnv1a(const std::string& bytes) {
    std::uint64_t h = 0xcbf29ce484222325ULL;
    for (unsigned char c : bytes) {
        h ^= c;
        h *= 0x100000001b3ULL;
    }
    return h;
}

std::string hex(std::uint64_t v) {
    char text[17];
    std::snprintf(text, sizeof text, "%016" PRIx64, v);
    return text;
}

const std::map<std::string, std::string> kExpected = {
    {"almond@120/42", "d1834fc40a82dab8"},
    {"almond@120/7", "85dc6941ccf1268c"},
    {"almond@630/42", "7069db0db88c02e2"},
    {"almond@630/7", "233aacdcfcd219cb"},
    {"almond@1000/42", "16a203a937d6ef40"},
    {"almond@1000/7", "ed7858a6ab52a594"},
    {"almond_aldrich@120/42", "86a034aa63d88692"},
    {"almond_aldrich@120/7", "bac880ca6b7f2874"},
    {"almond_aldrich@630/42", "3b1574baa1398a7f"},
    {"almond_aldrich@630/7", "90e8d15d7f3b9cd5"},
    {"almond_aldrich@1000/42", "471701e922b75428"},
    {"almond_aldrich@1000/7", "223fac471575eaa4"},
    {"almond_wood_colony@120/42", "06adfd7c0c4084b4"},
    {"almond_wood_colony@120/7", "46795bdcb1222563"},
    {"almond_wood_colony@630/42", "ddb7559f94bf299e"},
    {"almond_wood_colony@630/7", "3d5cfd72b52803e2"},
    {"almond_wood_colony@1000/42", "ce46d2c4459309f8"},
    {"almond_wood_colony@1000/7", "49b196a4d40d7ccc"},
    {"apple@200/42", "42277405713fff75"},
    {"apple@200/7", "57d80f5ceb2e2716"},
    {"apple@630/42", "8ecf11f52432d390"},
    {"apple@630/7", "ef65d003cfdfd8de"},
    {"apple@1400/42", "3e2d090208416d64"},
    {"apple@1400/7", "c7e37d009fed106c"},
    {"apple_fruitingwall@200/42", "5dcf1962393e778c"},
    {"apple_fruitingwall@200/7", "8b58261a1c817584"},
    {"apple_fruitingwall@630/42", "b8ec08d8da2dd36f"},
    {"apple_fruitingwall@630/7", "04bb685d2bae76fb"},
    {"apple_fruitingwall@720/42", "b8ec08d8da2dd36f"},
    {"apple_fruitingwall@720/7", "04bb685d2bae76fb"},
    {"asparagus@5/42", "16752f8e2d76a8ea"},
    {"asparagus@5/7", "cfc4c8226df53285"},
    {"asparagus@20/42", "8566ca0ad67b1e21"},
    {"asparagus@20/7", "642949db2298824d"},
    {"asparagus@20/42", "8566ca0ad67b1e21"},
    {"asparagus@20/7", "642949db2298824d"},
    {"bean@10/42", "04a98cc5e8e0cc7b"},
    {"bean@10/7", "c6f641c6471d7f16"},
    {"bean@45/42", "6707987214391d09"},
    {"bean@45/7", "70fc8394b2e2a919"},
    {"bean@100/42", "8935a92d0d259ad1"},
    {"bean@100/7", "2f30a8c5561abe74"},
    {"bindweed@10/42", "96985a60a9ecd26d"},
    {"bindweed@10/7", "dd5449ad15f18fe3"},
    {"bindweed@50/42", "e66ef3008bcb12b9"},
    {"bindweed@50/7", "7cbf6e6a23e2c541"},
    {"bindweed@50/42", "e66ef3008bcb12b9"},
    {"bindweed@50/7", "7cbf6e6a23e2c541"},
    {"bougainvillea@30/42", "c7315036809a55de"},
    {"bougainvillea@30/7", "1014282b7cc593f3"},
    {"bougainvillea@180/42", "5ab60b5bba904ab7"},
    {"bougainvillea@180/7", "c005601ba54df4a2"},
    {"bougainvillea@365/42", "be7ad04012804e39"},
    {"bougainvillea@365/7", "c73198498305afa4"},
    {"butterlettuce@10/42", "760cadc15142ac58"},
    {"butterlettuce@10/7", "58b4870383f4dda7"},
    {"butterlettuce@50/42", "6ba85a4b64cc898e"},
    {"butterlettuce@50/7", "7b42ede1c931dce0"},
    {"butterlettuce@70/42", "5e179942cdb895b0"},
    {"butterlettuce@70/7", "e72e662a759cb6d1"},
    {"capsicum@10/42", "c07224343a5fd53c"},
    {"capsicum@10/7", "56e7361067df8f3e"},
    {"capsicum@50/42", "01c2e794f84159db"},
    {"capsicum@50/7", "286fba752f4ada11"},
    {"capsicum@150/42", "a5131c7b2ae5f64c"},
    {"capsicum@150/7", "415f7fc8f4ec04bf"},
    {"cheeseweed@10/42", "ddb159ee040c5b50"},
    {"cheeseweed@10/7", "6b0d6153f1904ef2"},
    {"cheeseweed@40/42", "d4b18361b290faf6"},
    {"cheeseweed@40/7", "74af5bc13eebfca6"},
    {"cheeseweed@40/42", "d4b18361b290faf6"},
    {"cheeseweed@40/7", "74af5bc13eebfca6"},
    {"cherrytomato@10/42", "8deacfdc30f91ab3"},
    {"cherrytomato@10/7", "e1a6d05d050566b6"},
    {"cherrytomato@50/42", "99c7d7d05a3b64c7"},
    {"cherrytomato@50/7", "41ab82119a3791ec"},
    {"cherrytomato@175/42", "a8ac656e16323b85"},
    {"cherrytomato@175/7", "43cf1215c42b19ca"},
    {"cowpea@10/42", "f0ba5636a5debf26"},
    {"cowpea@10/7", "f1d7db6103dbbfcb"},
    {"cowpea@50/42", "8a9cba61e073df84"},
    {"cowpea@50/7", "30acb74b1c6c77a1"},
    {"cowpea@100/42", "082d128632aadf00"},
    {"cowpea@100/7", "b047b444837ba6ed"},
    {"easternredbud@200/42", "abc9b0d876f4c04b"},
    {"easternredbud@200/7", "15ecb9c247650c8e"},
    {"easternredbud@630/42", "9ccee62e3a7c5e4a"},
    {"easternredbud@630/7", "c54ade0bd9ae4602"},
    {"easternredbud@1400/42", "c96f3af0860ff974"},
    {"easternredbud@1400/7", "81d02a3c9eea7886"},
    {"grapevine_VSP@180/42", "3259c96f8250f847"},
    {"grapevine_VSP@180/7", "a2050e0f6a69df7e"},
    {"grapevine_VSP@270/42", "08b1f81d02a77a8a"},
    {"grapevine_VSP@270/7", "38f64df32d9a65c8"},
    {"grapevine_VSP@360/42", "08b1f81d02a77a8a"},
    {"grapevine_VSP@360/7", "38f64df32d9a65c8"},
    {"grapevine_Wye@180/42", "8438888ca62c946d"},
    {"grapevine_Wye@180/7", "187ac8f1f4710056"},
    {"grapevine_Wye@270/42", "225f68077312d226"},
    {"grapevine_Wye@270/7", "dcfd0fd135a501f7"},
    {"grapevine_Wye@360/42", "225f68077312d226"},
    {"grapevine_Wye@360/7", "dcfd0fd135a501f7"},
    {"groundcherryweed@10/42", "7938e7ee5635dcc6"},
    {"groundcherryweed@10/7", "416de265d52392db"},
    {"groundcherryweed@50/42", "32dc6110eefb4bb5"},
    {"groundcherryweed@50/7", "d30a3f6aae7e732d"},
    {"groundcherryweed@80/42", "feaebf287b29e76f"},
    {"groundcherryweed@80/7", "b3fb60f098bd1bb2"},
    {"maize@10/42", "05d5722b3ddcf53b"},
    {"maize@10/7", "d8bd70f0641b6172"},
    {"maize@50/42", "a52ae9de3ba6e4e5"},
    {"maize@50/7", "c22bcc65fb4c45e4"},
    {"maize@120/42", "a52ae9de3ba6e4e5"},
    {"maize@120/7", "c22bcc65fb4c45e4"},
    {"olive@200/42", "cdd6bd97a66407dc"},
    {"olive@200/7", "b6119351f62a9cfa"},
    {"olive@630/42", "03d6a64e0a0b8482"},
    {"olive@630/7", "e72b769316fd5528"},
    {"olive@1400/42", "ac23a36eb8fbc78e"},
    {"olive@1400/7", "2b22eb195f2c35f9"},
    {"pistachio@200/42", "377f93e730bef227"},
    {"pistachio@200/7", "8ee96a23f15daf5c"},
    {"pistachio@630/42", "d0d7d30076947e82"},
    {"pistachio@630/7", "c6bfa7a5cc2ff766"},
    {"pistachio@1000/42", "cbe65c03ce158e80"},
    {"pistachio@1000/7", "79bfe9c10490ef9d"},
    {"puncturevine@10/42", "861b81218e1ff9d3"},
    {"puncturevine@10/7", "7549af65eb1e1a6a"},
    {"puncturevine@45/42", "cda1da3fcde1328a"},
    {"puncturevine@45/7", "5badaa5dd0032210"},
    {"puncturevine@45/42", "cda1da3fcde1328a"},
    {"puncturevine@45/7", "5badaa5dd0032210"},
    {"rice@10/42", "613fa475cf39fb04"},
    {"rice@10/7", "944ed9e3d2d3861a"},
    {"rice@50/42", "0cc9f74c5cd66ffd"},
    {"rice@50/7", "c5ad27c049be63d5"},
    {"rice@120/42", "dd78c1163c8d7396"},
    {"rice@120/7", "594c5ba00f0e34c0"},
    {"sorghum@10/42", "e39eb8bd35865035"},
    {"sorghum@10/7", "0e3c2092cd192dc7"},
    {"sorghum@50/42", "fa6edea3a453017c"},
    {"sorghum@50/7", "eac44607e24b3da2"},
    {"sorghum@120/42", "fa6edea3a453017c"},
    {"sorghum@120/7", "eac44607e24b3da2"},
    {"soybean@10/42", "78069e47b2326057"},
    {"soybean@10/7", "9514f5c1060411f3"},
    {"soybean@50/42", "ba62e73fa1d8e195"},
    {"soybean@50/7", "a3eeb05fcc2cc44f"},
    {"soybean@100/42", "17e7d6fb4246c523"},
    {"soybean@100/7", "a21ea004e0b88514"},
    {"strawberry@10/42", "c1335cc886f541f5"},
    {"strawberry@10/7", "b224e96bc45ea7ed"},
    {"strawberry@50/42", "656f30aae2036709"},
    {"strawberry@50/7", "a0be71d7d6d45ccf"},
    {"strawberry@120/42", "e5307899d2af2cbe"},
    {"strawberry@120/7", "78d2a6dbb56f154e"},
    {"sugarbeet@10/42", "7a9958ff436876d2"},
    {"sugarbeet@10/7", "d60efb71cc91665c"},
    {"sugarbeet@50/42", "301b0de9c8dc4ac8"},
    {"sugarbeet@50/7", "69a2244d6d52830e"},
    {"sugarbeet@150/42", "37f4cdbd51d66f33"},
    {"sugarbeet@150/7", "95cc4f3b007ae2a4"},
    {"tomato@10/42", "5e436ae139a42b2e"},
    {"tomato@10/7", "381ddeb0facf5b2e"},
    {"tomato@50/42", "b433b653054c7f6a"},
    {"tomato@50/7", "b9952be399cc3de0"},
    {"tomato@120/42", "2c8e7e60c68d0b00"},
    {"tomato@120/7", "f3e1dbb56d84bc2b"},
    {"walnut@200/42", "d55d164ee6429d96"},
    {"walnut@200/7", "3004d7317c7ade64"},
    {"walnut@630/42", "d374c0498ffb3c6b"},
    {"walnut@630/7", "307aa8bb6cd774a4"},
    {"walnut@1000/42", "17d644abae8f8e83"},
    {"walnut@1000/7", "2ebc711660b6a422"},
    {"wheat@10/42", "9ed2b19aa6d7d216"},
    {"wheat@10/7", "8307a49b03a9830e"},
    {"wheat@50/42", "16357602aeb2c5b3"},
    {"wheat@50/7", "61ac1645b8427a59"},
    {"wheat@120/42", "5d90cb7be7604fc1"},
    {"wheat@120/7", "c45aa8708d272491"},
};

}  // namespace

TEST(SpeciesChecksum, EveryLibraryPlantAtThreeAgesAndTwoSeedsIsUnchanged) {
    const std::vector<std::string> names = listSpecies();
    std::size_t checked = 0;
    for (const std::string& name : names) {
        const SpeciesModel model = loadSpecies(name);
        const std::set<float> ages = {model.recommendedAgeMin, model.recommendedAge,
                                      model.recommendedAgeMax};
        for (float age : ages)
            for (std::uint64_t seed : {42u, 7u}) {
                const std::string key =
                    name + "@" + std::to_string(int(age)) + "/" + std::to_string(seed);
                SCOPED_TRACE(key);
                ++checked;
                Context ctx;
                PlantArchitecture arch(&ctx);
                arch.setSeed(seed);
                arch.loadPlantModelFromLibrary(name);
                const unsigned p = arch.buildPlantInstanceFromLibrary(vec3(0.0f), age);
                const std::string sum = hex(fnv1a(plantarch::testing::organBytes(arch, {p})));
                const auto expected = kExpected.find(key);
                if (expected == kExpected.end()) {
                    ADD_FAILURE() << "no recorded checksum: {\"" << key << "\", \"" << sum
                                  << "\"},";
                    continue;
                }
                EXPECT_EQ(sum, expected->second) << "{\"" << key << "\", \"" << sum << "\"},";
            }
    }
    EXPECT_EQ(checked, kExpected.size()) << "a species or one of its ages was added or removed";
}
