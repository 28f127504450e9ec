#pragma once
// The bending options of build and grow (apps/bend_options.cpp; docs/measured-plants.md,
// "Shoots bending under load"): --bend bends the plants' shoots under their load, --pull
// and --displace pull one node and print the forces.

#include <string>
#include <vector>

#include "cli.h"

namespace plantarch::cli {

struct BendArgs {
    bool bend = false;
    std::string pull;      ///< SHOOT:NODE:FX,FY,FZ (N)
    std::string displace;  ///< SHOOT:NODE:DX,DY,DZ (m)
};

void addBendOptions(CLI::App& app, BendArgs& args);
/// Checks the options before any work (one-line plantarch::Error).
void checkBendOptions(const BendArgs& args);
bool bendOn(const BendArgs& args);
/// Turns the plants' mechanics on, so that they bend as they grow (--bend).
void enableBending(PlantArchitecture& arch, const std::vector<unsigned>& plants,
                   const BendArgs& args);
/// Bends the plants now (--bend) and pulls the first plant's node (--pull, --displace),
/// printing what the pull took to `out` (stdout, or stderr when stdout holds JSON).
void applyBending(PlantArchitecture& arch, const std::vector<unsigned>& plants,
                  const BendArgs& args, std::FILE* out);

}  // namespace plantarch::cli
