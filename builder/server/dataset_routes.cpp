// Dataset endpoints: a dataset spec checked, one of its samples previewed (written into the
// server's own temporary folder and shown as pictures: RGB, coloured masks, depth), and a
// local run of its samples into a folder under the output folder, on a thread of its own,
// with progress and cancel (plantarch/Dataset.h: writeDatasetSample for each sample, then
// writeDatasetManifest and mergeDataset, as `plantarch dataset SPEC --out DIR` does).

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstring>
#include <deque>
#include <fstream>
#include <map>
#include <memory>
#include <mutex>
#include <set>
#include <sstream>
#include <thread>

#include "builder/server/export_files.h"
#include "builder/server/server_impl.h"
#include "plantarch/Dataset.h"
#include "plantarch/Error.h"
#include "plantarch/Export.h"
#include "plantarch/Render.h"
#include "plantarch/SpeciesIO.h"

namespace plantarch::builder {

namespace {

/// A spec's text in a request: at most this many bytes (a spec is a few kilobytes).
constexpr std::size_t kMaxSpecText = 1u << 20;
/// Previews kept for their pictures to be fetched (at most this many, of at most this many
/// bytes of pictures together, the last always); older ones are forgotten.
constexpr std::size_t kKeptPreviews = 16;
constexpr std::size_t kKeptPreviewBytes = 256u << 20;
/// Finished runs kept; older ones are forgotten.
constexpr std::size_t kKeptRuns = 8;

// Thrown by a cancelled run's progress callback (and between samples).
struct RunCancelled {};

}  // namespace

enum class DatasetRunState { Running, Done, Failed, Cancelled };

namespace {

const char* runStateName(DatasetRunState s) {
    switch (s) {
        case DatasetRunState::Running:
            return "running";
        case DatasetRunState::Done:
            return "done";
        case DatasetRunState::Failed:
            return "failed";
        case DatasetRunState::Cancelled:
            return "cancelled";
    }
    return "failed";
}

}  // namespace

// One run. Its fields are read and written under DatasetState::mutex.
struct DatasetRun {
    std::string id;
    std::string name;  ///< the spec's
    std::string out;   ///< relative to OUTPUT
    std::size_t total = 0, done = 0, made = 0, kept = 0;
    std::uint64_t bytes = 0;
    DatasetRunState state = DatasetRunState::Running;
    std::string error;
    std::atomic<bool> cancel{false};
    std::chrono::steady_clock::time_point start = std::chrono::steady_clock::now();
    double seconds = 0.0;  ///< once finished
};

// The pictures of one preview, PNG bytes by name, and its summary.
struct DatasetPreview {
    std::map<std::string, std::string> pictures;
    json summary;
};

// The server's dataset state (Server::Impl::datasets): its previews and runs.
struct DatasetState {
    std::mutex mutex;       ///< guards everything below but `previewing`
    std::mutex previewing;  ///< held while a preview is made: one at a time
    std::unique_ptr<TemporaryFolder> previewFolder;  ///< made on the first preview
    std::map<std::string, DatasetPreview> previews;
    std::deque<std::string> previewOrder;
    std::size_t previewBytes = 0;  ///< of the pictures kept
    std::uint64_t nextPreview = 1, nextRun = 1;
    std::map<std::string, std::shared_ptr<DatasetRun>> runs;
    std::deque<std::string> finishedRuns;
    std::shared_ptr<DatasetRun> running;  ///< the run under way, if any
    std::thread worker;

    ~DatasetState() {
        {
            std::lock_guard<std::mutex> lock(mutex);
            if (running) running->cancel = true;
        }
        if (worker.joinable()) worker.join();
    }
};

namespace {

// ---- the spec of a request ----------------------------------------------------------------

// A spec file a request names: a relative path to a regular file under OUTPUT (403 outside
// it, 404 missing, 400 a directory, pipe or device).
fs::path specFile(const fs::path& output, const std::string& path) {
    const fs::path p(path);
    const std::string named = "path = \"" + clip(path) + "\"";
    if (path.empty() || path.find('\0') != std::string::npos || p.is_absolute() ||
        std::any_of(p.begin(), p.end(), [](const fs::path& part) { return part == ".."; }) ||
        !isUnder(output / p, output))
        throw HttpError{403, named +
                                 ": not a file inside the output folder (valid: a "
                                 "relative path such as \"datasets/tiny.json\")"};
    std::error_code ec;
    const fs::file_status status = fs::status(output / p, ec);
    if (!fs::exists(status)) throw HttpError{404, named + ": no such file"};
    if (!fs::is_regular_file(status))
        throw HttpError{400, named + ": not a regular file (a directory, pipe or device)"};
    return output / p;
}

// The spec a request names: "text" (the spec's JSON text; relative paths from OUTPUT/datasets)
// or "path" (a spec file under OUTPUT). Its species files must lie under OUTPUT, and the files
// they name under the builder's folders; a species saved in the builder is named by its name.
DatasetSpec requestSpec(const Server::Impl& s, const json& body) {
    const auto text = stringField(body, "text");
    const auto path = stringField(body, "path");
    if (text.has_value() == path.has_value())
        throw HttpError{400,
                        "spec: give one of text (the spec's JSON) and path (a spec file "
                        "under the output folder)"};
    DatasetSpec spec;
    if (text) {
        if (text->size() > kMaxSpecText)
            throw HttpError{413, "text: " + std::to_string(text->size()) +
                                     " bytes: a spec too large (valid: at most " +
                                     std::to_string(kMaxSpecText) + " bytes)"};
        spec = readDatasetSpecString(*text, "spec", (s.output / "datasets").string());
    } else {
        spec = readDatasetSpecFile(specFile(s.output, *path).string());
        spec.file = *path;
    }
    // Species: a name saved in the builder becomes its file; a file must lie under OUTPUT.
    const std::vector<std::string> library = listSpecies();
    Project where;
    where.folder = spec.folder;
    auto confine = [&](DatasetSpecies& entry, const std::string& field) {
        const bool file =
            entry.species.find('/') != std::string::npos || entry.species.ends_with(".xml");
        if (!file && std::find(library.begin(), library.end(), entry.species) == library.end())
            if (const auto user = s.userSpecies(entry.species)) entry.species = user->string();
        if (file && !isUnder(projectPath(where, entry.species), s.output))
            throw HttpError{403, "spec: " + field + "/species = \"" + clip(entry.species) +
                                     "\": outside the output folder (valid: a species name or a "
                                     "file under " +
                                     s.output.string() + ")"};
    };
    for (std::size_t i = 0; i < spec.species.size(); ++i)
        confine(spec.species[i], "scene/species/" + std::to_string(i));
    for (std::size_t i = 0; i < spec.weeds.species.size(); ++i)
        confine(spec.weeds.species[i], "scene/weeds/species/" + std::to_string(i));
    checkDatasetSpec(spec);
    // The files each species names (textures, OBJ models) under the builder's folders.
    std::set<std::string> checked;
    auto confineFiles = [&](const DatasetSpecies& entry, const std::string& field) {
        ProjectBlock b;
        b.species = entry.species;
        const std::string species = projectSpecies(where, b);
        if (!checked.insert(species).second) return;
        const SpeciesModel model = loadSpecies(species);
        try {
            s.confineSpecies(model, model.sourceFile);
        } catch (const HttpError& e) {
            throw HttpError{e.status, "spec: " + field + "/species = \"" + clip(entry.species) +
                                          "\": " + e.message};
        }
    };
    for (std::size_t i = 0; i < spec.species.size(); ++i)
        confineFiles(spec.species[i], "scene/species/" + std::to_string(i));
    for (std::size_t i = 0; i < spec.weeds.species.size(); ++i)
        confineFiles(spec.weeds.species[i], "scene/weeds/species/" + std::to_string(i));
    return spec;
}

// A whole number field of a request within [lo, hi], or `fallback` when absent.
std::size_t wholeField(const json& body, const char* name, double lo, double hi,
                       std::size_t fallback) {
    if (!body.contains(name) || body[name].is_null()) return fallback;
    const json& v = body[name];
    const std::string valid = " (valid: " + std::to_string(std::size_t(lo)) + " to " +
                              std::to_string(std::size_t(hi)) + ")";
    if (!v.is_number())
        throw HttpError{400, std::string(name) + " = " + shownJSON(v) + ": not a number" + valid};
    const double x = v.get<double>();
    if (!std::isfinite(x) || x != std::floor(x))
        throw HttpError{400,
                        std::string(name) + " = " + shownJSON(v) + ": not a whole number" + valid};
    if (x < lo || x > hi)
        throw HttpError{400, std::string(name) + " = " + shownJSON(v) + ": out of range" + valid};
    return std::size_t(x);
}

void onlyFields(const json& body, std::initializer_list<const char*> names) {
    for (auto it = body.begin(); it != body.end(); ++it) {
        const std::string& key = it.key();
        if (std::none_of(names.begin(), names.end(), [&](const char* n) { return key == n; })) {
            std::string valid;
            for (const char* n : names) valid += (valid.empty() ? "" : ", ") + std::string(n);
            throw HttpError{400, clip(key) + ": unknown field (valid: " + valid + ")"};
        }
    }
}

json specSummary(const DatasetSpec& spec) {
    json splits = json::array();
    for (const auto& [name, fraction] : spec.splits)
        splits.push_back({{"name", name}, {"fraction", fraction}});
    json species = json::array(), weeds = json::array(), outputs = json::array();
    for (const DatasetSpecies& s : spec.species)
        species.push_back(fs::path(s.species).stem().string());
    for (const DatasetSpecies& s : spec.weeds.species)
        weeds.push_back(fs::path(s.species).stem().string());
    for (DatasetOutput o : spec.outputs) outputs.push_back(datasetOutputName(o));
    return {{"name", spec.name},
            {"seed", spec.seed},
            {"samples", spec.samples},
            {"splits", splits},
            {"species", species},
            {"weeds", weeds},
            {"image", {spec.camera.width, spec.camera.height}},
            {"outputs", outputs}};
}

// ---- preview pictures ---------------------------------------------------------------------

std::string fileBytes(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream ss;
    ss << in.rdbuf();
    if (!in) throw Error("cannot read a file of the preview", {.file = path.string()});
    return ss.str();
}

// A colour of its own for each whole number (instances): hues a golden angle apart.
std::array<std::uint8_t, 3> labelColor(std::uint32_t label) {
    const double hue = std::fmod(double(label) * 0.6180339887, 1.0) * 6.0;
    const double v = label % 2 ? 0.95 : 0.78, s = label % 3 ? 0.7 : 0.5;
    const double c = v * s, x = c * (1.0 - std::fabs(std::fmod(hue, 2.0) - 1.0)), m = v - c;
    double r = 0, g = 0, b = 0;
    switch (int(hue)) {
        case 0:
            r = c, g = x;
            break;
        case 1:
            r = x, g = c;
            break;
        case 2:
            g = c, b = x;
            break;
        case 3:
            g = x, b = c;
            break;
        case 4:
            r = x, b = c;
            break;
        default:
            r = c, b = x;
    }
    auto byte = [&](double u) { return std::uint8_t(std::lround(255.0 * (u + m))); };
    return {byte(r), byte(g), byte(b)};
}

constexpr std::array<std::uint8_t, 3> kBackground{34, 38, 43};

// A mask as a picture: each value's colour from `color` (0: the background).
template <class Color>
std::string coloured(const Image16& mask, double scale, const Color& color) {
    Image out(mask.width, mask.height);
    for (std::size_t i = 0; i < mask.values.size(); ++i) {
        const auto v = std::uint32_t(std::lround(mask.values[i] * scale));
        const std::array<std::uint8_t, 3> c = v == 0 ? kBackground : color(v);
        std::copy(c.begin(), c.end(), out.rgb.begin() + std::ptrdiff_t(3 * i));
    }
    return encodePNG(out);
}

// depth.npy (float32, shape (height, width)) as a picture.
std::string depthPNG(const fs::path& npy, int width, int height) {
    const std::string bytes = fileBytes(npy);
    const std::size_t values = std::size_t(width) * std::size_t(height);
    if (bytes.size() < 10 + 4 * values || bytes.compare(0, 6, "\x93NUMPY") != 0 ||
        bytes.find("'<f4'") == std::string::npos)
        throw Error("depth.npy of the preview: not float32 values of its size",
                    {.file = npy.string()});
    DepthImage depth;
    depth.width = width;
    depth.height = height;
    depth.depth.resize(values);
    std::memcpy(depth.depth.data(), bytes.data() + (bytes.size() - 4 * values), 4 * values);
    return encodePNG(depthPicture(depth));
}

// Writes sample `index` of `spec` into `folder` (removed afterwards) and makes its pictures.
DatasetPreview makePreview(Server::Impl& s, DatasetSpec spec, std::size_t index,
                           const fs::path& folder) {
    spec.outputs = {DatasetOutput::RGB, DatasetOutput::Semantic, DatasetOutput::OrganInstances,
                    DatasetOutput::PlantInstances, DatasetOutput::Depth};
    struct Removed {
        fs::path path;
        ~Removed() {
            std::error_code ec;
            fs::remove_all(path, ec);
        }
    } removed{folder};
    DatasetSampleResult r;
    {
        std::lock_guard<std::mutex> lock(s.files);
        r = writeDatasetSample(spec, index, folder.string());
    }
    const fs::path sample = folder / "samples" / datasetSampleName(index);
    const json meta = json::parse(fileBytes(sample / "metadata.json"));
    const int w = meta["render"]["width"], h = meta["render"]["height"];
    std::map<std::uint32_t, std::array<std::uint8_t, 3>> categories;
    for (const json& c : meta["categories"])
        categories[c["id"].get<std::uint32_t>()] = organLabelColor(c["name"].get<std::string>());
    const Image16 semantic = readImage16((sample / "semantic.png").string());
    DatasetPreview p;
    p.pictures["rgb.png"] = fileBytes(sample / "rgb.png");
    // 8-bit semantic.png reads as values times 257.
    p.pictures["semantic.png"] = coloured(semantic, 1.0 / 257.0, [&](std::uint32_t v) {
        const auto it = categories.find(v);
        return it == categories.end() ? std::array<std::uint8_t, 3>{255, 255, 255} : it->second;
    });
    p.pictures["instances.png"] =
        coloured(readImage16((sample / "organ_instances.png").string()), 1.0, labelColor);
    p.pictures["plants.png"] =
        coloured(readImage16((sample / "plant_instances.png").string()), 1.0, labelColor);
    p.pictures["depth.png"] = depthPNG(sample / "depth.npy", w, h);
    json species = json::object();
    for (const json& plant : meta["plants"]) {
        const std::string name = fs::path(plant["species"].get<std::string>()).stem().string();
        species[name] = species.value(name, 0) + 1;
    }
    p.summary = {{"sample", index},
                 {"seed", meta["seed"]},
                 {"split", meta["split"]},
                 {"species", fs::path(meta["species"].get<std::string>()).stem().string()},
                 {"plants", r.plants},
                 {"plants_by_species", species},
                 {"triangles", r.triangles},
                 {"annotations", r.annotations},
                 {"instances", meta["instances"].size()},
                 {"day_of_year", meta["day_of_year"]},
                 {"solar_hour", meta["solar_hour"]},
                 {"image", {w, h}}};
    return p;
}

// ---- runs ---------------------------------------------------------------------------------

json runJSON(const DatasetRun& r) {
    using namespace std::chrono;
    const double seconds = r.state == DatasetRunState::Running
                               ? duration<double>(steady_clock::now() - r.start).count()
                               : r.seconds;
    const double perMinute = seconds > 0.0 ? 60.0 * double(r.made) / seconds : 0.0;
    json left = nullptr;
    if (r.state == DatasetRunState::Running && r.made > 0)
        left = double(r.total - r.done) * seconds / double(r.made);
    return {{"id", r.id},
            {"name", r.name},
            {"state", runStateName(r.state)},
            {"out", r.out},
            {"done", r.done},
            {"total", r.total},
            {"kept", r.kept},
            {"progress", r.total ? double(r.done) / double(r.total) : 0.0},
            {"bytes", r.bytes},
            {"seconds", seconds},
            {"per_minute", perMinute},
            {"seconds_left", left},
            {"error", r.error.empty() ? json(nullptr) : json(r.error)}};
}

// Removes what a stopped run leaves that holds nothing: its temporary folder, and the
// folders it made that stayed empty.
void tidy(const fs::path& out, bool madeOut) {
    std::error_code ec;
    fs::remove_all(out / ".partial", ec);
    if (fs::is_empty(out / "samples", ec)) fs::remove(out / "samples", ec);
    if (madeOut && fs::is_empty(out, ec)) fs::remove(out, ec);
}

void runSamples(Server::Impl& s, DatasetState& state, const std::shared_ptr<DatasetRun>& run,
                const DatasetSpec& spec, const fs::path& out, bool resume, bool madeOut) {
    DatasetWriteOptions options;
    options.resume = resume;
    options.progress = [run](std::string_view, double) {
        if (run->cancel) throw RunCancelled{};
    };
    DatasetRunState end = DatasetRunState::Done;
    std::string error;
    try {
        for (std::size_t i = 0; i < run->total; ++i) {
            if (run->cancel) throw RunCancelled{};
            DatasetSampleResult r;
            {
                std::lock_guard<std::mutex> lock(s.files);
                r = writeDatasetSample(spec, i, out.string(), options);
            }
            std::lock_guard<std::mutex> lock(state.mutex);
            ++run->done;
            (r.skipped ? run->kept : run->made) += 1;
            run->bytes += r.bytes;
        }
        std::lock_guard<std::mutex> lock(s.files);
        std::error_code ec;
        fs::remove(out / ".partial", ec);  // only when empty
        writeDatasetManifest(spec, out.string(), run->total, 0, 1);
        mergeDataset(spec, out.string(), run->total);
    } catch (const RunCancelled&) {
        end = DatasetRunState::Cancelled;
    } catch (const Error& e) {
        end = DatasetRunState::Failed;
        error = oneLine(e.what());
    } catch (const std::bad_alloc&) {
        end = DatasetRunState::Failed;
        error = "out of memory";
    } catch (const std::exception& e) {
        end = DatasetRunState::Failed;
        error = "internal error: " + oneLine(e.what());
    }
    if (end != DatasetRunState::Done) {
        std::lock_guard<std::mutex> lock(s.files);
        tidy(out, madeOut);
    }
    std::lock_guard<std::mutex> lock(state.mutex);
    run->state = end;
    run->error = error;
    run->seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - run->start).count();
    state.running.reset();
    state.finishedRuns.push_back(run->id);
    while (state.finishedRuns.size() > kKeptRuns) {
        state.runs.erase(state.finishedRuns.front());
        state.finishedRuns.pop_front();
    }
}

// The output folder of a run: relative, under OUTPUT, not OUTPUT itself (403), not a file.
fs::path runFolder(const fs::path& output, const std::string& out) {
    if (out.empty())
        throw HttpError{400,
                        "out: missing (valid: a folder under the output folder, such as "
                        "\"datasets/tiny\")"};
    try {
        return outputSubfolder(output, out);
    } catch (HttpError& e) {
        if (e.message.starts_with("folder")) e.message = "out" + e.message.substr(6);
        throw;
    }
}

}  // namespace

void Server::Impl::datasetRoutes() {
    datasets = std::make_shared<DatasetState>();
    DatasetState& state = *datasets;
    on("POST", "/api/dataset/check", [this](const httplib::Request& req, httplib::Response& res) {
        guarded(res, [&] {
            const json body = bodyJSON(req);
            onlyFields(body, {"text", "path"});
            try {
                sendJSON(res, specSummary(requestSpec(*this, body)));
            } catch (const Error& e) {
                // The library's line, with its field and line for the page to point at.
                sendJSON(res,
                         {{"error", oneLine(e.what())},
                          {"field", e.parameter()},
                          {"line", e.line() ? json(e.line()) : json(nullptr)}},
                         400);
            }
        });
    });
    on("GET", "/api/dataset/specs", [this](const httplib::Request&, httplib::Response& res) {
        guarded(res, [&] {
            std::vector<std::string> names;
            std::error_code ec;
            const fs::path folder = output / "datasets";
            if (isUnder(folder, output))
                for (const auto& entry : fs::directory_iterator(folder, ec))
                    if (entry.path().extension() == ".json" && entry.is_regular_file(ec))
                        names.push_back("datasets/" + entry.path().filename().string());
            std::sort(names.begin(), names.end());
            sendJSON(res, names);
        });
    });
    on("GET", "/api/dataset/spec", [this](const httplib::Request& req, httplib::Response& res) {
        guarded(res, [&] {
            const std::string path = req.get_param_value("path");
            const fs::path file = specFile(output, path);
            if (std::error_code ec; fs::file_size(file, ec) > kMaxSpecText)
                throw HttpError{413, "path = \"" + clip(path) +
                                         "\": a spec too large (valid: at most " +
                                         std::to_string(kMaxSpecText) + " bytes)"};
            sendJSON(res, {{"path", path}, {"text", fileBytes(file)}});
        });
    });
    on("POST", "/api/dataset/preview",
       [this, &state](const httplib::Request& req, httplib::Response& res) {
           guarded(res, [&] {
               const json body = bodyJSON(req);
               onlyFields(body, {"text", "path", "sample"});
               const std::size_t index =
                   wholeField(body, "sample", 0, double(kMaxDatasetSamples - 1), 0);
               const DatasetSpec spec = requestSpec(*this, body);
               std::unique_lock<std::mutex> one(state.previewing, std::try_to_lock);
               if (!one.owns_lock())
                   throw HttpError{429, "a preview is being made: one at a time (wait for it)"};
               std::string id;
               fs::path folder;
               {
                   std::lock_guard<std::mutex> lock(state.mutex);
                   if (!state.previewFolder)
                       state.previewFolder = std::make_unique<TemporaryFolder>();
                   id = "p" + std::to_string(state.nextPreview++);
                   folder = state.previewFolder->path() / id;
               }
               DatasetPreview p = makePreview(*this, spec, index, folder);
               json images = json::object();
               for (const auto& [name, bytes] : p.pictures)
                   images[fs::path(name).stem().string()] =
                       "/api/dataset/previews/" + id + "/" + name;
               json answer = {{"id", id}, {"images", images}, {"summary", p.summary}};
               {
                   std::lock_guard<std::mutex> lock(state.mutex);
                   for (const auto& [name, bytes] : p.pictures) state.previewBytes += bytes.size();
                   state.previews[id] = std::move(p);
                   state.previewOrder.push_back(id);
                   while (
                       state.previewOrder.size() > kKeptPreviews ||
                       (state.previewOrder.size() > 1 && state.previewBytes > kKeptPreviewBytes)) {
                       for (const auto& [name, bytes] :
                            state.previews[state.previewOrder.front()].pictures)
                           state.previewBytes -= bytes.size();
                       state.previews.erase(state.previewOrder.front());
                       state.previewOrder.pop_front();
                   }
               }
               sendJSON(res, answer);
           });
       });
    on("GET", "/api/dataset/previews/([^/]+)/([a-z]+\\.png)",
       [&state](const httplib::Request& req, httplib::Response& res) {
           guarded(res, [&] {
               std::lock_guard<std::mutex> lock(state.mutex);
               const auto it = state.previews.find(req.matches[1].str());
               if (it == state.previews.end())
                   throw HttpError{404, "no preview " + clip(req.matches[1].str(), 20)};
               const auto picture = it->second.pictures.find(req.matches[2].str());
               if (picture == it->second.pictures.end())
                   throw HttpError{404, "no picture " + clip(req.matches[2].str(), 20)};
               res.set_header("Cache-Control", "no-store");
               res.set_content(picture->second, "image/png");
           });
       });
    on("POST", "/api/dataset/runs",
       [this, &state](const httplib::Request& req, httplib::Response& res) {
           guarded(res, [&] {
               const json body = bodyJSON(req);
               onlyFields(body, {"text", "path", "out", "samples", "resume"});
               const fs::path out = runFolder(output, stringField(body, "out").value_or(""));
               bool resume = false;
               if (body.contains("resume")) {
                   if (!body["resume"].is_boolean())
                       throw HttpError{400, "resume = " + shownJSON(body["resume"]) +
                                                ": expected true or false"};
                   resume = body["resume"].get<bool>();
               }
               const std::size_t requested =
                   wholeField(body, "samples", 1, double(kMaxDatasetSamples), 0);
               const DatasetSpec spec = requestSpec(*this, body);
               const std::string shown = stringField(body, "out").value_or("");
               std::lock_guard<std::mutex> lock(state.mutex);
               if (state.running)
                   throw HttpError{409, "a dataset run is under way (" + state.running->id +
                                            ", into " + state.running->out +
                                            "): wait for it or cancel it"};
               std::error_code ec;
               if (fs::exists(out, ec) && !fs::is_directory(out, ec))
                   throw HttpError{400, "out = \"" + clip(shown) + "\": not a folder"};
               if (!resume && fs::exists(out / "samples", ec) && !fs::is_empty(out / "samples", ec))
                   throw HttpError{409, "out = \"" + clip(shown) +
                                            "\": holds samples already (valid: a new or empty "
                                            "folder, or resume: true to keep them and make the "
                                            "others)"};
               const bool madeOut = !fs::exists(out, ec);
               fs::create_directories(out, ec);
               if (!fs::is_directory(out, ec))
                   throw HttpError{400, "out = \"" + clip(shown) + "\": cannot make the folder"};
               auto run = std::make_shared<DatasetRun>();
               run->id = "d" + std::to_string(state.nextRun++);
               run->name = spec.name;
               run->out = out.lexically_relative(output).generic_string();
               run->total = requested ? requested : spec.samples;
               state.runs[run->id] = run;
               state.running = run;
               if (state.worker.joinable()) state.worker.join();  // the last run, finished
               state.worker = std::thread([this, &state, run, spec, out, resume, madeOut] {
                   runSamples(*this, state, run, spec, out, resume, madeOut);
               });
               sendJSON(res, {{"id", run->id}}, 202);
           });
       });
    on("GET", "/api/dataset/runs/([^/]+)",
       [&state](const httplib::Request& req, httplib::Response& res) {
           guarded(res, [&] {
               std::lock_guard<std::mutex> lock(state.mutex);
               const auto it = state.runs.find(req.matches[1].str());
               if (it == state.runs.end())
                   throw HttpError{404, "no dataset run " + clip(req.matches[1].str(), 20)};
               sendJSON(res, runJSON(*it->second));
           });
       });
    on("DELETE", "/api/dataset/runs/([^/]+)",
       [&state](const httplib::Request& req, httplib::Response& res) {
           guarded(res, [&] {
               std::lock_guard<std::mutex> lock(state.mutex);
               const std::string id = req.matches[1].str();
               const auto it = state.runs.find(id);
               if (it == state.runs.end()) throw HttpError{404, "no dataset run " + clip(id, 20)};
               if (it->second->state == DatasetRunState::Running) {
                   it->second->cancel = true;
                   return sendJSON(res, {{"state", "cancelling"}});
               }
               state.runs.erase(it);
               state.finishedRuns.erase(
                   std::remove(state.finishedRuns.begin(), state.finishedRuns.end(), id),
                   state.finishedRuns.end());
               sendJSON(res, {{"state", "deleted"}});
           });
       });
}

}  // namespace plantarch::builder
