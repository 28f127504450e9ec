// plantarch: the command-line front end. Exit status: 0 success, 2 bad input (one line on
// stderr naming what was wrong), 1 internal error.

#include <omp.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <exception>

#include "cli.h"
#include "plantarch/Error.h"
#include "plantarch/Version.h"

namespace plantarch::cli {

std::vector<Command>& commandRegistry() {
    static std::vector<Command> registry;
    return registry;
}

ProgressCallback terminalProgress() {
    if (!isatty(STDERR_FILENO)) return {};
    const auto start = std::chrono::steady_clock::now();
    return [start](std::string_view stage, double fraction) {
        const double seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        if (seconds < 1.0 && fraction < 1.0) return;
        const int width = 30, filled = int(fraction * width + 0.5);
        std::fprintf(stderr, "\r%-10.*s [%.*s%*s] %3d%%", int(stage.size()), stage.data(), filled,
                     "##############################", width - filled, "",
                     int(fraction * 100 + 0.5));
        if (fraction >= 1.0) std::fprintf(stderr, "\r%*s\r", width + 20, "");
        std::fflush(stderr);
    };
}

void info(const GlobalOptions& g, const std::string& message) {
    if (g.verbose > 0) std::fprintf(stderr, "%s\n", message.c_str());
}

}  // namespace plantarch::cli

int main(int argc, char** argv) {
    using namespace plantarch::cli;
    CLI::App app{"plantarch: builds and grows 3D plants from a phytomer-based parameter model",
                 "plantarch"};
    app.set_version_flag("--version", std::string("plantarch ") + PLANTARCH_VERSION_STRING);
    app.require_subcommand(1);
    GlobalOptions global;
    app.add_flag("-v,--verbose", global.verbose, "Report progress and details on stderr");
    app.add_option("--seed", global.seed, "Random seed of the scene (same seed, same output)");
    app.add_option("--threads", global.threads, "Worker threads (0 = all cores)")
        ->check(CLI::NonNegativeNumber);

    auto& registry = commandRegistry();
    std::sort(registry.begin(), registry.end(),
              [](const Command& a, const Command& b) { return a.order < b.order; });
    std::vector<std::pair<CLI::App*, std::function<int()>>> runners;
    for (auto& cmd : registry) {
        CLI::App* sub = app.add_subcommand(cmd.name);
        runners.emplace_back(sub, cmd.setup(*sub, global));
    }

    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForAllHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForVersion& e) {
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        std::fprintf(stderr, "plantarch: %s\n", e.what());
        return 2;
    } catch (const plantarch::Error& e) {  // thrown by an option's own check
        std::fprintf(stderr, "plantarch: %s\n", e.what());
        return 2;
    }

    if (global.threads > 0) omp_set_num_threads(global.threads);
    try {
        for (auto& [sub, run] : runners)
            if (sub->parsed()) return run();
    } catch (const plantarch::Error& e) {
        std::fprintf(stderr, "plantarch: %s\n", e.what());
        return 2;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "plantarch: internal error: %s\n", e.what());
        return 1;
    }
    return 1;
}
