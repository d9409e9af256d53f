"""write_vtu: the one writer of every lubrication result's ``.vtu`` file (film and EHL solutions)."""
from __future__ import annotations

import logging
import os
import tempfile
from pathlib import Path

from .errors import InputError

log = logging.getLogger(__name__)


def _umask() -> int:
    mask = os.umask(0)
    os.umask(mask)
    return mask


def write_vtu(grid, path) -> Path:
    """Write a pyvista grid to ``path`` (``.vtu``) through a temporary file and
    a rename, with the usual file mode; shared by every lubrication result."""
    path = Path(path)
    if path.suffix != ".vtu":
        raise InputError(f"output path = {str(path)!r} must end in .vtu")
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(suffix=".vtu", dir=path.parent)
    os.close(fd)
    try:
        grid.save(tmp)
        os.chmod(tmp, 0o666 & ~_umask())  # mkstemp creates 0600; give the usual mode
        os.replace(tmp, path)
    finally:
        if os.path.exists(tmp):
            os.remove(tmp)
    log.info("wrote %s", path)
    return path
