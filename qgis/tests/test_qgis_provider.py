# SPDX-License-Identifier: Apache-2.0
"""The lidarfx QGIS provider, headless: qgis_process lists its algorithms and runs each on small generated
inputs; every output opens in GDAL/OGR with the input's CRS and plausible values.

The plugin under test is this checkout's (qgis/lidarfx_processing), linked into a temporary QGIS profile
(QGIS_CUSTOM_CONFIG_PATH), never an installed copy. Environment: LIDARFX_PROGRAM (the lidarfx program),
LIDARFX_MAKE_SURVEY (make_water_survey, for a LAS survey), PYTHONPATH (the lidarfx Python module)."""
import json
import math
import os
import shutil
import struct
import subprocess

import numpy as np
import pytest

QGIS_PROCESS = shutil.which("qgis_process.bin") or "/usr/bin/qgis_process.bin"
if not os.path.exists(QGIS_PROCESS):
    pytest.skip("QGIS is not installed (no qgis_process.bin): the provider test is skipped",
                allow_module_level=True)

from osgeo import gdal, ogr, osr  # noqa: E402  (python3-gdal comes with QGIS)

gdal.UseExceptions()
os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")  # QGIS in this process and in qgis_process: no display
ogr.UseExceptions()
PLUGIN = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "lidarfx_processing")
EPSG = 32633
X0, Y0 = 500000.0, 4000080.0


@pytest.fixture(scope="module")
def qgis(tmp_path_factory):
    """Runs qgis_process.bin with a temporary profile holding the checkout's plugin, enabled."""
    config = tmp_path_factory.mktemp("qgis_config")
    plugins = config / "profiles" / "default" / "python" / "plugins"
    plugins.mkdir(parents=True)
    os.symlink(os.path.abspath(PLUGIN), plugins / "lidarfx_processing")
    env = dict(os.environ, QT_QPA_PLATFORM="offscreen", QGIS_CUSTOM_CONFIG_PATH=str(config))

    def run(*arguments, check=True):
        done = subprocess.run([QGIS_PROCESS, *arguments], env=env, capture_output=True, text=True, timeout=600)
        if check and done.returncode != 0:
            raise AssertionError(f"qgis_process {' '.join(arguments)} failed ({done.returncode}):\n"
                                 f"{done.stdout[-3000:]}\n{done.stderr[-3000:]}")
        return done

    run("plugins", "enable", "lidarfx_processing")
    return run


def write_raster(path, values, epsg=EPSG, cell=1.0, nodata=None):
    rows, cols = values.shape
    ds = gdal.GetDriverByName("GTiff").Create(str(path), cols, rows, 1, gdal.GDT_Float32)
    ds.SetGeoTransform((X0, cell, 0, Y0, 0, -cell))
    srs = osr.SpatialReference()
    srs.ImportFromEPSG(epsg)
    ds.SetProjection(srs.ExportToWkt())
    if nodata is not None:
        ds.GetRasterBand(1).SetNoDataValue(nodata)
    ds.GetRasterBand(1).WriteArray(values)
    ds = None
    return str(path)


@pytest.fixture(scope="module")
def town(tmp_path_factory):
    """An 80 m x 80 m DSM and DTM (1 m cells, EPSG:32633) with one gabled house of 20 m x 14 m (eaves 106 m,
    ridge 109.5 m, ridge east-west: planes facing north and south at 26.6°) on ground at 100 m, and its
    footprint as a GeoPackage layer with building_id 7."""
    folder = tmp_path_factory.mktemp("town")
    yy, xx = np.mgrid[0:80, 0:80] + 0.5
    inside = (np.abs(xx - 40) < 10) & (np.abs(yy - 40) < 7)
    dtm = np.full((80, 80), 100.0, np.float32)
    dsm = np.where(inside, 109.5 - 0.5 * np.abs(yy - 40), dtm).astype(np.float32)
    paths = {"dsm": write_raster(folder / "dsm.tif", dsm), "dtm": write_raster(folder / "dtm.tif", dtm)}
    srs = osr.SpatialReference()
    srs.ImportFromEPSG(EPSG)
    ds = ogr.GetDriverByName("GPKG").CreateDataSource(str(folder / "footprints.gpkg"))
    layer = ds.CreateLayer("footprints", srs, ogr.wkbPolygon)
    layer.CreateField(ogr.FieldDefn("building_id", ogr.OFTInteger))
    feature = ogr.Feature(layer.GetLayerDefn())
    feature.SetField("building_id", 7)
    x0, x1, y0, y1 = X0 + 30, X0 + 50, Y0 - 47, Y0 - 33
    feature.SetGeometry(ogr.CreateGeometryFromWkt(f"POLYGON(({x0} {y0},{x1} {y0},{x1} {y1},{x0} {y1},{x0} {y0}))"))
    layer.CreateFeature(feature)
    ds = None
    paths["footprints"] = str(folder / "footprints.gpkg")
    paths["folder"] = folder
    return paths


def write_las(path, x, y, z, epsg=EPSG):
    """LAS 1.2, point format 0 (one return per pulse, intensity 100), GeoKeys naming EPSG (metres)."""
    keys = [1, 1, 0, 4, 1024, 0, 1, 1, 1025, 0, 1, 1, 3072, 0, 1, epsg, 3076, 0, 1, 9001]
    key_bytes = struct.pack("<%dH" % len(keys), *keys)
    vlr = struct.pack("<H16sHH32s", 0, b"LASF_Projection", 34735, len(key_bytes), b"GeoKeyDirectoryTag")
    vlr += key_bytes
    scale, offset = 0.001, (float(np.floor(x.min())), float(np.floor(y.min())), 0.0)
    header = struct.pack("<4sHH16sBB32s32sHHHIIBHI5I3d3d6d", b"LASF", 0, 0, bytes(16), 1, 2, b"lidarfx tests",
                         b"test_qgis_provider.py", 1, 2026, 227, 227 + len(vlr), 1, 0, 20, len(x), len(x), 0, 0,
                         0, 0, scale, scale, scale, *offset, x.max(), x.min(), y.max(), y.min(), z.max(), z.min())
    points = np.zeros(len(x), np.dtype([("x", "<i4"), ("y", "<i4"), ("z", "<i4"), ("intensity", "<u2"),
                                        ("flags", "u1"), ("cls", "u1"), ("angle", "i1"), ("user", "u1"),
                                        ("source", "<u2")]))
    points["x"] = np.round((x - offset[0]) / scale)
    points["y"] = np.round((y - offset[1]) / scale)
    points["z"] = np.round(z / scale)
    points["intensity"] = 100
    points["flags"] = 0b00001001  # return 1 of 1
    with open(path, "wb") as f:
        f.write(header + vlr + points.tobytes())


@pytest.fixture(scope="module")
def las_house(tmp_path_factory):
    """The town's gabled house as a LAS survey (a folder with one file, points every 0.5 m, EPSG:32633) and its
    footprint as GeoJSON whose integer id field is named 'bid' (value 7)."""
    folder = tmp_path_factory.mktemp("las_house")
    (folder / "las").mkdir()
    yy, xx = np.mgrid[0:160, 0:160] * 0.5 + 0.25  # metres from the top-left (north-west) corner
    inside = (np.abs(xx - 40) < 10) & (np.abs(yy - 40) < 7)
    z = np.where(inside, 109.5 - 0.5 * np.abs(yy - 40), 100.0)
    write_las(folder / "las" / "house.las", X0 + xx.ravel(), Y0 - yy.ravel(), z.ravel())
    x0, x1, y0, y1 = X0 + 30, X0 + 50, Y0 - 47, Y0 - 33
    footprints = {"type": "FeatureCollection",
                  "crs": {"type": "name", "properties": {"name": f"urn:ogc:def:crs:EPSG::{EPSG}"}},
                  "features": [{"type": "Feature", "properties": {"bid": 7, "name": "house"},
                                "geometry": {"type": "Polygon", "coordinates": [
                                    [[x0, y0], [x1, y0], [x1, y1], [x0, y1], [x0, y0]]]}}]}
    (folder / "footprints.geojson").write_text(json.dumps(footprints))
    return {"folder": str(folder / "las"), "file": str(folder / "las" / "house.las"),
            "footprints": str(folder / "footprints.geojson")}


@pytest.fixture(scope="module")
def survey(tmp_path_factory):
    """Two LAS files (EPSG:32633) with lakes, an island and a river, from make_water_survey."""
    maker = os.environ.get("LIDARFX_MAKE_SURVEY")
    if not maker or not os.path.exists(maker):
        pytest.skip("LIDARFX_MAKE_SURVEY (make_water_survey) is not set")
    folder = tmp_path_factory.mktemp("survey") / "las"
    subprocess.run([maker, str(folder), "--size", "200", "--file", "200"], check=True, capture_output=True)
    return sorted(str(folder / f) for f in os.listdir(folder))


@pytest.fixture(scope="module", autouse=True)
def qgis_core():
    """QGIS's core library in this process, to open every output as QGIS does."""
    from qgis.core import QgsApplication
    app = QgsApplication([], False)
    app.initQgis()
    yield app


def opens_in_qgis(path, kind):
    """The output loads as a valid QGIS layer; returns its CRS's authority id (e.g. EPSG:32633)."""
    from qgis.core import QgsRasterLayer, QgsVectorLayer
    layer = QgsRasterLayer(str(path), "out") if kind == "raster" else QgsVectorLayer(str(path), "out", "ogr")
    assert layer.isValid(), path
    return layer.crs().authid()


def raster(path):
    assert opens_in_qgis(path, "raster") == f"EPSG:{EPSG}"
    ds = gdal.Open(str(path))
    srs = osr.SpatialReference(wkt=ds.GetProjection())
    srs.AutoIdentifyEPSG()
    return ds.GetRasterBand(1).ReadAsArray(), int(srs.GetAuthorityCode(None) or 0), ds.GetRasterBand(1).GetNoDataValue()


def vector(path):
    assert opens_in_qgis(path, "vector") == f"EPSG:{EPSG}"
    ds = ogr.Open(str(path))
    layer = ds.GetLayer(0)
    srs = layer.GetSpatialRef()
    srs.AutoIdentifyEPSG()
    features = [{**f.items(), "area": f.GetGeometryRef().GetArea()} for f in layer]
    return features, int(srs.GetAuthorityCode(None) or 0)


def test_the_toolbox_lists_every_lidarfx_algorithm(qgis):
    listed = qgis("list").stdout
    for algorithm in ("water", "hydroflatten", "irradiation", "skyviewfactor", "shadows", "rooftoppv", "buildings"):
        assert f"lidarfx:{algorithm}" in listed
    help_text = qgis("help", "lidarfx:water").stdout
    assert "Cell size (metres)" in help_text and "waterbody polygons" in help_text.lower()


def test_water_maps_the_survey_s_lakes_in_its_crs(qgis, survey, tmp_path):
    args = [f"FILES={f}" for f in survey]
    qgis("run", "lidarfx:water", "--", *args, "CELL=2", f"WATER={tmp_path / 'water.tif'}",
         f"BODIES={tmp_path / 'bodies.gpkg'}")
    water, epsg, _ = raster(tmp_path / "water.tif")
    assert epsg == EPSG and (water == 1).sum() > 1000 and (water == 0).sum() > 5000
    bodies, epsg = vector(tmp_path / "bodies.gpkg")
    assert epsg == EPSG and len(bodies) >= 2
    assert max(b["area"] for b in bodies) > 3000


def test_hydroflatten_writes_a_flat_lake_its_breaklines_and_checks_in_the_survey_s_crs(qgis, survey, tmp_path):
    args = [f"FILES={f}" for f in survey]
    qgis("run", "lidarfx:hydroflatten", "--", *args, "CELL=2", "MIN_LAKE_AREA=2000", "MIN_RIVER_WIDTH=10",
         f"DEM={tmp_path / 'dem.tif'}", f"BREAKLINES={tmp_path / 'breaklines.gpkg'}", f"QA={tmp_path / 'qa.csv'}")
    dem, epsg, nodata = raster(tmp_path / "dem.tif")
    assert epsg == EPSG
    bodies, epsg = vector(tmp_path / "breaklines.gpkg")
    assert epsg == EPSG and len(bodies) >= 1
    for body in bodies:
        assert body["type"] in ("lake", "river") and body["level_max_m"] >= body["level_min_m"]
        assert body["type"] == "river" or body["level_max_m"] == body["level_min_m"]
    # The flattened water holds its level exactly (float32): a lake over all its cells, a river over its lowest
    # cross-section at least.
    largest = max(bodies, key=lambda b: b["area"])
    assert (dem == np.float32(largest["level_min_m"])).sum() >= 20
    rows = (tmp_path / "qa.csv").read_text().splitlines()
    header = rows[0].split(",")
    assert len(rows) >= 2 and all(r.split(",")[header.index("pass")] == "1" for r in rows[1:])


def test_irradiation_and_its_sky_view_factor(qgis, town, tmp_path):
    qgis("run", "lidarfx:irradiation", "--", f"DSM={town['dsm']}", f"OUTPUT={tmp_path / 'annual.tif'}",
         f"SVF={tmp_path / 'svf.tif'}")
    annual, epsg, _ = raster(tmp_path / "annual.tif")
    assert epsg == EPSG
    open_ground, north_of_house = annual[5, 5], annual[34 - 3, 40]  # the house shades the ground north of it
    assert 1500 < open_ground < 2600 and north_of_house < 0.8 * open_ground
    svf, epsg, _ = raster(tmp_path / "svf.tif")
    assert epsg == EPSG and svf[5, 5] == pytest.approx(1.0, abs=0.01) and svf[31, 40] < 0.95
    qgis("run", "lidarfx:irradiation", "--", f"DSM={town['dsm']}", "SVF_METHOD=1", "SURFACE=1",
         f"OUTPUT={tmp_path / 'a2.tif'}", f"SVF={tmp_path / 'svf_share.tif'}")
    share, _, _ = raster(tmp_path / "svf_share.tif")
    assert not np.array_equal(share, svf) and 0 < share[31, 40] < 1
    tilted, _, _ = raster(tmp_path / "a2.tif")
    assert tilted[45, 40] > 1.1 * annual[45, 40]  # the south roof plane, on its own 26.6° tilt, gets more


def test_sky_view_factor_both_definitions(qgis, town, tmp_path):
    for method, index in (("cosine", 0), ("share", 1)):
        out = tmp_path / f"svf_{method}.tif"
        qgis("run", "lidarfx:skyviewfactor", "--", f"DSM={town['dsm']}", f"METHOD={index}", "DIRECTIONS=36",
             f"OUTPUT={out}")
        svf, epsg, _ = raster(out)
        assert epsg == EPSG and svf[5, 5] == pytest.approx(1.0, abs=0.01)  # the house rises 5° there
        assert 0.5 < svf[32, 40] < 0.97  # beside the house's north wall


def test_shadows_fall_north_of_the_house_at_noon(qgis, town, tmp_path):
    # 15° E: solar noon near 11:00 UTC; at 40° N in December the sun stands about 27° high in the south.
    done = qgis("run", "lidarfx:shadows", "--", f"DSM={town['dsm']}", "DATETIME=2024-12-21T11:00:00",
                f"OUTPUT={tmp_path / 'lit.tif'}")
    assert "elevation" in done.stdout
    lit, epsg, nodata = raster(tmp_path / "lit.tif")
    assert epsg == EPSG and nodata == 255
    assert lit[5, 40] == 1 and lit[70, 40] == 1            # open ground
    # The sun at 30.4°: the 6 m eave casts 10.2 m of shadow north of the wall (rows 23-32), no further.
    assert (lit[24:33, 40] == 0).all() and lit[20, 40] == 1
    assert lit[45, 40] == 1                                # the south-facing roof plane is lit


def test_rooftop_pv_finds_the_south_plane_suitable(qgis, town, tmp_path):
    qgis("run", "lidarfx:rooftoppv", "--", f"DSM={town['dsm']}", f"DTM={town['dtm']}",
         f"FOOTPRINTS={town['footprints']}", "LAT=36.1", "LON=15.0", f"OUTPUT={tmp_path / 'patches.gpkg'}")
    patches, epsg = vector(tmp_path / "patches.gpkg")
    assert epsg == EPSG and len(patches) >= 2
    south = [p for p in patches if abs(float(p["azimuth_deg"]) - 180) < 10]
    north = [p for p in patches if min(float(p["azimuth_deg"]), 360 - float(p["azimuth_deg"])) < 10]
    assert south and all(str(p["suitable"]).lower() in ("1", "true", "yes") for p in south)
    assert north and all(str(p["suitable"]).lower() in ("0", "false", "no") for p in north)
    assert float(south[0]["tilt_deg"]) == pytest.approx(math.degrees(math.atan(0.5)), abs=2)
    assert all(int(p["building_id"]) == 7 for p in patches)


def test_buildings_and_facade_energy(qgis, town, tmp_path):
    qgis("run", "lidarfx:buildings", "--", f"DSM={town['dsm']}", "LAT=36.1", "LON=15.0",
         f"BUILDINGS={tmp_path / 'buildings.gpkg'}", f"FACADES={tmp_path / 'facades.csv'}")
    buildings, epsg = vector(tmp_path / "buildings.gpkg")
    assert epsg == EPSG and len(buildings) == 1
    assert buildings[0]["area"] == pytest.approx(20 * 14, rel=0.1)
    rows = open(tmp_path / "facades.csv").read().splitlines()
    assert rows[0].startswith("building_id") and len(rows) > 8


def test_rooftop_pv_from_a_las_folder_and_geojson_footprints(qgis, las_house, tmp_path):
    qgis("run", "lidarfx:rooftoppv", "--", f"FOLDER={las_house['folder']}", f"FOOTPRINTS={las_house['footprints']}",
         "ID_FIELD=bid", "CELL=1", "LAT=36.1", "LON=15.0", f"OUTPUT={tmp_path / 'patches.gpkg'}")
    patches, epsg = vector(tmp_path / "patches.gpkg")
    assert epsg == EPSG and len(patches) == 2
    assert all(int(p["building_id"]) == 7 for p in patches)  # the id came from the field chosen
    south = [p for p in patches if abs(float(p["azimuth_deg"]) - 180) < 10]
    assert len(south) == 1 and str(south[0]["suitable"]).lower() in ("1", "true", "yes")
    assert float(south[0]["tilt_deg"]) == pytest.approx(math.degrees(math.atan(0.5)), abs=2)
    assert 1500 < float(south[0]["annual_kwh_m2"]) < 3000  # a clear-sky year at 36° N on a 27° south roof


def test_buildings_from_las_files(qgis, las_house, tmp_path):
    qgis("run", "lidarfx:buildings", "--", f"FILES={las_house['file']}", "CELL=1", "LAT=36.1", "LON=15.0",
         f"BUILDINGS={tmp_path / 'buildings.gpkg'}", f"FACADES={tmp_path / 'facades.csv'}",
         f"IRRADIATION={tmp_path / 'annual.tif'}")
    buildings, epsg = vector(tmp_path / "buildings.gpkg")
    assert epsg == EPSG and len(buildings) == 1
    assert buildings[0]["area"] == pytest.approx(20 * 14, rel=0.15)
    facades = open(tmp_path / "facades.csv").read().splitlines()
    header = facades[0].split(",")
    energy = [float(row.split(",")[header.index("annual_kwh_m2")]) for row in facades[1:]]
    assert len(energy) > 8 and max(energy) > 0
    annual, epsg, _ = raster(tmp_path / "annual.tif")
    assert epsg == EPSG and 1500 < annual[5, 5] < 2600


def test_buildings_from_the_survey_s_class_6(qgis, las_house, tmp_path):
    # 'Buildings from' = the survey's building class: the program is asked for --buildings class6; this survey
    # carries no class 6, which the program says, and nothing is delivered.
    done = qgis("run", "lidarfx:buildings", "--", f"FILES={las_house['file']}", "CELL=1", "SOURCE=1", "LAT=36.1",
                "LON=15.0", f"BUILDINGS={tmp_path / 'buildings.gpkg'}", f"FACADES={tmp_path / 'facades.csv'}",
                check=False)
    assert done.returncode != 0 and "class 6" in done.stdout + done.stderr
    assert not (tmp_path / "buildings.gpkg").exists()


def test_shadows_take_a_time_with_its_offset(qgis, town, tmp_path):
    # 12:00 at +01:00 is the 11:00 UTC of the noon test: the same sun, the same shadows.
    done = qgis("run", "lidarfx:shadows", "--", f"DSM={town['dsm']}", "DATETIME=2024-12-21T12:00:00+01:00",
                f"OUTPUT={tmp_path / 'lit.tif'}")
    assert "2024-12-21 11:00:00 UTC" in done.stdout and "SUN_ELEVATION_DEG" in done.stdout
    lit, _, _ = raster(tmp_path / "lit.tif")
    assert (lit[24:33, 40] == 0).all() and lit[20, 40] == 1


def test_irradiation_refuses_tmy_years_without_a_tmy(qgis, town, tmp_path):
    done = qgis("run", "lidarfx:irradiation", "--", f"DSM={town['dsm']}", "YEAR_FROM_TMY=true",
                f"OUTPUT={tmp_path / 'annual.tif'}", check=False)
    assert done.returncode != 0 and "needs a TMY3 file" in done.stdout + done.stderr
    assert not (tmp_path / "annual.tif").exists()


def test_a_failing_run_reports_the_program_s_reason(qgis, tmp_path):
    empty = tmp_path / "not_a_survey.las"
    empty.write_text("not a LAS file")
    done = qgis("run", "lidarfx:water", "--", f"FILES={empty}", f"WATER={tmp_path / 'w.tif'}",
                f"BODIES={tmp_path / 'b.gpkg'}", check=False)
    assert done.returncode != 0
    assert "exit code" in done.stdout + done.stderr and "not_a_survey.las" in done.stdout + done.stderr


def test_the_engine_reports_progress_and_cancels_the_program(tmp_path, survey):
    """In-process (PyQGIS): "NN %" lines move the feedback's progress; cancelling stops the program at once."""
    import sys
    import threading
    import time
    sys.path.insert(0, os.path.dirname(os.path.abspath(PLUGIN)))
    from qgis.core import QgsProcessingException, QgsProcessingFeedback
    from lidarfx_processing import engine

    feedback = QgsProcessingFeedback()
    seen = []
    feedback.progressChanged.connect(seen.append)
    engine.run_program(["water", *survey, "--cell", "2", "--out", str(tmp_path / "water")], feedback)
    assert seen and max(seen) == 100 and (tmp_path / "water" / "water.asc").exists()

    feedback = QgsProcessingFeedback()
    threading.Timer(1.0, feedback.cancel).start()
    start = time.perf_counter()
    with pytest.raises(QgsProcessingException, match="Cancelled"):
        engine.run_program(["demo", "--out", str(tmp_path / "demo"), "--size", "3000", "--threads", "1"], feedback)
    assert time.perf_counter() - start < 15
