"""One exception hierarchy: every exception class of the host lives in timeline.errors, and each
is either shown to a user (a HapticTimelineError) or control flow (a ControlFlow), never both.

The editor (timeline.gui) is left out: its job-cancelling exceptions are its own.
"""

from __future__ import annotations

import importlib
import pkgutil

import pytest

from timeline import errors
from timeline.errors import ControlFlow, HapticTimelineError

PLUGIN_PACKAGES = ("device", "importers", "tracks")


def _import_all(package_name: str, skip: str = "") -> list[str]:
    """Import a package and every module under it (but `skip`); their names."""
    package = importlib.import_module(package_name)
    names = [package_name]
    for info in pkgutil.walk_packages(package.__path__, f"{package_name}."):
        if skip and (info.name == skip or info.name.startswith(f"{skip}.")):
            continue
        importlib.import_module(info.name)
        names.append(info.name)
    return names


def _exception_classes() -> list[type[BaseException]]:
    """Every exception class loaded so far (subclasses of subclasses included)."""
    found, todo = [], [BaseException]
    while todo:
        cls = todo.pop()
        found.append(cls)
        todo.extend(cls.__subclasses__())
    return found


def _defined_in(classes: list[type[BaseException]], prefix: str) -> list[type[BaseException]]:
    return [c for c in classes if c.__module__ == prefix or c.__module__.startswith(f"{prefix}.")]


def misplaced(classes: list[type[BaseException]]) -> list[str]:
    """Host exception classes (timeline/, not its gui) defined anywhere but timeline.errors."""
    host = [
        c for c in _defined_in(classes, "timeline") if not c.__module__.startswith("timeline.gui")
    ]
    return [f"{c.__module__}.{c.__qualname__}" for c in host if c.__module__ != "timeline.errors"]


def unclassified(classes: list[type[BaseException]]) -> list[str]:
    """Classes that are neither exactly a HapticTimelineError nor exactly a ControlFlow."""
    return [
        f"{c.__module__}.{c.__qualname__}"
        for c in classes
        if issubclass(c, HapticTimelineError) == issubclass(c, ControlFlow)
    ]


@pytest.fixture(scope="module")
def loaded() -> list[type[BaseException]]:
    _import_all("timeline", skip="timeline.gui")
    for package in PLUGIN_PACKAGES:
        _import_all(package)
    return _exception_classes()


def test_every_host_exception_lives_in_timeline_errors(loaded):
    assert misplaced(loaded) == []


def test_every_exception_is_shown_to_a_user_or_is_control_flow(loaded):
    host = _defined_in(loaded, "timeline.errors")
    assert unclassified(host) == []
    shown = {c.__name__ for c in host if issubclass(c, HapticTimelineError)}
    assert {"FieldError", "FormatError", "DeviceError", "SettingsError", "SandboxError"} <= shown
    assert {c.__name__ for c in host if issubclass(c, ControlFlow)} == {"ControlFlow", "NotPlain"}


def test_plugins_errors_derive_from_the_hosts(loaded):
    plugin = [c for p in PLUGIN_PACKAGES for c in _defined_in(loaded, p)]
    names = {c.__name__ for c in plugin}
    assert {"UsbDeviceError", "DeviceNotFound", "ProtocolError"} <= names
    assert unclassified(plugin) == []
    assert all(issubclass(c, errors.DeviceError) for c in plugin if "Device" in c.__name__)


def test_the_checks_find_a_stray_class():
    stray = type("StrayError", (Exception,), {"__module__": "timeline.files.somewhere"})
    both = type("Both", (HapticTimelineError, ControlFlow), {"__module__": "timeline.errors"})
    gui = type("Stopped", (Exception,), {"__module__": "timeline.gui.player"})
    assert misplaced([stray, both, gui]) == ["timeline.files.somewhere.StrayError"]
    assert unclassified([stray, both, errors.EditError, errors.NotPlain]) == [
        "timeline.files.somewhere.StrayError",
        "timeline.errors.Both",
    ]
