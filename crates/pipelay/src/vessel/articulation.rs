//! An articulated stinger: rigid sections in a chain, hinged to the vessel and to each other about the
//! vessel's lateral axis b2, each turning by its own hinge angle φ_i (rad; positive turns its aft end down).
//!
//! **Geometry.** The sections lie along the stinger's arc at φ = 0 ([`crate::vessel::lay::stinger_station`]):
//! section i runs from its hinge h_i (the arc point at its start) to the next hinge. A point p of section j
//! (its place at φ = 0) is at S_j(p) = T_1 ∘ … ∘ T_j (p), with T_i(x) = h_i + R(φ_i)(x − h_i) and R(φ) the
//! rotation by φ about the axis e: a plane rigid motion, rotation R(Φ_j) with Φ_j = φ_1 + … + φ_j, and
//! ∂S_j(p)/∂φ_i = e × (S_j(p) − H_i) for i ≤ j, where H_i = S_{i−1}(h_i) is where hinge i is.
//!
//! **Each section** is a rigid body: its mass as two points on its chord at ±c/(2√3) from the chord's middle
//! (c the chord; the pair has the section's mass and moment of inertia about its middle, m c²/12), their
//! inertia with the section's added mass; a constant buoyancy (its ballast set, N) at those points; drag
//! there; a hinge spring k φ and stiff springs beyond the hinge's limits.
// Indexing cannot go out of bounds here: section indices of the articulation's own lists.
#![allow(clippy::indexing_slicing)]
use crate::error::{finite, positive, Error, Result};
use crate::vessel::stinger_arc::stinger_station;
use nalgebra::{Matrix3, Rotation3, Unit, Vector3};

/// Most sections of an articulated stinger: their hinge angles join the vessel's node in the border of the
/// factorisation ([`crate::linalg::border_lu`]).
pub const MAX_SECTIONS: usize = 10;

/// Stiffness of the springs that hold a hinge within its limits, relative to its own stiffness and never
/// below [`LIMIT_STIFFNESS_FLOOR`] (N·m/rad).
const LIMIT_STIFFNESS_FACTOR: f64 = 100.0;
const LIMIT_STIFFNESS_FLOOR: f64 = 1e9;

/// One section of an articulated stinger (SI units).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StingerSection {
    /// Arc length of the stinger's top line the section carries (m).
    pub length: f64,
    /// Mass (kg).
    pub mass: f64,
    /// Buoyancy (N, upward), constant: the section's displaced water with its ballast set.
    pub buoyancy: f64,
    /// Hinge stiffness k (N·m/rad) about its rest angle 0; 0 for a free hinge.
    pub hinge_stiffness: f64,
    /// The hinge's angle limits [φ_min, φ_max] (rad).
    pub limits: [f64; 2],
    /// Drag area C_d A (m²) of the section across the flow.
    pub drag_area: f64,
    /// Added mass (kg): the water it carries along as it moves, isotropic, joining its mass's inertia (not its
    /// weight).
    pub added_mass: f64,
}

impl StingerSection {
    /// A checked section.
    pub fn new(
        length: f64,
        mass: f64,
        buoyancy: f64,
        hinge_stiffness: f64,
        limits: [f64; 2],
        drag_area: f64,
    ) -> Result<Self> {
        positive("length", length, "m")?;
        for (name, value, unit) in [
            ("mass", mass, "kg"),
            ("buoyancy", buoyancy, "N"),
            ("hinge_stiffness", hinge_stiffness, "N·m/rad"),
            ("drag_area", drag_area, "m²"),
        ] {
            if !(value.is_finite() && value >= 0.0) {
                return Err(Error::input(
                    name,
                    value,
                    format!("must be finite and ≥ 0 ({unit})"),
                ));
            }
        }
        finite("hinge_limits", &limits)?;
        if !(limits[0] <= 0.0 && 0.0 <= limits[1] && limits[1] - limits[0] < std::f64::consts::PI) {
            return Err(Error::input(
                "hinge_limits",
                format!("{limits:?}"),
                "must be [min, max] rad with min ≤ 0 ≤ max and max − min < π",
            ));
        }
        Ok(StingerSection {
            length,
            mass,
            buoyancy,
            hinge_stiffness,
            limits,
            drag_area,
            added_mass: 0.0,
        })
    }

    /// The section with `added_mass` (kg, finite, ≥ 0).
    pub fn with_added_mass(mut self, added_mass: f64) -> Result<Self> {
        if !(added_mass.is_finite() && added_mass >= 0.0) {
            return Err(Error::input(
                "added_mass",
                added_mass,
                "must be finite and ≥ 0 (kg)",
            ));
        }
        self.added_mass = added_mass;
        Ok(self)
    }

    /// The hinge's potential (J) at angle φ: its spring and the limit springs.
    pub fn hinge_energy(&self, angle: f64) -> f64 {
        let beyond = (angle - self.limits[1]).max(0.0) + (angle - self.limits[0]).min(0.0);
        0.5 * self.hinge_stiffness * angle * angle + 0.5 * self.limit_stiffness() * beyond * beyond
    }

    /// The hinge's moment ∂U/∂φ (N·m) at angle φ.
    pub fn hinge_moment(&self, angle: f64) -> f64 {
        let beyond = (angle - self.limits[1]).max(0.0) + (angle - self.limits[0]).min(0.0);
        self.hinge_stiffness * angle + self.limit_stiffness() * beyond
    }

    /// Discrete gradient of the hinge's potential over a step from `start` to `end` (N·m): ΔU/Δφ, exact work;
    /// the moment at the midpoint where the step is below round-off.
    pub fn hinge_moment_over(&self, start: f64, end: f64) -> f64 {
        let change = end - start;
        if change.abs() > 1e-9 * (1.0 + start.abs()) {
            (self.hinge_energy(end) - self.hinge_energy(start)) / change
        } else {
            self.hinge_moment(0.5 * (start + end))
        }
    }

    fn limit_stiffness(&self) -> f64 {
        (LIMIT_STIFFNESS_FACTOR * self.hinge_stiffness).max(LIMIT_STIFFNESS_FLOOR)
    }
}

/// The hinges of the chain in some frame: the axis e and each hinge's point at φ = 0.
#[derive(Debug, Clone, PartialEq)]
pub struct Chain {
    pub axis: Vector3<f64>,
    pub hinges: Vec<Vector3<f64>>,
}

impl Chain {
    /// The chain in the frame whose rotation from this one is `rotation` and whose origin lies at `origin`.
    pub fn in_frame(&self, rotation: &Matrix3<f64>, origin: &Vector3<f64>) -> Chain {
        Chain {
            axis: rotation * self.axis,
            hinges: self
                .hinges
                .iter()
                .map(|h| rotation * (h - origin))
                .collect(),
        }
    }

    /// R(Φ_j): the rotation of section j at the hinge angles `angles`.
    pub fn rotation(&self, angles: &[f64], section: usize) -> Matrix3<f64> {
        let total: f64 = angles[..=section].iter().sum();
        Rotation3::from_axis_angle(&Unit::new_unchecked(self.axis), total).into_inner()
    }

    /// Where each hinge of sections 0..=`section` is at `angles`: H_i = S_{i−1}(h_i).
    pub fn hinge_positions(&self, angles: &[f64], section: usize) -> [Vector3<f64>; MAX_SECTIONS] {
        let mut positions = [Vector3::zeros(); MAX_SECTIONS];
        // S_{i−1} as a rotation and translation: S(x) = R x + t.
        let mut rotation = Matrix3::identity();
        let mut translation = Vector3::zeros();
        for i in 0..=section {
            positions[i] = rotation * self.hinges[i] + translation;
            let turn =
                Rotation3::from_axis_angle(&Unit::new_unchecked(self.axis), angles[i]).into_inner();
            // S_i(x) = S_{i−1}(h_i + R_i(x − h_i)).
            translation = rotation * (self.hinges[i] - turn * self.hinges[i]) + translation;
            rotation *= turn;
        }
        positions
    }

    /// S_j at `angles` as (R, t): S_j(x) = R x + t.
    pub fn placement(&self, angles: &[f64], section: usize) -> (Matrix3<f64>, Vector3<f64>) {
        let hinges = self.hinge_positions(angles, section);
        let rotation = self.rotation(angles, section);
        // S_j(h_j) = H_j.
        (rotation, hinges[section] - rotation * self.hinges[section])
    }
}

/// An articulated stinger: its sections along the stinger's arc, in the body frame.
#[derive(Debug, Clone, PartialEq)]
pub struct Articulation {
    pub sections: Vec<StingerSection>,
    /// The hinges (body frame, relative to CO), about b2.
    pub chain: Chain,
    /// Each section's far end at φ = 0 (body frame, m).
    pub ends: Vec<Vector3<f64>>,
    /// Each section's hinge's arc length along the stinger from its start (m), and the stinger's length last.
    pub arc_lengths: Vec<f64>,
    /// The stinger's arc: radius (m), start (body frame, m) and slope there (rad below the horizontal).
    radius: f64,
    origin: Vector3<f64>,
    angle: f64,
}

impl Articulation {
    /// The sections of a stinger of `radius` starting at `origin` with the slope `angle` (as
    /// [`crate::vessel::lay::stinger_rollers`]), the first hinged to the vessel at arc length `fixed_length`.
    pub fn new(
        radius: f64,
        origin: Vector3<f64>,
        angle: f64,
        fixed_length: f64,
        sections: Vec<StingerSection>,
    ) -> Result<Self> {
        if sections.is_empty() || sections.len() > MAX_SECTIONS {
            return Err(Error::input(
                "sections",
                sections.len(),
                format!("must be between 1 and {MAX_SECTIONS} sections"),
            ));
        }
        if !(fixed_length.is_finite() && fixed_length >= 0.0) {
            return Err(Error::input(
                "fixed_length",
                fixed_length,
                "must be finite and ≥ 0 (m)",
            ));
        }
        let mut arc_lengths = vec![fixed_length];
        for section in &sections {
            arc_lengths.push(arc_lengths[arc_lengths.len() - 1] + section.length);
        }
        let point = |s: f64| stinger_station(radius, origin, angle, s).0;
        let hinges = arc_lengths[..sections.len()]
            .iter()
            .map(|&s| point(s))
            .collect();
        let ends = arc_lengths[1..].iter().map(|&s| point(s)).collect();
        Ok(Articulation {
            sections,
            chain: Chain {
                axis: Vector3::y(),
                hinges,
            },
            ends,
            arc_lengths,
            radius,
            origin,
            angle,
        })
    }

    /// The stinger's whole length (m): the fixed part and the sections.
    pub fn length(&self) -> f64 {
        self.arc_lengths[self.arc_lengths.len() - 1]
    }

    /// The section that carries the stinger's top line at arc length `s` (m), None on the fixed part. A
    /// support at a hinge rides on the section before it (on the vessel at the first hinge).
    pub fn section_at(&self, s: f64) -> Option<usize> {
        let scale = 1e-9 * (1.0 + self.length());
        (0..self.sections.len())
            .find(|&i| s > self.arc_lengths[i] + scale && s <= self.arc_lengths[i + 1] + scale)
    }

    /// The arc length (m) of the point of the stinger's top line at `station` (body frame, on the arc).
    pub fn arc_length_of(&self, station: &Vector3<f64>) -> f64 {
        // The arc's centre C = origin + R(sin a, 0, cos a); station − C = R(−sin φ, 0, −cos φ).
        let centre =
            self.origin + self.radius * Vector3::new(self.angle.sin(), 0.0, self.angle.cos());
        let v = station - centre;
        self.radius * ((-v.x).atan2(-v.z) - self.angle)
    }

    /// Section j's mass points at φ = 0 (body frame, m): ±c/(2√3) about the chord's middle.
    pub fn mass_points(&self, section: usize) -> [Vector3<f64>; 2] {
        let (start, end) = (self.chain.hinges[section], self.ends[section]);
        let middle = 0.5 * (start + end);
        let half = (end - start) / (2.0 * 3f64.sqrt());
        [middle - half, middle + half]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn articulation() -> Articulation {
        let section = StingerSection::new(20.0, 5e4, 1e5, 1e6, [-0.2, 0.4], 10.0).unwrap();
        Articulation::new(
            120.0,
            Vector3::new(-30.0, 0.0, 4.0),
            0.05,
            10.0,
            vec![section; 3],
        )
        .unwrap()
    }

    #[test]
    fn the_chain_turns_each_point_about_the_hinges_before_it() {
        let art = articulation();
        let chain = &art.chain;
        let angles = [0.1, -0.05, 0.2];
        let p = art.ends[2];
        let (rotation, translation) = chain.placement(&angles, 2);
        let moved = rotation * p + translation;
        // Composing the three turns one by one.
        let turn = |x: Vector3<f64>, i: usize| {
            let r = Rotation3::from_axis_angle(&Unit::new_unchecked(chain.axis), angles[i]);
            chain.hinges[i] + r * (x - chain.hinges[i])
        };
        let expected = turn(turn(turn(p, 2), 1), 0);
        assert!((moved - expected).norm() < 1e-12);
        // ∂S_j(p)/∂φ_i = e × (S_j(p) − H_i).
        let hinges = chain.hinge_positions(&angles, 2);
        for i in 0..3 {
            let h = 1e-6;
            let (mut plus, mut minus) = (angles, angles);
            plus[i] += h;
            minus[i] -= h;
            let at = |a: &[f64; 3]| {
                let (r, t) = chain.placement(a, 2);
                r * p + t
            };
            let difference = (at(&plus) - at(&minus)) / (2.0 * h);
            let formula = chain.axis.cross(&(moved - hinges[i]));
            assert!((difference - formula).norm() < 1e-7, "{i}");
        }
        // At zero angles every point stays; a positive angle turns the aft end down (b3).
        let (r0, t0) = chain.placement(&[0.0; 3], 2);
        assert!((r0 * p + t0 - p).norm() < 1e-12);
        assert!(moved.z > p.z);
    }

    #[test]
    fn supports_ride_on_the_section_that_carries_them() {
        let art = articulation();
        assert_eq!(art.section_at(5.0), None);
        assert_eq!(art.section_at(10.0), None);
        assert_eq!(art.section_at(10.5), Some(0));
        assert_eq!(art.section_at(30.0), Some(0));
        assert_eq!(art.section_at(31.0), Some(1));
        assert_eq!(art.section_at(70.0), Some(2));
        assert_eq!(art.section_at(71.0), None);
        // The mass points keep the section's moment of inertia about its middle.
        let [a, b] = art.mass_points(1);
        let chord = (art.ends[1] - art.chain.hinges[1]).norm();
        let inertia = 2.0 * 0.5 * (0.5 * (a - b).norm()).powi(2);
        assert!((inertia - chord * chord / 12.0).abs() < 1e-9);
    }

    #[test]
    fn hinge_limits_are_stiff_springs_whose_work_is_exact() {
        let section = StingerSection::new(20.0, 5e4, 1e5, 1e6, [-0.2, 0.4], 0.0).unwrap();
        assert!((section.hinge_moment(0.1) - 1e5).abs() < 1e-6);
        assert!(section.hinge_moment(0.5) > 1e8);
        for (a, b) in [(0.3, 0.5), (-0.3, 0.1), (0.2, 0.2 + 1e-12)] {
            let work = section.hinge_moment_over(a, b) * (b - a);
            let change = section.hinge_energy(b) - section.hinge_energy(a);
            assert!((work - change).abs() <= 1e-9 * change.abs().max(1.0));
        }
        assert!(StingerSection::new(20.0, 5e4, 1e5, 1e6, [0.1, 0.4], 0.0).is_err());
        assert!(StingerSection::new(20.0, -1.0, 1e5, 1e6, [-0.1, 0.4], 0.0).is_err());
    }
}
