// The species library on disk: where it is, what it holds, loading by name or path.

#include <dlfcn.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>

#include "core/value_text.h"
#include "plantarch/Error.h"
#include "plantarch/SpeciesIO.h"

namespace plantarch {

namespace fs = std::filesystem;

namespace {

fs::path executableDirectory() {
    std::error_code ec;
    const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
    return ec ? fs::path() : exe.parent_path();
}

// The folder of the file this code was loaded from when that is not the executable: a
// shared library, or the Python extension that links plantarch.
fs::path loadedObjectDirectory() {
    Dl_info info{};
    if (dladdr(reinterpret_cast<void*>(&loadedObjectDirectory), &info) == 0 || !info.dli_fname)
        return {};
    std::error_code ec;
    const fs::path object = fs::canonical(info.dli_fname, ec);
    const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
    if (object.empty() || object == exe) return {};
    return object.parent_path();
}

// The species/ folder of the source tree this file was compiled from: the build system
// names it (CMake passes PLANTARCH_SOURCE_SPECIES_DIR); otherwise __FILE__ gives it when it is
// absolute (a relative one is not trusted).
fs::path sourceTreeSpecies() {
#ifdef PLANTARCH_SOURCE_SPECIES_DIR
    return fs::path(PLANTARCH_SOURCE_SPECIES_DIR);
#else
    const fs::path self(__FILE__);
    if (!self.is_absolute()) return {};
    return self.parent_path().parent_path().parent_path() / "species";
#endif
}

bool isDirectory(const fs::path& p) {
    std::error_code ec;
    return !p.empty() && fs::is_directory(p, ec);
}

bool looksLikePath(const std::string& s) {
    return s.find('/') != std::string::npos ||
           (s.size() >= 4 && s.compare(s.size() - 4, 4, ".xml") == 0);
}

}  // namespace

std::string speciesLibraryDirectory() {
    if (const char* env = std::getenv("PLANTARCH_SPECIES_DIR"); env && *env) return env;
    std::vector<fs::path> candidates;
    // A wheel's species/ beside its extension, or <prefix>/share/plantarch/species above a
    // shared library or an extension that `cmake --install` put under <prefix>/lib.
    if (const fs::path objectDir = loadedObjectDirectory(); !objectDir.empty()) {
        candidates.push_back(objectDir / "species");
        fs::path up = objectDir;
        for (int level = 0; level < 5 && up.has_relative_path(); ++level) {
            up = up.parent_path();
            candidates.push_back(up / "share" / "plantarch" / "species");
        }
    }
    const fs::path exeDir = executableDirectory();
    if (!exeDir.empty()) candidates.push_back(exeDir / ".." / "share" / "plantarch" / "species");
    candidates.push_back(sourceTreeSpecies());
    if (!exeDir.empty()) {
        candidates.push_back(exeDir / ".." / "species");
        candidates.push_back(exeDir / "species");
    }
    candidates.push_back(fs::path("species"));
    std::vector<std::string> searched;
    for (const fs::path& c : candidates) {
        if (c.empty()) continue;
        if (isDirectory(c)) return c.lexically_normal().string();
        searched.push_back(c.lexically_normal().string());
    }
    throw Error("species library not found; set PLANTARCH_SPECIES_DIR",
                {.validRange = "searched: " + text::joinNames(searched)});
}

std::vector<std::string> listSpecies() {
    const fs::path dir = speciesLibraryDirectory();
    std::error_code ec;
    fs::directory_iterator it(dir, ec);
    if (ec) throw Error("cannot list the species library: " + ec.message(), {.file = dir.string()});
    std::vector<std::string> names;
    // Every .xml entry but folders: a dangling or looping link, a FIFO or a device named like
    // a species is listed too, so that reading it reports what is wrong with it instead of
    // the library leaving it out without a word.
    for (const fs::directory_entry& entry : it) {
        std::error_code fileEc;
        if (entry.path().extension() == ".xml" && !entry.is_directory(fileEc))
            names.push_back(entry.path().stem().string());
    }
    std::sort(names.begin(), names.end());
    return names;
}

SpeciesModel loadSpecies(const std::string& nameOrPath) {
    if (looksLikePath(nameOrPath)) return readSpeciesFile(nameOrPath);
    const fs::path file = fs::path(speciesLibraryDirectory()) / (nameOrPath + ".xml");
    std::error_code ec;
    if (fs::exists(fs::symlink_status(file, ec)) && !fs::is_directory(file, ec))
        return readSpeciesFile(file.string());  // names what is wrong when it is no file
    const std::vector<std::string> names = listSpecies();
    const std::string near = text::closestMatch(nameOrPath, names);
    throw Error("unknown species" + (near.empty() ? "" : ", did you mean '" + near + "'?"),
                {.parameter = "species",
                 .value = nameOrPath,
                 .validRange = names.empty() ? "the library at " + speciesLibraryDirectory() +
                                                   " holds no species"
                                             : "one of: " + text::joinNames(names)});
}

}  // namespace plantarch
