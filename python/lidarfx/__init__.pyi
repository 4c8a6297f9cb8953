# SPDX-License-Identifier: Apache-2.0
# Type stubs of the lidarfx module (the extension _lidarfx re-exported), written by python/tools/make_stubs.py;
# tests/test_stubs.py keeps them in step with the module's signatures and docstrings.
from datetime import datetime
from typing import Any, Callable, Mapping, Optional, Tuple, Union

import numpy as np
from numpy.typing import ArrayLike

from ._types import (AzimuthSelection, Building, Buildings, ChannelJoin, Components, Grid, HydroBody, HydroCheck,
                     HydroFlattened, IrradianceMaps, KsResult, Rasters,
                     RoofPatch, RoofSuitability, RoofSurface, SlopeAspect, SunPosition, SurfaceOutliers, Survey, WaterIssue,
                     Waterbodies, Waterbody, Weather)

__version__: str
has_io: bool


class Cancelled(RuntimeError):
    """A long call stopped because its progress callable returned False."""


def angular_filter(z: ArrayLike, cell_m: float, radius: int = 2, *, threads: int = 1, progress: Optional[Callable[[float], Optional[bool]]] = None) -> np.ndarray:
    """Angular filter: for every cell p, the steepest angle to any cell q of the (2 radius + 1)^2 window around
it, max atan(|z(q) - z(p)| / (cell_m |p - q|)), degrees in [0, 90]: 0 on flat ground, near 90 beside walls.
NaN neighbours are skipped, a NaN centre gives NaN, a cell without a valid neighbour gives 0.

z: 2-D elevations in metres (float32 read in place; other real or integer dtypes are converted).
cell_m: cell size in metres, > 0. radius: window half-size in cells, >= 1 (default 2: "two tiers").
Returns a float32 array of z's shape."""
    ...


def azimuth_mode_select(hist360: ArrayLike, *, window_deg: float = 10.0) -> AzimuthSelection:
    """The PV azimuth of a roof from its aspect histogram (360 one-degree bins of cell counts, bin i = aspects in
[i, i + 1) degrees clockwise from north): the mode, swapped by 180 degrees for two-plane roofs facing north,
turned west for three- and four-plane roofs when more cells face west; unsuitable for no cells or more than
four planes. Returns AzimuthSelection(azimuth_deg (NaN when unsuitable), mode_deg, planes, form, reason,
suitable)."""
    ...


def clear_sky_year(year: int, latitude_deg: float, longitude_deg: float, *, interval_s: int = 3600) -> Weather:
    """A clear-sky weather year at a place: one record per interval_s (default hourly) from 1 January 00:00 UTC,
with the sun at the middle of each interval; night records hold zeros. Returns a Weather for
irradiance_maps (utc_offset_h 0: months are UTC months)."""
    ...


def connected_components(mask: ArrayLike, connectivity: int = 8, *, threads: int = 1, progress: Optional[Callable[[float], Optional[bool]]] = None) -> Components:
    """Connected components of a mask (nonzero = foreground) under 4- or 8-connectivity (default 8).

Returns Components(labels, sizes): labels, int32 of mask's shape, 0 = background and 1..n in raster order
(first cell met row by row); sizes, int64 of length n + 1, sizes[0] = background cells, sizes[l] = cells of
component l. The result does not depend on threads."""
    ...


def count_points_above(x: ArrayLike, y: ArrayLike, z: ArrayLike, reference: ArrayLike, height_m: float, *, grid: Grid, return_lowest: bool = False) -> Union[np.ndarray, Tuple[np.ndarray, np.ndarray]]:
    """Per cell of grid, the points standing at least height_m above the reference surface there (z >= reference +
height_m, metres; a cell whose reference is NaN counts none): with the terrain as reference and
height_m = 2.5, the raised points extract_buildings decides each building's rim by (raised_count).

x, y, z: 1-D coordinates in metres (float64; others converted). reference: float32 raster of the grid's shape
(e.g. fill_ground of the class-2 terrain). grid: the Grid the points are binned on, as in rasterize. Returns a
uint32 raster; with return_lowest, a tuple (counts, lowest): lowest is the lowest of each cell's counted points
(float32 metres, NaN where none), extract_buildings' lowest_raised."""
    ...


def extract_buildings(dsm: ArrayLike, cell_m: Optional[float] = None, *, grid: Optional[Grid] = None, ground: Optional[ArrayLike] = None, vegetation: Optional[ArrayLike] = None, point_count: Optional[ArrayLike] = None, multiple_return_count: Optional[ArrayLike] = None, raised_count: Optional[ArrayLike] = None, lowest_raised: Optional[ArrayLike] = None, building_cells: Optional[ArrayLike] = None, min_height_m: float = 2.5, min_area_m2: float = 15.0, party_wall_step_m: float = 1.0, threads: int = 1, progress: Optional[Callable[[float], Optional[bool]]] = None) -> Buildings:
    """Buildings and their roof surfaces from a DSM: a terrain model (edges of >= 45 degrees, hulls, IDW; or the given
ground), cells higher than min_height_m above it in footprints of at least min_area_m2 that are roofs (planar
enough, or with the pulse counts: few split pulses), roof surfaces grown from local planes and merged, then
numbered by area.

dsm: heights in metres, row 0 north (float32 read in place). cell_m or grid (a Grid; outlines are in its world
coordinates, else in metres from the top-left corner). ground: optional terrain (DTM) in metres; vegetation:
optional bool mask of trees; or point_count and multiple_return_count (uint32, Rasters.count and
Rasters.multiple_return_count of the DSM's points): trees told from roofs by their split pulses (a cell with
half its points from pulses of several returns is vegetation, a part with 20 %); with them raised_count (uint32,
count_points_above against the ground, which must then be filled: fill_ground) decides each building's one-cell
rim by its points: a cell leaves when under half its points stand min_height_m above the ground, a cell beside
the roof at its height (within 0.5 m) with half its points raised joins; and with lowest_raised (float32, the
lowest of each cell's raised points: count_points_above(..., return_lowest=True)) the roof under an overhanging
crown joins its building when 90 % of a cell's points are raised and the lowest lies on the roof's plane (within
0.3 m plus half the plane's fall across a cell). Or building_cells (bool or uint8, e.g.
where at least half of the points are of the vendor's building class 6): those cells are the buildings (parts
under min_area_m2 dropped, holes under it filled), only their roof surfaces are found. A block is split into
buildings where two of its roof surfaces do not meet along most of their boundary but stand more than
party_wall_step_m (metres, > 0; inf never splits) apart: terraced houses of different heights. Returns Buildings(building_id, surface_id: int32 rasters (0 = none), ground,
vegetation, under_crowns (bool: roof cells found under overhanging crowns, whose DSM is the crown), buildings: list of Building (outline as a GeoJSON MultiPolygon, ground_z, eave_z, ridge_z, roof
areas in m^2, surface ids), surfaces: list of RoofSurface (tilt_deg, azimuth_deg, areas), grid)."""
    ...


def extract_waterbodies(rasters: Union[Rasters, Mapping[str, ArrayLike], Any], cell_m: Optional[float] = None, *, method: str = 'flat_seeds', check_inputs: bool = True, island_min_area_m2: float = 200.0, theta_max_deg: float = 30.0, threads: int = 1, progress: Optional[Callable[[float], Optional[bool]]] = None) -> Waterbodies:
    """Waterbodies from point-cloud rasters: seeds where the laser found no return (water absorbs it) or, with the
default method, level low cells with fewer returns; each seed grows over cells whose angular filter value stays
under a rising threshold theta (2, 3, ... theta_max_deg degrees) while a one-sided KS test on the intensity
says the new cells are not brighter than the body so far, and while the cells keep the body's level.

rasters: a Rasters (from rasterize) or any object or dict with min_z, max_z (metres, NaN = no return),
mean_intensity, dropout (bool/uint8) and optionally multiple_returns, count (uint32) and footprint (1 = inside
the surveyed area). cell_m: cell size in metres (default: rasters.grid.cell_m).
method: 'flat_seeds' (default; the lidarfx program's default, the most accurate on the project's test family)
or 'dropout_seeds' (the library's defaults: dropout seeds only). check_inputs: refuse (ran = False, issues say
why) data that cannot support the method, such as too few points per cell. island_min_area_m2: smaller holes
inside a body become water (default 200 m^2). theta_max_deg: last angular threshold (default 30).
Returns Waterbodies(water: bool map, labels: int32 (0 land, 1..n by decreasing area), bodies: list of
Waterbody (area_m2, water_level_m = median lowest return, ...), issues, ran, ...)."""
    ...


def fill_ground(ground: ArrayLike, cell_m: float, *, threads: int = 1) -> np.ndarray:
    """A terrain model (metres, e.g. Rasters.min_z of the class-2 points) with its NaN cells filled by IDW from the
finite ones (8 nearest, weights 1 / distance), exactly as extract_buildings fills a given ground. cell_m: cell size in metres.
Returns a float32 raster."""
    ...


def horizon_map(dsm: ArrayLike, cell_m: float, azimuth_deg: float, *, line_phases: int = 1, threads: int = 1, progress: Optional[Callable[[float], Optional[bool]]] = None) -> np.ndarray:
    """Horizon angle of every cell looking towards azimuth_deg (clockwise from north): max(0, max over the cells q
before p on p's ray line of atan((z_q - z_p) / distance)), degrees in [0, 90); NaN for NaN cells. Exact upper
convex hull sweep, O(cells) per line family. line_phases (1..64, default 1): each cell's line comes from the
nearest of that many families of parallel lines, as in raylines_shadow; with the same line_phases a cell is lit
by a sun of this azimuth exactly when its horizon is at or below the sun's elevation. dsm in metres (float32
read in place), cell_m in metres. Returns float32."""
    ...


def hydro_flatten(dem: Any, labels: Any, min_z: Any, max_z: Any, cell_m: float, *, min_lake_area_m2: float = 8093.71, min_river_width_m: float = 30.48, min_island_area_m2: float = 4046.86, shoreline: str = 'lift', join_channels: bool = True, to_banks: bool = True, under_decks: bool = True, threads: int = 1, progress: Optional[Callable[[float], Optional[bool]]] = None) -> HydroFlattened:
    """Hydro-flattens a bare-earth DEM with the waterbodies of the same survey: every lake at one level (the median of
its water heights in their densest 0.1 m), every river in flat cross-sections whose levels only fall downstream
(each section read at its lowest dense 0.1 m of heights; isotonic regression; decks and stretches without returns
at the interpolated level, lowered to their banks where those stand lower (to_banks); sections beside a weir cut
along its crest), pieces of one river cut apart at a weir
or a deck joined into one body first (join_channels, with the water under the deck), the rivers continued under
their bridge decks (under_decks: the water lost beside a deck taken back at the river's level within 8 m of it,
then runs of deck cells between two cells of the river at the level interpolated across), islands under
min_island_area_m2 flattened with the water, and shore ground below the water beside it lifted to it
(shoreline='lift') or only counted ('flag'). Water under the minimum sizes (defaults: the USGS Lidar Base
Specification's 2 acres, 100 ft, 1 acre, in metres) is left to the terrain.

dem: float32 bare-earth DEM, metres (NaN = unknown). labels: int32 waterbodies (0 land, 1..n), e.g.
extract_waterbodies(...).labels. min_z, max_z: the survey's lowest and highest return per cell, metres.
cell_m: cell size, metres. Returns HydroFlattened(dem, water_surface (NaN off the water), body (id per
flattened cell), bodies: list of HydroBody, checks: list of HydroCheck (flatness, monotonic_fall, shoreline,
minimum_size per flattened body), joins: list of ChannelJoin (kept, part_a, part_b labels, gap_m, contact_m, gap_cells),
shore_cells_below, deck_cells and deck_level_cells (cells the rivers took under and beside decks))."""
    ...


def irradiance_maps(dsm: ArrayLike, cell_m: float, weather: Weather, *, latitude_deg: Optional[float] = None, longitude_deg: Optional[float] = None, utc_offset_h: Optional[float] = None, meridian_convergence_deg: float = 0.0, svf_method: str = 'source_share', svf_directions: int = 72, diffuse: str = 'isotropic', albedo: float = 0.0, surface_tilt_deg: Optional[ArrayLike] = None, surface_azimuth_deg: Optional[ArrayLike] = None, shadow_line_phases: int = 4, threads: int = 1, progress: Optional[Callable[[float], Optional[bool]]] = None) -> IrradianceMaps:
    """Annual and monthly irradiation of every cell, kWh/m^2: for each weather record with the sun up, beam
DNI cos(incidence) on lit cells (raylines_shadow at the sun of the record's middle) plus diffuse light
(isotropic: DHI SVF (1 + cos tilt) / 2; 'perez': Perez 1990 with the circumsolar part shaded) plus
albedo-reflected light, times the record's interval.

dsm: heights in metres, row 0 north (float32 read in place); cell_m in metres. weather: a Weather
(read_tmy3 or clear_sky_year, or lidarfx.Weather(start_utc, dni_w_m2, dhi_w_m2, ghi_w_m2, interval_s)).
latitude_deg, longitude_deg, utc_offset_h: the site (default: the weather's). Months are those of local
standard time UTC + utc_offset_h. meridian_convergence_deg: angle from true north to grid north (east
positive). surface_tilt_deg / surface_azimuth_deg: optional per-cell surface orientation (default horizontal).
Returns IrradianceMaps(annual_kwh_m2, month_kwh_m2 (12 x rows x cols), sky_view_factor, ghi_kwh_m2,
month_ghi_kwh_m2, sun_up_records)."""
    ...


def ks_one_sided(previous: ArrayLike, current: ArrayLike, alpha: float = 0.05, *, critical: str = 'documents_table') -> KsResult:
    """One-sided two-sample Kolmogorov-Smirnov test: is `current` significantly larger (shifted up) than `previous`?

d = sup_x (F_previous(x) - F_current(x)); reject when d > c(alpha) sqrt((n + m) / (n m)), n and m the sample
sizes. critical='documents_table' (default) takes c(alpha) from the table 0.10, 0.05, 0.025, 0.01, 0.005, 0.001
-> 1.22, 1.36, 1.48, 1.63, 1.73, 1.95 (sqrt(-ln(alpha / 2) / 2) for other alpha); 'one_sided' takes
sqrt(-ln(alpha) / 2). p_value = exp(-2 d^2 n m / (n + m)). alpha in (0, 1), default 0.05.
Returns KsResult(d, critical, reject, p_value)."""
    ...


def morph_close(mask: ArrayLike, size: int = 5, *, height: int = 0, threads: int = 1, progress: Optional[Callable[[float], Optional[bool]]] = None) -> np.ndarray:
    """Closing: dilation then erosion; fills gaps narrower than the rectangle.
Binary morphology with a size x height rectangle of cells (height 0 = square), clipped at the border;
the cost does not depend on the size. mask: 2-D bool or uint8 (nonzero = set; read in place), integer
masks are converted. size: odd width of the rectangle in cells, >= 1 (default 5); height: its height in
cells (0 = size). Returns a bool array of mask's shape."""
    ...


def morph_dilate(mask: ArrayLike, size: int = 5, *, height: int = 0, threads: int = 1, progress: Optional[Callable[[float], Optional[bool]]] = None) -> np.ndarray:
    """Dilation: a cell is set when any cell of the rectangle centred on it is set.
Binary morphology with a size x height rectangle of cells (height 0 = square), clipped at the border;
the cost does not depend on the size. mask: 2-D bool or uint8 (nonzero = set; read in place), integer
masks are converted. size: odd width of the rectangle in cells, >= 1 (default 5); height: its height in
cells (0 = size). Returns a bool array of mask's shape."""
    ...


def morph_erode(mask: ArrayLike, size: int = 5, *, height: int = 0, threads: int = 1, progress: Optional[Callable[[float], Optional[bool]]] = None) -> np.ndarray:
    """Erosion: a cell stays set when every cell of the rectangle inside the raster is set.
Binary morphology with a size x height rectangle of cells (height 0 = square), clipped at the border;
the cost does not depend on the size. mask: 2-D bool or uint8 (nonzero = set; read in place), integer
masks are converted. size: odd width of the rectangle in cells, >= 1 (default 5); height: its height in
cells (0 = size). Returns a bool array of mask's shape."""
    ...


def morph_open(mask: ArrayLike, size: int = 5, *, height: int = 0, threads: int = 1, progress: Optional[Callable[[float], Optional[bool]]] = None) -> np.ndarray:
    """Opening: erosion then dilation; removes set parts narrower than the rectangle.
Binary morphology with a size x height rectangle of cells (height 0 = square), clipped at the border;
the cost does not depend on the size. mask: 2-D bool or uint8 (nonzero = set; read in place), integer
masks are converted. size: odd width of the rectangle in cells, >= 1 (default 5); height: its height in
cells (0 = size). Returns a bool array of mask's shape."""
    ...


def rasterize(x: ArrayLike, y: ArrayLike, z: ArrayLike, intensity: Optional[ArrayLike] = None, returns: Optional[float] = None, nreturns: Optional[float] = None, cell_m: float = 1.0, *, classification: Optional[ArrayLike] = None, grid: Optional[Grid] = None, return_selection: str = 'all', threads: int = 1, progress: Optional[Callable[[float], Optional[bool]]] = None) -> Rasters:
    """Bins points into rasters: per cell the lowest and highest z (metres, NaN where no point), the mean intensity
(0 where no point), the point count, the dropout mask (True = no return) and the multiple-returns mask (True =
some point has number_of_returns > 1).

x, y, z: 1-D coordinates in metres (float64; others converted). intensity (uint16), returns (the return
number of each point), nreturns (its pulse's number of returns), classification (uint8): optional, of the
same length. cell_m: cell size in metres (default
1). grid: a Grid to bin on; default the snapped grid around the points (corners on multiples of cell_m).
return_selection: the points binned, 'all' (default), 'first' or 'last' returns. Points outside the grid or with NaN coordinates are counted, not
binned. Returns Rasters (min_z, max_z, mean_intensity, count, dropout, multiple_returns, multiple_return_count,
grid, point counts)."""
    ...


def raylines_shadow(dsm: ArrayLike, cell_m: float, azimuth_deg: float, elevation_deg: float, *, nan_cell: int = 255, line_phases: int = 4, threads: int = 1, progress: Optional[Callable[[float], Optional[bool]]] = None) -> np.ndarray:
    """Cast shadows for one sun position: 1 = lit, 0 = shadow, nan_cell (default 255) where the DSM is NaN.
A cell p is in shadow when a cell q before it on the ray line towards the sun has z_q - d tan(elevation) > z_p,
d the distance between them along the sun's azimuth in metres; NaN cells cast no shadow. Every cell takes
the nearest of line_phases (1..64, default 4) families of parallel lines. Cost O(cells).
dsm: 2-D heights in metres, row 0 north (float32 read in place). cell_m: cell size in metres.
azimuth_deg: clockwise from north (grid north); elevation_deg above the horizon (<= 0: all shadow).
Returns a uint8 array of dsm's shape."""
    ...


def read_survey(path: str) -> Survey:
    """Reads every point of a LAS (1.0-1.4) or LAZ file. Returns Survey(x, y, z: float64 metres; intensity: uint16;
return_number, number_of_returns, classification: uint8; epsg: the horizontal EPSG code (0 = none);
wkt: the CRS as WKT when the file carries one). Errors name the file: FileNotFoundError for a missing file,
ValueError or RuntimeError for a malformed one."""
    ...


def read_tmy3(path: str) -> Weather:
    """Reads a TMY3 weather year (NREL CSV: station line, header line, 8760 hourly rows stamped at the end of the hour
in local standard time). Returns a Weather: start_utc (datetime64[s], UTC start of each hour), dni_w_m2,
dhi_w_m2, ghi_w_m2 (W/m^2), interval_s = 3600, and the station's latitude_deg, longitude_deg, utc_offset_h."""
    ...


def remove_surface_outliers(z: ArrayLike, *, radius: int = 2, spike_height_m: float = 10.0, pit_depth_m: float = 10.0, min_support_cells: int = 3, threads: int = 1, progress: Optional[Callable[[float], Optional[bool]]] = None) -> SurfaceOutliers:
    """Isolated spikes (birds, noise) and pits (returns through canopy gaps) of a surface model, replaced by the median of
their neighbours. A cell is a spike when fewer than k of the finite cells of its (2 radius + 1)^2 window stand at
or above its height minus spike_height_m, a pit when fewer than k lie at or below its height plus pit_depth_m;
k = min_support_cells (default 3) scaled to the part of the window inside the raster. Defaults: 5 x 5 window,
10 m. z in metres (float32 read in place). Returns SurfaceOutliers(surface: float32, outlier: uint8 (0 none,
1 spike, 2 pit), spikes, pits)."""
    ...


def roof_suitability(dsm: ArrayLike, dtm: ArrayLike, building_id: ArrayLike, cell_m: Optional[float] = None, *, grid: Optional[Grid] = None, mode: str = 'planes', min_height_m: float = 2.0, min_patch_m2: float = 8.0, m2_per_kwp: float = 8.0, min_tilt_deg: float = 15.0, max_tilt_deg: float = 60.0, min_azimuth_deg: float = 90.0, max_azimuth_deg: float = 270.0, flat_below_deg: float = 15.0, threads: int = 1, progress: Optional[Callable[[float], Optional[bool]]] = None) -> RoofSuitability:
    """Which roof patches suit PV panels. Roof cells are the cells of each building (building_id > 0, int32, e.g. from
extract_buildings or burned footprints) standing min_height_m above the DTM. mode='planes' (default): every
roof plane is segmented and judged on its fitted tilt and azimuth; 'paper': one PV plane per building (mean
tilt, aspect mode). A patch suits when its sloped area >= min_patch_m2 and its tilt lies in [min_tilt_deg,
max_tilt_deg] and its azimuth in [min_azimuth_deg, max_azimuth_deg] (clockwise from north); a patch flatter than
flat_below_deg suits on its area alone. kwp = sloped area / m2_per_kwp.
Returns RoofSuitability(patch_id: int32 raster, patches: list of RoofPatch)."""
    ...


def sky_view_factor(dsm: ArrayLike, cell_m: float, *, method: str = 'source_share', directions: int = 72, threads: int = 1, progress: Optional[Callable[[float], Optional[bool]]] = None) -> np.ndarray:
    """Sky view factor of every cell in [0, 1] (1 on open flat ground; NaN for NaN cells), from one exact horizon
sweep per azimuth i * 360 / directions (directions >= 4, default 72 = 5 degree steps).
method='source_share' (default): the share of point sources visible from the cell, one at each elevation
15, 20, ..., 85 degrees of each azimuth plus the zenith (1,081 sources for 72 azimuths).
method='cosine_weighted': the view factor of a horizontal surface under an isotropic sky, the mean over the
azimuths of cos^2(horizon angle) (the SVF of GRASS r.skyview and SAGA). Returns float32."""
    ...


def slope_aspect(z: ArrayLike, cell_m: float, *, flat_slope_deg: float = 0.0, threads: int = 1, progress: Optional[Callable[[float], Optional[bool]]] = None) -> SlopeAspect:
    """Slope and aspect by Horn's 3 x 3 weighted differences (row 0 north): slope = atan(|grad z|), degrees in [0, 90];
aspect = azimuth of the down-slope direction, degrees clockwise from north in [0, 360), NaN where flat (slope
<= flat_slope_deg, default 0). At borders and beside NaN cells no cell is invented: one-sided differences are
used, so planes come out exact everywhere. z in metres (float32 read in place), cell_m in metres.
Returns SlopeAspect(slope_deg, aspect_deg: float32; flat: bool). slope_deg and aspect_deg are the
surface_tilt_deg and surface_azimuth_deg of irradiance_maps."""
    ...


def sun_position(time: Union[datetime, str, float], lat: float, lon: float, *, model: str = 'spa', elevation_m: float = 0.0, pressure_mbar: float = 1013.25, temperature_c: float = 12.0, refraction: bool = True, delta_t_s: float = 69.0) -> SunPosition:
    """Sun position at a time and place. time: a datetime (naive = UTC; aware ones are converted to UTC), an ISO 8601
string (same rule) or POSIX seconds. lat: latitude, degrees north in [-90, 90]; lon: longitude, degrees east
in [-180, 180].
model: 'spa' (NREL's Solar Position Algorithm, +-0.0003 deg; default) or 'simple' (equation of time,
declination and hour angle). elevation_m: observer height above sea level, metres; pressure_mbar and
temperature_c: annual means for refraction; delta_t_s: TT - UT in seconds (SPA).
Returns SunPosition(azimuth_deg clockwise from true north in [0, 360), elevation_deg above the horizon,
zenith_deg = 90 - elevation_deg)."""
    ...
