"""Shared pytest setup: make the helper modules beside the tests (``irvine.py``) importable.

pytest's default ``prepend`` import mode already puts this folder on ``sys.path``; doing it here as well keeps
``from irvine import ...`` working under ``--import-mode=importlib``.
"""

from __future__ import annotations

import sys
from pathlib import Path

_HERE = str(Path(__file__).resolve().parent)
if _HERE not in sys.path:
    sys.path.insert(0, _HERE)
