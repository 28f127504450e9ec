// The terminal side of the plantarch command: the subcommand registry, the progress bar on
// stderr and -v messages.

#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <string>

#include "cli.h"

namespace plantarch::cli {

namespace {
std::vector<std::string>& savedCommandLine() {
    static std::vector<std::string> line;
    return line;
}
}  // namespace

void setCommandLine(int argc, char** argv) {
    savedCommandLine().assign(argv, argv + argc);
}

const std::vector<std::string>& commandLine() {
    return savedCommandLine();
}

std::vector<Command>& commandRegistry() {
    static std::vector<Command> registry;
    return registry;
}

namespace {

// The one progress bar of the process: at most one line on stderr, redrawn in place and
// wiped when its stage ends, before a message and before exit.
struct ProgressBar {
    ProgressMode mode = ProgressMode::Auto;
    bool enabled = false;
    std::chrono::steady_clock::time_point start = std::chrono::steady_clock::now();
    std::string stage;
    int shown = -1;                // per cent on screen, -1 when nothing is drawn
    int width_ = 15 + 2 + 30 + 6;  // the longest line drawn (a long stage name makes it longer)

    void draw(std::string_view name, double fraction) {
        fraction = std::clamp(fraction, 0.0, 1.0);
        if (fraction >= 1.0) {
            clear();
            return;
        }
        // A job that ends within a second shows nothing (unless --progress always).
        const double seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        if (mode == ProgressMode::Auto && seconds < 1.0) return;
        const int percent = int(fraction * 100.0);
        if (percent == shown && name == stage) return;
        stage = name;
        shown = percent;
        const int width = 30, filled = int(fraction * width);
        const int drawn =
            std::fprintf(stderr, "\r%-15.*s [%.*s%*s] %3d%%", int(name.size()), name.data(), filled,
                         "##############################", width - filled, "", percent);
        // A shorter line than the last leaves none of it behind.
        if (drawn > 0 && drawn - 1 < width_) std::fprintf(stderr, "%*s", width_ - drawn + 1, "");
        if (drawn > 0) width_ = std::max(width_, drawn - 1);
        std::fflush(stderr);
    }
    void clear() {
        if (shown < 0) return;
        std::fprintf(stderr, "\r%*s\r", width_, "");
        std::fflush(stderr);
        shown = -1;
    }
};

ProgressBar& progressBar() {
    static ProgressBar bar;
    return bar;
}

}  // namespace

void setProgressMode(ProgressMode mode) {
    ProgressBar& bar = progressBar();
    bar.mode = mode;
    bar.enabled =
        mode == ProgressMode::Always || (mode == ProgressMode::Auto && isatty(STDERR_FILENO) != 0);
}

ProgressCallback terminalProgress() {
    if (!progressBar().enabled) return {};
    return [](std::string_view stage, double fraction) { progressBar().draw(stage, fraction); };
}

void clearProgress() {
    progressBar().clear();
}

std::string standardOutputFailure() {
    errno = 0;
    if (std::fflush(stdout) == 0 && !std::ferror(stdout)) return "";
    int err = errno;
    // A write that failed earlier left its reason in an errno long overwritten: ask the
    // output again with one byte (what it should have held is lost already).
    if (err == 0 && ::write(STDOUT_FILENO, "\n", 1) < 0) err = errno;
    return std::string("cannot write standard output") +
           (err ? std::string(": ") + std::strerror(err) : std::string());
}

double millisecondsSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
        .count();
}

void info(const GlobalOptions& g, const std::string& message) {
    if (g.verbose == 0) return;
    clearProgress();
    std::fprintf(stderr, "%s\n", message.c_str());
}

}  // namespace plantarch::cli
