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
    {"almond@120/42", "6b70632e023a0d7c"},
    {"almond@120/7", "e42faa4538665cf8"},
    {"almond@630/42", "751b19f2b536d08a"},
    {"almond@630/7", "3ae73e12c50a0076"},
    {"almond@1000/42", "6e0f3bef868ea817"},
    {"almond@1000/7", "36d46653f3c8a217"},
    {"almond_aldrich@120/42", "8d6e265cc9347995"},
    {"almond_aldrich@120/7", "2c0f23b06fb90f37"},
    {"almond_aldrich@630/42", "acf6bc86f2c11525"},
    {"almond_aldrich@630/7", "056319a4a9046a0d"},
    {"almond_aldrich@1000/42", "6617423fea323b04"},
    {"almond_aldrich@1000/7", "745b69b78771b3a2"},
    {"almond_wood_colony@120/42", "0657d9e1bcb1b1ca"},
    {"almond_wood_colony@120/7", "66d6a7fd4009560a"},
    {"almond_wood_colony@630/42", "7b0066b4cc8d1e00"},
    {"almond_wood_colony@630/7", "0c84dbe31a3ce761"},
    {"almond_wood_colony@1000/42", "a4f9829fab934645"},
    {"almond_wood_colony@1000/7", "adcc2903c800f9b5"},
    {"apple@200/42", "3c8e49954df58905"},
    {"apple@200/7", "11db673077bff662"},
    {"apple@630/42", "97ad451c54faa47f"},
    {"apple@630/7", "76dfce59f9406fc0"},
    {"apple@1400/42", "87fb516953f5fca3"},
    {"apple@1400/7", "7ae4f140761a0068"},
    {"apple_fruitingwall@200/42", "6f886d50cf0f628d"},
    {"apple_fruitingwall@200/7", "083278f83b35df1b"},
    {"apple_fruitingwall@630/42", "7f3b6012e4536dd1"},
    {"apple_fruitingwall@630/7", "18c9bb212b2f8c12"},
    {"apple_fruitingwall@720/42", "7f3b6012e4536dd1"},
    {"apple_fruitingwall@720/7", "18c9bb212b2f8c12"},
    {"asparagus@5/42", "16752f8e2d76a8ea"},
    {"asparagus@5/7", "cfc4c8226df53285"},
    {"asparagus@20/42", "8566ca0ad67b1e21"},
    {"asparagus@20/7", "642949db2298824d"},
    {"asparagus@20/42", "8566ca0ad67b1e21"},
    {"asparagus@20/7", "642949db2298824d"},
    {"bean@10/42", "e38b406ccc005f05"},
    {"bean@10/7", "479f871c2ab8f248"},
    {"bean@45/42", "38d909b232a57d20"},
    {"bean@45/7", "a32f9ef37ed00aae"},
    {"bean@100/42", "3614a04029b3d942"},
    {"bean@100/7", "0fbd744ad2ca48db"},
    {"bindweed@10/42", "f1a251211ee92a2f"},
    {"bindweed@10/7", "740a99e779a23ab6"},
    {"bindweed@50/42", "44d12f66db5b51cb"},
    {"bindweed@50/7", "cfeefc7adfa735c2"},
    {"bindweed@50/42", "44d12f66db5b51cb"},
    {"bindweed@50/7", "cfeefc7adfa735c2"},
    {"bougainvillea@30/42", "176454193e776f53"},
    {"bougainvillea@30/7", "c985238ac6d295ba"},
    {"bougainvillea@180/42", "d93ceaa68589595c"},
    {"bougainvillea@180/7", "1b6e481d8a8e54c2"},
    {"bougainvillea@365/42", "fac268959938b566"},
    {"bougainvillea@365/7", "b5994eb907e83d63"},
    {"butterlettuce@10/42", "c4442dbae323714f"},
    {"butterlettuce@10/7", "6ddbd373dd98c521"},
    {"butterlettuce@50/42", "8e3e061ee412925b"},
    {"butterlettuce@50/7", "5ae7e134468526b9"},
    {"butterlettuce@70/42", "928417d77b9086e0"},
    {"butterlettuce@70/7", "f57789348421d7ad"},
    {"capsicum@10/42", "c07224343a5fd53c"},
    {"capsicum@10/7", "56e7361067df8f3e"},
    {"capsicum@50/42", "6f0d463143c192fb"},
    {"capsicum@50/7", "4d14bb11e3e45f35"},
    {"capsicum@150/42", "e110cd13a9021c6b"},
    {"capsicum@150/7", "4260408c5cc0f00a"},
    {"cheeseweed@10/42", "ddb159ee040c5b50"},
    {"cheeseweed@10/7", "6b0d6153f1904ef2"},
    {"cheeseweed@40/42", "d4b18361b290faf6"},
    {"cheeseweed@40/7", "74af5bc13eebfca6"},
    {"cheeseweed@40/42", "d4b18361b290faf6"},
    {"cheeseweed@40/7", "74af5bc13eebfca6"},
    {"cherrytomato@10/42", "a02c0db45920352b"},
    {"cherrytomato@10/7", "cfcfae05936caacd"},
    {"cherrytomato@50/42", "8ee33e937cc040a5"},
    {"cherrytomato@50/7", "a8695ffdaa215988"},
    {"cherrytomato@175/42", "b75babc25f71be43"},
    {"cherrytomato@175/7", "e041c4c77a3f225b"},
    {"cowpea@10/42", "f6102f1d88a1f2f3"},
    {"cowpea@10/7", "edce3b41f16360b9"},
    {"cowpea@50/42", "c4ec774acbab9848"},
    {"cowpea@50/7", "07f65101d9c73cba"},
    {"cowpea@100/42", "b044bfedbb2e535f"},
    {"cowpea@100/7", "72b4cbb63613a296"},
    {"easternredbud@200/42", "66da6e9ce54ed31a"},
    {"easternredbud@200/7", "6717bcb9ab002c02"},
    {"easternredbud@630/42", "41c5f203b75f1d93"},
    {"easternredbud@630/7", "a9b528f4d043a33a"},
    {"easternredbud@1400/42", "6fbb64d4086467df"},
    {"easternredbud@1400/7", "1eb2109c865a0ac6"},
    {"grapevine_VSP@180/42", "ff9eba579f4f4681"},
    {"grapevine_VSP@180/7", "13a0ea3674cf2236"},
    {"grapevine_VSP@270/42", "1087a395d3adf921"},
    {"grapevine_VSP@270/7", "e2f32ddd292df286"},
    {"grapevine_VSP@360/42", "1087a395d3adf921"},
    {"grapevine_VSP@360/7", "e2f32ddd292df286"},
    {"grapevine_Wye@180/42", "03ad4884f5222402"},
    {"grapevine_Wye@180/7", "9b4ef57fc3fe4e8b"},
    {"grapevine_Wye@270/42", "8908f975e7efc01a"},
    {"grapevine_Wye@270/7", "83ec8b1b38299bc9"},
    {"grapevine_Wye@360/42", "8908f975e7efc01a"},
    {"grapevine_Wye@360/7", "83ec8b1b38299bc9"},
    {"groundcherryweed@10/42", "c6d6bf4f5664c439"},
    {"groundcherryweed@10/7", "db19b6fab823c6fb"},
    {"groundcherryweed@50/42", "75937859b0c29c05"},
    {"groundcherryweed@50/7", "1b82e6a373671cf7"},
    {"groundcherryweed@80/42", "911c5ba62854a315"},
    {"groundcherryweed@80/7", "452be62cb383bb91"},
    {"maize@10/42", "46664ce56590a6c7"},
    {"maize@10/7", "c478639f9624b469"},
    {"maize@50/42", "f6a95fc6fdea9a90"},
    {"maize@50/7", "5360dc3921224495"},
    {"maize@120/42", "f6a95fc6fdea9a90"},
    {"maize@120/7", "5360dc3921224495"},
    {"olive@200/42", "cdd6bd97a66407dc"},
    {"olive@200/7", "b6119351f62a9cfa"},
    {"olive@630/42", "03d6a64e0a0b8482"},
    {"olive@630/7", "e72b769316fd5528"},
    {"olive@1400/42", "ac23a36eb8fbc78e"},
    {"olive@1400/7", "2b22eb195f2c35f9"},
    {"pistachio@200/42", "16920f06bef52629"},
    {"pistachio@200/7", "f9997b85f02c71d6"},
    {"pistachio@630/42", "cd26224b531ec447"},
    {"pistachio@630/7", "b00547fbf8cc8dc1"},
    {"pistachio@1000/42", "c0e2e71828e09bd1"},
    {"pistachio@1000/7", "59461b2738d536d8"},
    {"puncturevine@10/42", "05648515ea95fc8c"},
    {"puncturevine@10/7", "e9b8027a434fc793"},
    {"puncturevine@45/42", "892ff84386e6804c"},
    {"puncturevine@45/7", "23de0e11ae3d7a78"},
    {"puncturevine@45/42", "892ff84386e6804c"},
    {"puncturevine@45/7", "23de0e11ae3d7a78"},
    {"rice@10/42", "7fc1f59a7636fe58"},
    {"rice@10/7", "e7389d6f60be583c"},
    {"rice@50/42", "8a915787f718bbe9"},
    {"rice@50/7", "9236f23ee6d26296"},
    {"rice@120/42", "5f48f724ec047fa2"},
    {"rice@120/7", "0cfd47c71fbe4d04"},
    {"sorghum@10/42", "3bc35df062111a3e"},
    {"sorghum@10/7", "863f4d89b4852b60"},
    {"sorghum@50/42", "78137e788c5b28eb"},
    {"sorghum@50/7", "a78ce9d1c207cd77"},
    {"sorghum@120/42", "78137e788c5b28eb"},
    {"sorghum@120/7", "a78ce9d1c207cd77"},
    {"soybean@10/42", "ad04ba0f15111ce7"},
    {"soybean@10/7", "6ad98a36df3607b5"},
    {"soybean@50/42", "0eea3bf863378c99"},
    {"soybean@50/7", "b503b0fb89cd385f"},
    {"soybean@100/42", "e3bac5f865a1ba08"},
    {"soybean@100/7", "d8a4e4257ca9c2d6"},
    {"strawberry@10/42", "cfa55dba6a5c6199"},
    {"strawberry@10/7", "0cf8f809e63b95fe"},
    {"strawberry@50/42", "a4353e04a4a4034c"},
    {"strawberry@50/7", "fef256c96d2b742d"},
    {"strawberry@120/42", "897ee22ce3d341e4"},
    {"strawberry@120/7", "d2bef51abc52cccc"},
    {"sugarbeet@10/42", "18ef900c7ce98c6e"},
    {"sugarbeet@10/7", "8a68010e171c3ed0"},
    {"sugarbeet@50/42", "7b84c6e421cc983f"},
    {"sugarbeet@50/7", "d3cfe46df198feb2"},
    {"sugarbeet@150/42", "fd0dc95cb98ec132"},
    {"sugarbeet@150/7", "65de20eca0933399"},
    {"tomato@10/42", "e6ad2550c45dd4e5"},
    {"tomato@10/7", "f0a73cd443812b3b"},
    {"tomato@50/42", "14f8a09dd02ef917"},
    {"tomato@50/7", "1eaec68291e0378f"},
    {"tomato@120/42", "0474f9342b761511"},
    {"tomato@120/7", "35f0d739ade30eec"},
    {"walnut@200/42", "13c28a6ba59428c2"},
    {"walnut@200/7", "8ef2b62ed1232de2"},
    {"walnut@630/42", "03def5a500a93a9d"},
    {"walnut@630/7", "b7714b387e7f9f0f"},
    {"walnut@1000/42", "d4863d96cb097822"},
    {"walnut@1000/7", "c9d9993e51c3eb19"},
    {"wheat@10/42", "67e4009dcdb89d10"},
    {"wheat@10/7", "915a201cfabd8673"},
    {"wheat@50/42", "d19fbec1139f1f48"},
    {"wheat@50/7", "9b8d7c437967bc91"},
    {"wheat@120/42", "13625273c73b1616"},
    {"wheat@120/7", "84f60e9ee0ffbb09"},
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
