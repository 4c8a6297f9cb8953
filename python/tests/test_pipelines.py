# SPDX-License-Identifier: Apache-2.0
"""The pipelines on scenes with known truth: a lake in a field, a gabled house."""
import math

import numpy as np
import pytest

import lidarfx


def lake_survey(rng, density_per_m2=4.0):
    """A 240 m x 240 m field rising gently away from a round lake (radius 45 m, level 100 m). Water returns are
    rare (97 % of pulses lost) and dark; land is bright. Returns the points and the truth function."""
    area = 240.0 * 240.0
    n = int(area * density_per_m2)
    x = rng.uniform(0, 240, n)
    y = rng.uniform(0, 240, n)
    r = np.hypot(x - 120, y - 120)
    water = r < 45
    keep = ~water | (rng.random(n) < 0.03)
    x, y, r, water = x[keep], y[keep], r[keep], water[keep]
    z = np.where(water, 100.0 + rng.normal(0, 0.01, water.size),
                 100.4 + 0.04 * np.maximum(r - 45, 0) + rng.normal(0, 0.03, water.size))
    intensity = np.where(water, rng.integers(5, 30, water.size), rng.integers(120, 220, water.size)).astype(np.uint16)
    ones = np.ones(x.size, np.uint8)
    return (x, y, z, intensity, ones, ones), (lambda xx, yy: np.hypot(xx - 120, yy - 120) < 45)


def test_extract_waterbodies_finds_the_lake_and_its_level(rng):
    points, truth = lake_survey(rng)
    rasters = lidarfx.rasterize(*points, 2.0)
    result = lidarfx.extract_waterbodies(rasters)
    assert result.ran, [i.message for i in result.issues]
    g = rasters.grid
    cols, rows = np.meshgrid(np.arange(g.cols), np.arange(g.rows))
    true_water = truth(g.x0 + (cols + 0.5) * g.cell_m, g.y0 - (rows + 0.5) * g.cell_m)
    inter = (result.water & true_water).sum()
    union = (result.water | true_water).sum()
    assert inter / union > 0.9
    lake = result.bodies[0]
    assert lake.label == 1 and lake.area_m2 == pytest.approx(math.pi * 45 ** 2, rel=0.1)
    assert lake.water_level_m == pytest.approx(100.0, abs=0.05)
    np.testing.assert_array_equal(result.water, result.labels > 0)
    # The library's defaults (dropout seeds only) find it too; a dict of rasters works like Rasters.
    as_dict = {k: getattr(rasters, k) for k in ("min_z", "max_z", "mean_intensity", "dropout", "count")}
    other = lidarfx.extract_waterbodies(as_dict, 2.0, method="dropout_seeds")
    assert (other.water & true_water).sum() / (other.water | true_water).sum() > 0.9


def test_hydro_flatten_puts_the_lake_at_one_level_and_lifts_no_shore_above_it(rng):
    points, _ = lake_survey(rng)
    rasters = lidarfx.rasterize(*points, 2.0)
    water = lidarfx.extract_waterbodies(rasters)
    dem = rasters.min_z.copy()
    dem[np.isnan(dem)] = 100.0  # the lake's unreturned cells: any value, hydro_flatten replaces them
    flat = lidarfx.hydro_flatten(dem, water.labels, rasters.min_z, rasters.max_z, 2.0, min_lake_area_m2=1000)
    lake = [b for b in flat.bodies if b.flattened]
    assert len(lake) == 1 and lake[0].type == "lake"
    assert abs(lake[0].level_min_m - 100.0) < 0.05
    on_lake = flat.body == lake[0].id
    assert np.all(flat.dem[on_lake] == np.float32(lake[0].level_min_m))
    assert np.all(np.isnan(flat.water_surface[~on_lake]))
    assert all(c.passed for c in flat.checks)
    assert {c.check for c in flat.checks} == {"flatness", "shoreline", "minimum_size"}
    # Under the specification's 2 acres (8,094 m²) the 6,360 m² lake is left to the terrain.
    spec = lidarfx.hydro_flatten(dem, water.labels, rasters.min_z, rasters.max_z, 2.0)
    assert not any(b.flattened for b in spec.bodies)
    assert np.array_equal(spec.dem, dem)
    with pytest.raises(ValueError, match="shoreline"):
        lidarfx.hydro_flatten(dem, water.labels, rasters.min_z, rasters.max_z, 2.0, shoreline="sideways")


def test_hydro_flatten_joins_a_river_cut_at_a_deck_and_flattens_under_it():
    labels = np.zeros((100, 400), np.int32)
    labels[40:80, :190] = 1
    labels[40:80, 200:] = 2  # a 10 m deck over columns 190-199
    water = 100.0 - 0.002 * np.arange(400, dtype=np.float32)
    min_z = np.where(labels > 0, water, np.nan).astype(np.float32)
    min_z[40:80, 190:200] = 106.0  # the deck
    dem = np.where(np.isnan(min_z), 103.0, min_z).astype(np.float32)
    flat = lidarfx.hydro_flatten(dem, labels, min_z, min_z, 1.0)
    assert [(j.kept, j.part_a, j.part_b, j.gap_cells) for j in flat.joins] == [(1, 1, 2, 400)]
    assert len(flat.bodies) == 1 and flat.bodies[0].type == "river"
    assert np.all(flat.body[40:80, 190:200] == 1)
    np.testing.assert_allclose(flat.dem[60, 190:200], water[190:200], atol=0.03)
    apart = lidarfx.hydro_flatten(dem, labels, min_z, min_z, 1.0, join_channels=False)
    assert apart.joins == [] and len(apart.bodies) == 2
    assert np.all(apart.dem[60, 190:200] == 106.0)


def test_hydro_flatten_continues_a_river_under_a_deck_that_notches_it():
    labels = np.zeros((100, 400), np.int32)
    labels[40:80, :] = 1
    labels[40:70, 190:200] = 0  # a 10 m deck over three quarters of the river: one body with a notch
    water = 100.0 - 0.002 * np.arange(400, dtype=np.float32)
    min_z = np.where(labels > 0, water, np.nan).astype(np.float32)
    min_z[38:70, 190:200] = 106.0  # the deck, over the north bank too
    dem = np.where(np.isnan(min_z), 103.0, min_z).astype(np.float32)
    flat = lidarfx.hydro_flatten(dem, labels, min_z, min_z, 1.0)
    assert flat.deck_cells == 300 and flat.deck_level_cells == 0
    assert np.all(flat.body[40:70, 190:200] == 1) and np.all(flat.body[38:40, 190:200] == 0)
    np.testing.assert_allclose(flat.dem[50, 190:200], water[190:200], atol=0.03)
    notched = lidarfx.hydro_flatten(dem, labels, min_z, min_z, 1.0, under_decks=False)
    assert notched.deck_cells == 0 and np.all(notched.body[40:70, 190:200] == 0)
    assert np.all(notched.dem[50, 190:200] == 106.0)


def test_extract_waterbodies_refuses_data_too_sparse_for_its_cells(rng):
    points, _ = lake_survey(rng, density_per_m2=0.2)
    result = lidarfx.extract_waterbodies(lidarfx.rasterize(*points, 1.0))
    assert not result.ran and not result.water.any()
    assert any(i.severity == "problem" and "points per" in i.message for i in result.issues)
    assert result.suggested_cell_m > 1.0
    with pytest.raises(ValueError, match="missing dropout"):
        lidarfx.extract_waterbodies({"min_z": np.zeros((3, 3)), "max_z": np.zeros((3, 3)),
                                     "mean_intensity": np.zeros((3, 3))}, 1.0)
    with pytest.raises(ValueError, match="method must be"):
        lidarfx.extract_waterbodies(lidarfx.rasterize(*points, 1.0), method="best")


def gabled_house(rng):
    """100 m x 100 m at 0.5 m cells: flat ground at 50 m, a 24 m x 14 m house (eaves 6 m, ridge 9.5 m, ridge
    running east-west), so its roof planes face north and south with a tilt of atan(3.5 / 7) = 26.57 deg."""
    cell = 0.5
    rows = cols = 200
    yy, xx = np.mgrid[0:rows, 0:cols] * cell + cell / 2
    dsm = 50.0 + rng.normal(0, 0.02, (rows, cols))
    inside = (np.abs(xx - 50) < 12) & (np.abs(yy - 50) < 7)
    roof = 59.5 - 0.5 * np.abs(yy - 50)
    dsm = np.where(inside, roof, dsm).astype(np.float32)
    return dsm, cell, inside


def test_extract_buildings_and_roof_suitability_on_a_gabled_house(rng):
    dsm, cell, inside = gabled_house(rng)
    grid = lidarfx.Grid(x0=1000.0, y0=2000.0, cell_m=cell, rows=dsm.shape[0], cols=dsm.shape[1])
    b = lidarfx.extract_buildings(dsm, grid=grid)
    assert len(b.buildings) == 1
    house = b.buildings[0]
    assert house.roof_area_horizontal_m2 == pytest.approx(24 * 14, rel=0.05)
    assert house.ridge_z == pytest.approx(59.5, abs=0.2) and house.ground_z == pytest.approx(50, abs=0.1)
    assert house.outline["type"] == "MultiPolygon" and not house.clipped
    xs = [p[0] for p in house.outline["coordinates"][0][0]]
    assert min(xs) == pytest.approx(1000 + 50 - 12, abs=cell) and max(xs) == pytest.approx(1000 + 50 + 12, abs=cell)
    big = [s for s in b.surfaces if s.horizontal_area_m2 > 50]
    assert len(big) == 2
    assert sorted(round(s.azimuth_deg) % 360 for s in big) == [0, 180]
    for s in big:
        assert s.tilt_deg == pytest.approx(math.degrees(math.atan(0.5)), abs=1.5)
    pv = lidarfx.roof_suitability(dsm, b.ground, b.building_id, grid=grid)
    south = [p for p in pv.patches if abs(p.azimuth_deg - 180) < 10]
    north = [p for p in pv.patches if min(p.azimuth_deg, 360 - p.azimuth_deg) < 10]
    assert south and all(p.suitable for p in south) and south[0].kwp == pytest.approx(south[0].sloped_area_m2 / 8)
    assert north and not any(p.suitable for p in north)
    assert pv.patch_id.shape == dsm.shape and (pv.patch_id[~inside] == 0).all()
    with pytest.raises(ValueError, match="grid must have the DSM's shape"):
        lidarfx.extract_buildings(dsm[:10], grid=grid)


def test_azimuth_mode_select_swaps_a_north_facing_two_plane_roof():
    h = np.zeros(360, np.uint32)
    h[10] = 500     # the larger plane faces north
    h[190] = 400
    s = lidarfx.azimuth_mode_select(h)
    assert s.planes == 2 and s.form == "two_planes" and s.reason == "swapped"
    assert s.azimuth_deg == pytest.approx(190.5, abs=1) and s.suitable
    assert not lidarfx.azimuth_mode_select(np.zeros(360)).suitable
    with pytest.raises(ValueError, match="360"):
        lidarfx.azimuth_mode_select(np.zeros(100))


def test_extract_buildings_with_pulse_counts_keeps_a_rough_roof_and_drops_a_crown(rng):
    # A rough old roof (heights jumping by up to 1.2 m) with whole pulses, and a crown with 30 % split pulses.
    dsm = np.full((80, 80), 100.0, dtype=np.float32)
    dsm[10:40, 10:40] = 108.0 + rng.uniform(0.0, 1.2, (30, 30))
    dsm[50:70, 20:60] = 100.0 + rng.uniform(6.0, 10.0, (20, 40))
    points = np.full((80, 80), 10, dtype=np.uint32)
    split = np.zeros((80, 80), dtype=np.uint32)
    split[10:40, 10:40] = 1
    split[50:70, 20:60] = 3
    b = lidarfx.extract_buildings(dsm, 0.5, point_count=points, multiple_return_count=split)
    assert len(b.buildings) == 1
    assert b.building_id[25, 25] == 1 and b.building_id[60, 40] == 0
    with pytest.raises(ValueError):
        lidarfx.extract_buildings(dsm, 0.5, point_count=points)
    with pytest.raises(ValueError):
        lidarfx.extract_buildings(dsm, 0.5, vegetation=split > 0, point_count=points, multiple_return_count=split)



def test_extract_buildings_splits_a_terrace_at_its_party_walls():
    # Three flat-roofed houses of 8 m x 10 m side by side, eaves 6, 8 and 6 m above level ground: one block.
    dsm = np.zeros((30, 44), np.float32)
    for house, height in enumerate((6.0, 8.0, 6.0)):
        dsm[10:20, 10 + 8 * house:18 + 8 * house] = height
    ground = np.zeros_like(dsm)
    split = lidarfx.extract_buildings(dsm, 1.0, ground=ground)
    assert len(split.buildings) == 3
    assert len({int(split.building_id[15, c]) for c in (12, 20, 30)}) == 3
    whole = lidarfx.extract_buildings(dsm, 1.0, ground=ground, party_wall_step_m=float("inf"))
    assert len(whole.buildings) == 1
    with pytest.raises(ValueError, match="min_step_m"):
        lidarfx.extract_buildings(dsm, 1.0, ground=ground, party_wall_step_m=0.0)


def test_extract_buildings_finds_the_roof_under_an_overhanging_crown(rng):
    # A 20 m x 12 m flat roof 8 m high on level ground at 100 m, 1 m cells; a crown at 116 m reaches from 4 m beyond
    # the east wall 6 m over the roof. Its pulses split: foliage first, then the roof (or, beyond the wall, the ground).
    grid = lidarfx.Grid(x0=0.0, y0=40.0, cell_m=1.0, rows=40, cols=40)
    n = 40 * 40 * 8
    x, y = rng.uniform(0, 40, n), rng.uniform(0, 40, n)
    on_roof = (x >= 10) & (x < 30) & (y >= 14) & (y < 26)
    under_crown = (x >= 24) & (x < 34) & (y >= 14) & (y < 26)
    below = np.where(on_roof, 108.0, 100.0) + rng.normal(0, 0.02, n)
    crown = 116.0 + rng.normal(0, 0.3, n)
    xs = np.concatenate([x, x[under_crown]])
    ys = np.concatenate([y, y[under_crown]])
    zs = np.concatenate([np.where(under_crown, crown, below), below[under_crown]])
    k = int(under_crown.sum())
    returns = np.concatenate([np.ones(n, np.uint8), np.full(k, 2, np.uint8)])
    nreturns = np.concatenate([np.where(under_crown, 2, 1).astype(np.uint8), np.full(k, 2, np.uint8)])
    r = lidarfx.rasterize(xs, ys, zs, returns=returns, nreturns=nreturns, grid=grid)
    ground = lidarfx.fill_ground(np.where(r.min_z < 104, r.min_z, np.nan).astype(np.float32), 1.0)
    raised, lowest = lidarfx.count_points_above(xs, ys, zs, ground, 2.5, grid=grid, return_lowest=True)
    assert lowest.dtype == np.float32 and np.isnan(lowest[2, 2]) and abs(float(lowest[20, 26]) - 108.0) < 0.1
    counts = dict(dsm=r.max_z, grid=grid, ground=ground, point_count=r.count,
                  multiple_return_count=r.multiple_return_count, raised_count=raised)
    without = lidarfx.extract_buildings(**counts)
    with_lowest = lidarfx.extract_buildings(**counts, lowest_raised=lowest)
    assert len(without.buildings) == len(with_lowest.buildings) == 1
    # Without the lowest raised points the covered roof is left to the crown (14 x 12 cells found); with them the
    # roof joins (20 x 12 = 240 m^2), and the crown beyond the wall, whose pulses end on the ground, does not.
    assert without.buildings[0].roof_area_horizontal_m2 < 190
    assert with_lowest.buildings[0].roof_area_horizontal_m2 == pytest.approx(240, abs=6)
    assert with_lowest.building_id[20, 31] == 0
    # The roof cells found under the crown are flagged (the DSM there is the crown); none without the lowest points.
    assert with_lowest.under_crowns.dtype == bool and with_lowest.under_crowns[20, 26] and not without.under_crowns.any()
    assert not with_lowest.under_crowns[20, 15]
    with pytest.raises(ValueError, match="lowest_raised needs raised_count"):
        lidarfx.extract_buildings(r.max_z, grid=grid, ground=ground, point_count=r.count,
                                  multiple_return_count=r.multiple_return_count, lowest_raised=lowest)


def test_extract_buildings_decides_the_rim_by_the_raised_points(rng):
    # A 20 m x 12 m flat roof 8 m high on level ground at 100 m, 1 m cells, 16 points per m^2. The DSM keeps each
    # cell's highest point, so the cells the walls cross read as roof although most of their points are ground.
    grid = lidarfx.Grid(x0=0.0, y0=40.0, cell_m=1.0, rows=40, cols=40)
    n = 40 * 40 * 16
    x, y = rng.uniform(0, 40, n), rng.uniform(0, 40, n)
    on_roof = (x >= 10.7) & (x < 30.3) & (y >= 14.7) & (y < 26.3)   # the walls cross the edge cells, 30 % roof
    z = np.where(on_roof, 108.0, 100.0) + rng.normal(0, 0.02, n)
    r = lidarfx.rasterize(x, y, z, grid=grid)
    dsm = r.max_z
    ground = lidarfx.fill_ground(np.where(r.max_z < 104, r.min_z, np.nan).astype(np.float32), 1.0)
    assert np.isfinite(ground).all() and abs(float(ground[20, 20]) - 100.0) < 0.1
    raised = lidarfx.count_points_above(x, y, z, ground, 2.5, grid=grid)
    assert raised.dtype == np.uint32 and (raised <= r.count).all()
    assert raised[20, 20] == r.count[20, 20] and raised[2, 2] == 0
    no_split = np.zeros_like(r.count)
    by_dsm = lidarfx.extract_buildings(dsm, grid=grid, ground=ground, point_count=r.count,
                                       multiple_return_count=no_split)
    by_points = lidarfx.extract_buildings(dsm, grid=grid, ground=ground, point_count=r.count,
                                          multiple_return_count=no_split, raised_count=raised)
    assert len(by_dsm.buildings) == len(by_points.buildings) == 1
    # The true footprint is 19.6 m x 11.6 m = 227 m^2: the DSM's rule takes every cell a wall crosses (21 x 13 =
    # 273), the points' rule only the cells mostly under the roof (19 x 11 = 209).
    assert by_dsm.buildings[0].roof_area_horizontal_m2 == pytest.approx(273, abs=3)
    assert by_points.buildings[0].roof_area_horizontal_m2 == pytest.approx(209, abs=3)
    # The vendor's building cells taken as they are: exactly the 19 x 11 cells mostly under the roof.
    classified = np.zeros((40, 40), bool)
    classified[14:25, 11:30] = True
    vendor = lidarfx.extract_buildings(dsm, grid=grid, ground=ground, building_cells=classified)
    assert len(vendor.buildings) == 1 and (vendor.building_id > 0).sum() == classified.sum() == 209
    with pytest.raises(ValueError, match="building_cells are the buildings"):
        lidarfx.extract_buildings(dsm, grid=grid, building_cells=classified, point_count=r.count,
                                  multiple_return_count=no_split)
    with pytest.raises(ValueError, match="raised_count needs point_count"):
        lidarfx.extract_buildings(dsm, grid=grid, ground=ground, raised_count=raised)
    with pytest.raises(ValueError, match="raised_count needs the ground"):
        lidarfx.extract_buildings(dsm, grid=grid, point_count=r.count, multiple_return_count=no_split,
                                  raised_count=raised)
    with pytest.raises(ValueError, match="grid is required"):
        lidarfx.count_points_above(x, y, z, ground, 2.5, grid=None)
