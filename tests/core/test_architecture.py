"""docs/architecture.md, the import contract in pyproject.toml and the packages on disk agree."""

import re
import tomllib
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]


def _contract_layers() -> list[set[str]]:
    config = tomllib.loads((ROOT / "pyproject.toml").read_text())["tool"]["importlinter"]
    (layers,) = [c["layers"] for c in config["contracts"] if c["type"] == "layers"]
    return [{name.strip() for name in re.split(r"[|:]", row)} for row in layers]


def _documented_layers() -> list[str]:
    """The packages of the layer table in docs/architecture.md, top to bottom."""
    text = (ROOT / "docs" / "architecture.md").read_text()
    return re.findall(r"^\| \w+ \| `timeline\.(\w+)` \|", text, re.M)


def test_the_contract_names_every_package_of_timeline_once():
    on_disk = {p.parent.name for p in (ROOT / "timeline").glob("*/__init__.py")}
    in_contract = [name for row in _contract_layers() for name in row]
    assert sorted(in_contract) == sorted(on_disk | {"errors"})
    assert sorted((ROOT / "timeline").glob("*.py")) == [
        ROOT / "timeline" / "__init__.py",
        ROOT / "timeline" / "errors.py",
    ]


def test_the_documented_layers_are_the_contract_in_its_order():
    documented = _documented_layers()
    flattened = [name for row in _contract_layers() for name in sorted(row)]
    assert len(documented) == len(flattened) == 14
    # side-by-side layers may be listed in either order; the rows must follow the contract's
    position = {name: i for i, row in enumerate(_contract_layers()) for name in row}
    assert [position[name] for name in documented] == sorted(position[n] for n in documented)
    assert set(documented) == set(flattened)


def test_every_path_the_page_names_exists():
    text = (ROOT / "docs" / "architecture.md").read_text()
    paths = set(re.findall(r"`((?:timeline|device|importers|tracks)/[\w/]+\.py)`", text))
    assert len(paths) >= 10
    assert [p for p in sorted(paths) if not (ROOT / p).exists()] == []
