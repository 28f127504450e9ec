"""Synthetic datasets at scale (docs/datasets.md): the samples of a dataset spec made here one
after another or mapped over the workers of a Dask cluster, then the manifest and the merged
index written. Sample i is a pure function of (spec, i), so any split over workers writes the
same bytes per sample as a serial run (and as `plantarch dataset`).

    import plantarch.dataset
    from dask.distributed import Client, LocalCluster
    with LocalCluster(n_workers=2, threads_per_worker=1) as cluster, Client(cluster) as client:
        plantarch.dataset.generate("beans.json", "out", client=client)

Fields larger than one machine's memory, built in tiles: generate_field.
"""

from __future__ import annotations

import os
from typing import Any, Callable, Dict, List, Optional

from plantarch._field import generate_field

__all__ = ["generate", "generate_field"]


def _make_sample(spec: str, index: int, out: str, resume: bool) -> Dict[str, Any]:
    """Makes one sample; runs on a Dask worker (or here)."""
    from plantarch import _plantarch

    return _plantarch.writeDatasetSample(spec, index, out, resume)


def generate(spec: "str | os.PathLike[str]", out: "str | os.PathLike[str]",
             samples: Optional[int] = None, client: Optional[Any] = None,
             resume: bool = False,
             progress: Optional[Callable[[int, int], None]] = None) -> Dict[str, Any]:
    """Makes the samples 0 .. samples-1 of a dataset spec file (default: the spec's `samples`)
    into the folder `out` (made if missing), then writes manifest-0-of-1.json, dataset.json and
    the per-split COCO files, as `plantarch dataset SPEC --out OUT` does.

    client: a dask.distributed Client; its workers make the samples (client.map, results
    gathered as they finish), else they are made here one after another. resume: keep the
    samples already made. progress(done, total) is called here after each sample.

    Returns a dict: samples (the count), made (made now), kept (there already), bytes (of the
    samples made now), results (writeDatasetSample's dicts, in sample order). Errors are
    plantarch.Error with one line, raised here whichever worker met them.
    """
    from plantarch import _plantarch

    spec = os.path.abspath(os.fspath(spec))
    out = os.path.abspath(os.fspath(out))
    info = _plantarch.checkDatasetSpec(spec)
    count = info["samples"] if samples is None else int(samples)
    if count < 1:
        raise _plantarch.Error(f"samples = {count}: out of range (valid: 1 to 10000000)")
    os.makedirs(out, exist_ok=True)
    indices = list(range(count))
    results: List[Dict[str, Any]] = [{} for _ in indices]
    if client is None:
        for i in indices:
            results[i] = _make_sample(spec, i, out, resume)
            if progress is not None:
                progress(i + 1, count)
    else:
        from distributed import as_completed

        futures = client.map(_make_sample, [spec] * count, indices, [out] * count,
                             [resume] * count, pure=False)
        position = {f.key: i for i, f in enumerate(futures)}
        done = 0
        try:
            for future in as_completed(futures):
                results[position[future.key]] = future.result()
                done += 1
                if progress is not None:
                    progress(done, count)
        finally:
            client.cancel(futures)
    _plantarch.writeDatasetManifest(spec, out, count, 0, 1)
    _plantarch.mergeDataset(spec, out, count)
    made = [r for r in results if not r["skipped"]]
    return {"samples": count, "made": len(made), "kept": count - len(made),
            "bytes": sum(r["bytes"] for r in made), "results": results}
