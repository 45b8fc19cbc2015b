"""Which resampler should bring imported recordings to the project rate? Speed and quality.

    python benchmarks/resampler_choice.py [--quick] [--out DIR]

Same as `haptic-timeline bench resampler` (the measuring code is in timeline/bench/).
"""

import sys

from timeline.cli.main import main

if __name__ == "__main__":
    sys.exit(main(["bench", *sys.argv[1:], "resampler"]))
