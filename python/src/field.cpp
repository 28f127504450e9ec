// Fields larger than memory (plantarch/Field.h): a project's tiles, one tile built and written,
// and the index written; plantarch/_field.py maps the tiles over a Dask cluster with them.

#include "plantarch/Field.h"

#include <string>
#include <vector>

#include "bindings.h"
#include "docstrings.h"

namespace plantarch::python {

namespace {

FieldOptions fieldOptions(float tileSize, float halo, std::size_t maxTriangles) {
    FieldOptions o;
    o.tileSize = tileSize;
    o.halo = halo;
    o.maxTriangles = maxTriangles;
    return o;
}

py::list tilesInPython(const std::string& project, float tileSize, float halo) {
    const FieldPlan plan = fieldTiles(readProjectFile(project), fieldOptions(tileSize, halo, 0));
    py::list tiles;
    for (const FieldTile& t : plan.tiles) {
        py::dict d;
        d["name"] = t.name;
        d["ix"] = t.ix;
        d["iy"] = t.iy;
        d["min"] = t.min;
        d["max"] = t.max;
        std::vector<unsigned> plants, halo;
        for (const FieldPlant& p : t.plants) plants.push_back(p.id);
        for (const FieldPlant& p : t.halo) halo.push_back(p.id);
        d["plants"] = plants;
        d["halo"] = halo;
        tiles.append(d);
    }
    return tiles;
}

py::list tileInPython(const std::string& project, float tileSize, std::size_t tile,
                      const std::string& out, float halo, std::size_t maxTriangles) {
    const Project p = readProjectFile(project);
    std::vector<FieldPlantRow> rows;
    {
        // A worker's other threads (a Dask worker's heartbeat) run while the tile is built.
        py::gil_scoped_release release;
        rows = buildFieldTile(p, fieldOptions(tileSize, halo, maxTriangles), tile, out);
    }
    py::list out_rows;
    for (const FieldPlantRow& r : rows) {
        py::dict d;
        d["plant"] = r.id;
        d["block"] = r.block;
        d["species"] = r.species;
        d["tile"] = r.tile;
        d["base"] = r.base;
        d["age"] = r.age;
        d["seed"] = r.seed;
        d["stream"] = r.stream;
        d["triangles"] = r.triangles;
        d["height"] = r.height;
        d["leaf_area"] = r.leafArea;
        d["bounds"] = py::make_tuple(r.bounds.min, r.bounds.max);
        out_rows.append(d);
    }
    return out_rows;
}

void indexInPython(const std::string& project, const std::string& out, float tileSize, float halo) {
    writeFieldIndex(readProjectFile(project), fieldOptions(tileSize, halo, 0), out);
}

}  // namespace

void bindField(py::module_& m) {
    m.def("fieldTiles", &tilesInPython, py::arg("project"), py::arg("tile_size"),
          py::arg("halo") = 1.0f,
          inPython(docs::fieldTiles,
                   "In Python: fieldTiles(project, tile_size, halo=1.0) takes a project file "
                   "and returns the tiles holding plants, in order, as dicts: name, ix, iy, min, "
                   "max (the tile's rectangle), plants and halo (plant IDs)."));
    m.def("buildFieldTile", &tileInPython, py::arg("project"), py::arg("tile_size"),
          py::arg("tile"), py::arg("out"), py::arg("halo") = 1.0f, py::arg("max_triangles") = 0,
          inPython(docs::buildFieldTile,
                   "In Python: buildFieldTile(project, tile_size, tile, out, halo=1.0, "
                   "max_triangles=0) takes a project file and a tile's index in fieldTiles; "
                   "returns its plants as dicts (the columns of plants.csv: plant, block, "
                   "species, tile, base, age, seed, stream, triangles, height, leaf_area, "
                   "bounds)."));
    m.def("writeFieldIndex", &indexInPython, py::arg("project"), py::arg("out"),
          py::arg("tile_size"), py::arg("halo") = 1.0f,
          inPython(docs::writeFieldIndex,
                   "In Python: writeFieldIndex(project, out, tile_size, halo=1.0) takes a project "
                   "file."));
}

}  // namespace plantarch::python
