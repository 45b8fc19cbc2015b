"""Firmware tables: the fan knob as a C header a compiler accepts, and as JSON, values checked."""

from __future__ import annotations

import json
import math
import shutil
import subprocess
from pathlib import Path

import numpy as np
import pytest

from timeline.cli.main import main
from timeline.files import exporting, projectfile
from timeline.plugins.file_formats import FormatError

FAN_KNOB = Path(__file__).resolve().parents[2] / "projects" / "fan_knob.htl"
PER_DEGREE = 180.0 / math.pi  # one entry per degree
INDICES = (0, 1, 50, 110, 170, 279, 280)

PROGRAM = """
#include <stdio.h>
#include "{header}"
int main(void) {{
    const int at[] = {{{indices}}};
    printf("%d %.9g %.9g\\n", {upper}_COUNT, (double){upper}_START, (double){upper}_STEP);
    for (unsigned k = 0; k < sizeof at / sizeof at[0]; k++)
        printf("%.9g %.9g %.9g\\n", {torque}, {damping}, {mass});
    return 0;
}}
"""


def _compile_and_run(tmp_path: Path, header: Path, fixed: bool) -> list[list[float]]:
    name = header.stem
    values = {}
    for layer in ("torque", "damping", "mass"):
        table = f"{name}_{layer}[at[k]]"
        values[layer] = (
            f"(double){table} * {name.upper()}_{layer.upper()}_SCALE"
            if fixed
            else (f"(double){table}")
        )
    source = tmp_path / "main.c"
    source.write_text(
        PROGRAM.format(
            header=header.name,
            indices=", ".join(map(str, INDICES)),
            upper=name.upper(),
            **values,
        )
    )
    binary = tmp_path / "main"
    subprocess.run(
        ["gcc", "-std=c99", "-Wall", "-Werror", "-o", str(binary), str(source)],
        check=True,
        cwd=tmp_path,
    )
    out = subprocess.run([str(binary)], check=True, capture_output=True, text=True).stdout
    return [[float(x) for x in line.split()] for line in out.splitlines()]


@pytest.fixture
def layers():
    return exporting.project_layers(projectfile.load(FAN_KNOB), PER_DEGREE)


@pytest.mark.skipif(shutil.which("gcc") is None, reason="needs a C compiler")
@pytest.mark.parametrize("fixed", [False, True])
def test_the_header_compiles_and_holds_the_rendered_tables(tmp_path, layers, fixed):
    header = tmp_path / "fan_knob.h"
    args = ["export", str(FAN_KNOB), "-o", str(header), "--rate", "1"]  # per degree
    assert main(args + (["--fixed-point"] if fixed else [])) == 0
    (count, start, step), *rows = _compile_and_run(tmp_path, header, fixed)
    assert count == layers.length + 1 == 281 and start == 0.0  # 0 to 280 deg, both ends
    assert step == pytest.approx(math.radians(1.0), rel=1e-7)
    for k, row in zip(INDICES[:-1], rows[:-1], strict=True):
        for name, got in zip(("torque", "damping", "mass"), row, strict=True):
            want = layers.columns[name][k]
            peak = np.max(np.abs(layers.columns[name]))
            # float32: 7 digits; int16: half a count of the table's scale
            bound = peak / 32767 / 2 + 1e-12 if fixed else abs(want) * 1e-7 + 1e-12
            assert abs(got - want) <= bound, (name, k)
    # the walls survive: 0.8 of full torque up at Off, pushing back hard at 279 deg (past Hi)
    assert rows[0][0] == pytest.approx(0.144, rel=1e-4)
    assert rows[-2][0] == pytest.approx(-0.171 * 0.8, rel=1e-4)
    # ... and the axis end itself: the wall's value at 280 deg, not the one a degree before
    assert rows[-1][0] == pytest.approx(-0.144, rel=1e-4)


def test_the_default_tables_cover_the_axis_at_one_entry_per_degree_and_say_their_size(
    tmp_path, capsys
):
    header = tmp_path / "fan.h"
    assert main(["export", str(FAN_KNOB), "-o", str(header)]) == 0
    said = "3 table(s) x 281 entries (every 1 deg from 0 to 280 deg), 3,372 bytes of float32"
    assert said in capsys.readouterr().err
    text = header.read_text()
    assert "#define FAN_COUNT 281" in text and f"/* Size: {said}. */" in text
    assert "radians, not degrees" in text and "#define FAN_RATE 57.29577951308232" in text


def test_json_tables_follow_the_documented_layout(tmp_path, layers):
    out = tmp_path / "fan knob.json"
    exporting.export_project(projectfile.load(FAN_KNOB), out, rate=PER_DEGREE, fixed_point=True)
    doc = json.loads(out.read_text())
    assert (doc["format"], doc["version"], doc["axis"], doc["axis_unit"]) == (
        "haptic-timeline firmware tables",
        1,
        "position",
        "rad",
    )
    assert doc["count"] == 281 and doc["step"] == pytest.approx(math.radians(1.0))
    torque = doc["tables"]["torque"]
    assert torque["type"] == "int16" and torque["unit"] == "N*m"
    assert max(abs(v) for v in torque["values"]) == 32767
    restored = np.array(torque["values"])[:-1] * torque["scale"]
    assert np.max(np.abs(restored - layers.columns["torque"])) <= torque["scale"] / 2 + 1e-12


def test_the_header_is_named_after_the_file_not_its_temporary(tmp_path):
    out = tmp_path / "2 knob-v1.h"
    exporting.export_project(projectfile.load(FAN_KNOB), out, rate=PER_DEGREE)
    text = out.read_text()
    assert "#define T_2_KNOB_V1_COUNT 281" in text and "t_2_knob_v1_torque[" in text


def test_a_position_project_to_wav_explains_its_rate(tmp_path):
    said = r"samples per radian.*--rate N/rad \(e\.g\. --rate 5730/rad\)"
    with pytest.raises(FormatError, match=said):
        exporting.export_project(projectfile.load(FAN_KNOB), tmp_path / "fan.wav")
