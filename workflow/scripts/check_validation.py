"""Snakemake adapter: fail the workflow if a number expected to reproduce did not."""

import json
import sys
from pathlib import Path

from dccss.files import write_text

rows = json.loads(Path(snakemake.input[0]).read_text())
failing = [r for r in rows if not r["ok"]]
with open(snakemake.log[0], "w") as log:
    for r in failing:
        line = (f"{r['id']}: expected to reproduce with {r['expected']}, got {r['computed']} "
                f"({r['unit']}) against the paper's {r['paper_value']}")
        print(line, file=log)
        print(line, file=sys.stderr)
    if failing:
        sys.exit(f"validation failed: {len(failing)} stated number(s) expected to reproduce did not; "
                 "see figures/validation.md")
    write_text(f"{len(rows)} checks, all expected reproductions hold\n", snakemake.output[0])
