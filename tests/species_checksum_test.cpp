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
    {"almond@120/42", "16366ae6779afdaf"},
    {"almond@120/7", "9f07f38e7d65747e"},
    {"almond@630/42", "835908c037e8870f"},
    {"almond@630/7", "dd172778c7d1d48d"},
    {"almond@1000/42", "f3ec971cfd60b28c"},
    {"almond@1000/7", "f987dbe168a6ff99"},
    {"almond_aldrich@120/42", "cd192b80ec5676b9"},
    {"almond_aldrich@120/7", "fd6d80db3bd71fa2"},
    {"almond_aldrich@630/42", "1790a5c92401f84c"},
    {"almond_aldrich@630/7", "24443151d57f7895"},
    {"almond_aldrich@1000/42", "8856920fdd377ee6"},
    {"almond_aldrich@1000/7", "24f87f87dbd7bea2"},
    {"almond_wood_colony@120/42", "cd0af2bb402c856c"},
    {"almond_wood_colony@120/7", "2d2882ab9ae7bd61"},
    {"almond_wood_colony@630/42", "01c48d3c484691bc"},
    {"almond_wood_colony@630/7", "f4fedbf3aac530b3"},
    {"almond_wood_colony@1000/42", "99b5cfe78d51bbf9"},
    {"almond_wood_colony@1000/7", "d0cf7b2062423ea0"},
    {"apple@200/42", "73a243fd04fe4851"},
    {"apple@200/7", "2d601ce47b848da5"},
    {"apple@630/42", "248b280139ae3e8f"},
    {"apple@630/7", "55ec213b1e9dd846"},
    {"apple@1400/42", "09188b8a820f3a60"},
    {"apple@1400/7", "90ec82264799f234"},
    {"apple_fruitingwall@200/42", "1eed9a80f46d34cd"},
    {"apple_fruitingwall@200/7", "ae242aae8bae9b9a"},
    {"apple_fruitingwall@630/42", "15a00ebcae4c9887"},
    {"apple_fruitingwall@630/7", "d8ab4affd799eb78"},
    {"apple_fruitingwall@720/42", "15a00ebcae4c9887"},
    {"apple_fruitingwall@720/7", "d8ab4affd799eb78"},
    {"asparagus@5/42", "69dc943c161b6943"},
    {"asparagus@5/7", "0cf88e842c5134fc"},
    {"asparagus@20/42", "db5cff1c38f9c991"},
    {"asparagus@20/7", "7035912b56a1c167"},
    {"bean@10/42", "0f45dfe7fade1f10"},
    {"bean@10/7", "522641e7b0d6b089"},
    {"bean@45/42", "b0d4b9eba68b8336"},
    {"bean@45/7", "c2a5796a1995984d"},
    {"bean@100/42", "3cb8833bd86835b2"},
    {"bean@100/7", "9ba3e5b4f815c26f"},
    {"bindweed@10/42", "26e1fb71509cf36c"},
    {"bindweed@10/7", "de05b7dc76c6657e"},
    {"bindweed@50/42", "4fae445278873094"},
    {"bindweed@50/7", "8bdc37d93fdfec41"},
    {"bougainvillea@30/42", "7c080378e5bdbc42"},
    {"bougainvillea@30/7", "7c828807b1731068"},
    {"bougainvillea@180/42", "c1785a5ae0bd375a"},
    {"bougainvillea@180/7", "8f5ba19e6bb8f806"},
    {"bougainvillea@365/42", "2ab2f2809d7ce085"},
    {"bougainvillea@365/7", "b066099397646d34"},
    {"butterlettuce@10/42", "2d64e92de88bfe63"},
    {"butterlettuce@10/7", "e3f739910974f364"},
    {"butterlettuce@50/42", "bd60a829dd5ca056"},
    {"butterlettuce@50/7", "6589f3dc47f2e394"},
    {"butterlettuce@70/42", "b43a0ec5d5f59b7e"},
    {"butterlettuce@70/7", "899195bfc08255dd"},
    {"capsicum@10/42", "d4209fe8555e0b7c"},
    {"capsicum@10/7", "fb35245760d67ea5"},
    {"capsicum@50/42", "e20b77cb59725771"},
    {"capsicum@50/7", "62aed47100ac7987"},
    {"capsicum@150/42", "f3c69ff5f9b66cc3"},
    {"capsicum@150/7", "3b272e295a55f642"},
    {"cheeseweed@10/42", "5d772c1239755117"},
    {"cheeseweed@10/7", "aa19bb2c14c05735"},
    {"cheeseweed@40/42", "5783280e78c0478a"},
    {"cheeseweed@40/7", "2fc31d21162e1365"},
    {"cherrytomato@10/42", "746f194e2bc2f1f7"},
    {"cherrytomato@10/7", "279920b156c98874"},
    {"cherrytomato@50/42", "abefbbdf5e15386a"},
    {"cherrytomato@50/7", "a38b7af5f8372d44"},
    {"cherrytomato@175/42", "3e78edb56f7815da"},
    {"cherrytomato@175/7", "2cb583c989644bc5"},
    {"cowpea@10/42", "9ab111b6270273cc"},
    {"cowpea@10/7", "47859d5140de2030"},
    {"cowpea@50/42", "e213e7ab7accadcc"},
    {"cowpea@50/7", "b71e38a77c1fe106"},
    {"cowpea@100/42", "8500bae220f9ca11"},
    {"cowpea@100/7", "d7db8e3834529b3e"},
    {"easternredbud@200/42", "4cbfc6b8c3c21158"},
    {"easternredbud@200/7", "af9ac93e97b39ee2"},
    {"easternredbud@630/42", "c1197173a6043fc8"},
    {"easternredbud@630/7", "e3148327e856cc97"},
    {"easternredbud@1400/42", "d833148d9f722d2b"},
    {"easternredbud@1400/7", "e1ae5eae34913273"},
    {"grapevine_VSP@180/42", "9f6f26c150f67de8"},
    {"grapevine_VSP@180/7", "b74063fd7da0cf08"},
    {"grapevine_VSP@270/42", "83c1e6e410c57bcd"},
    {"grapevine_VSP@270/7", "bdc9a2933532c111"},
    {"grapevine_VSP@360/42", "83c1e6e410c57bcd"},
    {"grapevine_VSP@360/7", "bdc9a2933532c111"},
    {"grapevine_Wye@180/42", "bc2d71c4c70a464c"},
    {"grapevine_Wye@180/7", "03bee96fcb3ae527"},
    {"grapevine_Wye@270/42", "0661286f9337ceec"},
    {"grapevine_Wye@270/7", "b9b934631f752747"},
    {"grapevine_Wye@360/42", "0661286f9337ceec"},
    {"grapevine_Wye@360/7", "b9b934631f752747"},
    {"groundcherryweed@10/42", "dbf37dcd5290cb5a"},
    {"groundcherryweed@10/7", "0adaf0c1b4de4ac7"},
    {"groundcherryweed@50/42", "b2647dad814be6d0"},
    {"groundcherryweed@50/7", "968257a5afd4e5c1"},
    {"groundcherryweed@80/42", "351f893d349b1fec"},
    {"groundcherryweed@80/7", "6e9702b45fe266cd"},
    {"maize@10/42", "d7dc0face4d8fa43"},
    {"maize@10/7", "fb5a9a3bf5cde877"},
    {"maize@50/42", "b0fd39f91f0165af"},
    {"maize@50/7", "9e92cf97647ffda8"},
    {"maize@120/42", "b0fd39f91f0165af"},
    {"maize@120/7", "9e92cf97647ffda8"},
    {"olive@200/42", "6dfcd1ad8096575e"},
    {"olive@200/7", "62130fba70b548c2"},
    {"olive@630/42", "a5abb53b64236ef7"},
    {"olive@630/7", "64ada67a017e7f6e"},
    {"olive@1400/42", "360a9558d0a5837a"},
    {"olive@1400/7", "35aea63ca9a4bae9"},
    {"pistachio@200/42", "62a6332c9a9344c7"},
    {"pistachio@200/7", "73579e9cb840aad0"},
    {"pistachio@630/42", "f79439a40ebcf0c5"},
    {"pistachio@630/7", "4181e5904eb769c1"},
    {"pistachio@1000/42", "f5c794020009f59b"},
    {"pistachio@1000/7", "f77a97d72e846cc2"},
    {"puncturevine@10/42", "c81569beb8d06c83"},
    {"puncturevine@10/7", "87ed0227f6d71f74"},
    {"puncturevine@45/42", "d4159212b7a16447"},
    {"puncturevine@45/7", "d4aee4608656f965"},
    {"rice@10/42", "40d783a0b4ac60b8"},
    {"rice@10/7", "b7b766d5ae2e2271"},
    {"rice@50/42", "7126d01005ee1a7c"},
    {"rice@50/7", "6544d1ecb83e6dc4"},
    {"rice@120/42", "47f928abcedb850c"},
    {"rice@120/7", "c3865e39fcfdb2e7"},
    {"sorghum@10/42", "9201e7529166256b"},
    {"sorghum@10/7", "4c09875fb3fc49dc"},
    {"sorghum@50/42", "ae9cbe45cae089db"},
    {"sorghum@50/7", "bb0fc657e7b2e78b"},
    {"sorghum@120/42", "ae9cbe45cae089db"},
    {"sorghum@120/7", "bb0fc657e7b2e78b"},
    {"soybean@10/42", "81bffe44d023bf39"},
    {"soybean@10/7", "a6c44d170d59ea4e"},
    {"soybean@50/42", "b494a3de1d6167e0"},
    {"soybean@50/7", "16081a7c21356790"},
    {"soybean@100/42", "db104a1763542b4b"},
    {"soybean@100/7", "42e0d5c0fbd0277e"},
    {"strawberry@10/42", "0c8594103684caff"},
    {"strawberry@10/7", "981b0eb497ceaa4f"},
    {"strawberry@50/42", "80f861c0258a080b"},
    {"strawberry@50/7", "285097d57f7bb586"},
    {"strawberry@120/42", "033aeb16de485eb6"},
    {"strawberry@120/7", "75f62a63b3a34989"},
    {"sugarbeet@10/42", "51ef69654393a172"},
    {"sugarbeet@10/7", "3d045b3a51a7e1ee"},
    {"sugarbeet@50/42", "df970dc6585ad819"},
    {"sugarbeet@50/7", "45c5f99445d75a7a"},
    {"sugarbeet@150/42", "072584f691c4be26"},
    {"sugarbeet@150/7", "bedc0e8fd68d7257"},
    {"tomato@10/42", "404bb171fae17f14"},
    {"tomato@10/7", "985ff5554e7fefc3"},
    {"tomato@50/42", "08e56a5d7a512a6f"},
    {"tomato@50/7", "5e6cc6f0d9eb66be"},
    {"tomato@120/42", "422ee0f65cbe7876"},
    {"tomato@120/7", "e57518b66f439673"},
    {"walnut@200/42", "b319b124d260ca0f"},
    {"walnut@200/7", "eaed10e09edcac71"},
    {"walnut@630/42", "9c69edc70d1df18c"},
    {"walnut@630/7", "5d7a02e49831225c"},
    {"walnut@1000/42", "ae988f7ad6c459fe"},
    {"walnut@1000/7", "e6abe22dc02e763e"},
    {"wheat@10/42", "e10f29b6f14d0169"},
    {"wheat@10/7", "7a8df844ac51f2c6"},
    {"wheat@50/42", "d3b26590dd023d6c"},
    {"wheat@50/7", "f268fe6081b5fbb4"},
    {"wheat@120/42", "20beca2acefe3eba"},
    {"wheat@120/7", "a1f77b6722140548"},
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
