"""Shared by the examples: smoke mode (LUBEDYN_SMOKE=1: coarser meshes) and the plot file next to the script."""
import os
from pathlib import Path

SMOKE = os.environ.get("LUBEDYN_SMOKE", "") not in ("", "0")


def png(script: str) -> Path:
    """``<script stem>.png`` next to the script (or in LUBEDYN_EXAMPLE_OUT when set)."""
    folder = Path(os.environ.get("LUBEDYN_EXAMPLE_OUT", Path(script).parent))
    folder.mkdir(parents=True, exist_ok=True)
    return folder / (Path(script).stem + ".png")
