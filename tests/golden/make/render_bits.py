"""Write tests/golden/render_bits.json: the SHA-256 of each layer of the golden render
(tests/core/test_render_golden.py), from the code of the commit it is run in.

    cd WORKTREE && source /work/wt/wtenv && python tests/golden/make/render_bits.py
"""

import json
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[3]
sys.path.insert(0, str(ROOT / "tests" / "core"))

from test_render_golden import GOLDEN, render_digests  # noqa: E402

numpy_bits, loop_bits = render_digests(False), render_digests(True)
if numpy_bits != loop_bits:
    sys.exit("the compiled loops and the numpy forms disagree: no golden written")
commit = subprocess.run(["git", "rev-parse", "HEAD"], capture_output=True, text=True, cwd=ROOT,
                        check=True).stdout.strip()  # fmt: skip
GOLDEN.write_text(json.dumps({"commit": commit, "layers": numpy_bits}, indent=1) + "\n")
