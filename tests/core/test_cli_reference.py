"""docs/cli.md documents every verb and every option of the command line's parser, and no other.

The parsers are built from timeline/cli/main.py, so a new verb or option fails here until
docs/cli.md has it.
"""

import argparse
import re
from pathlib import Path

import pytest

from timeline.cli.main import VERBS, build_parser

DOC = Path(__file__).resolve().parents[2] / "docs" / "cli.md"
HEADING = re.compile(r"^## `([a-z-]+)`$", re.M)


def verb_parsers() -> dict[str, argparse.ArgumentParser]:
    """Each verb's parser, as `haptic-timeline` builds it."""
    sub = next(a for a in build_parser()._actions if isinstance(a, argparse._SubParsersAction))
    return dict(sub.choices)


def sections(text: str) -> dict[str, str]:
    """The text under each `## `verb`` heading, up to the next second-level heading."""
    found = {}
    for match in HEADING.finditer(text):
        rest = text[match.end() :]
        end = re.search(r"^## ", rest, re.M)
        found[match.group(1)] = rest[: end.start()] if end else rest
    return found


def options_of(parser: argparse.ArgumentParser) -> set[str]:
    """Every option string but help (both spellings of a --x/--no-x switch)."""
    return {
        option
        for action in parser._actions
        if not isinstance(action, argparse._HelpAction)
        for option in action.option_strings
    }


def positionals_of(parser: argparse.ArgumentParser) -> set[str]:
    """The positional arguments, as the page writes them (PROJECT, FILE, ...)."""
    return {a.dest.upper() for a in parser._actions if not a.option_strings}


def mentions(section: str, option: str) -> bool:
    """The option appears in backticks: `--rate`, `-o`, `--attack N`."""
    return re.search(r"`" + re.escape(option) + r"[` ]", section) is not None


def documented_options(section: str) -> set[str]:
    """The options a section's tables list in their first column."""
    found = set()
    for line in section.splitlines():
        if line.startswith("| `-"):
            first_cell = line.split("|")[1]
            found |= set(re.findall(r"`(-{1,2}[a-z][a-z0-9-]*)", first_cell))
    return found


DOCUMENTED = sections(DOC.read_text())
PARSERS = verb_parsers()


def test_every_verb_has_a_section_and_every_section_is_a_verb():
    assert set(PARSERS) == set(VERBS)
    assert set(DOCUMENTED) == set(PARSERS)


@pytest.mark.parametrize("verb", sorted(VERBS))
def test_every_option_of_the_verb_is_documented_in_its_section(verb):
    section = DOCUMENTED.get(verb, "")
    missing = sorted(o for o in options_of(PARSERS[verb]) if not mentions(section, o))
    assert missing == []


@pytest.mark.parametrize("verb", sorted(VERBS))
def test_every_positional_argument_is_documented(verb):
    section = DOCUMENTED.get(verb, "")
    missing = sorted(p for p in positionals_of(PARSERS[verb]) if p not in section)
    assert missing == []


@pytest.mark.parametrize("verb", sorted(VERBS))
def test_no_documented_option_is_missing_from_the_parser(verb):
    extra = documented_options(DOCUMENTED.get(verb, "")) - options_of(PARSERS[verb])
    assert extra == set()


def test_the_comparison_finds_a_missing_option():
    parser = argparse.ArgumentParser()
    parser.add_argument("--rate")
    parser.add_argument("--new-option")
    section = "| `--rate` | number | none | the rate |\n"
    assert [o for o in sorted(options_of(parser)) if not mentions(section, o)] == ["--new-option"]
    assert documented_options(section + "| `--gone` | x | y | z |\n") == {"--rate", "--gone"}
