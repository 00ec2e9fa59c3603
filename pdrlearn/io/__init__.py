"""Sessions, sensor streams, the PLASYS folder format and the Bluetooth text protocol."""

from pdrlearn.io.archive import read_session_zip
from pdrlearn.io.frames import THESIS_FOOT_FRAME, THESIS_WAIST_FRAME, AxisFrame, frames_from_meta
from pdrlearn.io.plasys import read_session, read_stream, write_session
from pdrlearn.io.protocol import BluetoothParser, format_protocol, parse_protocol
from pdrlearn.io.sensors import SENSORS, SensorSpec
from pdrlearn.io.session import (
    DIRECTION_CLASSES,
    LENGTH_CLASSES,
    TERRAIN_CLASSES,
    Gap,
    Session,
    Stream,
)

__all__ = [
    "AxisFrame", "THESIS_FOOT_FRAME", "THESIS_WAIST_FRAME", "frames_from_meta",
    "read_session", "read_session_zip", "read_stream", "write_session",
    "BluetoothParser", "parse_protocol", "format_protocol",
    "SENSORS", "SensorSpec", "Session", "Stream", "Gap",
    "TERRAIN_CLASSES", "DIRECTION_CLASSES", "LENGTH_CLASSES",
]
