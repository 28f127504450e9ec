"""The triangle limit: jobs too large are refused or stopped with TriangleBudgetError."""

import pytest

import plantarch


def test_canopy_over_the_limit_is_refused_before_it_is_grown(arch):
    arch.setTriangleLimit(1_000_000)
    assert arch.getTriangleLimit() == 1_000_000
    with pytest.raises(plantarch.TriangleBudgetError) as info:
        arch.buildPlantCanopyFromLibrary(
            plantarch.vec3(0, 0, 0), plantarch.vec2(0.3, 0.3), (1000, 1000), 40
        )
    e = info.value
    assert isinstance(e, plantarch.Error) and isinstance(e, ValueError)
    assert e.limit == 1_000_000
    assert e.estimate > 20_000_000_000  # a million beans of some 30,000 triangles
    assert "a canopy of 1000000 plants needs about" in str(e)
    assert "over the triangle limit of 1000000" in str(e)
    assert arch.getAllPlantIDs() == []


def test_plant_past_the_limit_stops_and_context_refuses_geometry(arch):
    arch.setTriangleLimit(2000)
    with pytest.raises(plantarch.TriangleBudgetError) as info:
        arch.buildPlantInstanceFromLibrary(plantarch.vec3(0, 0, 0), age=40)
    assert info.value.limit == 2000 and info.value.estimate > 2000
    assert arch.getAllPlantIDs() == []
    ctx = plantarch.Context()
    ctx.setTriangleLimit(0)
    assert ctx.triangleLimit() == 0
    assert plantarch.PlantArchitecture.defaultTriangleLimit() > 0
