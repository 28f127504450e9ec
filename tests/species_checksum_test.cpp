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
    {"almond@120/42", "c0a0d2b971cd47f4"},
    {"almond@120/7", "b32ea298cbe9bf1f"},
    {"almond@630/42", "4fb0cb988fc4356e"},
    {"almond@630/7", "9be25b9bdedfb24f"},
    {"almond@1000/42", "f5dc109ea73f99df"},
    {"almond@1000/7", "f32578f7ac99b5d4"},
    {"almond_aldrich@120/42", "be3a9974b0a7c89d"},
    {"almond_aldrich@120/7", "0cc5cd5eda05b00c"},
    {"almond_aldrich@630/42", "9aa9b1deba3c3130"},
    {"almond_aldrich@630/7", "5000f5f7a74fee29"},
    {"almond_aldrich@1000/42", "de7361ddacd65b4f"},
    {"almond_aldrich@1000/7", "7c1dc667e05c219a"},
    {"almond_wood_colony@120/42", "2e3846ffd63662f1"},
    {"almond_wood_colony@120/7", "36a33900daa0541f"},
    {"almond_wood_colony@630/42", "38bc71dae4cc498c"},
    {"almond_wood_colony@630/7", "799cd560daf8b200"},
    {"almond_wood_colony@1000/42", "42a2685896e0db30"},
    {"almond_wood_colony@1000/7", "7a197973861ed01b"},
    {"apple@200/42", "154b275891f81096"},
    {"apple@200/7", "885020dcecf5703b"},
    {"apple@630/42", "ff405a1fc20aa641"},
    {"apple@630/7", "272ff04327190207"},
    {"apple@1400/42", "4458ae580069de6a"},
    {"apple@1400/7", "f5a7d904e1e1cab2"},
    {"apple_fruitingwall@200/42", "438725a4a2372869"},
    {"apple_fruitingwall@200/7", "0c85d6781ffad4bc"},
    {"apple_fruitingwall@630/42", "823186ab4b085666"},
    {"apple_fruitingwall@630/7", "916f8ede1b52619d"},
    {"apple_fruitingwall@720/42", "823186ab4b085666"},
    {"apple_fruitingwall@720/7", "916f8ede1b52619d"},
    {"asparagus@5/42", "65642b3631f3d571"},
    {"asparagus@5/7", "3be21ce50230d9c6"},
    {"asparagus@20/42", "7d00c395c2775abb"},
    {"asparagus@20/7", "92bacbe86c88afed"},
    {"bean@10/42", "9396732881ac6b38"},
    {"bean@10/7", "73781d7fd29f9c23"},
    {"bean@45/42", "9bab9bb8af988c7a"},
    {"bean@45/7", "192d8586a34e2f5c"},
    {"bean@100/42", "c003c58f4b77a989"},
    {"bean@100/7", "1f8bc17fd9168239"},
    {"bindweed@10/42", "26e1fb71509cf36c"},
    {"bindweed@10/7", "672fda4d141f76bc"},
    {"bindweed@50/42", "4a09aa5059b1b85a"},
    {"bindweed@50/7", "9c2bf3cb93af03a1"},
    {"bougainvillea@30/42", "19978c2cb632bf76"},
    {"bougainvillea@30/7", "91db3af719672006"},
    {"bougainvillea@180/42", "ff3aaa3212d5c2a4"},
    {"bougainvillea@180/7", "848052e79531c4cf"},
    {"bougainvillea@365/42", "9515e6335aaf6676"},
    {"bougainvillea@365/7", "f698b2488804145c"},
    {"butterlettuce@10/42", "10240168057c2c0b"},
    {"butterlettuce@10/7", "ea1c17eff016ae3f"},
    {"butterlettuce@50/42", "702bd67561fe6c9c"},
    {"butterlettuce@50/7", "700b468e0ce6014c"},
    {"butterlettuce@70/42", "f71ac50d53365075"},
    {"butterlettuce@70/7", "af254407df99d3fa"},
    {"capsicum@10/42", "2b66db0798eb6ddd"},
    {"capsicum@10/7", "dc43c799d360e707"},
    {"capsicum@50/42", "dfbdb7f040674aaa"},
    {"capsicum@50/7", "1fb7d07b2e731016"},
    {"capsicum@150/42", "29539b4028f09f0a"},
    {"capsicum@150/7", "8657c65837d57354"},
    {"cheeseweed@10/42", "c80a0f322b0e85fd"},
    {"cheeseweed@10/7", "232a5f667538a16e"},
    {"cheeseweed@40/42", "ecd00a5df011ca4e"},
    {"cheeseweed@40/7", "c0f937d2812787ce"},
    {"cherrytomato@10/42", "36dd4e84a4f22ae7"},
    {"cherrytomato@10/7", "2394c04c2da679fb"},
    {"cherrytomato@50/42", "fae6781024aa244b"},
    {"cherrytomato@50/7", "1640ab19e4173c1b"},
    {"cherrytomato@175/42", "79da6193273330d4"},
    {"cherrytomato@175/7", "e9bdaac32a43c3c8"},
    {"cowpea@10/42", "7983ea12afe4d2ba"},
    {"cowpea@10/7", "cae109fe0bb624b7"},
    {"cowpea@50/42", "86281cc9f8dfcf91"},
    {"cowpea@50/7", "31afc4575ab914ae"},
    {"cowpea@100/42", "c4180679bd34d783"},
    {"cowpea@100/7", "661b031b0c4ef970"},
    {"easternredbud@200/42", "117efb7b978c73ee"},
    {"easternredbud@200/7", "334c38a73b1a36c5"},
    {"easternredbud@630/42", "6f4399506f3a8aa7"},
    {"easternredbud@630/7", "dbed738d0c69a5c1"},
    {"easternredbud@1400/42", "0875d3cee472d986"},
    {"easternredbud@1400/7", "9f97e99e2e2a3dd0"},
    {"grapevine_VSP@180/42", "2fea95e8e69e442f"},
    {"grapevine_VSP@180/7", "041df32647f7ab75"},
    {"grapevine_VSP@270/42", "eb258cdf9e9de27f"},
    {"grapevine_VSP@270/7", "5b6406aa7a702357"},
    {"grapevine_VSP@360/42", "eb258cdf9e9de27f"},
    {"grapevine_VSP@360/7", "5b6406aa7a702357"},
    {"grapevine_Wye@180/42", "94810546d12a914a"},
    {"grapevine_Wye@180/7", "0489230ec01ef57b"},
    {"grapevine_Wye@270/42", "855a78008166f598"},
    {"grapevine_Wye@270/7", "e0a9a854f7a6cd2b"},
    {"grapevine_Wye@360/42", "855a78008166f598"},
    {"grapevine_Wye@360/7", "e0a9a854f7a6cd2b"},
    {"groundcherryweed@10/42", "bcd8acc1c42141f3"},
    {"groundcherryweed@10/7", "62ae5746f9dd4676"},
    {"groundcherryweed@50/42", "5758dd3f1c45e4f2"},
    {"groundcherryweed@50/7", "1484d9593ba0d9a4"},
    {"groundcherryweed@80/42", "094da0716a82005e"},
    {"groundcherryweed@80/7", "176e39a082cc6d29"},
    {"maize@10/42", "06bb511f9e276784"},
    {"maize@10/7", "293b2a8ac923b521"},
    {"maize@50/42", "5703b8a8cdc4a095"},
    {"maize@50/7", "2dd3d41d480e4e5b"},
    {"maize@120/42", "a51c91976885c398"},
    {"maize@120/7", "6c2a6cd6164ae648"},
    {"olive@200/42", "370cb267f26738a7"},
    {"olive@200/7", "53460f70d9f50ab7"},
    {"olive@630/42", "35e1d7a6285c1668"},
    {"olive@630/7", "f4c3b9e45bae56b5"},
    {"olive@1400/42", "a81b819ad3169ece"},
    {"olive@1400/7", "5000e0f6bd97c82f"},
    {"pistachio@200/42", "5ab3ac4d6bcd1c3c"},
    {"pistachio@200/7", "edefc5850d14d593"},
    {"pistachio@630/42", "1d78cc21234f611c"},
    {"pistachio@630/7", "1de858b0653e4de5"},
    {"pistachio@1000/42", "17f030a6e9ffb907"},
    {"pistachio@1000/7", "0aaa6e7bf26fe55a"},
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
    {"sorghum@10/42", "95a30fa34b7cba40"},
    {"sorghum@10/7", "1bb0bdc8780741fa"},
    {"sorghum@50/42", "39d1e4ef74b246b6"},
    {"sorghum@50/7", "dcd6bf439588e9c6"},
    {"sorghum@120/42", "33719f19c060afc9"},
    {"sorghum@120/7", "d6c3ee6480e7ba6a"},
    {"soybean@10/42", "70cb3191a5a049ff"},
    {"soybean@10/7", "194ee29c8d761b8f"},
    {"soybean@50/42", "feadd596e5bc9c8c"},
    {"soybean@50/7", "4737864851a111de"},
    {"soybean@100/42", "bde270edfdca2b24"},
    {"soybean@100/7", "3f758e94befe5b35"},
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
    {"tomato@10/42", "086c29ebea319f46"},
    {"tomato@10/7", "df37304b85ef992e"},
    {"tomato@50/42", "518a016326ddf959"},
    {"tomato@50/7", "5a48bdfc08e243ed"},
    {"tomato@120/42", "daf3e3abc52a5e4e"},
    {"tomato@120/7", "888b383b8138b2f5"},
    {"walnut@200/42", "1b97265b4aa8c16f"},
    {"walnut@200/7", "80608a026bafda74"},
    {"walnut@630/42", "e1cf16b0af93b2e7"},
    {"walnut@630/7", "c889d78f9a95892e"},
    {"walnut@1000/42", "87d60f36a7c83ddb"},
    {"walnut@1000/7", "00b486690ac4cd05"},
    {"wheat@10/42", "4636b50ae9b386ee"},
    {"wheat@10/7", "b628cd2a75f1be1f"},
    {"wheat@50/42", "4c0ae443a660ad7f"},
    {"wheat@50/7", "81497dc874678688"},
    {"wheat@120/42", "7372a22fee354eca"},
    {"wheat@120/7", "f4645d8119cf7f89"},
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
