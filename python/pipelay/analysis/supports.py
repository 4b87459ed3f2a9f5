"""The loads on a stinger's supports in a state: each lone roller's or roller box's force on the pipe, split
into its vertical and lateral parts, and whether the pipe stays in its boxes.

```python
loads = pl.support_loads(state)         # None without rollers
loads.vertical, loads.lateral           # (m,) N per support: up, and to starboard, on the pipe (body frame)
loads.rollers[b]                        # the normal forces of box b's rollers (N)
loads.tip_offset, loads.boxes_left      # m to starboard at the stinger's tip; boxes the pipe is leaving
count, noun = support_count(state.roller_supports)   # 15, "box": how many supports, and what one is called
```

Imports of pipelay: the engine only.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

import pipelay as pl

FloatArray = npt.NDArray[np.float64]


@dataclass(frozen=True)
class SupportLoads:
    """The loads on a stinger's supports (lone rollers or roller boxes), numbered 0 … m − 1 from the hold point.

    Attributes:
        vertical: each support's force on the pipe, upward (−b3) (m,) (N).
        lateral: each support's force on the pipe, to starboard (+b2) (m,) (N).
        rollers: each support's rollers' normal forces (N), in the box's order (V port, V starboard, bottom,
            side port, side starboard, those it has).
        boxes: whether the supports are roller boxes (several rollers each, or finite ones).
        tip_offset: the pipe's lateral offset from the last support's station, to starboard (m).
        boxes_left: how many boxes the pipe is leaving (a contact at a roller's end); 0: it stays in them.
    """

    vertical: FloatArray
    lateral: FloatArray
    rollers: list[FloatArray]
    boxes: bool
    tip_offset: float
    boxes_left: int

    @property
    def stays_in_boxes(self) -> bool:
        """Whether the pipe stays in all its boxes."""
        return self.boxes_left == 0


def support_count(supports: Sequence[int]) -> tuple[int, str]:
    """How many supports rollers stand on (`supports`: each roller's, as `state.roller_supports`), and what
    people call one: "box" where a support holds several rollers, else "roller" (lone rollers, or none)."""
    count = max(supports, default=-1) + 1
    return count, "box" if count < len(supports) else "roller"


def support_loads(state: pl.State) -> SupportLoads | None:
    """The loads on the stinger's supports in `state`; None without rollers or a lay summary."""
    vectors = state.roller_reaction_vectors
    summary = state.lay_summary()
    if vectors is None or summary is None or len(vectors) == 0:
        return None
    count, noun = support_count(state.roller_supports)
    supports = np.asarray(state.roller_supports, dtype=int)
    vertical = np.array([-vectors[supports == b, 2].sum() for b in range(count)])
    lateral = np.array([vectors[supports == b, 1].sum() for b in range(count)])
    normal = np.asarray(state.roller_reactions)
    return SupportLoads(
        vertical=vertical,
        lateral=lateral,
        rollers=[normal[supports == b] for b in range(count)],
        boxes=noun == "box",
        tip_offset=float(summary["tip_offset"]),
        boxes_left=int(summary["boxes_left"]),
    )
