"""A DP controller as an FMU (FMI 2.0 co-simulation), for pipelay's co-simulation examples and tests.

PD on the vessel's pose, as pipelay's own PID computes it: τ = −Jᵀ(η)(K_p η̃ + K_d J(η)ν) in surge, sway and yaw
(body frame), η̃ = η − η_ref with the heading's error wrapped, J(η) = diag(R(Θ), T(Θ)) Fossen's kinematics.
Build it with pythonfmu: `pythonfmu build -f dp_pd.py` (writes dp_pd.fmu); it runs where Python and numpy are.
"""

import math

import numpy as np
from pythonfmu import Fmi2Causality, Fmi2Slave, Fmi2Variability, Real

POSE = ("x", "y", "z", "roll", "pitch", "yaw")
VELOCITY = ("u", "v", "w", "p", "q", "r")
AXES = ("surge", "sway", "yaw")
DOFS = (0, 1, 5)  # η's x, y and ψ; τ's surge, sway and yaw


def jacobian(eta: np.ndarray) -> np.ndarray:
    """J(η) = diag(R(Θ), T(Θ)), zyx Euler angles (Fossen 2021, eqs. 2.18 and 2.28)."""
    (cf, sf), (ct, st), (cp, sp) = ((math.cos(a), math.sin(a)) for a in eta[3:6])
    rz = np.array([[cp, -sp, 0.0], [sp, cp, 0.0], [0.0, 0.0, 1.0]])
    ry = np.array([[ct, 0.0, st], [0.0, 1.0, 0.0], [-st, 0.0, ct]])
    rx = np.array([[1.0, 0.0, 0.0], [0.0, cf, -sf], [0.0, sf, cf]])
    t = np.array([[1.0, sf * st / ct, cf * st / ct], [0.0, cf, -sf], [0.0, sf / ct, cf / ct]])
    j = np.zeros((6, 6))
    j[:3, :3] = rz @ ry @ rx
    j[3:, 3:] = t
    return j


class dp_pd(Fmi2Slave):  # its name is the FMU's model identifier
    author = "pipelay"
    description = "PD DP controller: tau = -J^T (Kp (eta - eta_ref) + Kd J nu) in surge, sway and yaw"

    def __init__(self, **kwargs):
        super().__init__(**kwargs)
        for name in (*POSE, *VELOCITY):
            setattr(self, name, 0.0)
            self.register_variable(Real(name, causality=Fmi2Causality.input))
        for axis in AXES:
            for gain in ("kp", "kd"):
                setattr(self, f"{gain}_{axis}", 0.0)
                self.register_variable(
                    Real(
                        f"{gain}_{axis}",
                        causality=Fmi2Causality.parameter,
                        variability=Fmi2Variability.tunable,
                    )
                )
        for name in ("x_ref", "y_ref", "yaw_ref"):
            setattr(self, name, 0.0)
            self.register_variable(
                Real(name, causality=Fmi2Causality.parameter, variability=Fmi2Variability.tunable)
            )
        for axis in AXES:
            setattr(self, f"tau_{axis}", 0.0)
            self.register_variable(Real(f"tau_{axis}", causality=Fmi2Causality.output))

    def do_step(self, current_time, step_size):
        eta = np.array([getattr(self, name) for name in POSE])
        nu = np.array([getattr(self, name) for name in VELOCITY])
        error = eta - np.array([self.x_ref, self.y_ref, 0.0, 0.0, 0.0, self.yaw_ref])
        error[3:] = (error[3:] + math.pi) % (2.0 * math.pi) - math.pi
        kp, kd = np.zeros(6), np.zeros(6)
        for axis, dof in zip(AXES, DOFS):
            kp[dof], kd[dof] = getattr(self, f"kp_{axis}"), getattr(self, f"kd_{axis}")
        j = jacobian(eta)
        tau = -j.T @ (kp * error + kd * (j @ nu))
        self.tau_surge, self.tau_sway, self.tau_yaw = (float(tau[dof]) for dof in DOFS)
        return True
