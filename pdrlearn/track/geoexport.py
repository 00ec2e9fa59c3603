"""A track's path for map tools (decisions L362, L363, B281, B295, B296; docs/decisions/localization.md,
bad-input.md).

With lat/lon in trajectory.csv (a geodetic start ``--start LAT,LON[,ALT]``, or an aided track's geodetic ``--gnss`` /
``--fixes``) ``track``, ``track-all`` and ``run`` also write

- ``track.gpx``: GPX 1.1 (https://www.topografix.com/GPX/1/1/): one ``<trk>`` named after the session, one
  ``<trkseg>`` per unbroken run of rows with finite lat/lon, a ``<trkpt lat lon>`` per row with ``<ele>`` when the
  start's altitude was given (``--start LAT,LON,ALT``; without it z is the height above the start, not an
  elevation) and ``<time>`` when the session gives its recording start with a UTC offset (L298's start; GPX times
  are UTC, so a start written without an offset, a local clock time of no known zone, gives no ``<time>``);
- ``track.geojson``: an RFC 7946 FeatureCollection (WGS 84, positions ``[lon, lat(, ele)]``, longitude first, RFC
  7946 section 3.1.1): the path as a LineString (a MultiLineString when rows without lat/lon cut it, B281) and
  Point features at its start and end;
- decision L570: each ramp (ramps.csv) and stair flight (stairs.csv) as a LineString feature of the path between its
  start and end times (properties: kind, number, direction, grade_pct, rise_m, L569's flags, ...:
  :func:`pdrlearn.track.ramp_audit.route_features`) and as a GPX ``<wpt>`` at its start (name, type).

Coordinates are written with 7 decimals (1e-7 degree is ~1 cm), elevations with 2 (cm). Standard library only.
"""

from __future__ import annotations

import json
import logging
import math
import xml.etree.ElementTree as ET
from datetime import UTC, datetime, timedelta
from pathlib import Path

import numpy as np

from pdrlearn.track.ramp_audit import trajectory_values

log = logging.getLogger("pdrlearn.track")

#: the files this module writes, in the order ``track``'s "wrote" line names them
GEO_FILES = ("track.gpx", "track.geojson")
#: GPX 1.1's namespace and schema (https://www.topografix.com/GPX/1/1/gpx.xsd)
GPX_NS = "http://www.topografix.com/GPX/1/1"
_GPX_XSD = "http://www.topografix.com/GPX/1/1/gpx.xsd"
_XSI = "http://www.w3.org/2001/XMLSchema-instance"
COORD_DECIMALS = 7  # decision L362: 1e-7 degree ~ 1.1 cm of latitude
ELE_DECIMALS = 2  # decision L362: cm


def geo_pieces(lat, lon) -> list[np.ndarray]:
    """Decision B281: the row indices of each unbroken run of rows whose ``lat`` and ``lon`` are both finite, in
    order; a row without them cuts the path (GPX 1.1: a new track segment where reception was lost). Empty when no
    row has them."""
    ok = np.isfinite(np.asarray(lat, float)) & np.isfinite(np.asarray(lon, float))
    idx = np.flatnonzero(ok)
    if not len(idx):
        return []
    return np.split(idx, np.flatnonzero(np.diff(idx) > 1) + 1)


def utc_times(start: datetime | None, seconds, *, where: str = "") -> list[str] | None:
    """Decision L362: ISO 8601 UTC texts (``...Z``, milliseconds) of session times ``seconds`` after the recording
    ``start`` (L298); None without a start or with one of no UTC offset (its zone unknown: no UTC time exists).
    Decision B296: None too (with one warning) when a time falls outside the years 1-9999 that ISO 8601 / Python
    dates hold (a start near 0001-01-01 or 9999-12-31): no point gets a time rather than some; ``where`` (the
    session) begins the warning."""
    if start is None or start.utcoffset() is None:
        return None
    try:
        return [(start + timedelta(seconds=float(s))).astimezone(UTC).isoformat(timespec="milliseconds")
                .replace("+00:00", "Z") for s in seconds]
    except OverflowError:
        log.warning("%srecording start %s (meta.json recording_start): the track's UTC times fall outside the "
                    "years 1-9999, so track.gpx and track.geojson have no times; correct the recording start if it "
                    "is wrong (decision B296)", f"{where}: " if where else "", start.isoformat())
        return None


def _xml_char(c: str) -> bool:
    """Decision B295: XML 1.0's Char production (section 2.2): tab, LF, CR, U+0020-U+D7FF, U+E000-U+FFFD and
    U+10000 up; no other character (a C0 control, a lone surrogate, U+FFFE, U+FFFF) can be in a well-formed file."""
    o = ord(c)
    return c in "\t\n\r" or 0x20 <= o <= 0xD7FF or 0xE000 <= o <= 0xFFFD or o >= 0x10000


def xml_text(text: str) -> str:
    """Decisions B281, B295: ``text`` without the characters XML 1.0 cannot hold (:func:`_xml_char`), which
    ElementTree would write into a file no reader parses."""
    return "".join(c for c in str(text) if _xml_char(c))


def _coord(v: float) -> str:
    return f"{v:.{COORD_DECIMALS}f}"


def gpx_text(lat, lon, pieces: list[np.ndarray], *, name: str, ele=None, times: list[str] | None = None,
             waypoints: list[dict] | None = None) -> str:
    """The GPX 1.1 document of the rows ``pieces`` (:func:`geo_pieces`): one ``<trk>`` called ``name`` with a
    ``<trkseg>`` per piece; ``ele`` (m, per row) gives each point's ``<ele>`` where finite, ``times`` its
    ``<time>`` (GPX 1.1 element order: ele, then time). Decision L570: ``waypoints`` (``lat``, ``lon``, ``name``,
    ``type``, optional ``ele`` / ``time``) are ``<wpt>`` elements before the track (GPX 1.1: wpt, rte, trk)."""
    ET.register_namespace("", GPX_NS)
    root = ET.Element(f"{{{GPX_NS}}}gpx", {"version": "1.1", "creator": "pdrlearn",
                                            f"{{{_XSI}}}schemaLocation": f"{GPX_NS} {_GPX_XSD}"})
    for w in waypoints or []:
        pt = ET.SubElement(root, f"{{{GPX_NS}}}wpt", {"lat": _coord(w["lat"]), "lon": _coord(w["lon"])})
        if w.get("ele") is not None and math.isfinite(w["ele"]):
            ET.SubElement(pt, f"{{{GPX_NS}}}ele").text = f"{w['ele']:.{ELE_DECIMALS}f}"
        if w.get("time") is not None:
            ET.SubElement(pt, f"{{{GPX_NS}}}time").text = w["time"]
        ET.SubElement(pt, f"{{{GPX_NS}}}name").text = xml_text(w["name"])
        ET.SubElement(pt, f"{{{GPX_NS}}}type").text = xml_text(w["type"])
    trk = ET.SubElement(root, f"{{{GPX_NS}}}trk")
    ET.SubElement(trk, f"{{{GPX_NS}}}name").text = xml_text(name)
    for piece in pieces:
        seg = ET.SubElement(trk, f"{{{GPX_NS}}}trkseg")
        for i in piece:
            pt = ET.SubElement(seg, f"{{{GPX_NS}}}trkpt", {"lat": _coord(lat[i]), "lon": _coord(lon[i])})
            if ele is not None and math.isfinite(ele[i]):
                ET.SubElement(pt, f"{{{GPX_NS}}}ele").text = f"{ele[i]:.{ELE_DECIMALS}f}"
            if times is not None:
                ET.SubElement(pt, f"{{{GPX_NS}}}time").text = times[i]
    ET.indent(root)
    return '<?xml version="1.0" encoding="UTF-8"?>\n' + ET.tostring(root, encoding="unicode") + "\n"


def geojson_dict(lat, lon, pieces: list[np.ndarray], *, properties: dict, ele=None,
                 times: list[str] | None = None) -> dict:
    """The RFC 7946 FeatureCollection of the rows ``pieces``: the path (``properties`` on it) and Point features
    ``start`` and ``end`` (with ``time`` when ``times``). ``ele`` is each position's third value only when every
    point written has one (one geometry, one dimension). A piece of one point is the two-position line
    ``[p, p]`` (RFC 7946 section 3.1.4: a LineString has two or more positions; decision B281)."""
    rows = np.concatenate(pieces)
    with_ele = ele is not None and bool(np.all(np.isfinite(np.asarray(ele, float)[rows])))

    def pos(i: int) -> list[float]:
        p = [round(float(lon[i]), COORD_DECIMALS), round(float(lat[i]), COORD_DECIMALS)]  # RFC 7946 3.1.1: lon first
        return p + [round(float(ele[i]), ELE_DECIMALS)] if with_ele else p

    lines = [[pos(i) for i in (piece if len(piece) > 1 else [piece[0], piece[0]])] for piece in pieces]
    path = ({"type": "LineString", "coordinates": lines[0]} if len(lines) == 1 else
            {"type": "MultiLineString", "coordinates": lines})  # decision B281: a cut path, RFC 7946 3.1.5

    def point(role: str, i: int) -> dict:
        props = {"session": properties.get("session"), "role": role}
        if times is not None:
            props["time"] = times[i]
        return {"type": "Feature", "geometry": {"type": "Point", "coordinates": pos(i)}, "properties": props}

    return {"type": "FeatureCollection",
            "features": [{"type": "Feature", "geometry": path, "properties": properties},
                         point("start", int(rows[0])), point("end", int(rows[-1]))]}


def feature_geometry(t, lat, lon, ele, t0: float, t1: float) -> list[list[float]]:
    """Decisions L570, L585: the RFC 7946 positions of the path from time ``t0`` to ``t1``: the rows' lat / lon
    (and ``ele`` when given) at the row at or before ``t0`` (L585: where the walker stood until the first stride
    ended, as ramps.csv's / stairs.csv's start), the rows strictly between ``t0`` and ``t1`` in order, and
    interpolated at ``t1``; empty where either end has no position (outside the rows with lat / lon)."""
    ok = np.isfinite(t) & np.isfinite(lat) & np.isfinite(lon) & (np.isfinite(ele) if ele is not None else True)
    tt = t[ok]
    if len(tt) < 2 or not (tt[0] <= t0 <= tt[-1] and tt[0] <= t1 <= tt[-1]):
        return []
    cols = [lon[ok], lat[ok]] + ([ele[ok]] if ele is not None else [])  # RFC 7946 3.1.1: lon first
    inner = np.flatnonzero((tt > t0) & (tt < t1))
    pts = [[float(trajectory_values(tt, c, [t0], held=True)[0]) for c in cols],
           *([float(c[i]) for c in cols] for i in inner),
           [float(trajectory_values(tt, c, [t1])[0]) for c in cols]]
    return [[round(v, COORD_DECIMALS if k < 2 else ELE_DECIMALS) for k, v in enumerate(p)] for p in pts]


def elevation(trajectory) -> np.ndarray | None:
    """Decision L630: the elevation of each row, trajectory.csv's ride-inclusive ``z_rides`` (a lift's height is the
    walker's) where written, else ``z``; None without either."""
    for c in ("z_rides", "z"):
        if c in trajectory:
            return trajectory[c].to_numpy(float)
    return None


def route_feature_parts(trajectory, features: list[dict], *, with_ele: bool, start: datetime | None,
                        session: str) -> tuple[list[dict], list[dict]]:
    """Decision L570: the GeoJSON Features and GPX waypoints of ``features``
    (:func:`pdrlearn.track.ramp_audit.route_features`) on ``trajectory``; a feature without a position at both ends
    is left out."""
    t, lat, lon = (trajectory[c].to_numpy(float) for c in ("t", "lat", "lon"))
    ele = elevation(trajectory) if with_ele else None
    geo, wpts = [], []
    for f in features:
        coords = feature_geometry(t, lat, lon, ele, f["start_s"], f["end_s"])
        if not coords:
            continue
        props = {"session": session, **f["properties"], "name": f["name"], "start_s": round(f["start_s"], 3),
                 "end_s": round(f["end_s"], 3)}
        geo.append({"type": "Feature", "geometry": {"type": "LineString", "coordinates": coords},
                    "properties": props})
        when = utc_times(start, [f["start_s"]], where=session)
        wpts.append({"lat": coords[0][1], "lon": coords[0][0], "ele": coords[0][2] if ele is not None else None,
                     "time": when[0] if when else None, "name": f["name"], "type": f["properties"]["kind"]})
    return geo, wpts


def write_geo_files(dest: Path, trajectory, *, session: str, pipeline: str | None, distance_m: float | None,
                    start: datetime | None = None, with_ele: bool = False,
                    features: list[dict] | None = None) -> tuple[str, ...]:
    """Decisions L362, L363: write :data:`GEO_FILES` into the folder ``dest`` (the caller's temporary folder: they
    appear with the track's other files or not at all) from ``trajectory``'s ``t``, ``lat``, ``lon`` (and ``z``
    as the elevation when ``with_ele``: the start's altitude was given); ``start``: the recording's clock start
    (L298) for the points' times; ``features`` (decision L570: the ramps and stair flights,
    :func:`pdrlearn.track.ramp_audit.route_features`) as GeoJSON features and GPX waypoints. Returns the names
    written: none when no row has lat/lon (no geodetic start)."""
    if "lat" not in trajectory or "lon" not in trajectory:
        return ()
    lat, lon = (trajectory[c].to_numpy(float) for c in ("lat", "lon"))
    pieces = geo_pieces(lat, lon)
    if not pieces:
        return ()
    ele = elevation(trajectory) if with_ele else None
    times = utc_times(start, trajectory["t"].to_numpy(float), where=session) if "t" in trajectory else None
    marks, wpts = (route_feature_parts(trajectory, features, with_ele=ele is not None, start=start, session=session)
                   if features and "t" in trajectory else ([], []))  # decision L570
    (Path(dest) / GEO_FILES[0]).write_text(gpx_text(lat, lon, pieces, name=session, ele=ele, times=times,
                                                    waypoints=wpts))
    finite = distance_m is not None and math.isfinite(float(distance_m))
    props = {"session": session, "pipeline": pipeline, "distance_m": round(float(distance_m), 3) if finite else None}
    doc = geojson_dict(lat, lon, pieces, properties=props, ele=ele, times=times)
    doc["features"] += marks
    # compact (a long walk's path is thousands of positions); RFC 8259 JSON: no NaN is ever written
    (Path(dest) / GEO_FILES[1]).write_text(json.dumps(doc, separators=(",", ":"), allow_nan=False) + "\n")
    return GEO_FILES
