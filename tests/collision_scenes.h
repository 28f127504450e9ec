#pragma once
// Scenes shared by the collision tests and their docs pictures: boxes as obstacles and a
// small trained vine species with a trellis wire declared in its file.

#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>

#include "plantarch/PlantArchitecture.h"

namespace plantarch::test {

// An axis-aligned box (12 triangles).
inline ObjectID addBox(Context& ctx, vec3 lo, vec3 hi, vec3 color = vec3(0.7f)) {
    Mesh m;
    for (int i = 0; i < 8; ++i)
        m.positions.push_back(
            {(i & 1) ? hi.x : lo.x, (i & 2) ? hi.y : lo.y, (i & 4) ? hi.z : lo.z});
    m.indices = {0, 2, 1, 1, 2, 3, 4, 5, 6, 5, 7, 6, 0, 1, 4, 1, 5, 4,
                 2, 6, 3, 3, 6, 7, 0, 4, 2, 2, 4, 6, 1, 3, 5, 3, 7, 5};
    return ctx.addObject(m, Material{color, "", "obstacle"});
}

// Extreme coordinate of every vertex of the plant's objects along `axis`.
inline float extreme(const Context& ctx, const PlantArchitecture& arch, unsigned plant, int axis,
                     bool max) {
    float v = max ? -1e30f : 1e30f;
    for (ObjectID o : arch.getAllPlantObjectIDs(plant))
        for (const vec3& p : ctx.object(o).positions)
            v = max ? std::max(v, p[axis]) : std::min(v, p[axis]);
    return v;
}

// A trained vine: a bare trunk up to the height of a trellis wire, then a cane trained along
// +x that grows about 4 cm a day, with lateral shoots; the wire, declared in the species
// file, attracts the cane only.
inline const char* kVine = R"(<?xml version="1.0" encoding="UTF-8"?>
<plantarch_species format="1">
  <name>test_vine</name>
  <phenology>
    <max_age>365</max_age>
  </phenology>
  <build_parameters>
    <parameter name="wire_height" default="0.5" min="0.2" max="2" unit="m" doc="trellis wire height"/>
    <parameter name="wire_length" default="1.2" min="0.2" max="5" unit="m" doc="wire length along +x"/>
  </build_parameters>
  <shoot_type label="cane">
    <max_nodes>@NODES@</max_nodes>
    <internode_length_max>0.04</internode_length_max>
    <phyllochron_min>1</phyllochron_min>
    <elongation_rate_max>0.25</elongation_rate_max>
    <gravitropic_curvature>60</gravitropic_curvature>
    <tortuosity>3</tortuosity>
    <child_shoot_types>
      <type label="shoot" probability="1"/>
    </child_shoot_types>
    <phytomer>
      <internode>
        <pitch>5</pitch>
        <phyllotactic_angle>180</phyllotactic_angle>
        <radius_initial>0.003</radius_initial>
      </internode>
      <petiole>
        <pitch>40</pitch>
        <length>0.05</length>
        <radius>0.001</radius>
      </petiole>
      <leaf>
        <prototype_scale>0.06</prototype_scale>
        <prototype>
          <shape>ovate</shape>
        </prototype>
      </leaf>
    </phytomer>
  </shoot_type>
  <shoot_type label="shoot" inherits="cane">
    <max_nodes>12</max_nodes>
    <gravitropic_curvature>500</gravitropic_curvature>
    <insertion_angle_tip>35</insertion_angle_tip>
  </shoot_type>
  <build>
    <base_stem id="trunk" type="cane" nodes="wire_height / 0.05" internode_length="0.05"
               leaves="false" vegetative_buds="false" apex="false"/>
    <append id="cordon" parent="trunk" type="cane" nodes="1" pitch="90"/>
  </build>@ATTRACTION@
</plantarch_species>
)";

inline const char* kVineWire = R"(
  <attraction_points half_angle="70" look_ahead="0.25" inertia="0.3" shoot_types="cane">
    <wire from="0.02, 0, wire_height" to="wire_length, 0, wire_height" spacing="0.02"/>
  </attraction_points>)";

inline std::string replaced(std::string s, const std::string& from, const std::string& to) {
    for (std::size_t i = 0; (i = s.find(from, i)) != std::string::npos; i += to.size())
        s.replace(i, from.size(), to);
    return s;
}

// Writes a species file into this process's temporary folder, removed when the tests end,
// and returns its path.
inline std::string speciesFile(const std::string& name, const std::string& text) {
    struct Folder {
        std::filesystem::path path = std::filesystem::temp_directory_path() /
                                     ("plantarch_collision_" + std::to_string(::getpid()));
        Folder() { std::filesystem::create_directories(path); }
        ~Folder() {
            std::error_code ignored;
            std::filesystem::remove_all(path, ignored);
        }
    };
    static const Folder folder;
    const std::string path = (folder.path / (name + ".xml")).string();
    std::ofstream(path, std::ios::binary) << text;
    return path;
}

inline std::string vine(bool wire, int nodes = 28) {
    return replaced(replaced(kVine, "@ATTRACTION@", wire ? kVineWire : ""), "@NODES@",
                    std::to_string(nodes));
}

}  // namespace plantarch::test
