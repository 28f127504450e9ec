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

/// A shell command line, with its output (give `2>&1` in it for stderr too).
inline Result runShell(const std::string& cmd) {
    FILE* pipe = popen(cmd.c_str(), "r");
    std::string out;
    std::array<char, 4096> buf{};
    if (pipe)
        while (std::size_t n = std::fread(buf.data(), 1, buf.size(), pipe))
            out.append(buf.data(), n);
    const int status = pipe ? pclose(pipe) : -1;
    return {status != -1 && WIFEXITED(status) ? WEXITSTATUS(status) : -1, out};
}

/// `plantarch ARGS`, with its output.
inline Result run(const std::string& args) {
    return runShell(std::string(PLANTARCH_CLI) + " " + args + " 2>&1");
}

struct SplitResult {
    int status;       ///< exit status (-1: did not exit normally)
    std::string out;  ///< stdout
    std::string err;  ///< stderr
};

/// `plantarch ARGS`, with stdout and stderr apart (stderr through a file next to `scratch`,
/// removed again).
inline SplitResult runSplit(const std::string& args, const std::string& scratch) {
    const std::string errFile = scratch + ".stderr";
    const std::string cmd = std::string(PLANTARCH_CLI) + " " + args + " 2>" + errFile;
    FILE* pipe = popen(cmd.c_str(), "r");
    std::string out;
    std::array<char, 4096> buf{};
    if (pipe)
        while (std::size_t n = std::fread(buf.data(), 1, buf.size(), pipe))
            out.append(buf.data(), n);
    const int status = pipe ? pclose(pipe) : -1;
    std::string err;
    if (FILE* f = std::fopen(errFile.c_str(), "rb")) {
        while (std::size_t n = std::fread(buf.data(), 1, buf.size(), f)) err.append(buf.data(), n);
        std::fclose(f);
    }
    std::remove(errFile.c_str());
    return {status != -1 && WIFEXITED(status) ? WEXITSTATUS(status) : -1, out, err};
}

}  // namespace cli
