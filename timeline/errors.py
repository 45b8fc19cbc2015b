"""Every exception class of the host (the editor's own job-cancelling ones aside), in one tree.

    Exception
    ├── HapticTimelineError      a user's mistake or a file's: one sentence, never a traceback
    │   ├── EditError            an edit was refused; the project is unchanged
    │   ├── ProjectFileError     a project file could not be read or written
    │   │   └── FieldError       a malformed field (loading reports it naming the file)
    │   ├── RenderError          rendering failed numerically
    │   ├── PluginError          a plugin is unknown or failed to load
    │   ├── FormatError          a file could not be read or written in its format
    │   ├── SandboxError         an isolated parser crashed or ran out of its limits
    │   ├── ConvertError         a sound cannot be converted as asked
    │   ├── SettingsError        an analysis setting outside its range
    │   ├── AnalysisError        a sound the analysis cannot use
    │   ├── DeviceError          a device is missing, refused a request or failed
    │   └── HandSpecError        a --hand specification could not be understood
    └── ControlFlow              unwinds to a caller that expects it; never shown to a user
        └── NotPlain             a clip the loader's fast path leaves to the checked reader

Plugins' errors derive from these (device/usb's UsbDeviceError and its kinds from DeviceError,
its ProtocolError from HapticTimelineError). The CLI and the editor show a HapticTimelineError's
message and carry on; anything else reaching them is a bug. A ControlFlow exception never leaves
the function that catches it.
"""

import math


class HapticTimelineError(Exception):
    """Base class for mistakes in input, reported as one sentence without a traceback."""


class EditError(HapticTimelineError):
    """An edit was refused; the project is unchanged."""


class ProjectFileError(HapticTimelineError):
    """A project file could not be read or written."""


class FieldError(ProjectFileError):
    """A project file's content is malformed; the message says where and how."""


class RenderError(HapticTimelineError):
    """Rendering failed numerically (e.g. a non-finite sample)."""


class PluginError(HapticTimelineError):
    """A plugin (track kind, format or device) is unknown or failed to load."""


class FormatError(HapticTimelineError):
    """A file could not be read or written in its format; nothing was changed."""


class SandboxError(HapticTimelineError):
    """An isolated parser crashed, ran out of its limits, or failed unexpectedly."""


class ConvertError(HapticTimelineError):
    """A conversion that cannot be done as asked; nothing was written."""


class SettingsError(HapticTimelineError):
    """A setting outside the range the analysis can use."""


class AnalysisError(HapticTimelineError):
    """A sound the analysis cannot use (no samples, no rate, non-finite samples)."""


class DeviceError(HapticTimelineError):
    """A device is missing, refused a request or failed while playing."""


class HandSpecError(HapticTimelineError):
    """A --hand specification could not be understood."""


class ControlFlow(Exception):
    """Base class for exceptions that unwind to a caller expecting them; never shown to a user."""


class NotPlain(ControlFlow):
    """A clip or fade not as the editor writes it: the project loader's fast path leaves it to the
    field-by-field reader."""


def finite(name: str, value: float) -> float:
    """`value` as a float, or an EditError naming `name` when it is NaN or infinite."""
    value = float(value)
    if not math.isfinite(value):
        raise EditError(f"{name} must be a finite number, not {value!r}")
    return value
