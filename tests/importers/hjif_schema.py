"""A JSON Schema of the .hjif fields the MPEG reference software requires, for jsonschema.

The published schema files (MPEG_haptics.schema.json and the files it refers to) are loaded by
the reference software from a folder its build names (JSON_SCHEMA_PATH); they were not among
the stored copies of MPEGGroup/HapticReferenceSoftware this project could read. This schema is
built instead from the reference reader and its conformance checks (source/IOHaptics/src/
IOJson.cpp: loadFile, loadPerceptions, loadChannels, loadBands, loadEffects, loadKeyframes,
loadAvatars, loadSyncs, and the semantic checks of versions, profiles, levels, timescales and
curve types): every field that reader requires, with its JSON type, and the enumerations and
ranges those checks enforce.
"""

from __future__ import annotations

from typing import Any

INT = {"type": "integer"}
NUMBER = {"type": "number"}
TEXT = {"type": "string"}

KEYFRAME = {
    "type": "object",
    "properties": {
        "relative_position": {"type": "integer", "minimum": 0},
        "amplitude_modulation": {"type": "number", "minimum": -1, "maximum": 1},
        "frequency_modulation": {"type": "integer", "minimum": 0},
    },
}

EFFECT = {
    "type": "object",
    "required": ["effect_type", "position"],
    "properties": {
        "effect_type": {"enum": ["Basis", "Reference", "Composite"]},
        "id": INT,
        "position": {"type": "integer", "minimum": 0},
        "phase": NUMBER,
        "base_signal": {"enum": ["Sine", "Square", "Triangle", "SawToothUp", "SawToothDown"]},
        "semantic_keywords": TEXT,
        "keyframes": {"type": "array", "items": KEYFRAME},
    },
    "allOf": [
        {
            "if": {"properties": {"effect_type": {"const": "Basis"}}},
            "then": {"required": ["phase", "base_signal", "keyframes"]},
        },
        {
            "if": {"properties": {"effect_type": {"const": "Reference"}}},
            "then": {"required": ["id"]},
        },
    ],
}

BAND = {
    "type": "object",
    "required": ["band_type", "lower_frequency_limit", "upper_frequency_limit", "effects"],
    "properties": {
        "band_type": {"enum": ["Transient", "Curve", "VectorialWave", "WaveletWave"]},
        "curve_type": {"enum": ["Cubic", "Linear", "Akima", "Bezier", "Bspline"]},
        "block_length": INT,
        "lower_frequency_limit": {"type": "integer", "minimum": 0},
        "upper_frequency_limit": {"type": "integer", "minimum": 0},
        "effects": {"type": "array", "items": EFFECT},
    },
    "allOf": [
        {  # the curve type is only given for curve bands
            "if": {"not": {"properties": {"band_type": {"const": "Curve"}}}},
            "then": {"not": {"required": ["curve_type"]}},
        },
        {
            "if": {"properties": {"band_type": {"const": "WaveletWave"}}},
            "then": {"required": ["block_length"]},
        },
    ],
}

CHANNEL = {
    "type": "object",
    "required": ["id", "description", "gain", "mixing_coefficient", "body_part_mask", "bands"],
    "properties": {
        "id": INT,
        "description": TEXT,
        "gain": NUMBER,
        "mixing_coefficient": NUMBER,
        "body_part_mask": {"type": "integer", "minimum": 0},
        "reference_device_id": INT,
        "frequency_sampling": {"type": "integer", "minimum": 0},
        "sample_count": {"type": "integer", "minimum": 0},
        "bands": {"type": "array", "maxItems": 7, "items": BAND},  # level 1: 7 bands
    },
}

PERCEPTION = {
    "type": "object",
    "required": [
        "id",
        "avatar_id",
        "description",
        "perception_modality",
        "effect_library",
        "channels",
    ],
    "properties": {
        "id": INT,
        "avatar_id": INT,
        "description": TEXT,
        "perception_modality": TEXT,
        "unit_exponent": INT,
        "perception_unit_exponent": INT,
        "reference_devices": {
            "type": "array",
            "items": {"type": "object", "required": ["id", "name"]},
        },
        "effect_library": {"type": "array", "items": EFFECT},
        "channels": {"type": "array", "maxItems": 128, "items": CHANNEL},  # level 1: 128
    },
}

HJIF_SCHEMA: dict[str, Any] = {
    "$schema": "https://json-schema.org/draft/2020-12/schema",
    "type": "object",
    "required": [
        "version",
        "profile",
        "level",
        "date",
        "description",
        "timescale",
        "avatars",
        "perceptions",
        "syncs",
    ],
    "properties": {
        "version": {"type": "string", "pattern": "^20[2-9][0-9](-[1-9][0-9]*)?$"},
        "profile": {"enum": ["Main", "Simple Parametric"]},
        "level": {"enum": [1, 2]},
        "date": {"type": "string", "pattern": "^[+-]?[0-9]{4}(-[01][0-9](-[0-3][0-9])?)?"},
        "description": TEXT,
        "timescale": {"type": "integer", "minimum": 1, "maximum": 48000},  # Main profile
        "avatars": {
            "type": "array",
            "items": {"type": "object", "required": ["id", "lod", "type"]},
        },
        "perceptions": {"type": "array", "items": PERCEPTION},
        "syncs": {
            "type": "array",
            "items": {"type": "object", "required": ["timestamp"]},
        },
    },
}
