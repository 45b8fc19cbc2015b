"""Accumulation at the extremes: an hour at 192 kHz in chunks (peak RSS), 10,000 clips vs fsum.

    python benchmarks/accumulation.py [--quick] [--out DIR]

Same as `haptic-timeline bench accumulation` (the measuring code is in timeline/bench/).
"""

import sys

from timeline.cli.main import main

if __name__ == "__main__":
    sys.exit(main(["bench", *sys.argv[1:], "accumulation"]))
