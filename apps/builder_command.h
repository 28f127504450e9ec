#pragma once
// The builder command (apps/builder.cpp) and the two ways it runs: plantarch starts
// plantarch-builder (apps/launch/builder_exec.cpp), which serves the builder
// (apps/launch/builder_serve.cpp). Each executable links one of the two.

#include <string>

#include "cli.h"

namespace plantarch::cli {

/// The builder command's options.
struct BuilderArgs {
    int port = 8080;
    std::string host = "127.0.0.1";
    bool open = false;
    std::string output = "builder-output";
};

/// Runs the builder command; its exit status.
int runBuilderCommand(const BuilderArgs& args, const GlobalOptions& global);

}  // namespace plantarch::cli
