//! The cable element: a two-node bar with axial stiffness only, for segments without bending and torsional
//! stiffness (wire ropes, A&R cables, initiation wires). Its nodes carry positions only: a cable node's
//! rotation is no degree of freedom, and at a joint with a rod the rod's end rotates freely (a pin: the
//! force passes, no moment).
//!
//! **Energy.** With the chord d = φ2 − φ1, q = d·d and the unstretched length L, the strain is
//! ε = √q/L − 1 and the stored energy W(q) = ½ EA L max(ε, 0)²: a cable carries tension N = EA max(ε, 0)
//! and goes slack in compression. Then ∂W/∂φ2 = 2W′(q) d = N d/|d|, W′(q) = ½EA max(1/L − q^(−1/2), 0).
//!
//! **The time step** (a discrete gradient, Gonzalez 1996): with d̄ = ½(d_n + d_{n+1}) and
//! W̄′ = (W(q_{n+1}) − W(q_n))/(q_{n+1} − q_n), the force 2W̄′d̄ on node 2 (and its opposite on node 1) does
//! the work 2W̄′d̄·Δd = W̄′Δq = ΔW exactly, and lies along the chord: the step conserves energy, linear and
//! angular momentum, like the rod's.
// Indexing cannot go out of bounds here: Fixed-size 12-vectors and 3-vectors indexed by constants.
#![allow(clippy::indexing_slicing)]
use super::dynamic_element::{ElementStep, GaussPoint, StressRule};
use super::element::{ElementMatrix, ElementReference, ElementVector};
use nalgebra::{Matrix3, Vector3};

/// The statics' tangent across a cable is at least this fraction of EA/L (of the axial stiffness). A cable
/// without tension has no stiffness, and the tangent of a line that starts unstressed (statics' first load
/// step) would be singular: the statics' tangent of a slack cable takes the taut stiffness EA/L along the chord
/// and this floor across it. Both change Newton's steps only, not the residual or the solution (a cable under
/// tension N has N/l ≫ 1e-6 EA/L across it).
const STATIC_TRANSVERSE_FLOOR: f64 = 1e-6;

/// Where a node's rows begin in an element's 12-vector [φ1, θ1, φ2, θ2].
const NODE_DOFS: usize = 6;

/// A cable's axial law W(q) of one element: axial stiffness EA (N) and unstretched length L (m).
#[derive(Debug, Clone, Copy)]
pub struct AxialLaw {
    pub ea: f64,
    pub length: f64,
}

impl AxialLaw {
    /// Strain ε = |d|/L − 1 of a chord whose squared length is `q`.
    pub fn strain(&self, q: f64) -> f64 {
        q.sqrt() / self.length - 1.0
    }

    /// Tension N = EA max(ε, 0) (N).
    pub fn tension(&self, q: f64) -> f64 {
        self.ea * self.strain(q).max(0.0)
    }

    /// Stored energy W(q) = ½ EA L max(ε, 0)² (J).
    pub fn energy(&self, q: f64) -> f64 {
        0.5 * self.ea * self.length * self.strain(q).max(0.0).powi(2)
    }

    /// W′(q) = ½EA max(1/L − q^(−1/2), 0).
    fn slope(&self, q: f64) -> f64 {
        0.5 * self.ea * (1.0 / self.length - 1.0 / q.sqrt()).max(0.0)
    }

    /// The discrete gradient of the energy per length w(ε) = ½EA max(ε, 0)² between the strains `e0` and
    /// `e1`, N̄ = (w(ε1) − w(ε0))/(ε1 − ε0), and ∂N̄/∂ε1. Taut at both, N̄ = ½EA(ε0 + ε1) exactly (no
    /// difference quotient to lose digits) and ∂N̄/∂ε1 = ½EA; slack at both, 0; slack at one, the quotient of
    /// the other's energy, taken as it is.
    fn mean_tension(&self, e0: f64, e1: f64) -> (f64, f64) {
        let w = |e: f64| 0.5 * self.ea * e.max(0.0).powi(2);
        match (e0 > 0.0, e1 > 0.0) {
            (true, true) => (0.5 * self.ea * (e0 + e1), 0.5 * self.ea),
            (false, false) => (0.0, 0.0),
            _ => {
                let tension = (w(e1) - w(e0)) / (e1 - e0);
                (tension, (self.ea * e1.max(0.0) - tension) / (e1 - e0))
            }
        }
    }

    /// W″(q) = ¼EA q^(−3/2) in tension, 0 when slack.
    fn curvature(&self, q: f64) -> f64 {
        if self.strain(q) > 0.0 {
            0.25 * self.ea / (q * q.sqrt())
        } else {
            0.0
        }
    }
}

/// The statics of one cable element at positions `x1`, `x2`.
#[derive(Debug, Clone)]
pub struct CableResponse {
    /// Internal forces on [x1, θ1, x2, θ2] (the moments zero).
    pub forces: ElementVector,
    /// Tension N (N).
    pub tension: f64,
    /// Stored energy (J).
    pub energy: f64,
}

/// Writes the 12×12 element tangent of a bar whose ∂f2/∂φ2 is `block`: ±block on the translations.
fn bar_tangent(block: &Matrix3<f64>, tangent: &mut ElementMatrix) {
    // The slice's fill, a few vector stores: nalgebra's `fill` walks the 144 entries one by one.
    tangent.as_mut_slice().fill(0.0);
    for (row, column, sign) in [(0, 0, 1.0), (0, 1, -1.0), (1, 0, -1.0), (1, 1, 1.0)] {
        tangent
            .fixed_view_mut::<3, 3>(NODE_DOFS * row, NODE_DOFS * column)
            .copy_from(&(block * sign));
    }
}

/// Forces ∓f on [x1, x2] of a 12-vector.
fn bar_forces(force: &Vector3<f64>) -> ElementVector {
    let mut forces = ElementVector::zeros();
    forces.fixed_rows_mut::<3>(0).copy_from(&(-force));
    forces.fixed_rows_mut::<3>(NODE_DOFS).copy_from(force);
    forces
}

/// Internal forces ∂W/∂φ of the cable element between `x1` and `x2`, and with `tangent` their derivatives
/// (all 144 entries written): ∂f2/∂φ2 = 4W″(q) d dᵀ + 2W′(q) I = EA/L d̂d̂ᵀ + N/l (I − d̂d̂ᵀ), along the chord
/// EA/L also when slack, and across it no less than `STATIC_TRANSVERSE_FLOOR` EA/L.
pub fn evaluate(
    x1: &Vector3<f64>,
    x2: &Vector3<f64>,
    reference: &ElementReference,
    ea: f64,
    tangent: Option<&mut ElementMatrix>,
) -> CableResponse {
    let law = AxialLaw {
        ea,
        length: reference.length,
    };
    let chord = x2 - x1;
    let q = chord.norm_squared();
    let force = 2.0 * law.slope(q) * chord;
    if let Some(tangent) = tangent {
        let floor = STATIC_TRANSVERSE_FLOOR * ea / reference.length;
        let along = chord * chord.transpose() / q;
        let block = along * (ea / reference.length)
            + (Matrix3::identity() - along) * (2.0 * law.slope(q)).max(floor);
        bar_tangent(&block, tangent);
    }
    CableResponse {
        forces: bar_forces(&force),
        tension: law.tension(q),
        energy: law.energy(q),
    }
}

/// The Gauss point a cable element stores: no rotation, the tensile strain max(ε, 0) as its axial strain
/// (so that the energy ½L EA Γ1² and the tension EA Γ1 read from it are the cable's).
pub fn gauss_point(chord: &Vector3<f64>, length: f64) -> GaussPoint {
    let law = AxialLaw { ea: 1.0, length };
    GaussPoint {
        rotation: Matrix3::identity(),
        strain: Vector3::new(law.strain(chord.norm_squared()).max(0.0), 0.0, 0.0),
        curvature: Vector3::zeros(),
    }
}

/// One time step's internal forces of a cable element and, if asked, their tangent with respect to
/// [Δφ1, θ1, Δφ2, θ2]. `chord` is φ2 − φ1 at step n; `length_start` the unstretched length L_n at step n and
/// `reference.length` L_{n+1} (they differ only for the element that grows with pay-out).
///
/// Each level's strain is its own, ε_n = l_n/L_n − 1 and ε_{n+1} = l_{n+1}/L_{n+1} − 1, as in the rod's step:
/// with N̄ their discrete-gradient tension, the force N̄ 2d̄/(l_n + l_{n+1}) on node 2 (its opposite on node 1)
/// does the work N̄ (l_{n+1} − l_n). At a fixed length that is L(w(ε_{n+1}) − w(ε_n)) = ΔW exactly; for the
/// growing element the rest of the change of stored energy is what pay-out brings in. (Taking both levels at
/// L_{n+1} instead would slacken a taut growing wire's start strain, ε̃_n = l_n/L_{n+1} − 1 < 0, whenever a
/// step pays out more than its stretch.)
///
/// `rendered`: for a winch's wire whose speed depends on its tension ([`crate::vessel::winch::WinchLaw`]),
/// L_{n+1} as a function of l_{n+1}, with dL_{n+1}/dl_{n+1}; it replaces `reference.length`, and the tangent
/// takes ∂ε_{n+1}/∂l_{n+1} = 1/L_{n+1} − l_{n+1}/L_{n+1}² dL_{n+1}/dl_{n+1}. Under the midpoint rule
/// L_{n+1}(l_{n+1}) enters the force but not the tangent.
#[allow(clippy::too_many_arguments)]
pub fn step(
    chord: &Vector3<f64>,
    increments: &ElementVector,
    length_start: f64,
    reference: &ElementReference,
    ea: f64,
    rule: StressRule,
    rendered: Option<&dyn Fn(f64) -> (f64, f64)>,
    tangent: Option<&mut ElementMatrix>,
) -> ElementStep {
    let dphi1 = increments.fixed_rows::<3>(0).into_owned();
    let dphi2 = increments.fixed_rows::<3>(NODE_DOFS).into_owned();
    let chord_next = chord + dphi2 - dphi1;
    let (length_next, d_length) =
        rendered.map_or((reference.length, 0.0), |law| law(chord_next.norm()));
    let law = AxialLaw {
        ea,
        length: length_next,
    };
    let mean = 0.5 * (chord + chord_next);
    let (q_n, q_next) = (chord.norm_squared(), chord_next.norm_squared());
    let q_mid = mean.norm_squared();
    let (force, block) = match rule {
        StressRule::AverageStrain => {
            let (l_n, l_next) = (q_n.sqrt(), q_next.sqrt());
            let strain_n = l_n / length_start - 1.0;
            let strain_next = l_next / length_next - 1.0;
            let (tension, d_tension) = law.mean_tension(strain_n, strain_next);
            // f = N̄ 2d̄/(l_n + l_{n+1}); with t_{n+1} = d_{n+1}/l_{n+1}, ∂ε_{n+1}/∂Δφ2 = t_{n+1}ᵀ ∂ε_{n+1}/∂l_{n+1},
            // ∂l_{n+1}/∂Δφ2 = t_{n+1}ᵀ and ∂d̄/∂Δφ2 = ½I.
            let d_strain = 1.0 / length_next - l_next * d_length / (length_next * length_next);
            let sum = l_n + l_next;
            let direction = 2.0 * mean / sum;
            let t_next = chord_next / l_next;
            let block = direction * t_next.transpose() * (d_tension * d_strain)
                + (Matrix3::identity() / sum - 2.0 * mean * t_next.transpose() / (sum * sum))
                    * tension;
            (direction * tension, block)
        }
        StressRule::MidpointConfiguration => {
            let slope = law.slope(q_mid);
            let block =
                2.0 * law.curvature(q_mid) * mean * mean.transpose() + Matrix3::identity() * slope;
            (2.0 * slope * mean, block)
        }
    };
    if let Some(tangent) = tangent {
        bar_tangent(&block, tangent);
    }
    ElementStep {
        forces: bar_forces(&force),
        next: gauss_point(&chord_next, length_next),
    }
}

/// The axial internal damping of a taut cable element over a step: the force B ε̇ along the step's mean chord,
/// with ε̇ = (l_{n+1} − l_n L/L_n)/(L Δt) (L_n → L: its unstretched length over the step, which pay-out grows)
/// and the direction u = (d_n + d_{n+1})/(l_n + l_{n+1}), for which u·Δd = Δl exactly: its work on the step's
/// increments, B Δl²/(L Δt) ≥ 0 for an element that does not grow, is all dissipated. Slack at both ends of the
/// step, the cable has no damping (a slack rope's strands do not rub). Returns the forces on [Δφ1, θ1, Δφ2, θ2]
/// and the energy dissipated (J); with `tangent`, their derivatives are added to it.
pub fn damping_step(
    chord: &Vector3<f64>,
    increments: &ElementVector,
    length_start: f64,
    length: f64,
    damping: f64,
    dt: f64,
    tangent: Option<&mut ElementMatrix>,
) -> (ElementVector, f64) {
    let chord_next = chord + increments.fixed_rows::<3>(NODE_DOFS) - increments.fixed_rows::<3>(0);
    let (l_n, l_next) = (chord.norm(), chord_next.norm());
    if l_n <= length_start && l_next <= length {
        return (ElementVector::zeros(), 0.0);
    }
    let sum = l_n + l_next;
    let direction = (chord + chord_next) / sum;
    let rate = damping / (length * dt);
    // ε̇ L Δt: the chord's stretch less what the element's growth under pay-out (L_n → L) accounts for.
    let stretch = l_next - l_n * (length / length_start);
    let force = direction * (rate * stretch);
    if let Some(tangent) = tangent {
        // ∂(B Δl/(L Δt) u)/∂Δφ2 with ∂l_{n+1}/∂Δφ2 = t_{n+1}ᵀ and ∂u/∂Δφ2 = (I − u t_{n+1}ᵀ)/(l_n + l_{n+1}).
        let t_next = chord_next / l_next;
        let block = direction * t_next.transpose() * rate
            + (Matrix3::identity() - direction * t_next.transpose()) * (rate * stretch / sum);
        let mut added = ElementMatrix::zeros();
        bar_tangent(&block, &mut added);
        *tangent += added;
    }
    // The force's work on the increments, u·Δd = Δl: B Δl²/(L Δt) ≥ 0 for an element that does not grow.
    (bar_forces(&force), rate * stretch * (l_next - l_n))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn damping_dissipates_its_work_and_has_its_tangent() {
        let chord = Vector3::new(10.05, 0.3, -0.2);
        let mut increments = ElementVector::zeros();
        increments
            .fixed_rows_mut::<3>(0)
            .copy_from(&Vector3::new(0.01, -0.02, 0.005));
        increments
            .fixed_rows_mut::<3>(6)
            .copy_from(&Vector3::new(0.04, 0.01, -0.01));
        let (damping, dt) = (2e6, 0.1);
        let mut tangent = ElementMatrix::zeros();
        let (forces, dissipated) = damping_step(
            &chord,
            &increments,
            10.0,
            10.0,
            damping,
            dt,
            Some(&mut tangent),
        );
        assert!(dissipated > 0.0);
        assert!((forces.dot(&increments) - dissipated).abs() < 1e-9 * dissipated);
        let h = 1e-7;
        for k in [0, 1, 2, 6, 7, 8] {
            let mut moved = increments;
            moved[k] += h;
            let (up, _) = damping_step(&chord, &moved, 10.0, 10.0, damping, dt, None);
            moved[k] -= 2.0 * h;
            let (down, _) = damping_step(&chord, &moved, 10.0, 10.0, damping, dt, None);
            let column = (up - down) / (2.0 * h);
            let error = (column - tangent.column(k)).norm();
            assert!(error < 1e-5 * tangent.norm(), "column {k}: {error}");
        }
        let slack = Vector3::new(9.0, 0.0, 0.0);
        assert_eq!(
            damping_step(&slack, &increments, 10.0, 10.0, damping, dt, None).1,
            0.0
        );
    }

    /// An element paid out at its end grows with its chord at one strain: no strain rate, no damping force
    /// (it resisted the pay-out itself before, with B v/L); stretched as it grows, the force's work on the
    /// increments is the dissipation booked.
    #[test]
    fn a_growing_element_is_damped_by_its_strain_rate_only() {
        let chord = Vector3::new(10.05, 0.0, 0.0);
        let (damping, dt, grown) = (2e6, 0.1, 10.5);
        let mut increments = ElementVector::zeros();
        increments[6] = chord.x * (grown / 10.0 - 1.0);
        let (forces, dissipated) =
            damping_step(&chord, &increments, 10.0, grown, damping, dt, None);
        assert!(forces.norm() < 1e-6 * damping, "{forces}");
        assert!(dissipated.abs() < 1e-9, "{dissipated}");
        increments[6] += 0.01;
        let (forces, dissipated) =
            damping_step(&chord, &increments, 10.0, grown, damping, dt, None);
        let rate = damping / (grown * dt);
        assert!((forces[6] - rate * 0.01).abs() < 1e-6 * rate * 0.01);
        assert!((forces.dot(&increments) - dissipated).abs() < 1e-9 * dissipated.abs());
    }

    fn reference(length: f64) -> ElementReference {
        ElementReference {
            length,
            strain: Vector3::zeros(),
            curvature: Vector3::zeros(),
        }
    }

    /// The statics' forces are the energy's gradient and their tangent its Hessian (central differences),
    /// in tension; slack, both vanish.
    #[test]
    fn forces_and_tangent_match_differences() {
        let (x1, x2) = (Vector3::new(0.1, -0.2, 0.3), Vector3::new(1.3, 0.4, -0.2));
        let reference = reference(1.2);
        let ea = 2.0e6;
        let mut tangent = ElementMatrix::zeros();
        let at = evaluate(&x1, &x2, &reference, ea, Some(&mut tangent));
        assert!(at.tension > 0.0);
        let h = 1e-6;
        for j in 0..3 {
            let mut plus = x2;
            plus[j] += h;
            let mut minus = x2;
            minus[j] -= h;
            let e_plus = evaluate(&x1, &plus, &reference, ea, None);
            let e_minus = evaluate(&x1, &minus, &reference, ea, None);
            let gradient = (e_plus.energy - e_minus.energy) / (2.0 * h);
            assert!((gradient - at.forces[NODE_DOFS + j]).abs() < 1e-6 * at.tension);
            for i in 0..3 {
                let difference =
                    (e_plus.forces[NODE_DOFS + i] - e_minus.forces[NODE_DOFS + i]) / (2.0 * h);
                assert!((difference - tangent[(NODE_DOFS + i, NODE_DOFS + j)]).abs() < 1e-6 * ea);
                assert!((difference + tangent[(i, NODE_DOFS + j)]).abs() < 1e-6 * ea);
            }
        }
        let slack = evaluate(&x1, &x2, &self::reference(2.0), ea, Some(&mut tangent));
        assert_eq!(slack.tension, 0.0);
        assert_eq!(slack.forces.norm(), 0.0);
        // Slack, the statics' tangent keeps EA/L along the chord and the floor across it.
        let (floor, l) = (STATIC_TRANSVERSE_FLOOR * ea / 2.0, (x2 - x1).norm());
        let block = tangent.fixed_view::<3, 3>(NODE_DOFS, NODE_DOFS);
        let along = block * (x2 - x1) / l;
        assert!((along - (x2 - x1) / l * (ea / 2.0)).norm() < 1e-9 * ea);
        assert!((block.trace() - ea / 2.0 - 2.0 * floor).abs() < 1e-9 * ea);
    }

    /// The step's forces do the work of the energy's change exactly (to round-off), across the slack limit
    /// too; for an element that grows (pay-out) they do the work N̄ (l_{n+1} − l_n) of the mean tension of the
    /// two levels' own strains; their tangent matches central differences in both cases.
    #[test]
    fn step_is_a_discrete_gradient_with_a_consistent_tangent() {
        let chord = Vector3::new(1.0, 0.2, -0.1);
        let reference = reference(0.98);
        let ea = 5.0e5;
        let law = AxialLaw {
            ea,
            length: reference.length,
        };
        let rule = StressRule::AverageStrain;
        for length_start in [0.98, 0.97] {
            for increments in [
                [
                    0.01, -0.02, 0.03, 0.0, 0.0, 0.0, -0.02, 0.01, 0.04, 0.0, 0.0, 0.0,
                ],
                [
                    0.0, 0.0, 0.0, 0.0, 0.0, 0.0, -0.06, -0.01, 0.01, 0.0, 0.0, 0.0,
                ],
                [0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1e-9, 0.0, 0.0, 0.0, 0.0, 0.0],
            ] {
                let increments = ElementVector::from_row_slice(&increments);
                let mut tangent = ElementMatrix::zeros();
                let at = |increments: &ElementVector, tangent: Option<&mut ElementMatrix>| {
                    step(
                        &chord,
                        increments,
                        length_start,
                        &reference,
                        ea,
                        rule,
                        None,
                        tangent,
                    )
                };
                let forces = at(&increments, Some(&mut tangent)).forces;
                let chord_next =
                    chord + increments.fixed_rows::<3>(6) - increments.fixed_rows::<3>(0);
                let (l_n, l_next) = (chord.norm(), chord_next.norm());
                let work = forces.dot(&increments);
                let start = AxialLaw {
                    ea,
                    length: length_start,
                };
                let strain = |l: f64, law: &AxialLaw| l / law.length - 1.0;
                let (tension, _) = law.mean_tension(strain(l_n, &start), strain(l_next, &law));
                let expected = if length_start == reference.length {
                    law.energy(chord_next.norm_squared()) - law.energy(chord.norm_squared())
                } else {
                    tension * (l_next - l_n)
                };
                let scale = law.energy(chord.norm_squared());
                assert!(
                    (work - expected).abs() <= 1e-12 * scale,
                    "work {work} vs {expected}"
                );
                // Momentum: the forces sum to zero.
                let total = forces.fixed_rows::<3>(0) + forces.fixed_rows::<3>(6);
                assert!(total.norm() < 1e-12 * forces.norm());
                let h = 1e-7;
                for j in [0, 1, 2, 6, 7, 8] {
                    let mut plus = increments;
                    plus[j] += h;
                    let mut minus = increments;
                    minus[j] -= h;
                    let (f_plus, f_minus) = (at(&plus, None).forces, at(&minus, None).forces);
                    for i in 0..12 {
                        let difference = (f_plus[i] - f_minus[i]) / (2.0 * h);
                        assert!(
                            (difference - tangent[(i, j)]).abs() < 1e-5 * ea,
                            "{increments:?} ({i}, {j}): {difference} vs {}",
                            tangent[(i, j)]
                        );
                    }
                }
            }
        }
    }

    /// A winch's wire in constant-tension mode: the step's unstretched length solves the winch's law at the
    /// tension of the step's end, and the tangent, with dL/dl, matches central differences, on the law's
    /// sloped part and on its flat parts.
    #[test]
    fn rendered_step_solves_the_law_with_a_consistent_tangent() {
        use crate::vessel::winch::WinchLaw;
        let chord = Vector3::new(10.0, 0.5, -2.0);
        let ea = 5.5e8;
        let length_start = chord.norm() / (1.0 + 1e6 / ea);
        let reference = reference(length_start);
        let (dt, rule) = (0.5, StressRule::AverageStrain);
        // Set tension 1 MN, band 50 kN: at the start, on the set tension; the three increments move the
        // tension into the band, onto the slope above it and past full speed.
        let law = WinchLaw {
            commanded: None,
            tension: Some(1e6),
            band: 5e4,
            speed_limit: 1.0,
            lowest: -1.0,
            highest: 1.0,
        };
        let rendered = |l: f64| law.length(ea, length_start, dt, l);
        for stretch in [1e-5, 4e-3, 0.7] {
            let mut increments = ElementVector::zeros();
            increments
                .fixed_rows_mut::<3>(6)
                .copy_from(&(chord.normalize() * stretch + Vector3::new(0.0, 1e-3, 0.0)));
            let at = |increments: &ElementVector, tangent: Option<&mut ElementMatrix>| {
                step(
                    &chord,
                    increments,
                    length_start,
                    &reference,
                    ea,
                    rule,
                    Some(&rendered),
                    tangent,
                )
            };
            let mut tangent = ElementMatrix::zeros();
            let result = at(&increments, Some(&mut tangent));
            // The law holds at the step's end: L = L_n + Δt v(EA ε_{n+1}).
            let l_next = (chord + increments.fixed_rows::<3>(6)).norm();
            let (length, _) = rendered(l_next);
            let tension = ea * (l_next / length - 1.0);
            let (speed, slope) = law.speed(tension);
            assert!((length - length_start - dt * speed).abs() < 1e-12 * length);
            // Within the band, on the slope, at full speed.
            let expected_speed = match stretch {
                s if s < 1e-3 => 0.0,
                s if s < 0.5 => speed,
                _ => 1.0,
            };
            assert_eq!(speed, expected_speed);
            assert_eq!(slope > 0.0, (1e-3..0.5).contains(&stretch));
            assert!((result.next.strain.x - (l_next / length - 1.0)).abs() < 1e-15);
            let h = 1e-8;
            for j in [0, 1, 2, 6, 7, 8] {
                let mut plus = increments;
                plus[j] += h;
                let mut minus = increments;
                minus[j] -= h;
                let (f_plus, f_minus) = (at(&plus, None).forces, at(&minus, None).forces);
                for i in 0..12 {
                    let difference = (f_plus[i] - f_minus[i]) / (2.0 * h);
                    assert!(
                        (difference - tangent[(i, j)]).abs() < 1e-5 * ea / length,
                        "stretch {stretch} ({i}, {j}): {difference} vs {}",
                        tangent[(i, j)]
                    );
                }
            }
        }
    }
}
