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

_MAX_SAMPLES = 10_000_000


def _make_sample(spec: str, index: int, out: str, resume: bool) -> Dict[str, Any]:
    """Makes one sample; runs on a Dask worker (or here)."""
    from plantarch import _plantarch

    return _plantarch.writeDatasetSample(spec, index, out, resume)


def generate(spec: "str | os.PathLike[str]", out: "str | os.PathLike[str]",
             samples: Optional[int] = None, client: Optional[Any] = None,
             resume: bool = False,
             progress: Optional[Callable[[int, int], None]] = None) -> Dict[str, Any]:
    """Makes the samples 0 .. samples-1 of a dataset spec file (default: the spec's `samples`,
    at most 10,000,000) into the folder `out` (made if missing), then writes
    manifest-0-of-1.json, dataset.json and the per-split COCO files, as
    `plantarch dataset SPEC --out OUT` does.

    client: a dask.distributed Client; its workers make the samples (a few tasks per worker in
    flight at a time, so any count fits the scheduler), else they are made here one after
    another. resume: keep the samples already made. progress(done, total) is called here after
    each sample.

    Returns a dict: samples (the count), made (made now), kept (there already), bytes, plants,
    triangles and annotations (of the samples made now), splits (samples made now per split).
    Errors are plantarch.Error with one line, raised here whichever worker met them; the
    samples finished before it stay (resume=True goes on from them).
    """
    from plantarch import _plantarch

    spec = os.path.abspath(os.fspath(spec))
    out = os.path.abspath(os.fspath(out))
    info = _plantarch.checkDatasetSpec(spec)
    count = info["samples"] if samples is None else samples
    if isinstance(count, bool) or not isinstance(count, int) or not 1 <= count <= _MAX_SAMPLES:
        raise _plantarch.Error(
            f"samples = {count!r}: out of range (valid: a whole number 1 to {_MAX_SAMPLES})")
    os.makedirs(out, exist_ok=True)
    summary: Dict[str, Any] = {"samples": count, "made": 0, "kept": 0, "bytes": 0, "plants": 0,
                               "triangles": 0, "annotations": 0, "splits": {}}
    done = 0

    def add(result: Dict[str, Any]) -> None:
        nonlocal done
        done += 1
        if result["skipped"]:
            summary["kept"] += 1
        else:
            summary["made"] += 1
            for key in ("bytes", "plants", "triangles", "annotations"):
                summary[key] += result[key]
            summary["splits"][result["split"]] = summary["splits"].get(result["split"], 0) + 1
        if progress is not None:
            progress(done, count)

    if client is None:
        for i in range(count):
            add(_make_sample(spec, i, out, resume))
    else:
        from distributed import as_completed

        workers = max(1, len(client.scheduler_info().get("workers", {})))
        window = 4 * workers
        pending = iter(range(count))
        first = [client.submit(_make_sample, spec, i, out, resume, pure=False)
                 for _, i in zip(range(window), pending)]
        running = as_completed(first)
        try:
            for future in running:
                add(future.result())
                nxt = next(pending, None)
                if nxt is not None:
                    running.add(client.submit(_make_sample, spec, nxt, out, resume, pure=False))
        finally:
            client.cancel(list(running.futures))
    _plantarch.writeDatasetManifest(spec, out, count, 0, 1)
    _plantarch.mergeDataset(spec, out, count)
    return summary
