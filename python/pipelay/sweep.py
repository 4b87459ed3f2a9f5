"""The old import path of `pipelay.analysis.sweep`, kept for compatibility.

``import pipelay`` registers that module under this name too (see `pipelay/__init__.py`), so Python does not
run this file: ``pipelay.sweep`` *is* ``pipelay.analysis.sweep``, and an attribute set through one name is set
for both. The attribute ``pl.sweep`` is the function `pipelay.analysis.sweep.sweep`; registering the module
keeps a later ``import pipelay.sweep`` from binding the module over it. This file says what the old path
holds, for type checkers and readers.
"""

from pipelay.analysis.sweep import *
