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
    {"almond@120/42", "056191dbe1462d80"},
    {"almond@120/7", "fafb6fbd42de0f5f"},
    {"almond@630/42", "023f9ce37fd15398"},
    {"almond@630/7", "901535beb905ca95"},
    {"almond@1000/42", "7dff7089659be82d"},
    {"almond@1000/7", "ed5f5a9fe780d45d"},
    {"almond_aldrich@120/42", "e7daac9b7a74720c"},
    {"almond_aldrich@120/7", "7f3f81467e8ce83f"},
    {"almond_aldrich@630/42", "1732ec9115406947"},
    {"almond_aldrich@630/7", "08b2f700502b55d2"},
    {"almond_aldrich@1000/42", "2db01ed9db899318"},
    {"almond_aldrich@1000/7", "c402bf34913069b7"},
    {"almond_wood_colony@120/42", "b6312b587c5eaadb"},
    {"almond_wood_colony@120/7", "f75b9e9d0263eafa"},
    {"almond_wood_colony@630/42", "b93f84788c6fe571"},
    {"almond_wood_colony@630/7", "ef8bbdff07b3c8ac"},
    {"almond_wood_colony@1000/42", "0ea3b9999f7a4de4"},
    {"almond_wood_colony@1000/7", "0a9a109b3520be93"},
    {"apple@200/42", "04088d6fc9b4a783"},
    {"apple@200/7", "33ee85b9eeee8c71"},
    {"apple@630/42", "73794afb85a92d76"},
    {"apple@630/7", "3e2f1b7c6b479a8b"},
    {"apple@1400/42", "3afe5c37be6eddc4"},
    {"apple@1400/7", "2a33b087940df84a"},
    {"apple_fruitingwall@200/42", "b1fee69957af2732"},
    {"apple_fruitingwall@200/7", "e1b9558356b14ffc"},
    {"apple_fruitingwall@630/42", "99ae1b3d3be41ae7"},
    {"apple_fruitingwall@630/7", "37fa8caa95346138"},
    {"apple_fruitingwall@720/42", "99ae1b3d3be41ae7"},
    {"apple_fruitingwall@720/7", "37fa8caa95346138"},
    {"asparagus@5/42", "747ba5c9e9d61908"},
    {"asparagus@5/7", "e1651a517d7b9a03"},
    {"asparagus@20/42", "9cb44847025824e4"},
    {"asparagus@20/7", "9dce09a7c1d15eec"},
    {"asparagus@20/42", "9cb44847025824e4"},
    {"asparagus@20/7", "9dce09a7c1d15eec"},
    {"bean@10/42", "2e5c9b4208e65abd"},
    {"bean@10/7", "9d91ad54a11e4e3a"},
    {"bean@45/42", "44332437a6f015f4"},
    {"bean@45/7", "b6c080e328915b31"},
    {"bean@100/42", "3d93f40d0855fefe"},
    {"bean@100/7", "f3df522caf1f3da0"},
    {"bindweed@10/42", "82e95b5548960a53"},
    {"bindweed@10/7", "472c54095a1b8b5c"},
    {"bindweed@50/42", "19a9d765b31e93b8"},
    {"bindweed@50/7", "91da91daa45dacc2"},
    {"bindweed@50/42", "19a9d765b31e93b8"},
    {"bindweed@50/7", "91da91daa45dacc2"},
    {"bougainvillea@30/42", "07c60d16528e18c1"},
    {"bougainvillea@30/7", "b4e2bbc19b96f813"},
    {"bougainvillea@180/42", "56f462cb030866f8"},
    {"bougainvillea@180/7", "287770d2165a98d6"},
    {"bougainvillea@365/42", "a14d41bf6e2bb527"},
    {"bougainvillea@365/7", "319d5a6e345044cc"},
    {"butterlettuce@10/42", "c4442dbae323714f"},
    {"butterlettuce@10/7", "6ddbd373dd98c521"},
    {"butterlettuce@50/42", "8e3e061ee412925b"},
    {"butterlettuce@50/7", "5ae7e134468526b9"},
    {"butterlettuce@70/42", "928417d77b9086e0"},
    {"butterlettuce@70/7", "f57789348421d7ad"},
    {"capsicum@10/42", "d4209fe8555e0b7c"},
    {"capsicum@10/7", "fb35245760d67ea5"},
    {"capsicum@50/42", "c1b3b4010b61e3cb"},
    {"capsicum@50/7", "810af410fcad9dd1"},
    {"capsicum@150/42", "2410642753f9c821"},
    {"capsicum@150/7", "6046c2b9f274c59a"},
    {"cheeseweed@10/42", "c75bf9c5ae3aac00"},
    {"cheeseweed@10/7", "c59ee5cd8f793ffe"},
    {"cheeseweed@40/42", "a4572ee0663f72af"},
    {"cheeseweed@40/7", "6bd577d632d9b096"},
    {"cheeseweed@40/42", "a4572ee0663f72af"},
    {"cheeseweed@40/7", "6bd577d632d9b096"},
    {"cherrytomato@10/42", "d0c83d51e425573c"},
    {"cherrytomato@10/7", "0d838267e3fe3e48"},
    {"cherrytomato@50/42", "d057b5d9721b8fd5"},
    {"cherrytomato@50/7", "89ecf65e9031ad3a"},
    {"cherrytomato@175/42", "af286655df57f6c2"},
    {"cherrytomato@175/7", "0cb99196c07ae910"},
    {"cowpea@10/42", "a0d0c8b26cbc41a5"},
    {"cowpea@10/7", "5ac9457b18f28250"},
    {"cowpea@50/42", "d8656ba1c0c8ffc7"},
    {"cowpea@50/7", "c680c37fb7adff87"},
    {"cowpea@100/42", "d2a878643a4725f2"},
    {"cowpea@100/7", "5dde0074048b9d13"},
    {"easternredbud@200/42", "2621166022322cb7"},
    {"easternredbud@200/7", "fd24bb92715cd47b"},
    {"easternredbud@630/42", "c4a3eacfc106779a"},
    {"easternredbud@630/7", "d3c5b2449e581580"},
    {"easternredbud@1400/42", "cc4c887f9635e37e"},
    {"easternredbud@1400/7", "35e9182400bcefd4"},
    {"grapevine_VSP@180/42", "61197b3f6982e3bd"},
    {"grapevine_VSP@180/7", "bb1c9627c31aea50"},
    {"grapevine_VSP@270/42", "a9a02bda7a7ffb85"},
    {"grapevine_VSP@270/7", "5f133369e1391248"},
    {"grapevine_VSP@360/42", "dd6ac6096a19b106"},
    {"grapevine_VSP@360/7", "419f627268cd09cd"},
    {"grapevine_Wye@180/42", "dc60abf5d995f9bc"},
    {"grapevine_Wye@180/7", "e247bd5458da6e33"},
    {"grapevine_Wye@270/42", "c586958e091a296c"},
    {"grapevine_Wye@270/7", "de55b46d0a7f5c5f"},
    {"grapevine_Wye@360/42", "c7e0da8d4670d751"},
    {"grapevine_Wye@360/7", "1fca6ba05537dcc3"},
    {"groundcherryweed@10/42", "07bd2ac69a4bf376"},
    {"groundcherryweed@10/7", "c9567fca4ef9bcb2"},
    {"groundcherryweed@50/42", "965f7c1ae49e5db5"},
    {"groundcherryweed@50/7", "8f9547ae532a1dc5"},
    {"groundcherryweed@80/42", "9929fac2de7b9750"},
    {"groundcherryweed@80/7", "306e86d993e77717"},
    {"maize@10/42", "6aaf7790d494a231"},
    {"maize@10/7", "7f0183efe101d460"},
    {"maize@50/42", "358f7bc77deb7333"},
    {"maize@50/7", "2e2fc8f9c93c9d5a"},
    {"maize@120/42", "358f7bc77deb7333"},
    {"maize@120/7", "2e2fc8f9c93c9d5a"},
    {"olive@200/42", "b8c65445a68013b8"},
    {"olive@200/7", "397b13ace99ff15d"},
    {"olive@630/42", "21f2098e34ba757d"},
    {"olive@630/7", "669d9c4271873cb6"},
    {"olive@1400/42", "622f6b6d360775f5"},
    {"olive@1400/7", "45a4916446cedee5"},
    {"pistachio@200/42", "ee0ce014ae0d390e"},
    {"pistachio@200/7", "efaa0db9132ec1f8"},
    {"pistachio@630/42", "d220ea55a7a046cf"},
    {"pistachio@630/7", "ac1e36be14fc7dd8"},
    {"pistachio@1000/42", "05feb54545c19223"},
    {"pistachio@1000/7", "6dd07f5f42c513b3"},
    {"puncturevine@10/42", "3deb05916af1b810"},
    {"puncturevine@10/7", "120003b59b0b3275"},
    {"puncturevine@45/42", "ce150cbbdbe9dcde"},
    {"puncturevine@45/7", "b2d2446bc7366dbb"},
    {"puncturevine@45/42", "ce150cbbdbe9dcde"},
    {"puncturevine@45/7", "b2d2446bc7366dbb"},
    {"rice@10/42", "f1ab4da29aa6811c"},
    {"rice@10/7", "fcc5f643050636e0"},
    {"rice@50/42", "01c378f19132b4f0"},
    {"rice@50/7", "9a6f32dbf467ee60"},
    {"rice@120/42", "d9438309f31e4918"},
    {"rice@120/7", "5b026e131cc46e5d"},
    {"sorghum@10/42", "a1fc4c0c124dec2e"},
    {"sorghum@10/7", "fc8d08247e1f769d"},
    {"sorghum@50/42", "13c81a7effa0e91c"},
    {"sorghum@50/7", "437bf25ee64e72e4"},
    {"sorghum@120/42", "13c81a7effa0e91c"},
    {"sorghum@120/7", "437bf25ee64e72e4"},
    {"soybean@10/42", "0ef7ce2183f30b1e"},
    {"soybean@10/7", "9855fdf5069a9827"},
    {"soybean@50/42", "45fe23cdf2f11efe"},
    {"soybean@50/7", "af340d269be57fd8"},
    {"soybean@100/42", "fbd422f463f683a6"},
    {"soybean@100/7", "8e8e079c6e9797d4"},
    {"strawberry@10/42", "8ee93672fcd5767e"},
    {"strawberry@10/7", "7e33c1091bab1a21"},
    {"strawberry@50/42", "0861eade3ec89da8"},
    {"strawberry@50/7", "aecfbf296dc0d681"},
    {"strawberry@120/42", "7ad79f574f33a6ce"},
    {"strawberry@120/7", "6c2ff769ed40ca3d"},
    {"sugarbeet@10/42", "830976406e71287c"},
    {"sugarbeet@10/7", "7c3ef76f1c60c9ae"},
    {"sugarbeet@50/42", "8e8e8cfa37c556da"},
    {"sugarbeet@50/7", "0f7601c917259f85"},
    {"sugarbeet@150/42", "ddd7fb62615ca0c2"},
    {"sugarbeet@150/7", "82f8d75c80d63fc6"},
    {"tomato@10/42", "b3fd0ecf683f3382"},
    {"tomato@10/7", "fc19df7a7a80e10d"},
    {"tomato@50/42", "c342a341b935b1f3"},
    {"tomato@50/7", "7b949ce241b3806f"},
    {"tomato@120/42", "de8ed279f9354049"},
    {"tomato@120/7", "419ec39581ad9a50"},
    {"walnut@200/42", "436b286ad8121672"},
    {"walnut@200/7", "4d2d30896054bbda"},
    {"walnut@630/42", "a1344f053e5b851f"},
    {"walnut@630/7", "bc2cf407979991fb"},
    {"walnut@1000/42", "d60f24f958ae0250"},
    {"walnut@1000/7", "4dd28dba6541dbef"},
    {"wheat@10/42", "4babee0a97107d12"},
    {"wheat@10/7", "65faf50315031644"},
    {"wheat@50/42", "0ebf347c8ed6403b"},
    {"wheat@50/7", "aadf84733b3fcb9e"},
    {"wheat@120/42", "0ebf347c8ed6403b"},
    {"wheat@120/7", "aadf84733b3fcb9e"},
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
