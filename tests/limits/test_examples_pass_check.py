"""Every shipped example and every project the docs build passes `check` on the default device
with no finding (issue 22.3): a newcomer's first icons do not saturate or destabilise the knob."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from timeline.files.projectfile import load
from timeline.limits.check import check
from timeline.model import Project
from timeline.plugins.device_protocol import open_device

ROOT = Path(__file__).resolve().parents[2]


@pytest.fixture(scope="module")
def info():
    with open_device("sim") as device:
        return device.info


@pytest.mark.parametrize("path", sorted((ROOT / "projects").glob("*.htl")), ids=lambda p: p.name)
def test_a_shipped_example_has_no_finding(path, info):
    assert check(load(path), info).findings == ()


def test_the_api_docs_projects_have_no_finding(info, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    text = (ROOT / "docs" / "api.md").read_text()
    namespace: dict = {}
    checked = 0
    for block in re.findall(r"```python\n(.*?)```", text, re.S):
        exec(compile(block, "docs/api.md", "exec"), namespace)
        for name, value in list(namespace.items()):
            if isinstance(value, Project) and not name.startswith("_"):
                findings = check(value, info).findings
                assert findings == (), f"{name}: {[f.describe() for f in findings]}"
                checked += 1
    assert checked >= 5
