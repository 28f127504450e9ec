// A dataset's index files: the manifest of each shard and, once every shard is done, the
// merged index and the per-split COCO files.

#include <fmt/format.h>

#include <algorithm>
#include <filesystem>
#include <set>
#include <system_error>

#include "core/atomic_file.h"
#include "core/input_file.h"
#include "dataset/dataset_internal.h"
#include "plantarch/Error.h"

namespace plantarch {

namespace fs = std::filesystem;
using dataset::OrderedJson;

namespace {

// A sample's files with their sizes; an Error naming the first one missing.
OrderedJson sampleEntry(const DatasetSpec& spec, const std::string& outDir, std::size_t i) {
    const std::string name = datasetSampleName(i);
    const fs::path folder = fs::path(dataset::samplesFolder(outDir)) / name;
    OrderedJson files = OrderedJson::object();
    for (const std::string& f : dataset::sampleFiles(spec)) {
        std::error_code ec;
        const auto size = fs::file_size(folder / f, ec);
        if (ec)
            throw Error(
                "a sample is missing or incomplete (make it, then write the manifest "
                "again)",
                {.file = (folder / f).string()});
        files[f] = size;
    }
    return {{"sample", i},
            {"folder", "samples/" + name},
            {"split", drawDatasetSample(spec, i).split},
            {"files", files}};
}

// Samples of 0..samples-1 not present.
std::vector<std::size_t> missingSamples(const std::string& outDir, std::size_t samples) {
    std::vector<std::size_t> missing;
    for (std::size_t i = 0; i < samples; ++i) {
        std::error_code ec;
        const fs::path f =
            fs::path(dataset::samplesFolder(outDir)) / datasetSampleName(i) / "metadata.json";
        if (!fs::is_regular_file(f, ec)) missing.push_back(i);
    }
    return missing;
}

std::string listed(const std::vector<std::size_t>& v) {
    std::string out;
    for (std::size_t k = 0; k < v.size() && k < 10; ++k)
        out += (k ? ", " : "") + std::to_string(v[k]);
    if (v.size() > 10) out += fmt::format(" and {} more", v.size() - 10);
    return out;
}

}  // namespace

void writeDatasetManifest(const DatasetSpec& spec, const std::string& outDir, std::size_t samples,
                          std::size_t shard, std::size_t shards) {
    OrderedJson list = OrderedJson::array();
    for (std::size_t i : datasetShard(samples, shard, shards))
        list.push_back(sampleEntry(spec, outDir, i));
    const OrderedJson doc = {{"plantarch_dataset_manifest", 1},
                             {"dataset", spec.name},
                             {"seed", spec.seed},
                             {"samples", samples},
                             {"shard", shard},
                             {"shards", shards},
                             {"entries", list}};
    io::writeWholeFile(
        (fs::path(outDir) / fmt::format("manifest-{}-of-{}.json", shard, shards)).string(),
        doc.dump(1) + "\n");
}

void mergeDataset(const DatasetSpec& spec, const std::string& outDir, std::size_t samples) {
    const std::vector<std::size_t> missing = missingSamples(outDir, samples);
    if (!missing.empty())
        throw Error(fmt::format("{} of {} samples are missing ({}): make them (--resume), then "
                                "merge",
                                missing.size(), samples, listed(missing)),
                    {.file = dataset::samplesFolder(outDir)});
    // Folders left by runs that were killed: nothing of them is a sample.
    std::error_code ec;
    fs::remove_all(fs::path(outDir) / ".partial", ec);

    OrderedJson entries = OrderedJson::array();
    std::map<std::string, OrderedJson> cocoBySplit;
    std::map<std::string, std::size_t> annotationIDs;
    for (std::size_t i = 0; i < samples; ++i) {
        OrderedJson e = sampleEntry(spec, outDir, i);
        const std::string split = e["split"].get<std::string>();
        const fs::path folder = fs::path(outDir) / e["folder"].get<std::string>();
        if (e["files"].contains("coco.json")) {
            OrderedJson c = OrderedJson::parse(io::readWholeFile(
                (folder / "coco.json").string(), io::InputKind{"COCO file", 1024 * io::kMiB}));
            OrderedJson& all = cocoBySplit[split];
            if (all.is_null())
                all = {{"info",
                        {{"description", "plantarch synthetic dataset"},
                         {"dataset", spec.name},
                         {"split", split}}},
                       {"images", OrderedJson::array()},
                       {"categories", c["categories"]},
                       {"annotations", OrderedJson::array()}};
            for (auto image : c["images"]) {
                image["file_name"] = e["folder"].get<std::string>() + "/rgb.png";
                image["seed"] = c["info"]["seed"];
                image["species"] = c["info"]["species"];
                all["images"].push_back(image);
            }
            for (auto a : c["annotations"]) {
                a["id"] = ++annotationIDs[split];
                all["annotations"].push_back(a);
            }
        }
        entries.push_back(e);
    }
    for (const auto& [split, doc] : cocoBySplit)
        io::writeWholeFile((fs::path(outDir) / ("coco_" + split + ".json")).string(),
                           doc.dump() + "\n");
    OrderedJson splits = OrderedJson::object();
    for (const auto& [name, fraction] : spec.splits) splits[name] = fraction;
    const OrderedJson doc = {{"plantarch_dataset_index", 1},
                             {"dataset", spec.name},
                             {"seed", spec.seed},
                             {"samples", samples},
                             {"splits", splits},
                             {"categories", dataset::categoryNames()},
                             {"entries", entries}};
    io::writeWholeFile((fs::path(outDir) / "dataset.json").string(), doc.dump(1) + "\n");
}

}  // namespace plantarch
