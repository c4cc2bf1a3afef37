"""Regenerate results/: run every shipped history, draw its figures, keep the small datasets.

Run from the repository root after installing the package:  python scripts/make_results.py

Each history of histories/ is run with the default settings and drawn by `fretting plot`;
the datasets named in KEEP stay in results/ (the others would make it tens of MB; any of them
is one `fretting run` away). The Table A comparison figure is redrawn too.
"""

import shutil
import sys
import tempfile
from pathlib import Path

from fretting import cli
from fretting.analysis.methods import comparison_figure
from fretting.loading.examples import EXAMPLES
from fretting.studies.sweeps import read_sweep, run_sweep, save_map

ROOT = Path(__file__).resolve().parents[1]
RESULTS = ROOT / "results"

#: Datasets kept in results/ (the quick-start example).
KEEP = {"hertz_shear_cycling"}


def main():
    RESULTS.mkdir(exist_ok=True)
    with tempfile.TemporaryDirectory() as scratch:
        for history in sorted(EXAMPLES.glob("*.toml")):
            dataset = Path(scratch) / f"{history.stem}.h5"
            for command in (["run", str(history), "-o", str(dataset)], ["plot", str(dataset), "-o", str(RESULTS)]):
                if cli.main(command) != 0:
                    return 1
            if history.stem in KEEP:
                shutil.copy(dataset, RESULTS / dataset.name)
    comparison_figure(RESULTS / "table_a_methods.png")
    save_map(run_sweep(read_sweep(EXAMPLES / "sweeps" / "hertz_fretting_map.toml")), RESULTS / "hertz_fretting_map.png")
    return 0


if __name__ == "__main__":
    sys.exit(main())
