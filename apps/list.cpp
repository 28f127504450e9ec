// plantarch list: the species of the library, one per line with common and latin names. A
// species file that does not read is left out with one line on stderr naming the file and
// its error; the others are listed and the status is 2.

#include <fmt/format.h>

#include <algorithm>
#include <cstdio>

#include "cli.h"
#include "plantarch/Error.h"
#include "plantarch/SpeciesIO.h"

namespace plantarch::cli {
namespace {

int run(const GlobalOptions& g) {
    const std::vector<std::string> names = listSpecies();
    info(g, "species library: " + speciesLibraryDirectory());
    std::size_t width = 0;
    for (const std::string& n : names) width = std::max(width, n.size());
    int status = 0;
    for (const std::string& name : names) {
        try {
            const SpeciesModel s = loadSpecies(name);
            std::string title = s.commonName;
            if (!s.latinName.empty())
                title += (title.empty() ? "" : " ") + ("(" + s.latinName + ")");
            std::printf("%s\n", fmt::format("{:<{}}  {}", name, width, title).c_str());
        } catch (const Error& e) {
            // One broken file does not hide the others: they are listed on stdout, each
            // broken one is one line on stderr (its file, line and error), and the status
            // says something was wrong.
            std::fflush(stdout);
            std::fprintf(stderr, "plantarch: skipped species '%s': %s\n", name.c_str(), e.what());
            status = 2;
        }
    }
    return status;
}

std::function<int()> setupList(CLI::App& app, GlobalOptions& global) {
    app.description("List the species of the library (PLANTARCH_SPECIES_DIR overrides where)");
    return [&global] { return run(global); };
}

}  // namespace

PLANTARCH_REGISTER_COMMAND(list, "list", 60, setupList);

}  // namespace plantarch::cli
