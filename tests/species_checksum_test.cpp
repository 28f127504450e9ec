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
    {"asparagus@5/42", "69dc943c161b6943"},
    {"asparagus@5/7", "0cf88e842c5134fc"},
    {"asparagus@20/42", "86e5f7a01b9eff69"},
    {"asparagus@20/7", "858232a443b1aae7"},
    {"bean@10/42", "4c6f5d20ed4e12ad"},
    {"bean@10/7", "ed193abc5477c5c7"},
    {"bean@45/42", "36b3c846f27fe117"},
    {"bean@45/7", "69f3eb0378554456"},
    {"bean@100/42", "0a24016770e1b6ee"},
    {"bean@100/7", "78adf4e10926b6b6"},
    {"bindweed@10/42", "26e1fb71509cf36c"},
    {"bindweed@10/7", "672fda4d141f76bc"},
    {"bindweed@50/42", "4a09aa5059b1b85a"},
    {"bindweed@50/7", "9c2bf3cb93af03a1"},
    {"bougainvillea@30/42", "7c080378e5bdbc42"},
    {"bougainvillea@30/7", "7c828807b1731068"},
    {"bougainvillea@180/42", "61e1261e4b35e89a"},
    {"bougainvillea@180/7", "6b30d731e9c52d1a"},
    {"bougainvillea@365/42", "b01ef183f4c66644"},
    {"bougainvillea@365/7", "148b321aacdcc439"},
    {"butterlettuce@10/42", "2d64e92de88bfe63"},
    {"butterlettuce@10/7", "66d76c410a496ec3"},
    {"butterlettuce@50/42", "cb3425249315f0fa"},
    {"butterlettuce@50/7", "0940246b6a2a3868"},
    {"butterlettuce@70/42", "09b899f8239c2493"},
    {"butterlettuce@70/7", "79570d32bcead3ae"},
    {"capsicum@10/42", "d4209fe8555e0b7c"},
    {"capsicum@10/7", "fb35245760d67ea5"},
    {"capsicum@50/42", "e20b77cb59725771"},
    {"capsicum@50/7", "62aed47100ac7987"},
    {"capsicum@150/42", "81591f5e76c8f146"},
    {"capsicum@150/7", "6cf2326f1b8b4933"},
    {"cheeseweed@10/42", "5d772c1239755117"},
    {"cheeseweed@10/7", "aa19bb2c14c05735"},
    {"cheeseweed@40/42", "902eeb6c1e609fdd"},
    {"cheeseweed@40/7", "5cc19e7206be6c40"},
    {"cherrytomato@10/42", "746f194e2bc2f1f7"},
    {"cherrytomato@10/7", "279920b156c98874"},
    {"cherrytomato@50/42", "abefbbdf5e15386a"},
    {"cherrytomato@50/7", "a38b7af5f8372d44"},
    {"cherrytomato@175/42", "3e78edb56f7815da"},
    {"cherrytomato@175/7", "2cb583c989644bc5"},
    {"cowpea@10/42", "1c2cddb42c251aec"},
    {"cowpea@10/7", "dd9113cec91e5aa9"},
    {"cowpea@50/42", "c6a3ffa7972afbe2"},
    {"cowpea@50/7", "365268c84c9f6d6a"},
    {"cowpea@100/42", "f66f84b760d411ca"},
    {"cowpea@100/7", "2b3fddbafc291afa"},
    {"easternredbud@200/42", "a82efbb8be79ae28"},
    {"easternredbud@200/7", "af18973273b97890"},
    {"easternredbud@630/42", "eb38e1b3669f212a"},
    {"easternredbud@630/7", "e001639858943046"},
    {"easternredbud@1400/42", "490c9f6911566597"},
    {"easternredbud@1400/7", "3f3656735ea44612"},
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
    {"groundcherryweed@10/42", "dbf37dcd5290cb5a"},
    {"groundcherryweed@10/7", "0adaf0c1b4de4ac7"},
    {"groundcherryweed@50/42", "15927b1520bc5620"},
    {"groundcherryweed@50/7", "d79349e89ba94bd0"},
    {"groundcherryweed@80/42", "94c690f12513ea5f"},
    {"groundcherryweed@80/7", "f7f88c264f9b1086"},
    {"maize@10/42", "d7dc0face4d8fa43"},
    {"maize@10/7", "fb5a9a3bf5cde877"},
    {"maize@50/42", "92b486a1f7069a19"},
    {"maize@50/7", "9487240dae3cc2a1"},
    {"maize@120/42", "92b486a1f7069a19"},
    {"maize@120/7", "9487240dae3cc2a1"},
    {"olive@200/42", "6dfcd1ad8096575e"},
    {"olive@200/7", "62130fba70b548c2"},
    {"olive@630/42", "d90d415ffa04a81e"},
    {"olive@630/7", "b8da25ecb6323aa9"},
    {"olive@1400/42", "b5376c068fbfcb7e"},
    {"olive@1400/7", "bdd0956bc1876790"},
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
    {"sorghum@10/42", "9201e7529166256b"},
    {"sorghum@10/7", "4c09875fb3fc49dc"},
    {"sorghum@50/42", "00c08c22ba6bb23e"},
    {"sorghum@50/7", "958b094edce1e1c7"},
    {"sorghum@120/42", "00c08c22ba6bb23e"},
    {"sorghum@120/7", "958b094edce1e1c7"},
    {"soybean@10/42", "40477bcfce7c4467"},
    {"soybean@10/7", "8052b205430c6cb5"},
    {"soybean@50/42", "85b1a7ca2ef337f8"},
    {"soybean@50/7", "337cf5076dfc940f"},
    {"soybean@100/42", "d88cc0ff04615bc7"},
    {"soybean@100/7", "3796130ffcfba8ee"},
    {"strawberry@10/42", "0c8594103684caff"},
    {"strawberry@10/7", "981b0eb497ceaa4f"},
    {"strawberry@50/42", "23bc57e1f3751b11"},
    {"strawberry@50/7", "e76ab7b60b7aacfd"},
    {"strawberry@120/42", "08213db927dc3ab4"},
    {"strawberry@120/7", "ed8ac1cf5245bd1e"},
    {"sugarbeet@10/42", "257148238cbf0eca"},
    {"sugarbeet@10/7", "3d045b3a51a7e1ee"},
    {"sugarbeet@50/42", "ebd1bf53b1bbedca"},
    {"sugarbeet@50/7", "9785f3c0fd1916a4"},
    {"sugarbeet@150/42", "9a5b8231fd03197d"},
    {"sugarbeet@150/7", "a0820a5fec293091"},
    {"tomato@10/42", "404bb171fae17f14"},
    {"tomato@10/7", "985ff5554e7fefc3"},
    {"tomato@50/42", "283956e5dbb669a8"},
    {"tomato@50/7", "ef2fd1b85f0109cd"},
    {"tomato@120/42", "0e6ae439e76e904d"},
    {"tomato@120/7", "00c697ef6a3d1d01"},
    {"walnut@200/42", "0120c353561b9150"},
    {"walnut@200/7", "390dd9081f7d0821"},
    {"walnut@630/42", "a66f0beb4f12e109"},
    {"walnut@630/7", "3861e6c8112153ae"},
    {"walnut@1000/42", "e6d812edfbc84939"},
    {"walnut@1000/7", "57e6ccf39b4916c0"},
    {"wheat@10/42", "e10f29b6f14d0169"},
    {"wheat@10/7", "7a8df844ac51f2c6"},
    {"wheat@50/42", "5624201e6a97c761"},
    {"wheat@50/7", "ddfc9fd7d962379f"},
    {"wheat@120/42", "66585fd69fbafdcb"},
    {"wheat@120/7", "53c89931ba743faf"},
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
