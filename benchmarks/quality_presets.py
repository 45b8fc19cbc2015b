"""Quality presets: time per rendered second against error on fixed scenes, Pareto plot.

    python benchmarks/quality_presets.py [--quick] [--out DIR]

Same as `haptic-timeline bench quality` (the measuring code is in timeline/bench/).
"""

import sys

from timeline.cli.main import main

if __name__ == "__main__":
    sys.exit(main(["bench", *sys.argv[1:], "quality"]))
