"""Writing a file atomically: the whole file or none, for every file pipelay writes whole (results,
checkpoints, a sweep's case records and summary).

Imports nothing of pipelay.
"""

from __future__ import annotations

import os
import tempfile
from pathlib import Path
from typing import Any


def _atomic_write(path: Path, write: Any) -> None:
    """Calls ``write(temporary_path)`` and renames the file into place: readers never see half a file."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    handle, temporary = tempfile.mkstemp(prefix=f".{path.name}.", suffix=".part", dir=path.parent)
    os.close(handle)
    try:
        write(Path(temporary))
        os.replace(temporary, path)
    except BaseException:
        Path(temporary).unlink(missing_ok=True)
        raise
