"""The old import path of `pipelay.analysis.checks`, kept for compatibility.

``import pipelay`` registers that module under this name too (see `pipelay/__init__.py`), so Python does not
run this file: ``pipelay.checks`` *is* ``pipelay.analysis.checks``, and an attribute set through one name is
set for both. This file says what the old path holds, for type checkers and readers.
"""

from pipelay.analysis.checks import *
