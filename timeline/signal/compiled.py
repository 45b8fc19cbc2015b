"""When a render takes its compiled loops (numba): once numba is loaded, or for work that repays
loading it.

Loading numba and the cached loops costs ~0.5 s CPU once per process, so a render loads them
only for work of COMPILED_SAMPLES or more (the mixer loads them for large sums on its own);
smaller renders (every example) keep the numpy forms and never load numba. The loops give the
numpy forms' bits, so which one a render takes changes no value.
"""

from __future__ import annotations

import sys

# Samples of one evaluation from which the compiled loops are loaded for it (numpy's sine of
# 2 million samples takes ~25 ms).
COMPILED_SAMPLES = 2_000_000
_LOADED = ("timeline.signal.render_kernels", "timeline.signal.shape_kernels")


def compiled_wanted(n: int) -> bool:
    """True when an evaluation of n samples takes the compiled loops."""
    modules = sys.modules
    return n >= COMPILED_SAMPLES or _LOADED[0] in modules or _LOADED[1] in modules
