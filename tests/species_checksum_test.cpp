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
    {"almond@120/42", "ecc673f514446195"},
    {"almond@120/7", "4c6617ccee04a9f1"},
    {"almond@630/42", "d86f0ef4810ae38f"},
    {"almond@630/7", "96314dfd71484b13"},
    {"almond@1000/42", "1b7c9e5e79956c61"},
    {"almond@1000/7", "bcff9da0016dd3ca"},
    {"almond_aldrich@120/42", "0ee63764f9dab981"},
    {"almond_aldrich@120/7", "bfc4c9bf9372dcfa"},
    {"almond_aldrich@630/42", "3e8858ae733cb3a8"},
    {"almond_aldrich@630/7", "a0ce9f636e2e6700"},
    {"almond_aldrich@1000/42", "c220211a168db31b"},
    {"almond_aldrich@1000/7", "8f05c9008c98d31d"},
    {"almond_wood_colony@120/42", "79a6e1c2c0c12f96"},
    {"almond_wood_colony@120/7", "5a12557af226eaf7"},
    {"almond_wood_colony@630/42", "cebc4b725f14345a"},
    {"almond_wood_colony@630/7", "69a9278c6f8d594c"},
    {"almond_wood_colony@1000/42", "5ffc23fbf4d18b7a"},
    {"almond_wood_colony@1000/7", "e2b3954e0187d571"},
    {"apple@200/42", "6d6b844c9d5b7ff1"},
    {"apple@200/7", "2d601ce47b848da5"},
    {"apple@630/42", "f93a8ba5570a7b2d"},
    {"apple@630/7", "f844c2e83b0629b7"},
    {"apple@1400/42", "3592e5bb9a64fb1f"},
    {"apple@1400/7", "671314f138330ab0"},
    {"apple_fruitingwall@200/42", "c07f56b1838c9191"},
    {"apple_fruitingwall@200/7", "20295f0352b75d98"},
    {"apple_fruitingwall@630/42", "64d29a1234a4e84c"},
    {"apple_fruitingwall@630/7", "601692bdc50c8694"},
    {"apple_fruitingwall@720/42", "64d29a1234a4e84c"},
    {"apple_fruitingwall@720/7", "601692bdc50c8694"},
    {"asparagus@5/42", "ddc57b323ff7b54c"},
    {"asparagus@5/7", "3fda820d1f58ae41"},
    {"asparagus@20/42", "974f56e6e370448f"},
    {"asparagus@20/7", "0e0b1df7078f97f4"},
    {"bean@10/42", "75ab850f1347e251"},
    {"bean@10/7", "f9bd202ac170aeb4"},
    {"bean@45/42", "787330590781cf2e"},
    {"bean@45/7", "335050d937ef2865"},
    {"bean@100/42", "22ab918d1f04c061"},
    {"bean@100/7", "401dc401cdd0e253"},
    {"bindweed@10/42", "26e1fb71509cf36c"},
    {"bindweed@10/7", "672fda4d141f76bc"},
    {"bindweed@50/42", "4a09aa5059b1b85a"},
    {"bindweed@50/7", "9c2bf3cb93af03a1"},
    {"bougainvillea@30/42", "d6b0f28dfe7cf713"},
    {"bougainvillea@30/7", "69ec6d76480d450e"},
    {"bougainvillea@180/42", "1aad3ca5d40a72df"},
    {"bougainvillea@180/7", "0f648b5cec4e7cc3"},
    {"bougainvillea@365/42", "8b5f55981fe3ca95"},
    {"bougainvillea@365/7", "cc7555bd289dce58"},
    {"butterlettuce@10/42", "b5660568381b9986"},
    {"butterlettuce@10/7", "c4c4b69f6e17f52f"},
    {"butterlettuce@50/42", "2779069a9845f882"},
    {"butterlettuce@50/7", "b1aa75250a25b912"},
    {"butterlettuce@70/42", "09b899f8239c2493"},
    {"butterlettuce@70/7", "79570d32bcead3ae"},
    {"capsicum@10/42", "d4209fe8555e0b7c"},
    {"capsicum@10/7", "fb35245760d67ea5"},
    {"capsicum@50/42", "23a395b39a777aaa"},
    {"capsicum@50/7", "47aa265cfa4d6ab7"},
    {"capsicum@150/42", "ce2279acee2beb67"},
    {"capsicum@150/7", "b0cd1d73d4435cfb"},
    {"cheeseweed@10/42", "c80a0f322b0e85fd"},
    {"cheeseweed@10/7", "232a5f667538a16e"},
    {"cheeseweed@40/42", "ecd00a5df011ca4e"},
    {"cheeseweed@40/7", "c0f937d2812787ce"},
    {"cherrytomato@10/42", "350e38845dc16192"},
    {"cherrytomato@10/7", "059b2290b58ca294"},
    {"cherrytomato@50/42", "58d57bf2a0f8492f"},
    {"cherrytomato@50/7", "9cfcf5ea86f3195b"},
    {"cherrytomato@175/42", "21b464b1fda82e09"},
    {"cherrytomato@175/7", "c3643c8467af96f2"},
    {"cowpea@10/42", "fe10ed3effa4ec56"},
    {"cowpea@10/7", "fe42808b01576b89"},
    {"cowpea@50/42", "fd3e3563d4340d8f"},
    {"cowpea@50/7", "f404a358f4b52bee"},
    {"cowpea@100/42", "30d4c6d371f091a3"},
    {"cowpea@100/7", "534b7bdd940218dd"},
    {"easternredbud@200/42", "8f7d166678ff53af"},
    {"easternredbud@200/7", "3069335d31ee93ac"},
    {"easternredbud@630/42", "ce712f689c4626ad"},
    {"easternredbud@630/7", "244e68ca3da8c162"},
    {"easternredbud@1400/42", "431c6b56a5b7a500"},
    {"easternredbud@1400/7", "30c9be9c866f136c"},
    {"grapevine_VSP@180/42", "9f6f26c150f67de8"},
    {"grapevine_VSP@180/7", "b74063fd7da0cf08"},
    {"grapevine_VSP@270/42", "f9f35aa44b345eed"},
    {"grapevine_VSP@270/7", "9336ea92d7682aa7"},
    {"grapevine_VSP@360/42", "f9f35aa44b345eed"},
    {"grapevine_VSP@360/7", "9336ea92d7682aa7"},
    {"grapevine_Wye@180/42", "bc2d71c4c70a464c"},
    {"grapevine_Wye@180/7", "03bee96fcb3ae527"},
    {"grapevine_Wye@270/42", "4e794bcc77c6d7b5"},
    {"grapevine_Wye@270/7", "372e05ca2c1d1516"},
    {"grapevine_Wye@360/42", "4e794bcc77c6d7b5"},
    {"grapevine_Wye@360/7", "372e05ca2c1d1516"},
    {"groundcherryweed@10/42", "b2a0167508553887"},
    {"groundcherryweed@10/7", "352a8e474d241796"},
    {"groundcherryweed@50/42", "e26c6e34b8d216d5"},
    {"groundcherryweed@50/7", "af7be91ee864a8de"},
    {"groundcherryweed@80/42", "69f53f49aabb8932"},
    {"groundcherryweed@80/7", "f07a9174995debd9"},
    {"maize@10/42", "9522a9a93853638d"},
    {"maize@10/7", "06c1707465460cc0"},
    {"maize@50/42", "1228579bc869c593"},
    {"maize@50/7", "7af624a6d8a5e40d"},
    {"maize@120/42", "ad18b881df428f83"},
    {"maize@120/7", "63d2326127474055"},
    {"olive@200/42", "0bd884b732ac75f9"},
    {"olive@200/7", "02e3ac43f2f450b4"},
    {"olive@630/42", "9fdbaa4935d15a0d"},
    {"olive@630/7", "a12452c7071d6cbe"},
    {"olive@1400/42", "b89320ae05adcba3"},
    {"olive@1400/7", "a28720ea686bda89"},
    {"pistachio@200/42", "113cfce70fd39681"},
    {"pistachio@200/7", "11ce63dad59c4afc"},
    {"pistachio@630/42", "9a892f1157d07707"},
    {"pistachio@630/7", "fed098418534da79"},
    {"pistachio@1000/42", "21bc11d6aedc508c"},
    {"pistachio@1000/7", "a2a934655f3e2e62"},
    {"puncturevine@10/42", "c81569beb8d06c83"},
    {"puncturevine@10/7", "87ed0227f6d71f74"},
    {"puncturevine@45/42", "845c69dd1cc8dd4e"},
    {"puncturevine@45/7", "71e460d803d91fa4"},
    {"rice@10/42", "8ffb55c52bfbd8ef"},
    {"rice@10/7", "339624c6553c2e21"},
    {"rice@50/42", "892b6c243e44ffcc"},
    {"rice@50/7", "fa9e11d86cc6559b"},
    {"rice@120/42", "f8536fdfce3ceeaf"},
    {"rice@120/7", "5c193649a9519c8b"},
    {"sorghum@10/42", "95c46da2dcf500c3"},
    {"sorghum@10/7", "8bd8575f9077c8d6"},
    {"sorghum@50/42", "d9981c3ed826bc60"},
    {"sorghum@50/7", "48403b2e06f49b02"},
    {"sorghum@120/42", "b10566d6f93b2683"},
    {"sorghum@120/7", "9d7cea57b8035960"},
    {"soybean@10/42", "c55163948445b6b0"},
    {"soybean@10/7", "c547391ead6ada8f"},
    {"soybean@50/42", "fe0f89a46bd1a844"},
    {"soybean@50/7", "4d8ab4d687d4640e"},
    {"soybean@100/42", "51917fd7c3661e6a"},
    {"soybean@100/7", "552db6f2fdd0108e"},
    {"strawberry@10/42", "0c8594103684caff"},
    {"strawberry@10/7", "981b0eb497ceaa4f"},
    {"strawberry@50/42", "23bc57e1f3751b11"},
    {"strawberry@50/7", "e76ab7b60b7aacfd"},
    {"strawberry@120/42", "08213db927dc3ab4"},
    {"strawberry@120/7", "ed8ac1cf5245bd1e"},
    {"sugarbeet@10/42", "e83aa786c43ebe35"},
    {"sugarbeet@10/7", "03fb5e9ea206fe3e"},
    {"sugarbeet@50/42", "723d6f0155c841b3"},
    {"sugarbeet@50/7", "074be13f6f3df951"},
    {"sugarbeet@150/42", "2ce29dfd040bb4e4"},
    {"sugarbeet@150/7", "a0820a5fec293091"},
    {"tomato@10/42", "9bba8edba99973cd"},
    {"tomato@10/7", "1f9744bda77820b9"},
    {"tomato@50/42", "3e104b2dee0711c2"},
    {"tomato@50/7", "1e3bedff39d3760f"},
    {"tomato@120/42", "0d07eb7f7bdb8e9c"},
    {"tomato@120/7", "255613b266aaba04"},
    {"walnut@200/42", "eb7c80ad40122ed1"},
    {"walnut@200/7", "7964ad1ddd87b11d"},
    {"walnut@630/42", "3e1ba12900ce9488"},
    {"walnut@630/7", "4f19f87cfb6680b3"},
    {"walnut@1000/42", "991fe0b1adafcfb7"},
    {"walnut@1000/7", "523201c4a448df5c"},
    {"wheat@10/42", "c378a53994b8e1ef"},
    {"wheat@10/7", "005895bb63e2c728"},
    {"wheat@50/42", "61c343c91f5cbbf9"},
    {"wheat@50/7", "cab31788d3544447"},
    {"wheat@120/42", "30cd6c269eeb69aa"},
    {"wheat@120/7", "0cd4bab5fbedda67"},
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
