"""Weather, the sun, the light model and leaf photosynthesis from Python."""

import threading
from typing import Any, cast

import numpy as np
import pytest

import plantarch as pa

DAVIS = (38.54, -121.74)


def bean(age=25):
    ctx = pa.Context()
    arch = pa.PlantArchitecture(ctx)
    arch.loadPlantModelFromLibrary("bean")
    arch.buildPlantInstanceFromLibrary(pa.vec3(0, 0, 0), age)
    return ctx, arch


def small_options():
    o = pa.LightOptions()
    o.diffuseRays = 16
    o.scatterRays = 8
    return o


def test_the_sun_and_a_clear_day():
    noon = pa.sunPosition(*DAVIS, "2026-06-21T20:00Z")
    assert 74 < noon.elevation < 76
    assert 150 < noon.azimuth < 210
    day = pa.clearSkyDay(*DAVIS, "2026-06-21", clearness=0.7)
    assert len(day) == 24
    assert str(day[20].time) == "2026-06-21T20:30:00Z"
    assert max(h.par for h in day) > 1800
    assert day[10].par == 0  # night
    sky = pa.skyLight(*DAVIS, day[20])
    assert sky.directNormal > 3 * sky.diffuseHorizontal


def test_light_per_triangle_as_arrays_and_on_the_leaves():
    ctx, _ = bean()
    model = pa.LightModel(ctx, small_options())
    sky = pa.skyLight(*DAVIS, pa.clearSkyDay(*DAVIS, "2026-06-21")[20])
    r = model.compute(sky)
    n = model.triangleCount()
    assert set(r) == {"absorbed", "sunlit", "incident", "absorbed_direct"}
    for a in r.values():
        assert a.shape == (n,) and a.dtype == np.float32
    assert np.all(r["absorbed"] <= r["incident"] + 1e-3)
    assert np.all((r["sunlit"] >= 0) & (r["sunlit"] <= 1))
    assert 0 < r["sunlit"].mean() < 1
    assert len(model.primitives()) == n
    pa.writeLightData(ctx, model, r)
    leaves = [i for i in ctx.objectIDs() if ctx.objectData(i, "organ") == "leaf"]
    values = [cast(float, ctx.objectData(i, "absorbed_par")) for i in leaves]
    assert max(values) > 5 * min(values)  # some leaves in the sun, some in the shade
    # Same seed, same numbers, whichever thread asks, two at once.
    results: list[Any] = [None, None]

    def run(k):
        results[k] = model.compute(sky)["absorbed"]

    threads = [threading.Thread(target=run, args=(k,)) for k in range(2)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert np.array_equal(results[0], r["absorbed"])
    assert np.array_equal(results[1], r["absorbed"])
    # Sampled per object: fewer ray origins, each triangle its object's mean.
    options = small_options()
    options.samplesPerObject = 4
    sampled = pa.LightModel(ctx, options)
    assert sampled.sampleCount() < n == sampled.triangleCount()
    rs = sampled.compute(sky)["absorbed"]
    objects = np.array(sampled.objects())
    for o in sorted(set(objects.tolist()))[:20]:
        assert np.ptp(rs[objects == o]) == 0


def test_photosynthesis():
    p = pa.FarquharParameters()
    assert pa.farquhar(p, 0, 25).net == pytest.approx(-p.rd25)
    full = pa.farquhar(p, 1800, 25)
    assert 20 < full.net < 35 and not full.lightLimited
    assert pa.farquhar(p, 1800, 25, co2=800).net > 1.3 * full.net
    mixed = pa.farquharSunlitShaded(p, 900, 800, 0.5, 25)
    assert mixed.net < pa.farquhar(p, 900, 25).net
    q = pa.LightResponseParameters()
    assert pa.lightResponse(q, 0).net == pytest.approx(-q.respiration)


def test_bad_values_are_plantarch_errors(tmp_path):
    with pytest.raises(pa.Error, match="latitude out of range"):
        pa.sunPosition(95, 0, "2026-06-21")
    with pytest.raises(pa.Error, match="day out of range"):
        pa.clearSkyDay(0, 0, "2026-02-30")
    with pytest.raises(pa.Error, match="not a weather file"):
        pa.readWeatherFile("/dev/zero")
    bad = tmp_path / "w.csv"
    bad.write_text("time,par,air_temperature\n2026-01-01T00:00Z,nan,20\n")
    with pytest.raises(pa.Error, match=r"w.csv:2: par = nan: not a finite number"):
        pa.readWeatherFile(str(bad))
    o = pa.LightOptions()
    o.leaf = pa.SurfaceOptics(0.6, 0.5)
    with pytest.raises(pa.Error, match="optical properties out of range"):
        pa.LightModel(pa.Context(), o)
    with pytest.raises(pa.Error, match="absorbed PAR"):
        pa.farquhar(pa.FarquharParameters(), -1, 25)
    ctx, _ = bean()
    model = pa.LightModel(ctx, small_options())
    with pytest.raises(pa.Error, match="light result does not match"):
        pa.writeLightData(ctx, model, {"absorbed": [1.0], "sunlit": [0.0], "incident": [1.0],
                                       "absorbed_direct": [0.0]})
    ctx.deleteObject(ctx.objectIDs()[0])
    with pytest.raises(pa.Error, match="no longer holds the light model's triangles"):
        pa.writeLightData(ctx, model, model.compute(pa.SkyLight()))
