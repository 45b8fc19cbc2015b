"""What a plugin implements, and how the host finds plugins.

discovery reads the entry points; track_kinds, file_formats and device_protocol are the three
protocols a plugin implements (a track kind, a file format, a device). timeline/ never imports a
particular plugin: it asks discovery for them by group and name.
"""

from timeline.plugins.discovery import (
    DEVICES,
    IMPORTERS,
    TRACKS,
    get,
    iter_group,
    load_group,
)

__all__ = [
    "DEVICES",
    "IMPORTERS",
    "TRACKS",
    "get",
    "iter_group",
    "load_group",
]
