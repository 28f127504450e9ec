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
    {"almond@120/42", "b53151575ef2204e"},
    {"almond@120/7", "9b966b71c23f69f6"},
    {"almond@630/42", "b2d3ab4d9b2304f8"},
    {"almond@630/7", "b080b302998692a0"},
    {"almond@1000/42", "cf34f8cfdf09fda8"},
    {"almond@1000/7", "c5a6f7ba8eaca860"},
    {"almond_aldrich@120/42", "c89d58cf6767f108"},
    {"almond_aldrich@120/7", "ec7fdb1744a78171"},
    {"almond_aldrich@630/42", "a1a1464e3ba158d5"},
    {"almond_aldrich@630/7", "d78eb677a48c751c"},
    {"almond_aldrich@1000/42", "f80b8657caa807b6"},
    {"almond_aldrich@1000/7", "b42c925558c768dd"},
    {"almond_wood_colony@120/42", "f79e8593c00841fd"},
    {"almond_wood_colony@120/7", "0826671d64fba1e0"},
    {"almond_wood_colony@630/42", "ebeb6e0ea2ab9511"},
    {"almond_wood_colony@630/7", "0b3f02141de14bc5"},
    {"almond_wood_colony@1000/42", "874184e5d46c2b66"},
    {"almond_wood_colony@1000/7", "794a84a8d238f734"},
    {"apple@200/42", "38d09e64c1c738f9"},
    {"apple@200/7", "93d15ae140c4bf21"},
    {"apple@630/42", "df5ff031ee9b0ae3"},
    {"apple@630/7", "8a29980c50e8b35b"},
    {"apple@1400/42", "abe961d9f29dc30b"},
    {"apple@1400/7", "a411111ea94fd286"},
    {"apple_fruitingwall@200/42", "a7e9e45738889aeb"},
    {"apple_fruitingwall@200/7", "5e7aaf6e9cacd1c8"},
    {"apple_fruitingwall@630/42", "0b1332f3d911675a"},
    {"apple_fruitingwall@630/7", "f7700c4038c576a7"},
    {"apple_fruitingwall@720/42", "0b1332f3d911675a"},
    {"apple_fruitingwall@720/7", "f7700c4038c576a7"},
    {"asparagus@5/42", "ddc57b323ff7b54c"},
    {"asparagus@5/7", "3fda820d1f58ae41"},
    {"asparagus@20/42", "75772d71165f8997"},
    {"asparagus@20/7", "0ab27f01b14416ac"},
    {"bean@10/42", "4b6652af09d38efb"},
    {"bean@10/7", "46228f6499a04b7a"},
    {"bean@45/42", "6022a42f6f03a8de"},
    {"bean@45/7", "4f4c6c56d955cc52"},
    {"bean@100/42", "c5fb578c7ecaed80"},
    {"bean@100/7", "230009f6a24cc9f3"},
    {"bindweed@10/42", "26e1fb71509cf36c"},
    {"bindweed@10/7", "672fda4d141f76bc"},
    {"bindweed@50/42", "4a09aa5059b1b85a"},
    {"bindweed@50/7", "9c2bf3cb93af03a1"},
    {"bougainvillea@30/42", "50ea42f2747c8210"},
    {"bougainvillea@30/7", "884a6b06d6f0b1ef"},
    {"bougainvillea@180/42", "8711d604fc0ffc72"},
    {"bougainvillea@180/7", "7a3135494a51adcc"},
    {"bougainvillea@365/42", "a91298bf95f51b7b"},
    {"bougainvillea@365/7", "9dabfc7144c35881"},
    {"butterlettuce@10/42", "10240168057c2c0b"},
    {"butterlettuce@10/7", "ea1c17eff016ae3f"},
    {"butterlettuce@50/42", "702bd67561fe6c9c"},
    {"butterlettuce@50/7", "700b468e0ce6014c"},
    {"butterlettuce@70/42", "f71ac50d53365075"},
    {"butterlettuce@70/7", "af254407df99d3fa"},
    {"capsicum@10/42", "d4209fe8555e0b7c"},
    {"capsicum@10/7", "fb35245760d67ea5"},
    {"capsicum@50/42", "fe25a99de9bfabd8"},
    {"capsicum@50/7", "0776f2c7d8f900cf"},
    {"capsicum@150/42", "89f2aa5c70d87be6"},
    {"capsicum@150/7", "7d88d488985b6354"},
    {"cheeseweed@10/42", "c80a0f322b0e85fd"},
    {"cheeseweed@10/7", "232a5f667538a16e"},
    {"cheeseweed@40/42", "ecd00a5df011ca4e"},
    {"cheeseweed@40/7", "c0f937d2812787ce"},
    {"cherrytomato@10/42", "38701745203017e2"},
    {"cherrytomato@10/7", "2f556fa7a5b49b29"},
    {"cherrytomato@50/42", "6d084e18041bbd09"},
    {"cherrytomato@50/7", "a8dbbbb96f24ce77"},
    {"cherrytomato@175/42", "4b67000d4f10bbab"},
    {"cherrytomato@175/7", "bd526310d7f0d5c0"},
    {"cowpea@10/42", "d9249457e4b28577"},
    {"cowpea@10/7", "9aa547fae71cb388"},
    {"cowpea@50/42", "c2305af7cca93114"},
    {"cowpea@50/7", "82766b90122337c8"},
    {"cowpea@100/42", "2a0ffe235d4e6d1a"},
    {"cowpea@100/7", "364bb5d97111e5a3"},
    {"easternredbud@200/42", "154d99d9ccff8404"},
    {"easternredbud@200/7", "caf557010fa5e95e"},
    {"easternredbud@630/42", "807519b5f8e368ef"},
    {"easternredbud@630/7", "7edffb5fa693f1b1"},
    {"easternredbud@1400/42", "4f62aac6a6713114"},
    {"easternredbud@1400/7", "098ec4107e97c6fb"},
    {"grapevine_VSP@180/42", "b7552f1bcac0d65c"},
    {"grapevine_VSP@180/7", "cd3c93f16f757c2c"},
    {"grapevine_VSP@270/42", "7b74a8e30f36b0cc"},
    {"grapevine_VSP@270/7", "f0b0d3601c4445bd"},
    {"grapevine_VSP@360/42", "7b74a8e30f36b0cc"},
    {"grapevine_VSP@360/7", "f0b0d3601c4445bd"},
    {"grapevine_Wye@180/42", "b1537e527bbd29f5"},
    {"grapevine_Wye@180/7", "26f24e7bff6735f9"},
    {"grapevine_Wye@270/42", "21e8ece8f7d47135"},
    {"grapevine_Wye@270/7", "35d7ddc122745312"},
    {"grapevine_Wye@360/42", "21e8ece8f7d47135"},
    {"grapevine_Wye@360/7", "35d7ddc122745312"},
    {"groundcherryweed@10/42", "3bfbcccfcf824c35"},
    {"groundcherryweed@10/7", "a313826b271de141"},
    {"groundcherryweed@50/42", "f37c5eafcba2d082"},
    {"groundcherryweed@50/7", "c7c7386aeecb7de9"},
    {"groundcherryweed@80/42", "f6b5f7547c4575bc"},
    {"groundcherryweed@80/7", "d700a20a0d38b40e"},
    {"maize@10/42", "088b50b2aa8c14bf"},
    {"maize@10/7", "42280c3c0df103b3"},
    {"maize@50/42", "8de4e792be84a53d"},
    {"maize@50/7", "b8752aa301a7c686"},
    {"maize@120/42", "0f0550e513dd26a9"},
    {"maize@120/7", "4cd0168fc2f62f19"},
    {"olive@200/42", "b6fc514c89535c4f"},
    {"olive@200/7", "0aa1915d543e5b3c"},
    {"olive@630/42", "df1ea44dc5fd8729"},
    {"olive@630/7", "e7a76f6f3488c94e"},
    {"olive@1400/42", "d6965ee7cfaa5480"},
    {"olive@1400/7", "ab577b17a24c34b8"},
    {"pistachio@200/42", "8bcacf4a3867ab3f"},
    {"pistachio@200/7", "7ed8a42bf115bb63"},
    {"pistachio@630/42", "17a368c6b6829a0e"},
    {"pistachio@630/7", "9725baea406cfaad"},
    {"pistachio@1000/42", "75ec50073fcc2bbd"},
    {"pistachio@1000/7", "f8096d8dcc83cf90"},
    {"puncturevine@10/42", "d10012e52058b063"},
    {"puncturevine@10/7", "c7c260fe73a25f73"},
    {"puncturevine@45/42", "8ac8d300695e3c95"},
    {"puncturevine@45/7", "3ac390e0806d04a1"},
    {"rice@10/42", "f7e180cab38ee187"},
    {"rice@10/7", "5725111fbb1f27c2"},
    {"rice@50/42", "5178fc8b40c41876"},
    {"rice@50/7", "8ae676fe5002cd91"},
    {"rice@120/42", "eb9d44fc11e4b8b7"},
    {"rice@120/7", "e65b5fe18f0c85cc"},
    {"sorghum@10/42", "dc841d3c7651979e"},
    {"sorghum@10/7", "dbf1c7603e216b66"},
    {"sorghum@50/42", "d29f68b7fa1a9a81"},
    {"sorghum@50/7", "d9c1e653816890af"},
    {"sorghum@120/42", "7f365e0bb833da75"},
    {"sorghum@120/7", "b3f5c537f0c87b03"},
    {"soybean@10/42", "1b7c373abc757ecf"},
    {"soybean@10/7", "5ae0e72ee67c5d7a"},
    {"soybean@50/42", "1c502244f1398b49"},
    {"soybean@50/7", "094aa689975ad4f2"},
    {"soybean@100/42", "e7d476490756cc8f"},
    {"soybean@100/7", "71ccb615c899fb1b"},
    {"strawberry@10/42", "842b9dcf2baffa9a"},
    {"strawberry@10/7", "28de92e604b267e8"},
    {"strawberry@50/42", "8c5b42966f6e2ef1"},
    {"strawberry@50/7", "109348193353634c"},
    {"strawberry@120/42", "d4e40cfa7d48aeca"},
    {"strawberry@120/7", "b3aaf3befe04b181"},
    {"sugarbeet@10/42", "da27855ca40b6c3b"},
    {"sugarbeet@10/7", "98966122cf1d2141"},
    {"sugarbeet@50/42", "598acfc3202e2565"},
    {"sugarbeet@50/7", "8093f77564c9b247"},
    {"sugarbeet@150/42", "5f8c53eb6a7ac9eb"},
    {"sugarbeet@150/7", "fe9e918f2c220e98"},
    {"tomato@10/42", "be22b22ec1544f4b"},
    {"tomato@10/7", "be41653d4983cc52"},
    {"tomato@50/42", "70c1fe5f1ea01e42"},
    {"tomato@50/7", "ab8ff39656b2a047"},
    {"tomato@120/42", "3c27155f745120dc"},
    {"tomato@120/7", "44f16656b95a45c2"},
    {"walnut@200/42", "c5ef26c5abffe827"},
    {"walnut@200/7", "75c15bca14bda51e"},
    {"walnut@630/42", "10b6f27e2f5a1388"},
    {"walnut@630/7", "57cdfb48d9675b10"},
    {"walnut@1000/42", "e09207985908d255"},
    {"walnut@1000/7", "ddd7e7ddaff4c2fc"},
    {"wheat@10/42", "cabaf39257c98d00"},
    {"wheat@10/7", "cab33736a1796790"},
    {"wheat@50/42", "41f056a243bfd68f"},
    {"wheat@50/7", "4d2885bc868c48c1"},
    {"wheat@120/42", "8556a9d6b39760f8"},
    {"wheat@120/7", "5e956c59f7e62f7c"},
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
