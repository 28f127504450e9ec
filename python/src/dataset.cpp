// Synthetic datasets (plantarch/Dataset.h): a spec checked, one sample written, a shard's
// manifest and the merged index; plantarch/dataset.py maps samples over a Dask cluster with
// them.

#include "plantarch/Dataset.h"

#include <string>

#include "bindings.h"
#include "docstrings.h"

namespace plantarch::python {

namespace {

py::dict checkInPython(const std::string& spec) {
    const DatasetSpec s = readDatasetSpecFile(spec);
    checkDatasetSpec(s);
    py::dict d;
    d["name"] = s.name;
    d["seed"] = s.seed;
    d["samples"] = s.samples;
    py::list splits;
    for (const auto& [name, fraction] : s.splits) splits.append(py::make_tuple(name, fraction));
    d["splits"] = splits;
    return d;
}

py::dict sampleInPython(const std::string& spec, std::size_t index, const std::string& out,
                        bool resume) {
    const DatasetSpec s = readDatasetSpecFile(spec);
    DatasetSampleResult r;
    {
        // A worker's other threads (a Dask worker's heartbeat) run while the sample is made.
        py::gil_scoped_release release;
        DatasetWriteOptions o;
        o.resume = resume;
        r = writeDatasetSample(s, index, out, o);
    }
    py::dict d;
    d["sample"] = r.index;
    d["split"] = r.split;
    d["skipped"] = r.skipped;
    d["bytes"] = r.bytes;
    d["plants"] = r.plants;
    d["triangles"] = r.triangles;
    d["annotations"] = r.annotations;
    return d;
}

void manifestInPython(const std::string& spec, const std::string& out, std::size_t samples,
                      std::size_t shard, std::size_t shards) {
    writeDatasetManifest(readDatasetSpecFile(spec), out, samples, shard, shards);
}

void mergeInPython(const std::string& spec, const std::string& out, std::size_t samples) {
    mergeDataset(readDatasetSpecFile(spec), out, samples);
}

}  // namespace

void bindDataset(py::module_& m) {
    m.def("checkDatasetSpec", &checkInPython, py::arg("spec"),
          inPython(docs::checkDatasetSpec,
                   "In Python: checkDatasetSpec(spec) reads the spec file and checks it; returns "
                   "a dict: name, seed, samples, splits [(name, fraction)]."));
    m.def("writeDatasetSample", &sampleInPython, py::arg("spec"), py::arg("index"), py::arg("out"),
          py::arg("resume") = false,
          inPython(docs::writeDatasetSample,
                   "In Python: writeDatasetSample(spec, index, out, resume=False) takes the spec "
                   "file's path; returns a dict: sample, split, skipped, bytes, plants, "
                   "triangles, annotations. Releases the GIL while it works."));
    m.def("writeDatasetManifest", &manifestInPython, py::arg("spec"), py::arg("out"),
          py::arg("samples"), py::arg("shard") = 0, py::arg("shards") = 1,
          inPython(docs::writeDatasetManifest, "In Python: takes the spec file's path."));
    m.def("mergeDataset", &mergeInPython, py::arg("spec"), py::arg("out"), py::arg("samples"),
          inPython(docs::mergeDataset, "In Python: takes the spec file's path."));
}

}  // namespace plantarch::python
