// plantarch: the command-line front end. Exit status: 0 success, 2 bad input (one line on
// stderr naming what was wrong), 1 internal error.

#include <omp.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <exception>
#include <new>
#include <string>

#include "cli.h"
#include "plantarch/Error.h"
#include "plantarch/PlantArchitecture.h"
#include "plantarch/Version.h"

namespace plantarch::cli {

namespace {

// Letters to change, add or drop to turn a into b.
std::size_t editDistance(const std::string& a, const std::string& b) {
    std::vector<std::size_t> row(b.size() + 1);
    for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
    for (std::size_t i = 1; i <= a.size(); ++i) {
        std::size_t diagonal = row[0];
        row[0] = i;
        for (std::size_t j = 1; j <= b.size(); ++j) {
            const std::size_t up = row[j];
            row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] != b[j - 1])});
            diagonal = up;
        }
    }
    return row[b.size()];
}

// The name of `names` nearest to `word` within two edits, or "" when none is.
std::string nearestName(const std::string& word, const std::vector<std::string>& names) {
    std::string nearest;
    std::size_t best = 3;
    for (const std::string& n : names)
        if (const std::size_t d = editDistance(word, n); d < best) {
            best = d;
            nearest = n;
        }
    return nearest;
}

// The long and short option names a command (and the global options) take: "--age", "-o".
std::vector<std::string> optionNames(const CLI::App& app, const CLI::App* chosen) {
    std::vector<std::string> names;
    for (const CLI::App* a : {&app, chosen}) {
        if (!a) continue;
        for (const CLI::Option* o : a->get_options()) {
            for (const std::string& l : o->get_lnames()) names.push_back("--" + l);
            for (const std::string& n : o->get_snames()) names.push_back("-" + n);
        }
    }
    return names;
}

// The one line printed for a command line CLI11 rejects: our own checks' messages as they
// are (without CLI11's "--option: " in front), a mistyped command with the nearest name, an
// unexpected argument with where to look.
std::string parseErrorLine(const CLI::App& app, int argc, char** argv, const CLI::ParseError& e) {
    std::string text = e.what();
    if (dynamic_cast<const CLI::ValidationError*>(&e)) {
        const auto colon = text.find(": ");
        if (colon != std::string::npos &&
            text.compare(colon + 2, colon, text, 0, colon) == 0)  // "--x: --x = ..."
            return text.substr(colon + 2);
        return text;
    }
    if (dynamic_cast<const CLI::ArgumentMismatch*>(
            &e)) {  // "--age: At Most 1 required but received 2"
        const std::string marker = ": At Most 1 required but received ";
        const auto at = text.find(marker);
        if (at != std::string::npos)
            return text.substr(0, at) + ": given " + text.substr(at + marker.size()) +
                   " times (valid: once)";
    }
    if (dynamic_cast<const CLI::ConversionError*>(&e)) {  // "Could not convert: --x = v"
        const std::string marker = "Could not convert: ";
        if (text.rfind(marker, 0) == 0)
            return text.substr(marker.size()) +
                   ": not a value of this option (valid: see the option in --help)";
    }
    std::vector<std::string> names;
    const CLI::App* chosen = nullptr;
    for (const CLI::App* sub : app.get_subcommands({})) {
        names.push_back(sub->get_name());
        if (sub->parsed()) chosen = sub;
    }
    std::string valid;
    for (const std::string& n : names) valid += (valid.empty() ? "" : ", ") + n;
    // The first word of the command line no subcommand took.
    std::vector<std::string> left = app.remaining(true);
    auto isLeft = [&](const std::string& a) {
        return std::find(left.begin(), left.end(), a) != left.end();
    };
    std::string first;
    for (int i = 1; i < argc && first.empty(); ++i)
        if (isLeft(argv[i])) first = argv[i];
    if (!chosen) {
        if (first.empty() || first[0] == '-')
            return "a command is required (valid: " + valid + "; see plantarch --help)";
        const std::string nearest = nearestName(first, names);
        return "'" + first + "' is not a command" +
               (nearest.empty() ? "" : ", did you mean '" + nearest + "'?") + " (valid: " + valid +
               ")";
    }
    if (dynamic_cast<const CLI::ExtrasError*>(&e) && !first.empty()) {
        if (first.size() > 1 && first[0] == '-') {  // a mistyped option
            const std::string option = first.substr(0, first.find('='));
            const std::string nearest = nearestName(option, optionNames(app, chosen));
            return chosen->get_name() + ": unknown option '" + option + "'" +
                   (nearest.empty() ? "" : ", did you mean '" + nearest + "'?") +
                   " (valid: the options in 'plantarch " + chosen->get_name() + " --help')";
        }
        return chosen->get_name() + ": unexpected argument '" + first +
               "' (valid: the arguments in 'plantarch " + chosen->get_name() + " --help')";
    }
    return text;
}

// The first word of the command line that is neither a global option nor its value: the
// command's name when the line is well formed.
std::string namedCommand(const CLI::App& app, int argc, char** argv) {
    for (int i = 1; i < argc; ++i) {
        const std::string word = argv[i];
        if (word.empty() || word[0] != '-') return word;
        if (word == "--") return {};
        if (word.find('=') != std::string::npos) continue;
        const CLI::Option* option = app.get_option_no_throw(word);
        if (!option) return {};  // a command's own option: CLI11 will say where it belongs
        if (option->get_type_size_max() > 0) ++i;  // its value
    }
    return {};
}

// Standard output is an output like any file: a write that failed (a full disk, a closed
// pipe's EPIPE) makes the command fail with one line instead of exiting 0 with a short file.
int checkedExit(int status) {
    const std::string failure = standardOutputFailure();
    if (failure.empty()) return status;
    clearProgress();
    std::fprintf(stderr, "plantarch: %s\n", failure.c_str());
    return status == 0 ? 2 : status;
}

}  // namespace

}  // namespace plantarch::cli

int main(int argc, char** argv) {
    using namespace plantarch::cli;
    setCommandLine(argc, argv);
    CLI::App app{"plantarch: builds and grows 3D plants from a phytomer-based parameter model",
                 "plantarch"};
    app.set_version_flag("--version", std::string("plantarch ") + PLANTARCH_VERSION_STRING);
    app.require_subcommand(1);
    app.fallthrough();  // global options may also follow the subcommand
    GlobalOptions global;
    app.add_flag("-v,--verbose", global.verbose, "Report progress and details on stderr");
    app.add_option("--seed", global.seed, "Random seed of the scene (same seed, same output)")
        ->check(numberCheck("--seed", "a seed", 0.0, 18446744073709551615.0, true,
                            "a whole number from 0 to 18446744073709551615"))
        ->check(CLI::Validator(
            [](std::string& t) {  // doubles cannot tell 2^64 - 1 from 2^64: check the digits
                return t.size() < 20 || (t.size() == 20 && t <= "18446744073709551615")
                           ? std::string()
                           : "--seed = " + t + ": not a seed (valid: a whole number from 0 " +
                                 "to 18446744073709551615)";
            },
            ""));
    app.add_option_function<std::string>(
           "--progress",
           [](const std::string& text) {
               if (text == "auto")
                   setProgressMode(ProgressMode::Auto);
               else if (text == "always")
                   setProgressMode(ProgressMode::Always);
               else if (text == "never")
                   setProgressMode(ProgressMode::Never);
               else
                   throw plantarch::Error("not a progress mode",
                                          {.parameter = "--progress",
                                           .value = text,
                                           .validRange = "auto, always, never"});
           },
           "Progress bar on stderr for jobs over a second: auto (when stderr is a terminal, "
           "the default), always (at once, even when stderr is not a terminal) or never")
        ->type_name("MODE");
    app.add_option("--threads", global.threads, "Worker threads (0 = all cores)")
        ->check(numberCheck("--threads", "a thread count", 0, 1024, true,
                            "0 to 1024, 0 for every core"));
    app.add_option("--points", global.points,
                   "PLY outputs as point clouds: N points drawn uniformly by area, each with a "
                   "normal and its plant, object and organ labels (0: triangles)")
        ->check(numberCheck("--points", "a point count", 0, 2147483648.0, true,
                            "0 to 2147483648, 0 for the triangles"));

    app.add_option("--max-triangles", global.maxTriangles,
                   "Largest job in triangles: a build or canopy that needs more is refused "
                   "before it is grown (a canopy's estimate: its first plants' mean times the "
                   "plant count) or stopped as soon as it passes the limit; 0 for no limit. "
                   "Default: half the physical memory at " +
                       std::to_string(plantarch::PlantArchitecture::kBytesPerTriangle) +
                       " bytes a triangle, " + std::to_string(global.maxTriangles) +
                       " on this machine")
        ->check(numberCheck("--max-triangles", "a triangle count", 0.0, 4294967295.0, true,
                            "0 to 4294967295, 0 for no limit"));

    app.add_option("--mesh-detail", global.meshDetail,
                   "Mesh resolution of every organ, as a factor on its species' own (leaf "
                   "subdivisions, flower and fruit subdivisions, tube sides): 0.1 to 4, default 1; "
                   "the plants grow the same at any detail")
        ->check(numberCheck("--mesh-detail", "a mesh detail", 0.1, 4.0, false, "0.1 to 4"));

    setProgressMode(ProgressMode::Auto);
    plantarch::removeTemporaryFilesOnSignal();  // named temporaries go on SIGINT and SIGTERM
    auto& registry = commandRegistry();
    std::sort(registry.begin(), registry.end(), [](const Command& a, const Command& b) {
        // (by name where two share a place: registration order is the linker's)
        return a.order != b.order ? a.order < b.order
                                  : std::string_view(a.name) < std::string_view(b.name);
    });
    // A command line that names its command before anything else but global options sets up
    // that command alone (the others' options cost a few hundred microseconds a process);
    // help, version and mistakes see every command.
    const std::string named = namedCommand(app, argc, argv);
    const bool one = std::any_of(registry.begin(), registry.end(),
                                 [&](const Command& c) { return named == c.name; });
    std::vector<std::pair<CLI::App*, std::function<int()>>> runners;
    for (auto& cmd : registry) {
        CLI::App* sub = app.add_subcommand(cmd.name);
        if (one && named != cmd.name) continue;
        runners.emplace_back(sub, cmd.setup(*sub, global));
        // A repeatable option (-o, --scanner, -D) takes one value each time it is given, so
        // `-o a.ply bean` leaves `bean` to the positional argument.
        for (CLI::Option* option : sub->get_options())
            if (option->get_expected_max() > 1 && option->nonpositional())
                option->expected(1)->allow_extra_args(false)->multi_option_policy(
                    CLI::MultiOptionPolicy::TakeAll);
    }

    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp& e) {
        return checkedExit(app.exit(e));
    } catch (const CLI::CallForAllHelp& e) {
        return checkedExit(app.exit(e));
    } catch (const CLI::CallForVersion& e) {
        return checkedExit(app.exit(e));
    } catch (const CLI::ParseError& e) {
        clearProgress();
        std::fprintf(stderr, "plantarch: %s\n", parseErrorLine(app, argc, argv, e).c_str());
        return 2;
    } catch (const plantarch::Error& e) {  // thrown by an option's own check
        std::fprintf(stderr, "plantarch: %s\n", e.what());
        return 2;
    }

    if (global.threads > 0) omp_set_num_threads(global.threads);
    try {
        for (auto& [sub, run] : runners)
            if (sub->parsed()) {
                const int status = run();
                clearProgress();
                return checkedExit(status);
            }
    } catch (const plantarch::TriangleBudgetError& e) {
        clearProgress();
        std::fprintf(stderr, "plantarch: %s (--max-triangles)\n", e.what());
        return 2;
    } catch (const plantarch::Error& e) {
        clearProgress();
        std::fprintf(stderr, "plantarch: %s\n", e.what());
        return 2;
    } catch (const std::bad_alloc&) {
        clearProgress();
        std::fprintf(stderr,
                     "plantarch: out of memory (lower --max-triangles, now %zu, to be told "
                     "before the work starts)\n",
                     global.maxTriangles);
        return 1;
    } catch (const std::exception& e) {
        clearProgress();
        std::fprintf(stderr, "plantarch: internal error: %s\n", e.what());
        return 1;
    }
    return 1;
}
