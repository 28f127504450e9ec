// plantarch dataset SPEC --out DIR [--samples N] [--shard K/N] [--resume] [--merge] [--check]
// Makes a synthetic dataset from a spec file: one folder of labelled files per sample, a
// manifest per shard and, once every sample is there, the index and per-split COCO files.

#include "plantarch/Dataset.h"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <system_error>

#include "cli.h"
#include "plantarch/Error.h"
#include "plantarch/OutputFiles.h"

namespace plantarch::cli {

namespace {

namespace fs = std::filesystem;

struct DatasetArgs {
    std::string spec, out, shard;
    std::size_t samples = 0;
    bool resume = false, merge = false, check = false;
};

std::string duration(double seconds) {
    const auto s = long(seconds + 0.5);
    if (s >= 3600) return fmt::format("{}:{:02d}:{:02d}", s / 3600, s / 60 % 60, s % 60);
    return fmt::format("{}:{:02d}", s / 60, s % 60);
}

std::string megabytes(std::uint64_t bytes) {
    return fmt::format("{:.1f} MB", double(bytes) / 1e6);
}

std::function<int()> setupDataset(CLI::App& app, GlobalOptions& global) {
    app.description(
        "Make a synthetic dataset from a spec file: per sample an RGB image, masks, depth, "
        "normals, camera, COCO, YOLO, leaf keypoints, point cloud and plant structure");
    auto a = std::make_shared<DatasetArgs>();
    app.add_option("spec", a->spec, "Dataset spec file (.json; docs/datasets.md)")->required();
    app.add_option("--out", a->out, "Folder of the dataset (made if missing)")->required();
    app.add_option("--samples", a->samples,
                   "Samples to make (default: the spec's `samples`; 1 to 10000000)")
        ->check(CLI::Range(std::size_t(1), kMaxDatasetSamples));
    app.add_option("--shard", a->shard,
                   "Make only the samples i with i % N == K (K/N; e.g. "
                   "$SLURM_ARRAY_TASK_ID/$SLURM_ARRAY_TASK_COUNT); merge afterwards");
    app.add_flag("--resume", a->resume, "Keep samples already made and make the others");
    app.add_flag("--merge", a->merge,
                 "Only write the index (dataset.json) and per-split COCO files, once every "
                 "sample is made");
    app.add_flag("--check", a->check,
                 "Only check the spec (every species and field) and show sample 0's choices");
    return [a, &global]() {
        const auto start = std::chrono::steady_clock::now();
        const DatasetSpec spec = readDatasetSpecFile(a->spec);
        const std::size_t samples = a->samples ? a->samples : spec.samples;
        checkDatasetSpec(spec);
        if (a->check) {
            const DatasetSample s = drawDatasetSample(spec, 0);
            std::printf(
                "%s", fmt::format("{}: {} samples; sample 0: {} ({}), split {}\n", a->spec, samples,
                                  s.species,
                                  s.project.blocks.size() > 1 ? "with weeds" : "no weeds", s.split)
                          .c_str());
            return 0;
        }
        std::error_code ec;
        if (fs::exists(a->out, ec) && !fs::is_directory(a->out, ec))
            throw Error("not a folder", {.file = a->out, .parameter = "--out"});
        if (a->merge) {
            mergeDataset(spec, a->out, samples);
            std::printf(
                "%s", fmt::format("merged {} samples: {}/dataset.json\n", samples, a->out).c_str());
            return 0;
        }
        const auto [k, n] = a->shard.empty() ? std::pair<std::size_t, std::size_t>{0, 1}
                                             : parseShard(a->shard, kMaxDatasetSamples);
        const std::vector<std::size_t> mine = datasetShard(samples, k, n);
        // The folders this run makes are removed again if it fails (or is stopped by a
        // signal) before a sample is in them.
        std::vector<FolderMadeForOutputs> madeFolders = makeFoldersForOutputs(a->out);
        struct RemoveIfEmpty {
            std::vector<FolderMadeForOutputs>& folders;
            bool armed = true;
            ~RemoveIfEmpty() {
                for (auto it = folders.rbegin(); armed && it != folders.rend(); ++it) it->remove();
            }
        } cleanup{madeFolders};
        const ProgressCallback bar = terminalProgress();
        std::size_t made = 0, skipped = 0;
        std::uint64_t bytes = 0;
        DatasetWriteOptions options;
        options.resume = a->resume;
        for (std::size_t j = 0; j < mine.size(); ++j) {
            if (bar) {
                // The sample's place, the rate of those made so far and the time left; the
                // fraction moves on as the sample is built.
                const double seconds = millisecondsSince(start) / 1000.0;
                const double rate = made > 0 ? double(made) / seconds : 0.0;
                const std::string label =
                    fmt::format("sample {}/{}", j + 1, mine.size()) +
                    (rate > 0.0 ? fmt::format(" {:.1f}/min {} left", 60.0 * rate,
                                              duration(double(mine.size() - j - skipped) / rate))
                                : "");
                const double n = double(mine.size());
                options.progress = [bar, label, j, n](std::string_view, double f) {
                    bar(label, (double(j) + 0.9 * std::clamp(f, 0.0, 1.0)) / n);
                };
                bar(label, double(j) / n);
            }
            const DatasetSampleResult r = writeDatasetSample(spec, mine[j], a->out, options);
            if (r.skipped) {
                ++skipped;
            } else {
                ++made;
                bytes += r.bytes;
                info(global,
                     fmt::format("sample {}: {} plants, {} triangles, {} annotations, {}", mine[j],
                                 r.plants, r.triangles, r.annotations, megabytes(r.bytes)));
            }
        }
        if (bar) bar("samples", 1.0);
        cleanup.armed = false;
        for (FolderMadeForOutputs& f : madeFolders) f.keep();
        fs::remove(fs::path(a->out) / ".partial", ec);  // only when empty
        writeDatasetManifest(spec, a->out, samples, k, n);
        const bool whole = n == 1;
        if (whole) mergeDataset(spec, a->out, samples);
        const double seconds = millisecondsSince(start) / 1000.0;
        std::printf(
            "%s", fmt::format("made {} sample(s){} in {:.1f} s ({:.1f} per minute), {} in {}{}\n",
                              made, skipped ? fmt::format(" ({} kept)", skipped) : "", seconds,
                              seconds > 0.0 ? 60.0 * double(made) / seconds : 0.0, megabytes(bytes),
                              a->out,
                              whole ? ""
                                    : fmt::format("; shard {}/{}: merge with --merge "
                                                  "when every shard is done",
                                                  k, n))
                      .c_str());
        return 0;
    };
}

}  // namespace

PLANTARCH_REGISTER_COMMAND(dataset, "dataset", 95, setupDataset);

}  // namespace plantarch::cli
