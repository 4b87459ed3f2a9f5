"""``python -m pipelay``: the same as the ``pipelay`` command (see ``pipelay.cli``)."""

from pipelay.cli import main

raise SystemExit(main())
