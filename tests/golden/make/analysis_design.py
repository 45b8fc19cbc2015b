"""Write tests/golden/analysis_design.json: the designs `golden_designs()` in
tests/analysis/test_design_golden.py makes, from the code of the commit it is run in.

    cd WORKTREE && source /work/wt/wtenv && python tests/golden/make/analysis_design.py
"""

import json
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[3]
sys.path.insert(0, str(ROOT / "tests" / "analysis"))

from test_design_golden import GOLDEN, design_record, golden_designs  # noqa: E402

commit = subprocess.run(["git", "rev-parse", "HEAD"], capture_output=True, text=True, cwd=ROOT,
                        check=True).stdout.strip()  # fmt: skip
with tempfile.TemporaryDirectory() as folder:
    designs = {name: design_record(d) for name, d in golden_designs(Path(folder)).items()}
GOLDEN.write_text(json.dumps({"commit": commit, "designs": designs}, indent=1) + "\n")
