"""``python -m derive --output generated``: derive the model and write generated/."""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

from derive.generate import generate


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="python -m derive", description=__doc__)
    parser.add_argument("--output", type=Path, default=Path("generated"), help="output folder")
    args = parser.parse_args(argv)
    start = time.perf_counter()
    names = generate(args.output)
    elapsed = time.perf_counter() - start
    print(f"wrote {len(names)} files to {args.output}/ in {elapsed:.2f} s")
    return 0


if __name__ == "__main__":
    sys.exit(main())
