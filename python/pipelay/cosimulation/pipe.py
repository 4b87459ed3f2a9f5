"""The pipe alone, its hold point carried by a vessel whose motion comes from outside: the model of the *pipe*
FMU (`pipelay fmu --kind pipe`), and the same in-process.

The vessel's pose η = [x, y, z, φ, θ, ψ] (CO in e, z down; zyx Euler angles) and velocity ν (body frame) are
given at communication points t_k; over the step the hold point moves with them: the vessel's CO at
p_k + R_k v_k (t − t_k) and its rotation exp((t − t_k) R_k ω_k) R_k, the hold point fixed in the vessel where the
scenario's statics put it (its position and, for a tower's clamp, its rotation relative to the vessel). The
pipe's force and moment on the vessel come back in the body frame about CO, as the plant's χ.
"""

from __future__ import annotations

import copy
import os
import warnings
from typing import Any

import numpy as np
from scipy.spatial.transform import Rotation

import pipelay as pl

__all__ = ["HeldPipe", "euler_rotation"]


def euler_rotation(angles: np.ndarray) -> np.ndarray:
    """R(Θ) = R_z(ψ) R_y(θ) R_x(φ) of zyx Euler angles (φ, θ, ψ) (rad)."""
    return Rotation.from_euler("ZYX", [angles[2], angles[1], angles[0]]).as_matrix()


class HeldPipe:
    """The scenario's pipe with its hold point on a vessel moved from outside (see the module).

    The scenario (`data`, parsed TOML; `origin` its file, for messages and relative paths) must have a
    `[vessel]` whose lay equipment has no rollers (a J-lay tower, or none): a stinger rides on the vessel, which
    this model leaves out. No winch, stages or pay-out. Raises pl.InputError naming the key otherwise.
    """

    def __init__(self, data: dict[str, Any], origin: str | os.PathLike[str]) -> None:
        from pipelay.scenario import parse_scenario

        vessel = data.get("vessel")
        if not isinstance(vessel, dict):
            raise pl.InputError(
                "vessel: the pipe FMU needs the scenario's [vessel], whose hold point it moves"
            )
        lay = vessel.get("lay") or {}
        if lay.get("kind", "j-lay") != "j-lay" or lay.get("guide") is not None:
            raise pl.InputError(
                f"vessel.lay: a {lay.get('kind')!r} with rollers rides on the vessel, which the pipe FMU leaves out: "
                "build the plant FMU (--kind plant)"
            )
        for key in ("winch", "stages", "pay_out"):
            if key in vessel or key in data:
                raise pl.InputError(
                    f"{key}: the pipe FMU has no winch, stages or pay-out; build the plant FMU"
                )
        full = parse_scenario(data, origin=str(origin))
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", pl.PhysicsWarning)
            state = full.model.static(steps=full.static_steps, start=full.static_start)
        self.end = str(vessel.get("end", "B"))
        node = 0 if self.end == "A" else -1
        assert state.eta is not None
        eta = np.array(state.eta, dtype=float)
        rotation = euler_rotation(eta[3:])
        self.arm = rotation.T @ (state.positions[node] - eta[:3])  # the hold point in the body frame (m)
        self.clamp = rotation.T @ state.rotations[node]  # the end node's frame in the body frame
        pipe = copy.deepcopy(data)
        for key in ("vessel", "controller", "environment"):
            pipe.pop(key, None)
        self.scenario = parse_scenario(pipe, origin=str(origin))
        self.model = self.scenario.model
        self.hold(0.0, eta, np.zeros(6))
        self.model.drive(self.end, position=self._position, velocity=self._velocity, rotation=self._rotation)

    def hold(self, time: float, eta: np.ndarray, nu: np.ndarray) -> None:
        """The vessel's pose η (6,) and velocity ν (6,) at `time` (s), held over the step from it."""
        for name, values in (("eta", eta), ("nu", nu)):
            if not np.all(np.isfinite(values)):
                raise pl.InputError(
                    f"{name}: {np.asarray(values).tolist()} must be finite numbers at t = {time} s"
                )
        self.time = float(time)
        self.eta = np.array(eta, dtype=float)
        self.vessel_rotation = euler_rotation(self.eta[3:])
        self.linear = self.vessel_rotation @ np.asarray(nu[:3], dtype=float)  # CO's velocity in e (m/s)
        self.spin = self.vessel_rotation @ np.asarray(nu[3:], dtype=float)  # angular velocity in e (rad/s)

    def vessel_pose(self, time: float) -> tuple[np.ndarray, np.ndarray]:
        """The vessel's CO (3,) and rotation (3, 3) at `time` (s), moved on from the held pose."""
        elapsed = time - self.time
        turn = Rotation.from_rotvec(self.spin * elapsed).as_matrix()
        return self.eta[:3] + self.linear * elapsed, turn @ self.vessel_rotation

    def _position(self, time: float) -> np.ndarray:
        centre, rotation = self.vessel_pose(time)
        return centre + rotation @ self.arm

    def _velocity(self, time: float) -> np.ndarray:
        _, rotation = self.vessel_pose(time)
        return self.linear + np.cross(self.spin, rotation @ self.arm)

    def _rotation(self, time: float) -> np.ndarray:
        _, rotation = self.vessel_pose(time)
        return rotation @ self.clamp

    def chi(self, state: Any, time: float) -> np.ndarray:
        """The pipe's force and moment on the vessel (6,) at `time` (s), body frame about CO (N, N·m)."""
        reaction = np.asarray(state.reaction(self.end), dtype=float)  # the rod's on its support, in e
        centre, rotation = self.vessel_pose(time)
        arm = self._position(time) - centre
        moment = reaction[3:] + np.cross(arm, reaction[:3])
        return np.concatenate([rotation.T @ reaction[:3], rotation.T @ moment])

    def simulation(self) -> pl.Simulation:
        """The simulation from statics of the held pose, with the scenario's settings."""
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", pl.PhysicsWarning)
            return self.scenario.simulation()
