// plantarch builder [--port 8080] [--host 127.0.0.1] [--open] [--output DIR]
// Starts the project builder: a local web app (embedded in plantarch-builder) and its JSON API
// (builder/API.md), until Ctrl-C. The options are parsed here; runBuilderCommand
// (builder_command.h) does the work: in plantarch it starts plantarch-builder with the same
// command line, in plantarch-builder it serves.

#include "builder_command.h"
#include "cli.h"

namespace plantarch::cli {

namespace {

std::function<int()> setupBuilder(CLI::App& app, GlobalOptions& global) {
    app.description(
        "Start the project builder: a web app on this machine for building scenes of plants");
    auto a = std::make_shared<BuilderArgs>();
    app.add_option("--port", a->port, "Port to listen on (default 8080; 0: any free port)")
        ->check(numberCheck("--port", "a port", 0, 65535, true, "0 to 65535"));
    app.add_option("--host", a->host,
                   "Address to listen on (default 127.0.0.1: this machine only; any other "
                   "lets other machines in, with a warning)");
    app.add_flag("--open", a->open, "Open the builder in the desktop's web browser");
    app.add_option("--output", a->output,
                   "The folder the builder writes exports, species and projects under (made if "
                   "missing; default builder-output)");
    return [a, &global]() { return runBuilderCommand(*a, global); };
}

}  // namespace

PLANTARCH_REGISTER_COMMAND(builder, "builder", 90, setupBuilder);

}  // namespace plantarch::cli
