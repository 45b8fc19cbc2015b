"""Nothing in the repository cites a file outside it: facts are copied into docs/references.md.

The test corpus is the one exception: tests/corpus.py (used by the conftest files) finds it beside
the repository, and tests/data/README.md says how the hand-written files there relate to it.
"""

import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
FOLDERS = ("docs", "timeline", "tracks", "importers", "device", "projects", "benchmarks", "tests")
SUFFIXES = {".md", ".py", ".toml", ".txt", ".cfg", ".ini", ".yml", ".yaml"}
# Built from pieces so that this file does not match itself.
OUTSIDE = re.compile(
    "|".join(
        re.escape(text)
        for text in ("REFERENCE" + ".md", "STYLE" + ".md", "DESIGN" + ".md", "shared" + "/")
    )
)
ALLOWED = {"conftest.py", "corpus.py"}  # the tests' lookup of the test corpus
ALLOWED_PATHS = {ROOT / "tests" / "data" / "README.md"}


def searched_files() -> list[Path]:
    """The repository's docs, code and tests, its README and its configuration."""
    files = [ROOT / "README.md", ROOT / "pyproject.toml"]
    for folder in FOLDERS:
        files += [
            path
            for path in (ROOT / folder).rglob("*")
            if path.suffix in SUFFIXES
            and path.is_file()
            and "__pycache__" not in path.parts
            and path.name not in ALLOWED
            and path not in ALLOWED_PATHS
        ]
    return files


def outside_citations(files: list[Path], root: Path = ROOT) -> list[str]:
    """`path:line: text` for each line that names a file outside the repository."""
    found = []
    for path in files:
        for number, line in enumerate(path.read_text(errors="replace").splitlines(), 1):
            if OUTSIDE.search(line):
                found.append(f"{path.relative_to(root).as_posix()}:{number}: {line.strip()}")
    return found


def test_the_pattern_finds_each_outside_path(tmp_path):
    cited = tmp_path / "cited.md"
    lines = ["REFERENCE" + ".md", "../" + "shared" + "/corpus", "STYLE" + ".md", "DESIGN" + ".md"]
    cited.write_text("\n".join([*lines, "docs/references.md is inside", "a shared folder"]))
    hits = outside_citations([cited], tmp_path)
    assert [hit.split(": ", 1)[0] for hit in hits] == [f"cited.md:{n}" for n in (1, 2, 3, 4)]


def test_the_search_covers_docs_code_and_tests():
    names = {path.relative_to(ROOT).as_posix() for path in searched_files()}
    assert {"README.md", "docs/references.md", "timeline/cli/main.py"} <= names
    assert "tests/core/test_no_outside_citations.py" in names
    assert not any(name.endswith("conftest.py") for name in names)


def test_no_file_cites_a_file_outside_the_repository():
    assert outside_citations(searched_files()) == []
