"""The lazily loaded packages show their public names to dir(), IDEs and pyright."""

import ast
import importlib
import json
import subprocess
import sys
from pathlib import Path
from types import ModuleType

import pytest

import timeline
import timeline.analysis as analysis
import timeline.plugins.device_protocol as device_protocol

LAZY = [timeline, analysis, device_protocol]


def _type_checking_imports(package: ModuleType) -> dict[str, object]:
    """Name -> the object each import of the package's `if TYPE_CHECKING:` block names (and each
    name it imports eagerly from timeline, such as the errors a plugin raises)."""
    tree = ast.parse(Path(package.__file__ or "").read_text())
    (block,) = [
        node
        for node in tree.body
        if isinstance(node, ast.If) and ast.unparse(node.test) == "TYPE_CHECKING"
    ]
    eager = [
        node
        for node in tree.body
        if isinstance(node, ast.ImportFrom) and (node.module or "").startswith("timeline")
    ]
    names = {}
    for statement in [*block.body, *eager]:
        assert isinstance(statement, ast.ImportFrom) and statement.module
        for alias in statement.names:
            if statement.module == package.__name__:  # `from timeline import edits`: a submodule
                names[alias.name] = importlib.import_module(f"{statement.module}.{alias.name}")
            else:
                names[alias.name] = getattr(importlib.import_module(statement.module), alias.name)
    return names


@pytest.mark.parametrize("package", LAZY, ids=lambda p: p.__name__)
def test_each_public_name_is_the_object_of_its_defining_module(package):
    seen_by_checker = _type_checking_imports(package)
    assert set(seen_by_checker) == set(package.__all__)
    for name, defined in seen_by_checker.items():
        assert getattr(package, name) is defined, name


def test_an_unknown_name_is_an_attribute_error():
    with pytest.raises(AttributeError, match="no attribute 'nothing'"):
        timeline.nothing  # noqa: B018


PROBE = """
import json, sys
import {package} as package
names = dir(package)
print(json.dumps([sorted(package.__all__), names, "numpy" in sys.modules]))
"""


@pytest.mark.parametrize("package", [p.__name__ for p in LAZY])
def test_a_fresh_import_shows_every_public_name_and_loads_no_numpy(package):
    done = subprocess.run(
        [sys.executable, "-c", PROBE.format(package=package)],
        capture_output=True,
        text=True,
        check=True,
    )
    public, names, numpy_loaded = json.loads(done.stdout)
    assert len(public) == len(set(public)) >= 5
    assert set(public) <= set(names)  # before any of them is used
    assert not numpy_loaded
