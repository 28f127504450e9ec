// QSM cylinders: one row per internode, each child cylinder starting where its parent ends,
// with the shoot's rank as branch order.

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "plantarch/ExportPlants.h"

using namespace plantarch;

TEST(Qsm, EveryInternodeIsACylinderJoinedToItsParent) {
    Context ctx;
    PlantArchitecture arch(&ctx);
    arch.loadPlantModelFromLibrary("almond");
    const unsigned plant = arch.buildPlantInstanceFromLibrary(vec3(1.0f, 0.0f, 0.0f), 400);
    const std::string path = (std::filesystem::temp_directory_path() /
                              ("plantarch_qsm_" + std::to_string(::getpid()) + ".csv"))
                                 .string();
    writeQSM(arch, {plant}, path);
    std::ifstream in(path);
    std::string line;
    struct Row {
        long id, parent;
        float start[3], axis[3], length, radius;
        int branch, order, position;
    };
    std::vector<Row> rows;
    bool header = false;
    while (std::getline(in, line)) {
        if (line.empty() || line[0] == '#') continue;
        if (!header) {
            EXPECT_EQ(line.rfind("id,parent,plant,start_x", 0), 0u);
            header = true;
            continue;
        }
        std::stringstream ss(line);
        std::string f;
        std::vector<std::string> fields;
        while (std::getline(ss, f, ',')) fields.push_back(f);
        ASSERT_EQ(fields.size(), 15u) << line;
        Row r{std::stol(fields[0]),
              std::stol(fields[1]),
              {},
              {},
              std::stof(fields[9]),
              std::stof(fields[10]),
              std::stoi(fields[11]),
              std::stoi(fields[12]),
              std::stoi(fields[13])};
        for (int k = 0; k < 3; ++k) r.start[k] = std::stof(fields[3 + std::size_t(k)]);
        for (int k = 0; k < 3; ++k) r.axis[k] = std::stof(fields[6 + std::size_t(k)]);
        EXPECT_EQ(std::stoul(fields[2]), plant);
        EXPECT_EQ(fields[14], arch.plant(plant).shoots[std::size_t(r.branch)].type);
        rows.push_back(r);
    }
    std::filesystem::remove(path);
    std::size_t internodes = 0;
    for (const Shoot& s : arch.plant(plant).shoots)
        if (!s.removed) internodes += s.phytomers.size();
    ASSERT_EQ(rows.size(), internodes);
    ASSERT_GT(rows.size(), 50u);
    for (std::size_t i = 0; i < rows.size(); ++i) {
        const Row& r = rows[i];
        EXPECT_EQ(r.id, long(i));
        EXPECT_GT(r.radius, 0.0f);
        EXPECT_EQ(r.order, int(arch.getShootRank(plant, unsigned(r.branch))));
        if (r.parent < 0) continue;
        ASSERT_LT(r.parent, r.id);
        const Row& p = rows[std::size_t(r.parent)];
        if (r.position > 1) {  // along a shoot: starts where the previous internode ends
            EXPECT_EQ(p.branch, r.branch);
            for (int k = 0; k < 3; ++k)
                EXPECT_NEAR(r.start[k], p.start[k] + p.axis[k] * p.length, 1e-4f);
        } else {  // a branch: from a node of its parent shoot
            EXPECT_EQ(p.branch, arch.getShootParent(plant, unsigned(r.branch)));
        }
    }
    EXPECT_EQ(rows[0].parent, -1);
    EXPECT_NEAR(rows[0].start[0], 1.0f, 1e-5f);  // the trunk starts at the plant's base
}
