"""Parameter sweeps, tables and charts for the FreeFEM Hertz penalty-contact solver."""
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
EDP_DIR = ROOT / "edp"
HERTZ_EDP = EDP_DIR / "hertz.edp"
RESULTS_DIR = ROOT / "results"
