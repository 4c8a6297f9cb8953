# SPDX-License-Identifier: Apache-2.0
"""The result types of lidarfx's functions: plain dataclasses holding NumPy arrays and numbers."""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, List, Optional

import numpy as np


@dataclass(frozen=True)
class Grid:
    """Georeferencing of a raster: square cells of cell_m metres, row 0 north, column 0 west.

    x0, y0: world coordinates of the top-left (north-west) corner of cell (0, 0), in the survey's units.
    """
    x0: float
    y0: float
    cell_m: float
    rows: int
    cols: int

    def geotransform(self) -> tuple:
        """The GDAL geotransform (x0, cell_m, 0, y0, 0, -cell_m)."""
        return (self.x0, self.cell_m, 0.0, self.y0, 0.0, -self.cell_m)

    def cell_center(self, row: float, col: float) -> tuple:
        """World (x, y) of the centre of cell (row, col)."""
        return (self.x0 + (col + 0.5) * self.cell_m, self.y0 - (row + 0.5) * self.cell_m)


@dataclass(frozen=True)
class Components:
    """connected_components: labels (int32, 0 = background, 1..n) and sizes (int64, sizes[0] = background)."""
    labels: np.ndarray
    sizes: np.ndarray

    @property
    def count(self) -> int:
        """Number of components n."""
        return max(0, len(self.sizes) - 1)


@dataclass(frozen=True)
class SlopeAspect:
    """slope_aspect: slope (degrees from horizontal), aspect (down-slope azimuth clockwise from north, NaN if
    flat) and the flat mask."""
    slope_deg: np.ndarray
    aspect_deg: np.ndarray
    flat: np.ndarray


@dataclass(frozen=True)
class SurfaceOutliers:
    """remove_surface_outliers: the surface with its outliers replaced, where they were (0 none, 1 spike, 2 pit),
    and how many."""
    surface: np.ndarray
    outlier: np.ndarray
    spikes: int
    pits: int


@dataclass(frozen=True)
class KsResult:
    """ks_one_sided: statistic d, critical value, rejection (current significantly larger), p-value."""
    d: float
    critical: float
    reject: bool
    p_value: float


@dataclass(frozen=True)
class Rasters:
    """rasterize: per-cell rasters of a point cloud on `grid`."""
    grid: Grid
    min_z: np.ndarray             #: lowest z per cell, metres (float32, NaN = no point)
    max_z: np.ndarray             #: highest z per cell, metres (float32, NaN = no point)
    mean_intensity: np.ndarray    #: mean intensity (float32, 0 = no point)
    count: np.ndarray             #: points per cell (uint32)
    dropout: np.ndarray           #: True = no return in the cell
    multiple_returns: np.ndarray  #: True = a point of the cell has number_of_returns > 1
    multiple_return_count: np.ndarray  #: points of the cell whose pulse had several returns (uint32)
    points_used: int
    points_outside: int
    points_nan: int
    points_unselected: int


@dataclass(frozen=True)
class SunPosition:
    """sun_position: azimuth clockwise from true north [0, 360), elevation above the horizon, zenith, degrees."""
    azimuth_deg: float
    elevation_deg: float
    zenith_deg: float


@dataclass(frozen=True)
class Weather:
    """Irradiance records: start_utc (datetime64[s], UTC start of each interval), DNI, DHI, GHI in W/m^2
    (means over the interval), interval_s seconds, and optionally the site (degrees; months of UTC + utc_offset_h)."""
    start_utc: np.ndarray
    dni_w_m2: np.ndarray
    dhi_w_m2: np.ndarray
    ghi_w_m2: np.ndarray
    interval_s: int = 3600
    latitude_deg: Optional[float] = None
    longitude_deg: Optional[float] = None
    utc_offset_h: Optional[float] = 0.0


@dataclass(frozen=True)
class IrradianceMaps:
    """irradiance_maps: annual and monthly irradiation, kWh/m^2, and the sky view factor used."""
    annual_kwh_m2: np.ndarray   #: float32, rows x cols
    month_kwh_m2: np.ndarray    #: float32, 12 x rows x cols (January first); sums to annual_kwh_m2
    sky_view_factor: np.ndarray
    ghi_kwh_m2: float           #: open flat ground, the year
    month_ghi_kwh_m2: List[float]
    sun_up_records: int


@dataclass(frozen=True)
class Waterbody:
    """One waterbody of extract_waterbodies."""
    label: int
    cells: int
    area_m2: float
    row_min: int
    col_min: int
    row_max: int
    col_max: int
    water_level_m: float        #: median lowest return of its cells with returns, metres
    mean_intensity: float
    dropout_fraction: float     #: share of its cells without returns
    theta_deg: float            #: angular threshold reached when growth stopped
    stopped_by_ks: bool         #: False: theta_max reached without a KS rejection
    seed: int


@dataclass(frozen=True)
class WaterIssue:
    """Why the data may not support the method: severity 'problem' (refused) or 'warning', and a sentence."""
    severity: str
    message: str


@dataclass(frozen=True)
class Waterbodies:
    """extract_waterbodies: the water map, labelled bodies and the input diagnostics."""
    water: np.ndarray           #: bool, True = water
    labels: np.ndarray          #: int32, 0 land, 1..n by decreasing area
    bodies: List[Waterbody]
    issues: List[WaterIssue]
    ran: bool                   #: False when check_inputs refused the data (see issues)
    points_per_cell: float
    suggested_cell_m: float
    seeds_found: int
    seeds_grown: int


@dataclass(frozen=True)
class HydroBody:
    """One waterbody as hydro_flatten saw it."""
    id: int
    type: str                       #: 'lake' or 'river'
    flattened: bool                 #: False: under the minimum size of its type, left to the terrain
    area_m2: float
    length_m: float                 #: longest path inside the body, metres
    width_m: float                  #: area / length, metres
    level_min_m: float              #: lowest water level (a lake: its level), metres
    level_max_m: float              #: highest water level (a river's upstream end), metres
    section_levels_m: List[float]   #: rivers: the level of each cross-section, upstream first
    weirs: int                      #: falls of at least 0.3 m between neighbouring sections
    shore_cells_lifted: int


@dataclass(frozen=True)
class HydroCheck:
    """One check of one flattened body: flatness (m), monotonic_fall (sections), shoreline (cells), minimum_size."""
    body: int
    check: str
    value: float
    limit: float
    passed: bool
    worst_row: int                  #: the worst offending cell, -1 when none
    worst_col: int


@dataclass(frozen=True)
class ChannelJoin:
    """A pair of pieces of one river that hydro_flatten joined (cut apart at a weir or a deck by the extraction)."""
    kept: int                       #: the label the channel keeps (its smallest)
    part_a: int                     #: the pair's smaller label, as extracted
    part_b: int                     #: the pair's larger label
    gap_m: float                    #: land crossed between the pieces, metres (0: they touch)
    contact_m: float                #: how far the pieces face each other, metres
    gap_cells: int                  #: land cells under the deck that joined the river


@dataclass(frozen=True)
class HydroFlattened:
    """hydro_flatten: the flattened DEM, the water surface and the checks."""
    dem: np.ndarray                 #: float32, metres
    water_surface: np.ndarray       #: float32, the level on flattened water, NaN elsewhere
    body: np.ndarray                #: int32, id of the flattened body per cell, 0 elsewhere
    bodies: List[HydroBody]
    checks: List[HydroCheck]
    joins: List[ChannelJoin]        #: pieces of one river joined (join_channels)
    shore_cells_below: int          #: shore cells found below the water (lifted with shoreline='lift')
    deck_cells: int                 #: cells under bridge decks the rivers took (under_decks)
    deck_level_cells: int           #: cells at a river's level beside a deck it took back (under_decks)


@dataclass(frozen=True)
class Building:
    """One building of extract_buildings; outline is a GeoJSON MultiPolygon in the grid's world coordinates."""
    id: int
    outline: dict
    ground_z: float
    eave_z: float
    ridge_z: float
    roof_area_horizontal_m2: float
    roof_area_sloped_m2: float
    surfaces: List[int]
    clipped: bool  #: the building reaches the raster's border and may go on beyond it


@dataclass(frozen=True)
class RoofSurface:
    """One roof surface: tilt (0 horizontal), down-slope azimuth clockwise from north, areas."""
    id: int
    building: int
    tilt_deg: float
    azimuth_deg: float
    horizontal_area_m2: float
    area_m2: float


@dataclass(frozen=True)
class Buildings:
    """extract_buildings: id rasters (0 = none), the terrain used, vegetation, the roof cells found under
    overhanging crowns (lowest_raised; the DSM holds the crown there), buildings and roof surfaces."""
    building_id: np.ndarray
    surface_id: np.ndarray
    ground: np.ndarray
    vegetation: np.ndarray
    under_crowns: np.ndarray
    buildings: List[Building]
    surfaces: List[RoofSurface]
    grid: Grid


@dataclass(frozen=True)
class RoofPatch:
    """One roof patch of roof_suitability."""
    building_id: int
    patch_id: int
    tilt_deg: float
    azimuth_deg: float
    area_m2: float
    sloped_area_m2: float
    kwp: float
    suitable: bool
    flat: bool
    centroid_x: float
    centroid_y: float
    rms_m: float
    reason: str


@dataclass(frozen=True)
class RoofSuitability:
    """roof_suitability: patch of each cell (int32, 0 = none) and the patches."""
    patch_id: np.ndarray
    patches: List[RoofPatch]


@dataclass(frozen=True)
class AzimuthSelection:
    """azimuth_mode_select: chosen azimuth (NaN when unsuitable), histogram mode, planes, roof form, reason."""
    azimuth_deg: float
    mode_deg: float
    planes: int
    form: str
    reason: str
    suitable: bool


@dataclass(frozen=True)
class Survey:
    """read_survey: the points of a LAS/LAZ file and its CRS."""
    x: np.ndarray
    y: np.ndarray
    z: np.ndarray
    intensity: np.ndarray
    return_number: np.ndarray
    number_of_returns: np.ndarray
    classification: np.ndarray
    epsg: int
    wkt: str
    path: str
