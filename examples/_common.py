"""Shared by the examples: smoke mode (LUBEDYN_SMOKE=1: coarser meshes) and the plot file next to the scripts."""
import os
from pathlib import Path

SMOKE = os.environ.get("LUBEDYN_SMOKE", "") not in ("", "0")
HERE = Path(__file__).resolve().parent


def png(name: str) -> Path:
    """``<name>.png`` in examples/ (or in LUBEDYN_EXAMPLE_OUT when set).  Takes the example's name, not its
    ``__file__``: sphinx-gallery runs the examples without ``__file__``."""
    folder = Path(os.environ.get("LUBEDYN_EXAMPLE_OUT", HERE))
    folder.mkdir(parents=True, exist_ok=True)
    return folder / (Path(name).stem + ".png")
