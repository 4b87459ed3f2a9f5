"""The old import path of `pipelay.results.streaming`, kept for compatibility.

``import pipelay`` registers that module under this name too (see `pipelay/__init__.py`), so Python does not
run this file: ``pipelay.streaming`` *is* ``pipelay.results.streaming``, and an attribute set through one name
(``monkeypatch.setattr(streaming, "SEGMENT_RECORDS", 7)``) is set for both. This file says what the old path
holds, for type checkers and readers.
"""

from pipelay.results.streaming import *
