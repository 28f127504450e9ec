// The builder command in the plantarch executable: it starts plantarch-builder, installed
// beside it, with the same command line, so that plantarch itself links and loads none of the
// server's libraries (HTTP, TLS, compression, zip) and every other command starts sooner.

#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "builder_command.h"
#include "plantarch/Error.h"

namespace plantarch::cli {

int runBuilderCommand(const BuilderArgs&, const GlobalOptions&) {
    std::error_code error;
    const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", error);
    if (error)
        throw Error("cannot find the plantarch executable, beside which the builder is installed",
                    {.parameter = "/proc/self/exe", .value = error.message()});
    const std::filesystem::path builder = self.parent_path() / "plantarch-builder";
    std::vector<std::string> args = commandLine();
    args.at(0) = builder.string();
    std::vector<char*> argv;
    for (std::string& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    std::fflush(stdout);
    std::fflush(stderr);
    ::execv(builder.c_str(), argv.data());
    throw Error(std::string("cannot start the builder: ") + std::strerror(errno),
                {.parameter = "plantarch builder",
                 .value = builder.string(),
                 .validRange = "plantarch-builder installed beside plantarch"});
}

}  // namespace plantarch::cli
