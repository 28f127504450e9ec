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
    {"almond@120/42", "41278363d6c612ec"},
    {"almond@120/7", "482957a34653f7a8"},
    {"almond@630/42", "d532019971d8e47e"},
    {"almond@630/7", "28ff61bc7bc00cd1"},
    {"almond@1000/42", "b4aac413941eecce"},
    {"almond@1000/7", "2ac6f6508cf268eb"},
    {"almond_aldrich@120/42", "921e9c1b13aa797f"},
    {"almond_aldrich@120/7", "1cd37082e48cc4fa"},
    {"almond_aldrich@630/42", "fd369eac3508f1a4"},
    {"almond_aldrich@630/7", "12f48e4175208c03"},
    {"almond_aldrich@1000/42", "d7f83ed90bddd98e"},
    {"almond_aldrich@1000/7", "2339109f73172f08"},
    {"almond_wood_colony@120/42", "52cebfe84d9272f1"},
    {"almond_wood_colony@120/7", "718b8528f72fc31b"},
    {"almond_wood_colony@630/42", "2c82cf65fd55b7ae"},
    {"almond_wood_colony@630/7", "d8ef38c3c1f50e98"},
    {"almond_wood_colony@1000/42", "1fd5c0de6b5d3ba0"},
    {"almond_wood_colony@1000/7", "01f188d8eb2a71ea"},
    {"apple@200/42", "c7d3027c11f1eb2f"},
    {"apple@200/7", "a2482db4331ce9b2"},
    {"apple@630/42", "be8c8786899cd4d0"},
    {"apple@630/7", "c59faf202f971e97"},
    {"apple@1400/42", "4bfec828753c3f3e"},
    {"apple@1400/7", "36f2454fad7abc48"},
    {"apple_fruitingwall@200/42", "69842478d390b5b6"},
    {"apple_fruitingwall@200/7", "0afcd69439e45d01"},
    {"apple_fruitingwall@630/42", "374760532e2178b3"},
    {"apple_fruitingwall@630/7", "d3767b8f6889388e"},
    {"apple_fruitingwall@720/42", "374760532e2178b3"},
    {"apple_fruitingwall@720/7", "d3767b8f6889388e"},
    {"asparagus@5/42", "747ba5c9e9d61908"},
    {"asparagus@5/7", "e1651a517d7b9a03"},
    {"asparagus@20/42", "9cb44847025824e4"},
    {"asparagus@20/7", "9dce09a7c1d15eec"},
    {"asparagus@20/42", "9cb44847025824e4"},
    {"asparagus@20/7", "9dce09a7c1d15eec"},
    {"bean@10/42", "1081c59c9766c63b"},
    {"bean@10/7", "8a95f13f4263e9dd"},
    {"bean@45/42", "2f296706cd48fce8"},
    {"bean@45/7", "fc76f9a3b904a521"},
    {"bean@100/42", "2e216649cd05748f"},
    {"bean@100/7", "446c77f5d8b59c9e"},
    {"bindweed@10/42", "ecc0f6f45e77ca18"},
    {"bindweed@10/7", "d992e2c374102caf"},
    {"bindweed@50/42", "bb4f1ab4d0e0f44e"},
    {"bindweed@50/7", "1f45a485e74f82a9"},
    {"bindweed@50/42", "bb4f1ab4d0e0f44e"},
    {"bindweed@50/7", "1f45a485e74f82a9"},
    {"bougainvillea@30/42", "16000c754d274084"},
    {"bougainvillea@30/7", "13b5af224a29a56e"},
    {"bougainvillea@180/42", "2c58f5735b16371d"},
    {"bougainvillea@180/7", "5efb0c1bd29da739"},
    {"bougainvillea@365/42", "2fcc6bb2d11840b6"},
    {"bougainvillea@365/7", "390e52ff320259e5"},
    {"butterlettuce@10/42", "760cadc15142ac58"},
    {"butterlettuce@10/7", "58b4870383f4dda7"},
    {"butterlettuce@50/42", "6ba85a4b64cc898e"},
    {"butterlettuce@50/7", "7b42ede1c931dce0"},
    {"butterlettuce@70/42", "5e179942cdb895b0"},
    {"butterlettuce@70/7", "e72e662a759cb6d1"},
    {"capsicum@10/42", "d4209fe8555e0b7c"},
    {"capsicum@10/7", "fb35245760d67ea5"},
    {"capsicum@50/42", "adb0ad76feadc679"},
    {"capsicum@50/7", "525040d4f1ab9ce4"},
    {"capsicum@150/42", "8605a6ef3b86580c"},
    {"capsicum@150/7", "a78fbb1c1c196ed1"},
    {"cheeseweed@10/42", "c75bf9c5ae3aac00"},
    {"cheeseweed@10/7", "c59ee5cd8f793ffe"},
    {"cheeseweed@40/42", "a4572ee0663f72af"},
    {"cheeseweed@40/7", "6bd577d632d9b096"},
    {"cheeseweed@40/42", "a4572ee0663f72af"},
    {"cheeseweed@40/7", "6bd577d632d9b096"},
    {"cherrytomato@10/42", "dc185f72210e9621"},
    {"cherrytomato@10/7", "c95536a12e00bf61"},
    {"cherrytomato@50/42", "0a4741b1bd6ee94c"},
    {"cherrytomato@50/7", "33c11d41a96cd9a6"},
    {"cherrytomato@175/42", "cca88cb3dae7a914"},
    {"cherrytomato@175/7", "79fd513ce15877c0"},
    {"cowpea@10/42", "e6c531830800a992"},
    {"cowpea@10/7", "0eb819502566490d"},
    {"cowpea@50/42", "dc7a6ff23eae2237"},
    {"cowpea@50/7", "83d03231dd7a6331"},
    {"cowpea@100/42", "94dc37688ed0d98b"},
    {"cowpea@100/7", "eb3f18a3c7fdca0a"},
    {"easternredbud@200/42", "9d67efa70cb007dd"},
    {"easternredbud@200/7", "d2909e4aabd5d540"},
    {"easternredbud@630/42", "50730478441c66dd"},
    {"easternredbud@630/7", "c4919ace48815413"},
    {"easternredbud@1400/42", "fcc2a45093df9227"},
    {"easternredbud@1400/7", "6cad6b7c77d4ce82"},
    {"grapevine_VSP@180/42", "a7def6466bb83f25"},
    {"grapevine_VSP@180/7", "896a9ee343c54856"},
    {"grapevine_VSP@270/42", "74aba3172642321e"},
    {"grapevine_VSP@270/7", "7576275ca0d2d0ce"},
    {"grapevine_VSP@360/42", "74aba3172642321e"},
    {"grapevine_VSP@360/7", "7576275ca0d2d0ce"},
    {"grapevine_Wye@180/42", "59c323cf46b1c44d"},
    {"grapevine_Wye@180/7", "8599d56fb7eb8790"},
    {"grapevine_Wye@270/42", "3783bd1ae414fc6a"},
    {"grapevine_Wye@270/7", "427a91c22d8ae069"},
    {"grapevine_Wye@360/42", "3783bd1ae414fc6a"},
    {"grapevine_Wye@360/7", "427a91c22d8ae069"},
    {"groundcherryweed@10/42", "1d43e8a5a234b56e"},
    {"groundcherryweed@10/7", "eefef37d5e417983"},
    {"groundcherryweed@50/42", "c11d0e989edfa36e"},
    {"groundcherryweed@50/7", "adea3801fa0c47b1"},
    {"groundcherryweed@80/42", "310f89f5a39eb648"},
    {"groundcherryweed@80/7", "9117e6d1b18db09a"},
    {"maize@10/42", "b69dbc649adcfd75"},
    {"maize@10/7", "cda7c8529d0c16f2"},
    {"maize@50/42", "961464067b024992"},
    {"maize@50/7", "7525007217bb6ae0"},
    {"maize@120/42", "961464067b024992"},
    {"maize@120/7", "7525007217bb6ae0"},
    {"olive@200/42", "b8c65445a68013b8"},
    {"olive@200/7", "397b13ace99ff15d"},
    {"olive@630/42", "21f2098e34ba757d"},
    {"olive@630/7", "669d9c4271873cb6"},
    {"olive@1400/42", "622f6b6d360775f5"},
    {"olive@1400/7", "45a4916446cedee5"},
    {"pistachio@200/42", "d67a1682d536a458"},
    {"pistachio@200/7", "76621ac3b26b4492"},
    {"pistachio@630/42", "48dd3b1f18cd4019"},
    {"pistachio@630/7", "537e45779ea1a936"},
    {"pistachio@1000/42", "58580d97fc8e9712"},
    {"pistachio@1000/7", "218fd5aaef890896"},
    {"puncturevine@10/42", "0dcff2a7b7ba6425"},
    {"puncturevine@10/7", "5d06efdd37a90ee1"},
    {"puncturevine@45/42", "06726dc2c29d1772"},
    {"puncturevine@45/7", "899cf81930fd9366"},
    {"puncturevine@45/42", "06726dc2c29d1772"},
    {"puncturevine@45/7", "899cf81930fd9366"},
    {"rice@10/42", "59d420f50839ddfb"},
    {"rice@10/7", "c3c9d969f4c59093"},
    {"rice@50/42", "c0b5b8f71e002394"},
    {"rice@50/7", "b8d1a75a9a72649a"},
    {"rice@120/42", "fd303690505411ff"},
    {"rice@120/7", "90aa5c100e2eb73c"},
    {"sorghum@10/42", "43046b15b07f50a5"},
    {"sorghum@10/7", "d7445759b31e7983"},
    {"sorghum@50/42", "b221bea317a83c47"},
    {"sorghum@50/7", "d0414f10abc43ae4"},
    {"sorghum@120/42", "b221bea317a83c47"},
    {"sorghum@120/7", "d0414f10abc43ae4"},
    {"soybean@10/42", "a296f8454874c3d8"},
    {"soybean@10/7", "8f26b8efc974db03"},
    {"soybean@50/42", "17334b0f58dd4624"},
    {"soybean@50/7", "8b4bcc37cb4ad0df"},
    {"soybean@100/42", "8b45dce326f0882b"},
    {"soybean@100/7", "31c0e490b087f7c3"},
    {"strawberry@10/42", "6fe60835c88e47ed"},
    {"strawberry@10/7", "bf803466c89bb201"},
    {"strawberry@50/42", "49a06ea021c07180"},
    {"strawberry@50/7", "37db958940ebbd1e"},
    {"strawberry@120/42", "f8aa667b8facf6b1"},
    {"strawberry@120/7", "67af8fdfe3b6f629"},
    {"sugarbeet@10/42", "dd8c2549bc388182"},
    {"sugarbeet@10/7", "46ced9f288339b76"},
    {"sugarbeet@50/42", "daf12454abe4857c"},
    {"sugarbeet@50/7", "10ecfd09e63b20f5"},
    {"sugarbeet@150/42", "37f4cdbd51d66f33"},
    {"sugarbeet@150/7", "95cc4f3b007ae2a4"},
    {"tomato@10/42", "ec05c53b84e6946b"},
    {"tomato@10/7", "b02900ceba5fda9c"},
    {"tomato@50/42", "6f7241312e580731"},
    {"tomato@50/7", "2205dabcdb2a99d9"},
    {"tomato@120/42", "eb73266eb87cb219"},
    {"tomato@120/7", "f4ffaf09c611787b"},
    {"walnut@200/42", "1028c5d00711d287"},
    {"walnut@200/7", "e1f068c8b1d2b690"},
    {"walnut@630/42", "e658165138c07061"},
    {"walnut@630/7", "d1744048ebdca2d7"},
    {"walnut@1000/42", "98f0a60bf77b8326"},
    {"walnut@1000/7", "7091635bb6477fba"},
    {"wheat@10/42", "b0a1b530351006d2"},
    {"wheat@10/7", "3c50649ef7e20fc3"},
    {"wheat@50/42", "3246192c62aa08f6"},
    {"wheat@50/7", "88a11fd41d9b195b"},
    {"wheat@120/42", "5ae45df06d11fd00"},
    {"wheat@120/7", "26f7195021a8272b"},
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
