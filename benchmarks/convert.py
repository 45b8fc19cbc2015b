"""Sound-to-haptic conversion: agreement with Lofelt Studio on the corpus pairs, and speed.

    python benchmarks/convert.py [--quick] [--out DIR]

Same as `haptic-timeline bench convert` (the measuring code is in timeline/bench/).
"""

import sys

from timeline.cli.main import main

if __name__ == "__main__":
    sys.exit(main(["bench", *sys.argv[1:], "convert"]))
