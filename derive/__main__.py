"""``python -m derive --output generated``: derive the model and write generated/."""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

from derive.generate import generate
from derive.input_hash import input_hash
from derive.numeric_models import write_numeric_models


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="python -m derive", description=__doc__)
    parser.add_argument("--output", type=Path, default=Path("generated"), help="output folder")
    parser.add_argument(
        "--no-numeric-models",
        dest="numeric_models",
        action="store_false",
        help="skip the default loader's numeric linear models (written with the runtime)",
    )
    args = parser.parse_args(argv)
    start = time.perf_counter()
    names = generate(args.output)
    elapsed = time.perf_counter() - start
    print(f"wrote {len(names)} files to {args.output}/ in {elapsed:.2f} s")
    if args.numeric_models:
        path = write_numeric_models(args.output, input_hash())
        print(f"wrote the default loader's linear models to {path}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
