// Plants as cylinders, one per internode: a quantitative structure model (QSM) as CSV.

#include <string>
#include <vector>

#include "core/atomic_file.h"
#include "geometry/tessellate.h"
#include "plant_io/plant_structure.h"
#include "plantarch/OutputFormats.h"
#include "scene_io/export_common.h"

namespace plantarch::plant_io {

void writeQSM(const std::vector<const PlantInstance*>& plants, const std::string& path) {
    requireOutputFormat(path, {".csv"}, "writeQSM writes cylinders as CSV");
    io::AtomicFile out(path);
    out.write(
        "# plantarch cylinders (one row per internode, as a quantitative structure model):\n"
        "# id, parent (-1: none), plant, start x y z (m), axis x y z (unit), length (m),\n"
        "# radius (m), branch (shoot ID), branch_order (shoot rank), position_in_branch\n"
        "# (node, from 1), shoot_type\n"
        "id,parent,plant,start_x,start_y,start_z,axis_x,axis_y,axis_z,length,radius,branch,"
        "branch_order,position_in_branch,shoot_type\n");
    std::int64_t next = 0;
    char line[512];
    for (const PlantInstance* plant : plants) {
        const PlantInstance& p = *plant;
        const unsigned plantID = p.id;
        // Cylinder IDs of every shoot's internodes, to find a first internode's parent.
        std::vector<std::vector<std::int64_t>> cylinder(p.shoots.size());
        for (const Shoot& s : p.shoots) {
            if (s.removed) continue;
            const std::vector<vec3> nodes = shootNodePositions(p, s.id);
            for (std::size_t k = 0; k < s.phytomers.size(); ++k) {
                const vec3 a = nodes[k], b = nodes[k + 1];
                const float length = glm::length(b - a);
                const vec3 axis =
                    length > 0.0f ? (b - a) / length : s.phytomers[k].internode.direction;
                std::int64_t parent = -1;
                if (k > 0)
                    parent = cylinder[s.id][k - 1];
                else if (s.parent >= 0 &&
                         std::size_t(s.parentNode) < cylinder[std::size_t(s.parent)].size())
                    parent = cylinder[std::size_t(s.parent)][std::size_t(s.parentNode)];
                const std::int64_t id = next++;
                cylinder[s.id].push_back(id);
                char* e = line;
                auto num = [&](float v) {
                    e = io::writeFloat(e, v);
                    *e++ = ',';
                };
                e = io::writeInt(e, id);
                *e++ = ',';
                e = io::writeInt(e, parent);
                *e++ = ',';
                e = io::writeInt(e, plantID);
                *e++ = ',';
                for (float v : {a.x, a.y, a.z, axis.x, axis.y, axis.z, length,
                                s.phytomers[k].internode.radius})
                    num(v);
                e = io::writeInt(e, s.id);
                *e++ = ',';
                e = io::writeInt(e, s.rank);
                *e++ = ',';
                e = io::writeInt(e, std::int64_t(k + 1));
                *e++ = ',';
                out.write(line, std::size_t(e - line));
                out.write(s.type);
                out.write("\n");
            }
        }
    }
    out.commit();
}

}  // namespace plantarch::plant_io
