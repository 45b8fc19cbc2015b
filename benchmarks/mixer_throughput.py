"""Mixer throughput against one memory pass, and re-render time after a 1 s clip edit.

    python benchmarks/mixer_throughput.py [--quick] [--out DIR]

Same as `haptic-timeline bench mixer` (the measuring code is in timeline/bench/).
"""

import sys

from timeline.cli.main import main

if __name__ == "__main__":
    sys.exit(main(["bench", *sys.argv[1:], "mixer"]))
