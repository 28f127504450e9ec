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
    {"almond@120/42", "338d021c1b60303c"},
    {"almond@120/7", "87a21db8c11853dc"},
    {"almond@630/42", "78c01e002c52906c"},
    {"almond@630/7", "9086c07853c78d6e"},
    {"almond@1000/42", "4ccf21ef528f4c35"},
    {"almond@1000/7", "1e320cfb19c50f7c"},
    {"almond_aldrich@120/42", "dc5b3e422b80c040"},
    {"almond_aldrich@120/7", "b2280a17799d249a"},
    {"almond_aldrich@630/42", "e1ff302d14ca9da7"},
    {"almond_aldrich@630/7", "b34e4b84f7b894d0"},
    {"almond_aldrich@1000/42", "274d00dc8a74aea5"},
    {"almond_aldrich@1000/7", "4e374d2d564af213"},
    {"almond_wood_colony@120/42", "001f7e92a527fbe5"},
    {"almond_wood_colony@120/7", "010e9d3ad09b79ef"},
    {"almond_wood_colony@630/42", "2e9e82580cdf040f"},
    {"almond_wood_colony@630/7", "8932df55542382ad"},
    {"almond_wood_colony@1000/42", "fafc01fd1e48d7e0"},
    {"almond_wood_colony@1000/7", "5ff6662b27bffbdf"},
    {"apple@200/42", "48ed128399b03515"},
    {"apple@200/7", "1284ff95cd9298ef"},
    {"apple@630/42", "8ffecd3c7f53272e"},
    {"apple@630/7", "9e018c224c308377"},
    {"apple@1400/42", "0fc7cb8f5c137dfa"},
    {"apple@1400/7", "854762ef4f61ba04"},
    {"apple_fruitingwall@200/42", "0b6fd6596c1438bc"},
    {"apple_fruitingwall@200/7", "fa0abe6821b99497"},
    {"apple_fruitingwall@630/42", "859780c2eed4ab04"},
    {"apple_fruitingwall@630/7", "9bdf9fcd51f5f591"},
    {"apple_fruitingwall@720/42", "859780c2eed4ab04"},
    {"apple_fruitingwall@720/7", "9bdf9fcd51f5f591"},
    {"asparagus@5/42", "747ba5c9e9d61908"},
    {"asparagus@5/7", "e1651a517d7b9a03"},
    {"asparagus@20/42", "9cb44847025824e4"},
    {"asparagus@20/7", "9dce09a7c1d15eec"},
    {"asparagus@20/42", "9cb44847025824e4"},
    {"asparagus@20/7", "9dce09a7c1d15eec"},
    {"bean@10/42", "2e5c9b4208e65abd"},
    {"bean@10/7", "9d91ad54a11e4e3a"},
    {"bean@45/42", "2fadcb807197dd8e"},
    {"bean@45/7", "f0f682a275509d46"},
    {"bean@100/42", "58f54e5fbd578091"},
    {"bean@100/7", "d34464b025dea8c7"},
    {"bindweed@10/42", "82e95b5548960a53"},
    {"bindweed@10/7", "472c54095a1b8b5c"},
    {"bindweed@50/42", "19a9d765b31e93b8"},
    {"bindweed@50/7", "91da91daa45dacc2"},
    {"bindweed@50/42", "19a9d765b31e93b8"},
    {"bindweed@50/7", "91da91daa45dacc2"},
    {"bougainvillea@30/42", "07c60d16528e18c1"},
    {"bougainvillea@30/7", "b4e2bbc19b96f813"},
    {"bougainvillea@180/42", "7757da0a26dae208"},
    {"bougainvillea@180/7", "4a4d004bd6b2b8be"},
    {"bougainvillea@365/42", "7050f8595bc89735"},
    {"bougainvillea@365/7", "e62f4b69ce36d436"},
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
    {"cowpea@50/42", "c7000f5c3a00e9d6"},
    {"cowpea@50/7", "34677173b09fb943"},
    {"cowpea@100/42", "35caf7b389ecacb2"},
    {"cowpea@100/7", "badd409c82cc6be5"},
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
    {"soybean@50/42", "82b7b8c9c746f67a"},
    {"soybean@50/7", "af86911677315af0"},
    {"soybean@100/42", "4e86f367f8e8502b"},
    {"soybean@100/7", "37825adc39f8c00d"},
    {"strawberry@10/42", "8ee93672fcd5767e"},
    {"strawberry@10/7", "7e33c1091bab1a21"},
    {"strawberry@50/42", "fdc57c28164aba11"},
    {"strawberry@50/7", "9123207c0641fd1b"},
    {"strawberry@120/42", "748b462c2bcb3cae"},
    {"strawberry@120/7", "0ec4adf429a0f997"},
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
    {"walnut@200/42", "d240767ae41da680"},
    {"walnut@200/7", "9cec60007d213ce0"},
    {"walnut@630/42", "68f8fb65356f5f34"},
    {"walnut@630/7", "6c1892db07f20f1f"},
    {"walnut@1000/42", "674fcc9524fa911c"},
    {"walnut@1000/7", "ef663d86714382f9"},
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
