#pragma once
// Runs the plantarch command line as a user does, for the CLI tests.

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <string>

namespace cli {

struct Result {
    int status;       ///< exit status (-1: did not exit normally)
    std::string out;  ///< stdout and stderr together
};

/// `plantarch ARGS`, with its output.
inline Result run(const std::string& args) {
    const std::string cmd = std::string(PLANTARCH_CLI) + " " + args + " 2>&1";
    FILE* pipe = popen(cmd.c_str(), "r");
    std::string out;
    std::array<char, 4096> buf{};
    if (pipe)
        while (std::size_t n = std::fread(buf.data(), 1, buf.size(), pipe))
            out.append(buf.data(), n);
    const int status = pipe ? pclose(pipe) : -1;
    return {status != -1 && WIFEXITED(status) ? WEXITSTATUS(status) : -1, out};
}

}  // namespace cli
