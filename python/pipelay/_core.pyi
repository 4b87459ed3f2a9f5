"""Type stubs of the compiled engine module (SI units; frame e with e3 pointing down)."""

import os
from collections.abc import Callable, Mapping, Sequence
from pathlib import Path
from typing import Any, Literal, TypeAlias, final

import numpy as np
import numpy.typing as npt

_ArrayLike = npt.ArrayLike
_FloatArray: TypeAlias = npt.NDArray[np.float64]
_IntArray: TypeAlias = npt.NDArray[np.int64]
_End: TypeAlias = Literal["A", "B"]

__all__ = [
    "PID",
    "Allocation",
    "Bathymetry",
    "Clump",
    "Coating",
    "ConvergenceError",
    "Current",
    "DriftCoefficients",
    "Force",
    "HullCoefficients",
    "InputError",
    "JLay",
    "Material",
    "Model",
    "Observer",
    "Raos",
    "ReelLay",
    "Results",
    "Rod",
    "RollerBox",
    "Route",
    "SLay",
    "Sea",
    "Seabed",
    "Section",
    "Segment",
    "Simulation",
    "Stage",
    "Stages",
    "State",
    "Stinger",
    "StingerSection",
    "Straightener",
    "TensionControl",
    "Thruster",
    "Touchdown",
    "Vessel",
    "Waves",
    "Winch",
    "Wind",
    "design_straightener",
    "dp_capability_wind",
    "environment_load",
]

class InputError(ValueError):
    """Bad input: the message names the argument (or scenario key), the value and what is allowed."""

class ConvergenceError(RuntimeError):
    """Newton failed: the message gives the load factor or time reached, iterations and residual."""

@final
class Clump:
    """A body to attach at a point of the line (Model.attach): mass in air (kg), displaced volume (m³), drag
    area C_d·A (m²) and added-mass coefficient on the displaced volume."""

    def __new__(
        cls, mass: float, volume: float = 0.0, drag_area: float = 0.0, added_mass: float = 1.0
    ) -> Clump: ...
    @property
    def mass(self) -> float:
        """Mass in air (kg)."""
    @property
    def volume(self) -> float:
        """Displaced volume (m³)."""
    @property
    def drag_area(self) -> float:
        """Drag area C_d·A (m²)."""
    @property
    def added_mass(self) -> float:
        """Added-mass coefficient on the displaced volume."""

@final
class Coating:
    """A layer outside a pipe's steel wall (a coating) or inside it (a lining): thickness (m), density
    (kg/m³) and the Young's modulus (Pa) it adds to the axial and bending stiffness (0: none)."""

    def __new__(cls, thickness: float, density: float, youngs_modulus: float = 0.0) -> Coating: ...
    @property
    def thickness(self) -> float:
        """Thickness (m)."""
    @property
    def density(self) -> float:
        """Density (kg/m³)."""
    @property
    def youngs_modulus(self) -> float:
        """Young's modulus added to the stiffness (Pa; 0: none)."""

@final
class Section:
    """Cross-section properties. GA, EI: one number (both principal axes) or a pair (axis 2, axis 3)."""

    def __new__(
        cls,
        EA: float,
        GA: float | Sequence[float],
        GJ: float,
        EI: float | Sequence[float],
        mass: float,
        inertia: Sequence[float] | None = None,
        outer_diameter: float = 0.0,
        displaced_area: float | None = None,
        drag: Sequence[float] | None = None,
        added_mass: Sequence[float] | None = None,
        rotational_damping: float | Sequence[float] | None = None,
    ) -> Section: ...
    @staticmethod
    def pipe(
        outer_diameter: float,
        wall_thickness: float,
        density: float = 7850.0,
        youngs_modulus: float = 207e9,
        poisson_ratio: float = 0.3,
        contents_density: float = 0.0,
        drag: Sequence[float] | None = None,
        added_mass: Sequence[float] | None = None,
        *,
        grade: str | None = None,
        coatings: Sequence[Coating] | None = None,
        lining: Coating | None = None,
        material: Material | None = None,
    ) -> Section:
        """A pipe from its geometry (m) and material; drag and added mass default to (0, 1). `grade` (a key of
        `pipelay.analysis.checks.GRADES`) is what the design checks take by default; `coatings` (from the
        steel outwards) and `lining` add their mass and set the hydrodynamic diameter, not the steel's;
        `material` is the steel's law beyond yield (its E replaces `youngs_modulus`)."""
    def moment_curvature(
        self, curvatures: Sequence[float] | _ArrayLike, axial_strain: float = 0.0
    ) -> _FloatArray:
        """The wall's bending moments (N·m) along a path of curvatures (1/m) from rest (history-dependent)."""
    @property
    def material(self) -> Material | None:
        """The steel's law beyond yield, or None (linear elastic)."""
    @staticmethod
    def cable(
        diameter: float,
        mass: float,
        EA: float,
        drag: Sequence[float] | None = None,
        added_mass: Sequence[float] | None = None,
        damping: float = 0.0,
    ) -> Section:
        """A cable (wire rope, chain) of nominal `diameter` (m), `mass` (kg/m) and axial stiffness `EA` (N):
        tension only, no bending or torsion; drag defaults to (0, 1.2), added mass to (0, 1); `damping` B
        (N·s): the axial internal damping of a taut cable, force B·ε̇."""
    def with_structural_damping(
        self, period: float, axial: float = 0.0, bending: float = 0.0, torsion: float = 0.0
    ) -> Section:
        """This section with structural (Kelvin–Voigt) damping: axial, bending and torsional fractions of
        critical damping (-) at `period` (s). Resultants gain β·C times the strain rates, β = ζ·period/π (shear
        with the axial ratio): a mode of period T is damped at ζ·period/T. Its work is dissipated. A cable takes
        only `axial`, which adds β·EA to its `damping`."""
    @property
    def structural_damping(self) -> tuple[float, float, float, float] | None:
        """(axial, bending, torsion) fractions of critical (-) and their period (s), or None."""
    @property
    def is_cable(self) -> bool:
        """Whether this is a cable's section (`Section.cable`)."""
    @property
    def damping(self) -> float:
        """A cable's axial internal damping B (N·s), its structural damping's β·EA included; 0 for rods."""
    @property
    def EA(self) -> float:
        """Axial stiffness (N)."""
    @property
    def wall_thickness(self) -> float | None:
        """Wall thickness (m) of a Section.pipe; None otherwise."""
    @property
    def youngs_modulus(self) -> float | None:
        """Young's modulus (Pa) of a Section.pipe; None otherwise."""
    @property
    def poisson_ratio(self) -> float | None:
        """Poisson's ratio of a Section.pipe; None otherwise."""
    @property
    def contents_density(self) -> float | None:
        """Contents density (kg/m³) of a Section.pipe; None otherwise."""
    @property
    def GA(self) -> tuple[float, float]:
        """Shear stiffnesses (N)."""
    @property
    def GJ(self) -> float:
        """Torsional stiffness (N·m²)."""
    @property
    def EI(self) -> tuple[float, float]:
        """Bending stiffnesses (N·m²)."""
    @property
    def mass(self) -> float:
        """Mass per unit length, contents included (kg/m)."""
    @property
    def inertia(self) -> tuple[float, float, float]:
        """Rotational inertia per unit length about t1, t2, t3 (kg·m)."""
    @property
    def outer_diameter(self) -> float:
        """Outer diameter (m): the steel's for a Section.pipe (coatings not included)."""
    @property
    def hydrodynamic_diameter(self) -> float:
        """Diameter over the coatings (m), to which drag, added mass, buoyancy, contact and rollers refer."""
    @property
    def submerged_weight(self) -> float:
        """Submerged weight per unit length in sea water of 1025 kg/m³ under g = 9.81 m/s² (N/m)."""
    @property
    def grade(self) -> str | None:
        """The steel's grade of a Section.pipe given one; None otherwise."""
    @property
    def coatings(self) -> list[Coating]:
        """The external coatings of a Section.pipe, from the steel outwards."""
    @property
    def lining(self) -> Coating | None:
        """The internal lining of a Section.pipe; None without one."""
    @property
    def displaced_area(self) -> float:
        """Buoyancy area per unit length (m²)."""
    @property
    def drag(self) -> tuple[float, float]:
        """Morison drag coefficients (axial, normal)."""
    @property
    def added_mass(self) -> tuple[float, float]:
        """Added-mass coefficients (axial, normal)."""
    @property
    def rotational_damping(self) -> tuple[float, float, float]:
        """Rotational damping about t1, t2, t3 (N·m·s per m)."""

@final
class Segment:
    """One segment of a line: its unstretched `length` (m), its `section` and its number of `elements`."""

    def __new__(cls, length: float, section: Section, elements: int) -> Segment: ...
    @property
    def length(self) -> float:
        """Unstretched length (m)."""
    @property
    def section(self) -> Section:
        """The segment's cross-section."""
    @property
    def elements(self) -> int:
        """Number of elements."""

@final
class Rod:
    """A rod in its stress-free reference configuration: nodes (n + 1, 3) in m and a section."""

    def __new__(cls, nodes: _ArrayLike, section: Section) -> Rod: ...
    @staticmethod
    def straight(start: _ArrayLike, end: _ArrayLike, elements: int, section: Section) -> Rod:
        """A straight rod of `elements` equal elements from `start` to `end` (m)."""
    @staticmethod
    def segments(start: _ArrayLike, direction: _ArrayLike, segments: Sequence[Segment]) -> Rod:
        """A straight line of consecutive `segments` from `start` (m) along `direction`, continuous at the
        joints."""
    @property
    def nodes(self) -> _FloatArray:
        """Reference node positions (n + 1, 3) (m)."""
    @property
    def elements(self) -> int:
        """Number of elements n."""
    @property
    def length(self) -> float:
        """Total reference length (m)."""
    @property
    def section(self) -> Section:
        """The cross-section of the first segment (of the whole rod for a rod of one segment)."""
    @property
    def sections(self) -> list[Section]:
        """The cross-section of each segment, from end A."""
    @property
    def segment_of(self) -> _IntArray:
        """The segment index of each element (n,)."""

@final
class Current:
    """A steady current; build it with `uniform`, `linear` or `profile`."""

    @staticmethod
    def uniform(velocity: _ArrayLike, start: float = 0.0) -> Current:
        """The same velocity (3,) (m/s, in e) at every depth, from time `start` (s)."""
    @staticmethod
    def linear(surface_velocity: _ArrayLike, start: float = 0.0) -> Current:
        """Linear shear: `surface_velocity` at the surface, zero at the seabed end's depth."""
    @staticmethod
    def profile(depths: _ArrayLike, velocities: _ArrayLike, start: float = 0.0) -> Current:
        """A table of depths below the surface (m, increasing) and velocities (k, 3) (m/s)."""
    def velocity(self, z: float, depth: float, t: float) -> tuple[float, float, float]:
        """Velocity (m/s) at elevation z (m) in a sea of the given depth at time t (s)."""
    @property
    def start(self) -> float:
        """Start time (s)."""

@final
class Waves:
    """A sea state: linear (Airy) components; build it with `regular`, `jonswap` or `spectrum`."""

    @staticmethod
    def regular(height: float, period: float, direction: float = 0.0, ramp: float | None = None) -> Waves:
        """A regular wave: crest-to-trough height (m), period (s), direction of travel (rad from e1 to e2),
        building up over `ramp` (s; None: one period)."""
    @staticmethod
    def jonswap(
        hs: float,
        tp: float,
        gamma: float = 3.3,
        direction: float = 0.0,
        seed: int = 0,
        components: int = 200,
        spreading: float | None = None,
        ramp: float | None = None,
    ) -> Waves:
        """A JONSWAP sea: Hs (m), Tp (s), peak enhancement, mean direction (rad), cos^2s spreading s, build-up
        time (s; None: Tp)."""
    @staticmethod
    def spectrum(
        frequencies: _ArrayLike,
        densities: _ArrayLike,
        direction: float = 0.0,
        seed: int = 0,
        components: int = 200,
        spreading: float | None = None,
        ramp: float | None = None,
    ) -> Waves:
        """A sea from S(ω): frequencies (rad/s, increasing), densities (m²·s/rad), build-up time (s; None: the
        period of the largest component)."""
    def elevation(self, t: float | _ArrayLike, x: float = 0.0, y: float = 0.0) -> _FloatArray:
        """Surface elevation (m, up) at times t (s) and the point (x, y) (deep water unless from a Sea)."""
    @property
    def ramp(self) -> float:
        """Time over which the sea builds up from calm (s)."""
    @property
    def hs(self) -> float:
        """Significant height 4√m0 of the components (m)."""
    @property
    def components(self) -> list[_FloatArray]:
        """Amplitude (m), frequency (rad/s), direction (rad) and phase (rad), (N,) each."""

@final
class Sea:
    """Water: depth (m; the surface is z = −depth), density (kg/m³), an optional current, an optional seabed
    and optional waves."""

    def __new__(
        cls,
        depth: float,
        density: float = 1025.0,
        current: Current | None = None,
        seabed: Seabed | None = None,
        waves: Waves | None = None,
        wind: Wind | None = None,
    ) -> Sea: ...
    @property
    def waves(self) -> Waves | None:
        """The sea state, resolved for this depth."""
    @property
    def wind(self) -> Wind | None:
        """The wind, if any."""
    @property
    def depth(self) -> float:
        """Water depth (m)."""
    @property
    def density(self) -> float:
        """Water density (kg/m³)."""
    @property
    def current(self) -> Current | None:
        """The current, if any."""
    @property
    def seabed(self) -> Seabed | None:
        """The seabed, if any."""

@final
class Bathymetry:
    """The seabed's shape (elevations z in frame e, e3 down: larger z is deeper)."""

    @staticmethod
    def flat(z: float = 0.0) -> Bathymetry:
        """The horizontal plane at elevation z (m)."""
    @staticmethod
    def plane(z: float = 0.0, gradient: _ArrayLike | None = None) -> Bathymetry:
        """The plane b(x, y) = z + gradient[0]·x + gradient[1]·y (m)."""
    @staticmethod
    def grid(x: _ArrayLike, y: _ArrayLike, z: _ArrayLike) -> Bathymetry:
        """Elevations z (nx, ny) on a grid x (nx,), y (ny,), interpolated bilinearly (m)."""
    def elevation(self, x: float, y: float) -> float:
        """Seabed elevation b(x, y) (m, e3 down)."""

@final
class Seabed:
    """Seabed contact: stiffness k (Pa/m; force per length k·d·penetration), damping (Pa·s/m), Coulomb
    friction (axial, lateral), mobilisation distance (m) and bathymetry."""

    def __new__(
        cls,
        stiffness: float = 1e5,
        damping: float = 0.0,
        friction: float | _ArrayLike | None = None,
        mobilisation: float = 0.01,
        bathymetry: Bathymetry | None = None,
    ) -> Seabed: ...
    @property
    def stiffness(self) -> float:
        """Normal stiffness k (Pa/m)."""
    @property
    def damping(self) -> float:
        """Normal damping (Pa·s/m)."""
    @property
    def friction(self) -> tuple[float, float]:
        """Friction coefficients (axial, lateral)."""
    @property
    def mobilisation(self) -> float:
        """Mobilisation distance (m)."""
    @property
    def bathymetry(self) -> Bathymetry:
        """The seabed's shape."""

@final
class Touchdown:
    """Where the pipe leaves the seabed, seen from end A."""

    @property
    def arc_length(self) -> float:
        """Arc length along the reference from end A (m)."""
    @property
    def position(self) -> _FloatArray:
        """Position (3,) (m, in e)."""

@final
class State:
    """A configuration of the model and what follows from it (SI units, frame e)."""

    @property
    def positions(self) -> _FloatArray:
        """Node positions (n + 1, 3) (m)."""
    @property
    def rotations(self) -> _FloatArray:
        """Nodal rotations R_t^e (n + 1, 3, 3)."""
    @property
    def velocities(self) -> _FloatArray:
        """Nodal velocities (n + 1, 3) (m/s)."""
    @property
    def angular_velocities(self) -> _FloatArray:
        """Spatial angular velocities (n + 1, 3) (rad/s)."""
    @property
    def section_forces(self) -> _FloatArray:
        """Material force (N) and moment (N·m) at element midpoints (n, 6)."""
    @property
    def tension(self) -> _FloatArray:
        """Axial force at element midpoints (n,) (N)."""
    @property
    def eta(self) -> _FloatArray | None:
        """Vessel pose η (6,) in e, None without a vessel."""
    @property
    def nu(self) -> _FloatArray | None:
        """Vessel velocity ν (6,), body frame, None without a vessel."""
    @property
    def tau(self) -> _FloatArray | None:
        """Thrust τ (6,), body frame (statics: the holding thrust), None without a vessel."""
    @property
    def chi(self) -> _FloatArray | None:
        """The pipe's force and moment on the vessel (6,), body frame, None without a vessel."""
    @property
    def time(self) -> float:
        """Time (s): 0 for static states."""
    @property
    def load_factor(self) -> float:
        """Load factor reached (1.0 when converged, 0.0 for Model.rest())."""
    @property
    def iterations(self) -> int:
        """Newton iterations spent over all load steps."""
    @property
    def steps(self) -> int:
        """Accepted load steps."""
    def reaction(self, end: _End) -> _FloatArray:
        """Force (N) and moment (N·m) (6,) the rod exerts on the support at `end`, in e."""
    @property
    def touchdown(self) -> Touchdown | None:
        """Where the pipe leaves the seabed (None: no seabed or no contact)."""
    @property
    def seabed_reaction(self) -> _FloatArray | None:
        """The seabed's force on each node (n + 1, 3) (N, in e); None without a seabed."""
    @property
    def attachment_forces(self) -> _FloatArray:
        """What each attachment applies to the line (k, 3) (N, in e): weight less buoyancy and drag."""
    @property
    def laid_length(self) -> float | None:
        """Reference length of pipe on the seabed (m); None without a seabed."""
    @property
    def strain(self) -> _FloatArray:
        """Largest longitudinal strain per element (n,): axial plus bending at the outer fibre."""
    @property
    def roller_reactions(self) -> _FloatArray | None:
        """Normal force of each roller (k,) (N, ≥ 0; 0: lifted off); None without rollers."""
    @property
    def roller_reaction_vectors(self) -> _FloatArray | None:
        """Each roller's force on the pipe (k, 3), body frame (forward, starboard, down; N); None without
        rollers."""
    @property
    def roller_offsets(self) -> _FloatArray | None:
        """Each roller's contact along it from its centre (k,) (m; NaN out of contact); None without rollers."""
    @property
    def roller_supports(self) -> list[int]:
        """The support (lone roller or box, 0-based) of each roller (k,)."""
    def lay_summary(self) -> dict[str, Any] | None:
        """Top tension, departure angle, lift-off roller, layback, touchdown, overbend and sagbend strain,
        sagbend moment, tip clearance, tip offset and boxes left (SI units, rad); None without a vessel.
        `liftoff_roller` is the 0-based index of the last support in contact (a lone roller or a box, as in
        `roller_supports`; None: none), where people read the rollers numbered from 1."""
    @property
    def roller_positions(self) -> _FloatArray | None:
        """The rollers' top points (k, 3) in e (m) in this state; None without rollers."""
    @property
    def roller_lines(self) -> _FloatArray | None:
        """The ends of each roller's top line (k, 2, 3) in e (m): a box's roller's, its length long; a lone
        roller's top point twice. None without rollers."""
    @property
    def plastic_strain(self) -> _FloatArray | None:
        """Each element's largest plastic strain over its wall (n,); None without a yielding wall."""
    @property
    def residual_curvature(self) -> _FloatArray | None:
        """Each element's residual curvature |κ − m/EI| (n,) (1/m); None without a yielding wall."""
    @property
    def hinge_angles(self) -> _FloatArray:
        """An articulated stinger's hinge angles (h,) (rad; positive: the aft end down); empty without."""
    @property
    def section_lines(self) -> _FloatArray | None:
        """An articulated stinger's sections (h, 2, 3) in e (m): each one's hinge and far end; None without."""
    @property
    def reference_arc_length(self) -> _FloatArray:
        """Each node's arc length from end A along the stress-free reference (n + 1,) (m)."""
    @property
    def section(self) -> Section:
        """The model's cross-section: its first segment's (the whole line's for a line of one segment)."""
    @property
    def sections(self) -> list[Section]:
        """The cross-section of each segment of the line, from end A."""
    @property
    def segment_of(self) -> _IntArray:
        """The segment index of each element (n,)."""
    @property
    def water_depth(self) -> float | None:
        """The sea's depth (m); None without a sea."""
    @property
    def water_density(self) -> float | None:
        """The sea's density (kg/m³); None without a sea."""
    def energy(self) -> dict[str, float]:
        """Energy parts (J): pipe_kinetic, pipe_strain, pipe_gravity, vessel_kinetic, vessel_potential, seabed,
        rollers, total."""

@final
@final
class Stinger:
    """Rollers over a circular arc (body frame, m): `rollers` rollers on an arc of `radius` and `length` from
    `origin`, starting at the slope `angle` (rad below horizontal), running aft and bending down; with
    `boxes`, a roller box at each roller's place (or at the box's own arc length) instead."""

    def __new__(
        cls,
        radius: float,
        length: float,
        rollers: int,
        *,
        origin: _ArrayLike | None = None,
        angle: float = 0.0,
        roller_radius: float = ...,
        boxes: Sequence[RollerBox] | None = None,
    ) -> Stinger: ...
    @staticmethod
    def from_rollers(
        positions: _ArrayLike, axes: _ArrayLike | None = None, roller_radius: float = ...
    ) -> Stinger:
        """Rollers at given top points (k, 3) with axes (k, 3) (default b2), body frame (m)."""
    @staticmethod
    def articulated(
        sections: Sequence[StingerSection],
        radius: float,
        rollers: int,
        *,
        fixed_length: float = 0.0,
        origin: _ArrayLike | None = None,
        angle: float = 0.0,
        roller_radius: float = ...,
        boxes: Sequence[RollerBox] | None = None,
    ) -> Stinger:
        """An arc whose first `fixed_length` (m) is on the vessel and whose `sections` follow, each hinged to
        the one before about b2; its supports as a `Stinger`'s, each on the section that carries its place."""
    @property
    def sections(self) -> list[StingerSection]:
        """The hinged sections (empty unless articulated)."""
    @property
    def hinges(self) -> _FloatArray:
        """Each section's hinge (h, 3), body frame (m), at zero hinge angles."""
    @property
    def roller_sections(self) -> list[int]:
        """The section each roller rides on (k,), -1 on the vessel."""
    @property
    def positions(self) -> _FloatArray:
        """The rollers' top points (k, 3), body frame (m)."""
    @property
    def stations(self) -> _FloatArray:
        """Each support's station on the stinger's top line (m, 3), body frame (m)."""
    @property
    def supports(self) -> list[int]:
        """The support (lone roller or box, 0-based) of each roller (k,)."""
    @property
    def axes(self) -> _FloatArray:
        """Each roller's axis (k, 3), unit, body frame."""
    @property
    def lengths(self) -> list[float]:
        """Each roller's length (k,) (m; inf for lone rollers)."""
    def __len__(self) -> int: ...

@final
class Material:
    """The pipe steel's uniaxial law (Pa), unloading by Masing's rule."""

    @staticmethod
    def elastic(E: float) -> Material: ...
    @staticmethod
    def elastic_perfectly_plastic(E: float, yield_stress: float) -> Material: ...
    @staticmethod
    def ramberg_osgood(E: float, yield_stress: float, n: float) -> Material: ...
    @staticmethod
    def table(strain: Sequence[float], stress: Sequence[float]) -> Material: ...
    @staticmethod
    def grade(name: str, n: float = ..., E: float = ...) -> Material: ...
    @property
    def youngs_modulus(self) -> float: ...
    @property
    def kind(self) -> str: ...
    def stress_strain(self, strain: Sequence[float]) -> _FloatArray:
        """The stresses (Pa) along a path of strains from rest."""

@final
class Straightener:
    """A reel-lay straightener: the curvature (1/m) of its reverse bending."""

    def __new__(cls, curvature: float) -> Straightener: ...
    @property
    def curvature(self) -> float: ...

@final
class ReelLay:
    """Reel-lay: reel and aligner (centreline radii, m), a straightener, and the ramp (its exit `position`,
    body frame, m; `ramp_angle` from the vertical toward the bow, rad) the pipe hangs from."""

    def __new__(
        cls,
        reel_radius: float,
        aligner_radius: float,
        straightener: Straightener | None = None,
        position: _ArrayLike | None = None,
        ramp_angle: float = 0.0,
    ) -> ReelLay: ...
    def history(self, section: Section, axial_strain: float = 0.0) -> dict[str, Any]:
        """A pipe section's curvature, moment, strain and stage along the reeling, its residual curvature and
        accumulated plastic strain."""
    @property
    def reel_radius(self) -> float: ...
    @property
    def aligner_radius(self) -> float: ...
    @property
    def straightener(self) -> Straightener: ...
    @property
    def position(self) -> tuple[float, float, float] | None: ...
    @property
    def ramp_angle(self) -> float: ...

def design_straightener(
    section: Section, reel_radius: float, aligner_radius: float, axial_strain: float = 0.0
) -> Straightener:
    """The straightener that leaves the pipe straight after the reel and the aligner."""

@final
class StingerSection:
    """A hinged section of an articulated stinger: `length` (m) of the arc, `mass` (kg), constant `buoyancy`
    (N, up), a hinge spring `hinge_stiffness` (N·m/rad) within `hinge_limits` (rad, min ≤ 0 ≤ max; positive:
    the aft end down), drag area `drag_area` (C_d A, m²), added mass `added_mass` (kg)."""

    def __new__(
        cls,
        length: float,
        mass: float,
        buoyancy: float,
        hinge_stiffness: float = 0.0,
        hinge_limits: Sequence[float] = ...,
        drag_area: float = 0.0,
        added_mass: float = 0.0,
    ) -> StingerSection: ...
    @property
    def length(self) -> float: ...
    @property
    def mass(self) -> float: ...
    @property
    def buoyancy(self) -> float: ...
    @property
    def hinge_stiffness(self) -> float: ...
    @property
    def hinge_limits(self) -> tuple[float, float]: ...
    @property
    def drag_area(self) -> float: ...
    @property
    def added_mass(self) -> float: ...

@final
class RollerBox:
    """A roller box: a V of two rollers at ±`half_angle` (rad) from the lateral, with an optional bottom
    roller and side rollers, or a U (bottom and sides), every roller `roller_length` (m) long, at
    `arc_length` (m) along the stinger (None: the place of the roller it replaces). Its rollers turn against
    `rolling_resistance` (along the pipe) and resist sliding along them with Coulomb `friction`; `locked`
    rollers resist with `friction` every way."""

    def __new__(
        cls,
        arc_length: float | None = None,
        kind: str = "v",
        half_angle: float = ...,
        roller_length: float = 1.2,
        bottom: bool = False,
        sides: bool = False,
        friction: float = 0.0,
        rolling_resistance: float = 0.0,
        locked: bool = False,
    ) -> RollerBox: ...
    @property
    def arc_length(self) -> float | None: ...
    @property
    def kind(self) -> str: ...
    @property
    def half_angle(self) -> float: ...
    @property
    def roller_length(self) -> float: ...
    @property
    def bottom(self) -> bool: ...
    @property
    def sides(self) -> bool: ...
    @property
    def friction(self) -> float: ...
    @property
    def rolling_resistance(self) -> float: ...
    @property
    def locked(self) -> bool: ...

@final
class SLay:
    """S-lay: the pipe held by the tensioner (body frame, m) on a horizontal firing line, over a stinger."""

    def __new__(
        cls,
        tensioner: _ArrayLike,
        stinger: Stinger | None = None,
        friction: float = 0.0,
        *,
        roller_stiffness: float = ...,
    ) -> SLay: ...
    @property
    def tensioner(self) -> tuple[float, float, float]:
        """The tensioner's position (body frame, m)."""
    @property
    def stinger(self) -> Stinger:
        """The rollers."""

@final
class JLay:
    """J-lay: the pipe held at the tower exit (body frame, m), the tower leaning `angle` (rad) from vertical;
    `guide` (m): a bellmouth of that bend radius at the exit, `guide_opening` (m) across at its narrowest."""

    def __new__(
        cls, position: _ArrayLike, angle: float = 0.0, guide: float | None = None, guide_opening: float = 1.0
    ) -> JLay: ...
    @property
    def guide(self) -> float | None:
        """The guide's bend radius (m), None without a guide."""
    @property
    def position(self) -> tuple[float, float, float]:
        """The tower exit's position (body frame, m)."""

@final
class Vessel:
    """A DP vessel: M = M_RB + M_A, damping D and restoring G (6×6, about CO)."""

    def __new__(
        cls,
        M: _ArrayLike,
        D: _ArrayLike,
        G: _ArrayLike,
        *,
        M_RB: _ArrayLike | None = None,
        quadratic_damping: _ArrayLike | None = None,
        raos: Raos | None = None,
        length: float | None = None,
        thrusters: Sequence[Thruster] | None = None,
        wind_coefficients: HullCoefficients | None = None,
        current_coefficients: HullCoefficients | None = None,
        drift_coefficients: DriftCoefficients | None = None,
    ) -> Vessel: ...
    @property
    def thrusters(self) -> list[Thruster]:
        """Its thrusters (the OSV: the six of Fossen's MSS supply vessel)."""
    @property
    def length(self) -> float | None:
        """Overall length (m), if given."""
    @property
    def wind_coefficients(self) -> HullCoefficients | None:
        """Wind coefficients of the hull (m², m³), if any."""
    @property
    def current_coefficients(self) -> HullCoefficients | None:
        """Current coefficients of the hull (m², m³), if any."""
    @property
    def drift_coefficients(self) -> DriftCoefficients | None:
        """Mean wave-drift coefficients (N/m², N·m/m²), if any."""
    def allocate(self, tau: _ArrayLike) -> Allocation:
        """One allocation of a commanded τ (6,) (body frame) to the thrusters, without rate limits."""
    @staticmethod
    def osv(raos: Raos | None = None) -> Vessel:
        """The 83 m offshore supply vessel of Fossen's MSS toolbox, with its Capytaine RAOs or `raos`, the six
        thrusters of the MSS supply vessel, its length and its wind, current and wave-drift tables."""
    @property
    def raos(self) -> Raos | None:
        """First-order displacement RAOs (its wave-frequency motion in waves), if any."""
    @property
    def M(self) -> _FloatArray:
        """M = M_RB + M_A (6, 6)."""
    @property
    def M_RB(self) -> _FloatArray:
        """Rigid-body mass (6, 6)."""
    @property
    def M_A(self) -> _FloatArray:
        """Added mass (6, 6)."""
    @property
    def D(self) -> _FloatArray:
        """Linear damping (6, 6)."""
    @property
    def G(self) -> _FloatArray:
        """Restoring (6, 6)."""
    def coriolis(self, nu: _ArrayLike) -> _FloatArray:
        """C(ν) = C_RB(ν) + C_A(ν) (6, 6)."""

@final
class Raos:
    """First-order displacement RAOs: for the elevation a cos(ωt) at CO, DOF j moves |R_j| a cos(ωt + arg R_j)
    (surge, sway, heave m/m; roll, pitch, yaw rad/m; body frame, z down), per period and relative heading
    (deg: 0 following seas, 180 head seas)."""

    @staticmethod
    def osv() -> Raos:
        """The built-in OSV's table (Capytaine, scripts/osv_raos.py)."""
    @staticmethod
    def read(path: str | os.PathLike[str]) -> Raos:
        """A table from a CSV file: period_s, heading_deg, <dof>_amp, <dof>_phase (rad) on a full grid."""
    @property
    def periods(self) -> _FloatArray:
        """Periods (s, increasing)."""
    @property
    def frequencies(self) -> _FloatArray:
        """2π/period (rad/s), one per period."""
    @property
    def headings(self) -> _FloatArray:
        """Relative headings (deg, increasing in [0, 360))."""
    @property
    def values(self) -> npt.NDArray[np.complex128]:
        """Complex RAOs (periods, headings, 6)."""
    def at(self, period: float, heading: float) -> npt.NDArray[np.complex128]:
        """The 6 complex RAOs at a period (s) and relative heading (deg), interpolated bilinearly."""

@final
class Route:
    """A lay route for a DP reference: from `start` (x, y) at `start_time` along `heading` at `speed` (m/s)."""

    def __new__(
        cls, start: _ArrayLike, heading: float = 0.0, speed: float = 0.0, start_time: float = 0.0
    ) -> Route: ...
    @staticmethod
    def legs(
        waypoints: _ArrayLike, radius: float = 0.0, speed: float = 0.0, start_time: float = 0.0
    ) -> Route:
        """A route through `waypoints` (k, 2) with its corners cut by arcs of `radius` (m), travelled at `speed`
        (m/s) from `start_time` (s), the heading along the path; it stops at the last waypoint."""
    def at(self, t: float) -> tuple[_FloatArray, _FloatArray]:
        """η_ref and η̇_ref (6,) each at time t (s)."""

@final
class TensionControl:
    """The lay-tension loop: moves the DP set-point along the reference's heading at −gain·(T − target) m/s."""

    def __new__(
        cls,
        target: float,
        gain: float,
        start: float = 0.0,
        rate_limit: float | None = None,
        filter: float = 20.0,
    ) -> TensionControl: ...
    @property
    def target(self) -> float:
        """Target top tension (N)."""

@final
class PID:
    """PID on η: τ = −Jᵀ(η)(K_p η̃ + K_d η̃̇ + K_i ∫η̃), η̃ = η − η_ref(t), from `start` (s); the reference is
    η_ref (6,), a pl.Route or a callable of t (with `reference_rate`, or central differences). With
    `allocation="qp"` its command goes to the vessel's thrusters through a QP each step; with `observer` it acts
    on the observer's estimate (both make it a loop sampled once per step). With `bumpless` (the default), a
    controller that starts after t = 0 takes the static holding thrust τ_h over in its integral: −Jᵀ(η)K_i z₀ =
    τ_h in surge, sway and yaw where K_i reaches, so the thrust is continuous at `start` with the vessel at its
    reference; `bumpless=False` starts ∫η̃ at 0 (the paper's PID). `passivity="certify"`: the time-domain passivity
    observer and controller keep the controller's work on the vessel within its storage at the start, every step
    (about a fixed reference); "observe": the observer books it, nothing more."""

    def __new__(
        cls,
        kp: _ArrayLike,
        kd: _ArrayLike,
        ki: _ArrayLike | None = None,
        reference: _ArrayLike | Route | Callable[[float], _ArrayLike] | None = None,
        start: float = 0.0,
        integral_limit: _ArrayLike | None = None,
        thrust_limit: _ArrayLike | None = None,
        reference_rate: Callable[[float], _ArrayLike] | None = None,
        tension: TensionControl | None = None,
        allocation: Literal["qp"] | None = None,
        observer: Observer | None = None,
        bumpless: bool = True,
        passivity: Literal["observe", "certify"] | None = None,
    ) -> PID: ...
    @staticmethod
    def external(
        law: Callable[[float, float, _FloatArray, _FloatArray], _ArrayLike],
        start: float = 0.0,
        thrust_limit: _ArrayLike | None = None,
        allocation: Literal["qp"] | None = None,
        observer: Observer | None = None,
        passivity: Literal["observe", "certify"] | None = None,
    ) -> PID:
        """A controller whose command comes from outside pipelay: `law(t, dt, eta, nu)` returns τ (6,) over the
        step from t to t + dt (s) (body frame: N, N·m; surge, sway and yaw kept, within `thrust_limit` (3,)) from
        the pose η (6,) and velocity ν (6,) the loop sees at t (the observer's estimate, if given, else the
        low-frequency pose and velocity), called once per time step at its start from `start` (s);
        `allocation="qp"` sends it to the thrusters. Statics hold the vessel by the holding thrust, which is the
        command until the law's first. `pl.Controller.fmu` makes the law of a controller FMU."""
    @property
    def is_external(self) -> bool:
        """Whether the command comes from outside pipelay (`PID.external`)."""
    @property
    def passivity(self) -> Literal["observe", "certify"] | None:
        """ "certify" if the time-domain passivity controller certifies the loop, "observe" if its observer only
        books the controller's work, else None."""
    @property
    def reference(self) -> _FloatArray:
        """η_ref (6,) at t = 0."""
    def reference_at(self, t: float) -> tuple[_FloatArray, _FloatArray]:
        """η_ref and η̇_ref (6,) each at time t (s)."""
    @property
    def start(self) -> float:
        """Start time (s)."""
    @property
    def bumpless(self) -> bool:
        """Whether the controller takes the holding thrust over in its integral at its start."""

@final
class Thruster:
    """A thruster: "tunnel" (pushes to starboard when positive), "azimuth" (along an azimuth it turns) or
    "main" (ahead when positive), at (l_x, l_y) (m, body frame from CO), with thrust limits (N), rates (N/s,
    rad/s) and the time constant of its thrust's response (s)."""

    def __new__(
        cls,
        kind: Literal["tunnel", "azimuth", "main"],
        position: _ArrayLike,
        max_thrust: float,
        reverse_thrust: float | None = None,
        thrust_rate: float | None = None,
        azimuth_rate: float | None = None,
        time_constant: float = 1.0,
    ) -> Thruster: ...
    @property
    def kind(self) -> str:
        """ "tunnel", "azimuth" or "main"."""
    @property
    def position(self) -> tuple[float, float]:
        """(l_x, l_y) (m, body frame from CO)."""
    @property
    def max_thrust(self) -> float:
        """Largest forward thrust (N)."""
    @property
    def reverse_thrust(self) -> float:
        """Largest reverse thrust (N)."""
    @property
    def thrust_rate(self) -> float | None:
        """Bound on the thrust's rate (N/s), if any."""
    @property
    def azimuth_rate(self) -> float | None:
        """Bound on the azimuth's rate (rad/s), if any."""
    @property
    def time_constant(self) -> float:
        """Time constant of the thrust's response (s)."""

@final
class Allocation:
    """One thrust allocation: each thruster's thrust and azimuth, the τ delivered, and whether it saturated."""

    @property
    def thrust(self) -> _FloatArray:
        """Each thruster's thrust (k,) (N)."""
    @property
    def azimuth(self) -> _FloatArray:
        """Each thruster's azimuth (k,) (rad)."""
    @property
    def tau(self) -> _FloatArray:
        """The τ delivered (6,) (body frame)."""
    @property
    def saturated(self) -> bool:
        """Whether the thrusters could not deliver the command."""

@final
class Observer:
    """A position observer for the DP controller."""

    @staticmethod
    def passive(noise: _ArrayLike | None = None, seed: int = 0, wave_period: float | None = None) -> Observer:
        """Fossen's nonlinear passive observer on x, y, ψ measured with Gaussian noise of standard deviations
        `noise` (m, m, rad) from `seed`; its notch at `wave_period` (s; None: the sea's peak period)."""
    @property
    def noise(self) -> tuple[float, float, float]:
        """Noise standard deviations (m, m, rad)."""
    @property
    def seed(self) -> int:
        """The noise's seed."""

@final
class Wind:
    """Wind of 1-hour mean speed (m/s at 10 m) blowing toward `direction` (rad, from e1 toward e2), with
    NPD gusts (ISO 19901-1) or steady (spectrum None)."""

    def __new__(
        cls, speed: float, direction: float = 0.0, spectrum: str | None = ..., seed: int = 0
    ) -> Wind: ...
    @property
    def speed(self) -> float:
        """Mean speed (m/s)."""
    @property
    def direction(self) -> float:
        """Direction it blows toward (rad)."""
    def speed_at(self, t: float) -> float:
        """Mean plus gust at time t (s) (m/s)."""

@final
class HullCoefficients:
    """Coefficients C_j(γ) (m², m³) of a flow's load on the hull, F_j = ½ρV_r²C_j(γ), by the relative angle γ
    the flow travels toward (deg from the bow toward starboard)."""

    def __new__(cls, angles: _ArrayLike, values: _ArrayLike) -> HullCoefficients: ...
    @staticmethod
    def read(path: str | os.PathLike[str]) -> HullCoefficients:
        """A table from a CSV file: angle_deg, surge, sway, heave, roll, pitch, yaw."""
    @property
    def angles(self) -> _FloatArray:
        """Angles (n,) (deg)."""
    @property
    def values(self) -> _FloatArray:
        """Coefficients (n, 6) (m², m³)."""
    def at(self, angle: float) -> _FloatArray:
        """C(γ) (6,) at a relative angle (deg)."""
    def load(self, density: float, relative: _ArrayLike) -> _FloatArray:
        """½ρV_r²C(γ) (6,) for a flow of velocity (2,) relative to the vessel, body frame (m/s)."""

@final
class DriftCoefficients:
    """Mean wave-drift coefficients (N/m², N·m/m²) per period and relative heading (deg, as the RAOs')."""

    @staticmethod
    def read(path: str | os.PathLike[str]) -> DriftCoefficients:
        """A table from a CSV file: period_s, heading_deg, surge, sway, heave, roll, pitch, yaw."""
    @property
    def periods(self) -> _FloatArray:
        """Periods (s)."""
    @property
    def headings(self) -> _FloatArray:
        """Headings (deg)."""
    @property
    def values(self) -> _FloatArray:
        """D (periods, headings, 6)."""
    def at(self, period: float, heading: float) -> _FloatArray:
        """D (6,) at a period (s) and relative heading (deg)."""

def dp_capability_wind(
    vessel: Vessel,
    headings: _ArrayLike,
    pipe_load: _ArrayLike,
    current: float = 0.75,
    max_wind: float = 60.0,
) -> _FloatArray:
    """The largest wind speed (m/s) held at each heading (rad, environment from, relative to the bow)."""

def environment_load(vessel: Vessel, wind_speed: float, heading: float, current: float = 0.75) -> _FloatArray:
    """The mean environmental load (6,) (body frame) of a wind speed from a heading, with its current and sea."""

@final
class Force:
    """A constant environmental force and moment (6,) on the vessel, body frame, from `start` (s)."""

    def __new__(cls, value: _ArrayLike, start: float = 0.0) -> Force: ...
    @property
    def value(self) -> _FloatArray:
        """The force and moment (6,)."""
    @property
    def start(self) -> float:
        """Start time (s)."""

@final
class Simulation:
    """A time simulation of a model (energy–momentum conserving integrator)."""

    def __new__(
        cls,
        model: Model,
        state: State | None = None,
        dt: float = 0.05,
        stages: Stages | None = None,
        high_frequency_damping: float = 0.0,
    ) -> Simulation: ...
    @property
    def high_frequency_damping(self) -> float:
        """The high-frequency damping ξ of the line's strains (0: energy conserving)."""
    def step(self) -> None:
        """Advance one time step dt."""
    def run(
        self,
        t_end: float | None = None,
        progress: bool = True,
        record_every: int = 1,
        *,
        output: str | os.PathLike[str] | None = None,
        record: str | Sequence[str] | None = None,
    ) -> Results:
        """Run to t_end (s; default: the end of the stages), recording the current state and every
        record_every-th step after it.

        Without `output`: returns every record in memory. With `output` (a path): the records are streamed to
        that netCDF file as the run goes (memory stays flat); it is `<output>.part` until the run ends, fails or
        is interrupted, then renamed; returns a Results of the last record only (the whole series: pl.load).
        `record`: None (everything) or groups from "positions", "rotations", "velocities", "section_forces",
        "reactions", "energy", "vessel", "seabed", "lay"; time always."""
    @property
    def time(self) -> float:
        """Current time (s)."""
    @property
    def dt(self) -> float:
        """Time step (s)."""
    @property
    def state(self) -> State:
        """The current state."""
    @property
    def eta_low_frequency(self) -> _FloatArray | None:
        """The vessel's low-frequency pose now (6,) in e (m, rad), what the DP controls; None without a vessel."""
    @property
    def energy(self) -> float:
        """The system's energy now (J): the ledger's total, E(t) − E(0) = W(t) − D(t)."""
    @property
    def supplied_work(self) -> float:
        """Work supplied since the simulation started (J)."""
    @property
    def dissipated(self) -> float:
        """Energy dissipated since the simulation started (J)."""
    def linear_momentum(self) -> tuple[float, float, float]:
        """Linear momentum (kg·m/s)."""
    def angular_momentum(self) -> tuple[float, float, float]:
        """Angular momentum about the origin (kg·m²/s)."""
    def checkpoint(self, path: str | os.PathLike[str]) -> Path:
        """Save the complete state (atomically); pl.resume continues it exactly."""
    @property
    def stage_names(self) -> list[str] | None:
        """The stages' names, None without stages."""
    @property
    def stage_starts(self) -> list[float] | None:
        """Each stage's start time and the last one's end (s), None without stages."""
    @property
    def pipe_walls(self) -> list[tuple[float, float] | None]:
        """Each segment's steel wall (outer diameter, wall thickness) (m); None for one without."""
    @property
    def water(self) -> tuple[float, float] | None:
        """The sea's (depth (m), density (kg/m³)), None without a sea."""
    @property
    def stages_end(self) -> float | None:
        """The end of the last stage (s), None without stages."""
    @property
    def winch_tension_limit(self) -> float | None:
        """The A&R winch's tension limit (N), None without a winch or a limit."""
    @property
    def winch_wire_segment(self) -> int | None:
        """The segment index of the A&R winch's wire (in Results.segment), None without a winch."""
    @property
    def hand_over_tension(self) -> float | None:
        """The axial force the A&R wire took on at the hand-over (N), None if none happened in this run."""
    @property
    def hand_back_time(self) -> float | None:
        """When the tensioner took the pipe back from the A&R winch (s), None if no hand-back happened in this
        run."""

@final
class Results:
    """Time series of a run (SI units, frame e)."""

    @property
    def time(self) -> _FloatArray:
        """Times (T,) (s)."""
    @property
    def positions(self) -> _FloatArray:
        """Node positions (T, n + 1, 3) (m)."""
    @property
    def rotations(self) -> _FloatArray:
        """Nodal rotations (T, n + 1, 3, 3)."""
    @property
    def velocities(self) -> _FloatArray:
        """Node velocities (T, n + 1, 3) (m/s)."""
    @property
    def section_forces(self) -> _FloatArray:
        """Material force and moment at element midpoints (T, n, 6)."""
    @property
    def segment(self) -> _FloatArray:
        """The segment of each element (T, n), as a float: NaN where a record had fewer elements."""
    @property
    def tension(self) -> _FloatArray:
        """Axial force at element midpoints (T, n) (N)."""
    def reaction(self, end: _End) -> _FloatArray:
        """Force and moment the rod exerts on the support at `end` (T, 6), in e."""
    @property
    def touchdown(self) -> _FloatArray | None:
        """Touchdown positions (T, 3) (m), NaN rows without contact; None without a seabed."""
    @property
    def touchdown_arc_length(self) -> _FloatArray | None:
        """Touchdown arc length from end A (T,) (m), NaN without contact; None without a seabed."""
    @property
    def laid_length(self) -> _FloatArray | None:
        """Reference length of pipe on the seabed (T,) (m); None without a seabed."""
    @property
    def roller_reactions(self) -> _FloatArray | None:
        """Normal force of each roller (T, k) (N); None without rollers."""
    def lay_summary(self) -> dict[str, _FloatArray] | None:
        """The lay summary over time: (T,) arrays with State.lay_summary()'s keys; None without a vessel."""
    @property
    def roller_reaction_vectors(self) -> _FloatArray | None:
        """Each roller's force on the pipe (T, k, 3), body frame (N); None without rollers or from older files."""
    @property
    def hinge_angles(self) -> _FloatArray | None:
        """An articulated stinger's hinge angles (T, h) (rad); None without."""
    @property
    def energy(self) -> dict[str, _FloatArray]:
        """Energy parts (T,) each (J), keys as State.energy()."""
    @property
    def supplied_work(self) -> _FloatArray:
        """Work done on the system since the start of the run (T,) (J)."""
    @property
    def length(self) -> _FloatArray:
        """Unstretched pipe length at each record (T,) (m)."""
    @property
    def pay_out_speed(self) -> _FloatArray:
        """The pay-out speed of the step that led to each record (T,) (m/s; the A&R winch's once it holds)."""
    @property
    def pay_out_energy(self) -> _FloatArray:
        """Energy pay-out brought in since the start of the run (T,) (J), part of supplied_work."""
    @property
    def dissipated(self) -> _FloatArray:
        """Energy dissipated since the start of the run (T,) (J)."""
    @property
    def iterations(self) -> _FloatArray:
        """Newton iterations of the step leading to each record (T,)."""
    @property
    def substeps(self) -> _FloatArray:
        """The most substeps any step since the record before was taken in (T,): 1 where no step was split."""
    @property
    def eta(self) -> _FloatArray | None:
        """Vessel pose η (T, 6) in e: its total motion (low and wave frequency), None without a vessel."""
    @property
    def eta_low_frequency(self) -> _FloatArray | None:
        """The low-frequency pose (T, 6), what the DP controls, None without a vessel."""
    @property
    def eta_wave_frequency(self) -> _FloatArray | None:
        """The wave-frequency motion η − η_LF (T, 6), angles wrapped, None without a vessel."""
    @property
    def eta_estimate(self) -> _FloatArray | None:
        """The observer's estimate of the low-frequency pose (T, 6), None without an observer."""
    @property
    def tau_commanded(self) -> _FloatArray | None:
        """The controller's command τ_c (T, 6), body frame (N, N·m), None without a vessel."""
    @property
    def thrust(self) -> _FloatArray | None:
        """Each thruster's delivered thrust (T, k) (N), None without allocation."""
    @property
    def azimuth(self) -> _FloatArray | None:
        """Each thruster's azimuth (T, k) (rad), None without allocation."""
    @property
    def nu(self) -> _FloatArray | None:
        """Vessel velocity ν (T, 6), body frame, None without a vessel."""
    @property
    def tau(self) -> _FloatArray | None:
        """Thrust applied τ (T, 6), body frame, None without a vessel."""
    @property
    def chi(self) -> _FloatArray | None:
        """The pipe's force and moment on the vessel χ (T, 6), body frame, None without a vessel."""
    def passivity_margin(self, loop: bool = False) -> float:
        """max over t of E(t) − E(0) − W(t) (J), W the supplied work: the plant's certificate, at round-off. With
        `loop=True`, the closed loop's, for a controller that certifies it (`passivity="certify"`): max over t of
        E(t) − E(0) − W(t) − R(t), R the `passivity_reserve`; ≤ 0 when certified."""
    @property
    def passivity_reserve(self) -> _FloatArray | None:
        """The energy a certifying controller may still give the vessel (T,) (J): its storage at the start less
        its work since; ≥ 0 when certified. None without one."""
    @property
    def passivity_withheld(self) -> _FloatArray | None:
        """The controller's work the passivity controller withheld since the simulation started (T,) (J); None
        without one."""
    @property
    def passivity_steps(self) -> _FloatArray | None:
        """The steps the passivity controller acted in since the simulation started (T,); None without one."""
    @property
    def nodes(self) -> int:
        """Number of nodes n + 1."""
    def to_xarray(self) -> Any:
        """The results as an xarray.Dataset (dimensions time, node, element, axis, column, dof; units)."""
    def to_netcdf(self, path: str | os.PathLike[str]) -> Path:
        """Write a netCDF-4 file atomically; pl.load reads it back exactly."""
    def __len__(self) -> int: ...
    @property
    def stage(self) -> _IntArray | None:
        """The stage of each record (T,), None for a run without stages."""
    @property
    def stage_names(self) -> list[str] | None:
        """The stages' names, None without stages."""
    @property
    def stage_starts(self) -> _FloatArray | None:
        """Each stage's start time and the last one's end (s), None without stages."""
    @property
    def pipe_walls(self) -> list[tuple[float, float] | None]:
        """Each segment's steel wall (outer diameter, wall thickness) (m), from end A; None for a segment
        without one (a cable, a section given by its stiffnesses); [] when the results do not say."""
    @property
    def water(self) -> tuple[float, float] | None:
        """The sea's (depth (m), density (kg/m³)) of the run; None without a sea or when not recorded."""
    def _with_line(
        self, walls: list[tuple[float, float] | None], water: tuple[float, float] | None
    ) -> Results: ...
    def stage_summary(self, model: Model | None = None, checks: Mapping[str, Any] | None = None) -> Any:
        """Per stage, the extremes users check (a pandas.DataFrame): see pipelay.analysis.stages."""
    def view(self, model: Model | None = None, **options: Any) -> Any:
        """The 3-D replay of the run (a plotly Figure, shown in Jupyter): see pipelay.plots.replay."""

@final
class Model:
    """A rod with its sea, gravity (m/s², along +e3), supports and loads."""

    def __new__(cls, rod: Rod, sea: Sea | None = None, gravity: float = 9.81) -> Model: ...
    def clamp(
        self, end: _End, position: _ArrayLike | None = None, rotation: _ArrayLike | None = None
    ) -> None:
        """Clamp an end: position (3,) (m) and rotation (3, 3) held (defaults: the reference)."""
    def pin(self, end: _End, position: _ArrayLike | None = None) -> None:
        """Pin an end: position (3,) (m) held, rotation free (default: the reference node)."""
    def drive(
        self,
        end: _End,
        position: Callable[[float], _ArrayLike] | _ArrayLike,
        velocity: Callable[[float], _ArrayLike] | _ArrayLike | None = None,
        rotation: Callable[[float], _ArrayLike] | None = None,
    ) -> None:
        """Drive an end: position(t) (m), initial velocity(t) (m/s), rotation(t) (3, 3); free rotation without it.
        position and velocity may be tables of rows [t, x, y, z] (interpolated in the engine, no Python per
        step); a position table's slope is then the default velocity."""
    def attach_vessel(
        self,
        end: _End,
        vessel: Vessel,
        *,
        eta: _ArrayLike,
        angle: _ArrayLike | None = None,
        controller: PID | None = None,
        environment: Sequence[Force] | None = None,
        lay: SLay | JLay | ReelLay | None = None,
        winch: Winch | None = None,
        hull_loads: bool = False,
    ) -> None:
        """Attach a vessel at `end`: starting pose eta (6,), clamp angle β (zyx, rad), controller, forces; or
        held by lay equipment (`lay`), with an A&R winch (`winch`) to hand the line over to. η's z must lie at
        the sea surface z = −depth within 10 m (at most half the depth) and above the seabed under the vessel. `hull_loads`: the
        sea's wind, current and waves act on the hull through the vessel's coefficient tables (mean and
        slowly varying drift); off, the hull feels only `environment` (the paper's model)."""
    def simulation(
        self,
        state: State | None = None,
        dt: float = 0.05,
        stages: Stages | None = None,
        high_frequency_damping: float = 0.0,
    ) -> Simulation:
        """A time simulation from `state` (default: self.static()) with time step `dt` (s), through `stages`,
        with the high-frequency damping ξ of the line's strains (0: energy conserving)."""
    def pay_out(
        self,
        end: _End = "B",
        speed: float | Callable[[float], float] | _ArrayLike | None = None,
        feed: Sequence[tuple[float, Section]] | None = None,
    ) -> None:
        """Pay pipe out (speed > 0, m/s) or in (< 0) at the vessel's or a driven end during a simulation; speed:
        a number, a callable of t or a table of rows [t, speed]. `feed`: the line still on board, (length (m),
        Section) parts in the order they are paid out after the end's segment."""
    def attach(self, arc_length: float, attachment: Clump) -> int:
        """Attaches a clump, buoyancy module or in-line structure at `arc_length` (m from end A along the
        reference); returns its index (its row of State.attachment_forces)."""
    def point_load(
        self,
        node: int | _End,
        force: _ArrayLike | None = None,
        moment: _ArrayLike | None = None,
        scale: Callable[[float], float] | None = None,
    ) -> None:
        """A fixed-direction force (N) and moment (N·m) in e at a node."""
    def static(
        self, steps: int | None = None, start: Literal["auto", "reference", "catenary"] = "auto"
    ) -> State:
        """Static equilibrium; raises ConvergenceError with the load factor reached."""
    def rest(self) -> State:
        """The reference configuration at rest, without solving."""
    @property
    def rod(self) -> Rod:
        """The rod."""
    @property
    def sea(self) -> Sea | None:
        """The sea, if any."""
    @property
    def vessel(self) -> Vessel | None:
        """The vessel attached to the model, if any."""
    @property
    def reel_lay(self) -> ReelLay | None:
        """The reel-lay equipment the vessel holds the pipe with, None for other lay equipment or none."""
    @property
    def gravity(self) -> float:
        """Gravitational acceleration (m/s²)."""
    @property
    def submerged_weight(self) -> float:
        """Submerged weight per unit length (N/m)."""

@final
class Winch:
    """An A&R winch on the vessel: where its wire enters the firing line (body frame), its rating, its wire,
    the length of the wire elements it pays out and the laydown head fitted at the hand-over."""

    def __new__(
        cls,
        position: _ArrayLike,
        tension_limit: float | None = None,
        *,
        wire: Section | None = None,
        element_length: float | None = None,
        head: Clump | None = None,
        head_length: float | None = None,
        head_diameter: float | None = None,
        speed_limit: float | None = None,
        acceleration_limit: float | None = None,
        tension_band: float | None = None,
    ) -> Winch: ...
    @property
    def position(self) -> list[float]:
        """Where the wire enters the firing line (3,) (body frame, m)."""
    @property
    def tension_limit(self) -> float | None:
        """The wire's rating (N), None for none."""
    @property
    def head_body(self) -> tuple[float, float] | None:
        """The head body's length and diameter (m), None for a point head."""
    @property
    def speed_limit(self) -> float:
        """The drive's largest speed either way (m/s)."""
    @property
    def acceleration_limit(self) -> float:
        """The drive's largest change of speed (m/s²)."""
    @property
    def tension_band(self) -> float:
        """The constant-tension mode's band and the rendering's, below the limit (N)."""

@final
class Stage:
    """One stage of a lay: a name, a duration (s) and what changes at its start."""

    def __new__(
        cls,
        name: str,
        duration: float | None = None,
        *,
        pay_out: float | None = None,
        route_speed: float | None = None,
        hold: Literal["tensioner", "winch"] | None = None,
        winch_speed: float | None = None,
        winch_tension: float | None = None,
        setpoint: _ArrayLike | None = None,
        statics: bool = False,
        ramp: float | None = None,
    ) -> Stage: ...
    @property
    def name(self) -> str: ...
    @property
    def duration(self) -> float:
        """Duration (s)."""
    @property
    def pay_out(self) -> float | None: ...
    @property
    def route_speed(self) -> float | None: ...
    @property
    def hold(self) -> str | None: ...
    @property
    def winch_speed(self) -> float | None: ...
    @property
    def winch_tension(self) -> float | None:
        """The tension the winch holds in constant-tension mode (N), None for none."""
    @property
    def setpoint(self) -> list[float] | None:
        """The DP set-point (x, y, ψ) the stage moves the reference to (m, rad), None for none."""
    @property
    def statics(self) -> bool:
        """Whether the stage starts from statics of its configuration."""
    @property
    def ramp(self) -> float:
        """The time the stage's speed changes take (s)."""

@final
class Stages:
    """The stages of a lay, in order."""

    def __new__(cls, stages: Sequence[Stage]) -> Stages: ...
    def __len__(self) -> int: ...
    def __getitem__(self, index: int, /) -> Stage:
        """The stage at `index` (negative: from the end)."""
    @property
    def names(self) -> list[str]:
        """The stages' names."""
    @property
    def duration(self) -> float:
        """The total duration (s)."""
