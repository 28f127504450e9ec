// `plantarch fit` as a user runs it: the example target of docs/measured-plants.md fitted, the
// fitted species file and the report written, the same bytes for any thread count, and one
// line with exit status 2 for every bad target or output.

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <filesystem>
#include <nlohmann/json.hpp>

#include "cli_run.h"
#include "folder_test.h"

namespace {

class CliFit : public FolderTest {
protected:
    CliFit() : FolderTest("plantarch-cli-fit-") {}
};

std::string example() {
    return std::string(PLANTARCH_SOURCE_DIR) + "/examples/fit/bean_target.json";
}

// A small target: one parameter, two seeds, a few evaluations.
const char* kSmall = R"({"plantarch_fit": 1,
 "parameters": [{"path": "trifoliate.internode_length_max", "lower": 0.015, "upper": 0.04}],
 "seeds": [1, 2],
 "optimizer": {"max_evaluations": 6},
 "ages": [{"age": 15, "height": {"value": 0.12, "sd": 0.01}}]}
)";

}  // namespace

TEST_F(CliFit, TheExampleFitsWritesTheSpeciesAndTheReport) {
    const auto r = cli::runSplit(
        "fit bean --target " + example() + " -o " + at("fitted.xml") + " --report " + at("report"),
        at("run"));
    ASSERT_EQ(r.status, 0) << r.out << r.err;
    EXPECT_NE(r.err.find("fit: evaluation 1: objective "), std::string::npos) << r.err;
    EXPECT_NE(r.out.find("bean fitted to "), std::string::npos) << r.out;
    const auto report = nlohmann::json::parse(existingBytes(at("report/report.json")));
    EXPECT_EQ(report["plantarch_fit_report"], 1);
    EXPECT_EQ(report["parameters"].size(), 2u);
    EXPECT_LT(report["objective_fitted"].get<double>(), report["objective_start"].get<double>());
    EXPECT_FALSE(report["residuals"].empty());
    EXPECT_EQ(report["evaluations"].size(), report["evaluations_used"].get<std::size_t>());
    // The fitted species is a species file that validates and builds.
    const auto v = cli::run("validate " + at("fitted.xml"));
    EXPECT_EQ(v.status, 0) << v.out;
    const auto b = cli::run("build " + at("fitted.xml") + " --age 20 --stats");
    EXPECT_EQ(b.status, 0) << b.out;
}

TEST_F(CliFit, TheSameBytesForAnyThreadCount) {
    put(at("t.json"), kSmall);
    for (const char* threads : {"1", "2"}) {
        const auto r = cli::run(std::string("--threads ") + threads + " fit bean --target " +
                                at("t.json") + " -o " + at(std::string("f") + threads + ".xml") +
                                " --report " + at(std::string("r") + threads));
        ASSERT_EQ(r.status, 0) << r.out;
    }
    EXPECT_EQ(existingBytes(at("f1.xml")), existingBytes(at("f2.xml")));
    EXPECT_EQ(existingBytes(at("r1/report.json")), existingBytes(at("r2/report.json")));
}

TEST_F(CliFit, BadTargetsAndOutputsGetOneLineAndNoFile) {
    put(at("t.json"), kSmall);
    std::filesystem::create_directories(at("dir.json"));
    ASSERT_EQ(mkfifo(at("fifo.json").c_str(), 0600), 0);
    std::string unknownKey = kSmall;
    unknownKey.replace(unknownKey.find("\"seeds\""), 7, "\"sedes\"");
    put(at("key.json"), unknownKey);
    std::string badPath = kSmall;
    badPath.replace(badPath.find("internode_length_max"), 20, "internode_lenght_max");
    put(at("path.json"), badPath);
    std::string nanBound = kSmall;
    nanBound.replace(nanBound.find("0.015"), 5, "NaN");
    put(at("nan.json"), nanBound);
    const std::pair<std::string, std::string> cases[] = {
        {"fit bean --target " + at("dir.json"), "is a directory, not a fit target file"},
        {"fit bean --target " + at("fifo.json"), "is a FIFO, not a fit target file"},
        {"fit bean --target " + at("key.json"),
         "key.json:3: sedes: unknown key, did you mean 'seeds'?"},
        {"fit bean --target " + at("path.json"),
         "path.json:2: parameters/0/path = trifoliate.internode_lenght_max: unknown parameter"},
        {"fit bean --target " + at("nan.json"), "nan.json:2: not a JSON document"},
        {"fit bean --target " + at("t.json") + " -o " + at("fitted.obj"),
         "fitted.obj: -o: not a species file name (valid: a .xml file)"},
        {"fit nosuchspecies --target " + at("t.json"), "unknown species"},
    };
    for (const auto& [args, message] : cases) {
        const auto r =
            cli::run(args + (args.find(" -o ") == std::string::npos ? " -o " + at("out.xml") : ""));
        EXPECT_EQ(r.status, 2) << args << "\n" << r.out;
        EXPECT_NE(r.out.find(message), std::string::npos) << args << "\n" << r.out;
        EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), 1) << r.out;
    }
    EXPECT_FALSE(std::filesystem::exists(at("out.xml")));
    EXPECT_FALSE(std::filesystem::exists(at("fitted.obj")));
}
