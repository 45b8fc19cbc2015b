"""Write tests/golden/convert_bits.json: the SHA-256 of each file `convert` writes for the
test's sound (tests/core/test_convert_golden.py), from the code of the commit it is run in.

    cd WORKTREE && source /work/wt/wtenv && python tests/golden/make/convert_bits.py
"""

import json
import os
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[3]
sys.path.insert(0, str(ROOT / "tests" / "core"))

from test_convert_golden import GOLDEN, WRITTEN_ON, convert_digests  # noqa: E402

os.environ["SOURCE_DATE_EPOCH"] = WRITTEN_ON

with tempfile.TemporaryDirectory() as folder:
    files = convert_digests(Path(folder))
commit = subprocess.run(["git", "rev-parse", "HEAD"], capture_output=True, text=True, cwd=ROOT,
                        check=True).stdout.strip()  # fmt: skip
GOLDEN.write_text(json.dumps({"commit": commit, "files": files}, indent=1) + "\n")
