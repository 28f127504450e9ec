"""Fields larger than one machine's memory, built tile by tile (docs/datasets.md, "Fields larger
than memory"): each tile of a project built on its own, serially or mapped over the workers of a
Dask cluster, then the index (tileset.json, 3D Tiles 1.1, and plants.csv) written.

A tile is a pure function of (project, tile size, halo, tile), so any split over workers gives
the same bytes per tile.
"""

from __future__ import annotations

import os
from typing import Any, Dict, List, Optional


def _build_tile(project: str, out: str, tile_size: float, halo: float, tile: int,
                max_triangles: int) -> List[Dict[str, Any]]:
    """Builds one tile and writes its GLB and CSV; runs on a Dask worker (or here)."""
    from plantarch import _plantarch

    return _plantarch.buildFieldTile(project, tile_size, tile, out, halo, max_triangles)


def generate_field(project: "str | os.PathLike[str]", out: "str | os.PathLike[str]",
                   tile_size: float, halo: float = 1.0, client: Optional[Any] = None,
                   resume: bool = False, max_triangles: int = 0) -> Dict[str, Any]:
    """Builds the field of a project file as tiles of `tile_size` metres into the folder `out`
    (made if missing): one labelled GLB and one CSV per tile, then tileset.json and plants.csv.

    halo: with soft collision avoidance, neighbours within this many metres of a tile are grown
    with it (not written). client: a dask.distributed Client; its workers build the tiles
    (client.map, then client.gather), else they are built here one after another. resume: skip
    the tiles whose GLB is there already. max_triangles: a limit per tile (0: none).

    Returns a dict: tiles (how many), built (tiles built now), plants (rows of the tiles built
    now, as buildFieldTile returns them), tileset and table (the index files' paths). Errors are
    plantarch.Error with one line, raised here whichever worker met them.
    """
    from plantarch import _plantarch

    project = os.path.abspath(os.fspath(project))
    out = os.path.abspath(os.fspath(out))
    tiles = _plantarch.fieldTiles(project, tile_size, halo)
    todo = [i for i, t in enumerate(tiles)
            if not (resume and os.path.isfile(os.path.join(out, t["name"] + ".glb")))]
    n = len(todo)
    if client is None:
        results = [_build_tile(project, out, tile_size, halo, i, max_triangles) for i in todo]
    else:
        futures = client.map(_build_tile, [project] * n, [out] * n, [tile_size] * n,
                             [halo] * n, todo, [max_triangles] * n, pure=False)
        results = client.gather(futures)
    _plantarch.writeFieldIndex(project, out, tile_size, halo)
    rows = [row for tile_rows in results for row in tile_rows]
    return {"tiles": len(tiles), "built": n, "plants": rows,
            "tileset": os.path.join(out, "tileset.json"),
            "table": os.path.join(out, "plants.csv")}
