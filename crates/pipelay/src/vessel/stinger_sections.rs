//! The articulated stinger's sections as rigid bodies on the vessel's node ([`crate::vessel::articulation`]):
//! their weight less buoyancy, drag and hinge springs in statics, and their energy–momentum step.
//!
//! A section's point a (two per section, mass m_a) sits at x_a = x_N + Λ_N d_a(φ), d_a = S(φ)(q_a) in the end
//! node's frame. A force F at the point does virtual work on the unknowns (Δx_N, spatial spin θ, φ):
//! - **statics**: F on x_N, (x_a − x_N) × F on θ, F·Λ_N (e × (d_a − H_i)) on φ_i;
//! - **in a step** (Cayley update Λ₁ = cay(θ)Λ₀), exactly:
//!   Δx_a = Δx_N + ½(Λ₁ − Λ₀)(d₀ + d₁) + ½(Λ₁ + Λ₀)(d₁ − d₀), with ½(Λ₁ − Λ₀)(d₀ + d₁) = θ × w,
//!   w = (I + ½θ̂)⁻¹ Λ₁ d̄: F on x_N, w × F on θ, and on φ the discrete gradient of
//!   ψ(φ) = (½(Λ₀ + Λ₁)ᵀF)·S(φ)(q_a).
//!
//! The point's velocity follows the trapezoidal rule, v₁ = 2Δx_a/Δt − v₀, and its inertia
//! F = m_a (v₁ − v₀)/Δt does work ½m_a(|v₁|² − |v₀|²) exactly. Weight less buoyancy is a dead load (its work
//! the potential's change). Drag ½ρ C_dA |u|u on the flow u = U − Δx_a/Δt relative to the point's mean
//! velocity (U the water's velocity at the point's start at the step's mid-time: the current and the waves'
//! particle velocity) splits exactly into Δt F·U supplied and Δt F·u dissipated. The hinge springs' moment is their discrete gradient ΔU/Δφ. So the sections'
//! energy — kinetic, potential and the hinges' — changes by the work supplied less that dissipated, to
//! round-off.
// Indexing cannot go out of bounds here: section, point and DOF indices of the articulation's own lists.
#![allow(clippy::indexing_slicing)]
use crate::contact::sinks::EntrySink;
use crate::so3::{cayley, exp, skew};
use crate::vessel::articulation::{Articulation, Chain, StingerSection, MAX_SECTIONS};
use crate::vessel::VesselAttachment;
use nalgebra::{Matrix3, UnitQuaternion, Vector3};

/// Unknowns of the sections' residual: the end node's Δx and θ, then the hinge angles' Δφ.
const MAX_UNKNOWNS: usize = 6 + MAX_SECTIONS;
/// Most mass points: two per section.
const MAX_POINTS: usize = 2 * MAX_SECTIONS;

/// Central differences' steps of the tangent: on the end node's position (m, times 1 + |x_N|), and on its
/// rotation and the hinge angles (rad).
const TANGENT_STEP: f64 = 1e-6;
const ROTATION_STEP: f64 = 1e-7;

/// One of a section's two mass points.
#[derive(Debug, Clone, Copy)]
struct MassPoint {
    section: usize,
    /// Where the point is at φ = 0, in the end node's frame (m).
    place: Vector3<f64>,
    /// Its share of the section's mass with its added mass (kg), weight less buoyancy (N, down) and drag area
    /// C_dA (m²).
    mass: f64,
    net_weight: f64,
    drag_area: f64,
}

/// The water the sections move in: density (kg/m³), the calm surface's z (the sea below it, z down), and the
/// water's velocity at a point (m/s): the current, and in a step the waves' particle velocity.
pub struct Water<'a> {
    pub density: f64,
    pub surface: f64,
    pub velocity: &'a dyn Fn(&Vector3<f64>) -> Vector3<f64>,
}

/// The sections of an articulated stinger on the end node `node`.
#[derive(Debug, Clone)]
pub struct StingerSections {
    sections: Vec<StingerSection>,
    chain: Chain,
    points: Vec<MassPoint>,
    node: usize,
    /// The global DOF of the first hinge angle.
    hinge_base: usize,
}

/// The sections' state over a step: the step's start (the end node's position and rotation, the hinge angles,
/// the points' velocities) and its unknowns.
pub struct SectionStep<'a> {
    pub position: Vector3<f64>,
    pub rotation: UnitQuaternion<f64>,
    pub angles: &'a [f64],
    pub velocities: &'a [Vector3<f64>],
    /// Increments over all DOFs (node-major, then the hinge angles').
    pub increments: &'a [f64],
    pub dt: f64,
}

/// What a step of the sections gives: their energy at its end (kinetic, potential of weight less buoyancy,
/// hinges'; J), the points' velocities there (the first [`StingerSections::point_count`]), and the drag's work
/// supplied and dissipated over it (J).
#[derive(Debug, Clone, Copy, Default)]
pub struct SectionWork {
    pub energy: f64,
    pub velocities: [Vector3<f64>; MAX_POINTS],
    pub supplied: f64,
    pub dissipated: f64,
}

/// The residual over the unknowns and the step's energy terms.
struct Evaluation {
    residual: [f64; MAX_UNKNOWNS],
    work: SectionWork,
}

impl StingerSections {
    /// The sections of `attachment`'s stinger, None unless it is articulated; `nodes` the rod's node count.
    pub fn new(attachment: &VesselAttachment, nodes: usize, gravity: f64) -> Option<Self> {
        let lay = attachment.lay.as_ref()?;
        let articulation: &Articulation = lay.articulation.as_ref()?;
        let (to_end, hold) = (attachment.angle, attachment.hang_off());
        let local = |p: &Vector3<f64>| to_end * (p - hold);
        let points = (0..articulation.sections.len())
            .flat_map(|j| {
                let section = articulation.sections[j];
                articulation.mass_points(j).map(|p| MassPoint {
                    section: j,
                    place: local(&p),
                    mass: 0.5 * (section.mass + section.added_mass),
                    net_weight: 0.5 * (section.mass * gravity - section.buoyancy),
                    drag_area: 0.5 * section.drag_area,
                })
            })
            .collect();
        Some(StingerSections {
            sections: articulation.sections.clone(),
            chain: articulation.chain.in_frame(&to_end, &hold),
            points,
            node: attachment.node,
            hinge_base: 6 * nodes,
        })
    }

    /// How many mass points (two per section).
    pub fn point_count(&self) -> usize {
        self.points.len()
    }

    /// Each mass point's position at the end node's pose and `angles` (m).
    pub fn point_positions(
        &self,
        position: &Vector3<f64>,
        rotation: &UnitQuaternion<f64>,
        angles: &[f64],
    ) -> Vec<Vector3<f64>> {
        let rotation = rotation.to_rotation_matrix().into_inner();
        self.points
            .iter()
            .map(|p| position + rotation * self.place(p, angles))
            .collect()
    }

    /// The sections' energy (J) at the end node's pose, `angles` and the points' `velocities`: kinetic,
    /// weight less buoyancy's potential (−W z, z down) and the hinges'.
    pub fn energy(
        &self,
        position: &Vector3<f64>,
        rotation: &UnitQuaternion<f64>,
        angles: &[f64],
        velocities: &[Vector3<f64>],
    ) -> f64 {
        let positions = self.point_positions(position, rotation, angles);
        let points: f64 = self
            .points
            .iter()
            .zip(&positions)
            .zip(velocities)
            .map(|((p, x), v)| 0.5 * p.mass * v.norm_squared() - p.net_weight * x.z)
            .sum();
        points + self.hinges_energy(angles)
    }

    fn hinges_energy(&self, angles: &[f64]) -> f64 {
        self.sections
            .iter()
            .zip(angles)
            .map(|(s, &a)| s.hinge_energy(a))
            .sum()
    }

    /// d_a = S(φ)(q_a): point `p` in the end node's frame at `angles`.
    fn place(&self, p: &MassPoint, angles: &[f64]) -> Vector3<f64> {
        let (rotation, translation) = self.chain.placement(angles, p.section);
        rotation * p.place + translation
    }

    /// The global DOF of unknown `i` (the end node's six, then the hinge angles).
    fn dof(&self, i: usize) -> usize {
        if i < 6 {
            6 * self.node + i
        } else {
            self.hinge_base + i - 6
        }
    }

    fn unknowns(&self) -> usize {
        6 + self.sections.len()
    }

    /// Adds the sections' static residual at the end node's pose, `angles` (rad) and with the current of
    /// `water`, and with `sink` its tangent (central differences).
    pub fn add_static(
        &self,
        position: &Vector3<f64>,
        rotation: &UnitQuaternion<f64>,
        angles: &[f64],
        water: &Water,
        residual: &mut [f64],
        sink: Option<&mut dyn EntrySink>,
    ) {
        let evaluate =
            |u: &[f64; MAX_UNKNOWNS]| self.static_residual(position, rotation, angles, water, u);
        let h = TANGENT_STEP * (1.0 + position.norm());
        self.add(&evaluate, &[0.0; MAX_UNKNOWNS], h, residual, sink);
    }

    /// The static residual after moving the end node by Δx, exp(θ) and the angles by Δφ (`u`).
    fn static_residual(
        &self,
        position: &Vector3<f64>,
        rotation: &UnitQuaternion<f64>,
        angles: &[f64],
        water: &Water,
        u: &[f64; MAX_UNKNOWNS],
    ) -> Evaluation {
        let x_n = position + Vector3::new(u[0], u[1], u[2]);
        let turn = exp(&Vector3::new(u[3], u[4], u[5]));
        let rotation = turn * rotation.to_rotation_matrix().into_inner();
        let phi: [f64; MAX_SECTIONS] =
            std::array::from_fn(|i| angles.get(i).map_or(0.0, |a| a + u[6 + i]));
        let mut residual = [0.0; MAX_UNKNOWNS];
        for p in &self.points {
            let d = self.place(p, &phi);
            let x = x_n + rotation * d;
            let mut force = Vector3::z() * p.net_weight;
            if x.z >= water.surface {
                let current = (water.velocity)(&x);
                force += current * (0.5 * water.density * p.drag_area * current.norm());
            }
            let moment = (x - x_n).cross(&force);
            for k in 0..3 {
                residual[k] -= force[k];
                residual[3 + k] -= moment[k];
            }
            let local_force = rotation.transpose() * force;
            let hinges = self.chain.hinge_positions(&phi, p.section);
            for (i, hinge) in hinges[..=p.section].iter().enumerate() {
                residual[6 + i] -= local_force.dot(&self.chain.axis.cross(&(d - hinge)));
            }
        }
        for (i, section) in self.sections.iter().enumerate() {
            residual[6 + i] += section.hinge_moment(phi[i]);
        }
        Evaluation {
            residual,
            work: SectionWork::default(),
        }
    }

    /// Adds the sections' residual over the step `step` in the water `water` (the current at mid-time), and
    /// with `sink` its tangent (central differences); returns their energy at the step's end, the points'
    /// velocities there and the drag's work.
    pub fn add_step(
        &self,
        step: &SectionStep,
        water: &Water,
        residual: &mut [f64],
        magnitude: Option<&mut [f64]>,
        sink: Option<&mut dyn EntrySink>,
    ) -> SectionWork {
        let u: [f64; MAX_UNKNOWNS] = std::array::from_fn(|i| {
            if i < self.unknowns() {
                step.increments[self.dof(i)]
            } else {
                0.0
            }
        });
        // The current at each point's start, once.
        let start_rotation = step.rotation.to_rotation_matrix().into_inner();
        let mut currents = [Vector3::zeros(); MAX_POINTS];
        for (current, p) in currents.iter_mut().zip(&self.points) {
            let x = step.position + start_rotation * self.place(p, step.angles);
            if x.z >= water.surface {
                *current = (water.velocity)(&x);
            }
        }
        let evaluate = |u: &[f64; MAX_UNKNOWNS]| self.step_residual(step, water, &currents, u);
        let h = TANGENT_STEP * (1.0 + step.position.norm());
        let evaluation = self.add(&evaluate, &u, h, residual, sink);
        if let Some(magnitude) = magnitude {
            for (i, term) in evaluation.residual[..self.unknowns()].iter().enumerate() {
                magnitude[self.dof(i)] += term.abs();
            }
        }
        evaluation.work
    }

    /// The step's residual at the unknowns `u` (see the module's docs).
    fn step_residual(
        &self,
        step: &SectionStep,
        water: &Water,
        currents: &[Vector3<f64>],
        u: &[f64; MAX_UNKNOWNS],
    ) -> Evaluation {
        let dt = step.dt;
        let theta = Vector3::new(u[3], u[4], u[5]);
        let start = step.rotation.to_rotation_matrix().into_inner();
        let end = cayley(&theta) * start;
        let mean = 0.5 * (start + end);
        let x_start = step.position;
        let x_end = step.position + Vector3::new(u[0], u[1], u[2]);
        let angles: [[f64; MAX_SECTIONS]; 2] = [
            std::array::from_fn(|i| step.angles.get(i).copied().unwrap_or(0.0)),
            std::array::from_fn(|i| step.angles.get(i).map_or(0.0, |a| a + u[6 + i])),
        ];
        let solve = (Matrix3::identity() + 0.5 * skew(&theta))
            .try_inverse()
            .unwrap_or_else(Matrix3::identity);
        let mut residual = [0.0; MAX_UNKNOWNS];
        let mut work = SectionWork::default();
        for (a, ((p, v_start), current)) in self
            .points
            .iter()
            .zip(step.velocities)
            .zip(currents)
            .enumerate()
        {
            let d = [self.place(p, &angles[0]), self.place(p, &angles[1])];
            let moved = (x_end + end * d[1]) - (x_start + start * d[0]);
            let v_end = 2.0 * moved / dt - v_start;
            let flow = current - moved / dt;
            let drag = flow * (0.5 * water.density * p.drag_area * flow.norm());
            let force = p.mass * (v_end - v_start) / dt - Vector3::z() * p.net_weight - drag;
            work.supplied += dt * drag.dot(current);
            work.dissipated += dt * drag.dot(&flow);
            work.energy +=
                0.5 * p.mass * v_end.norm_squared() - p.net_weight * (x_end + end * d[1]).z;
            work.velocities[a] = v_end;
            // w = (I + ½θ̂)⁻¹ Λ₁ d̄.
            let arm = solve * (end * (0.5 * (d[0] + d[1])));
            let moment = arm.cross(&force);
            for k in 0..3 {
                residual[k] += force[k];
                residual[3 + k] += moment[k];
            }
            let local_force = mean.transpose() * force;
            let torques = self.place_gradient(p, &angles, &local_force);
            for (i, torque) in torques[..=p.section].iter().enumerate() {
                residual[6 + i] += torque;
            }
        }
        for (i, section) in self.sections.iter().enumerate() {
            residual[6 + i] += section.hinge_moment_over(angles[0][i], angles[1][i]);
        }
        work.energy += self.hinges_energy(&angles[1][..self.sections.len()]);
        Evaluation { residual, work }
    }

    /// The discrete gradient over the step from `angles[0]` to `angles[1]` of ψ(φ) = f·S(φ)(q_a) (f in the
    /// end node's frame): ∇ψ(φ̄) + [Δψ − ∇ψ(φ̄)·Δφ]Δφ/|Δφ|², with ∂S(q)/∂φ_i = e × (S(q) − H_i).
    fn place_gradient(
        &self,
        p: &MassPoint,
        angles: &[[f64; MAX_SECTIONS]; 2],
        force: &Vector3<f64>,
    ) -> [f64; MAX_SECTIONS] {
        let j = p.section;
        let mid: [f64; MAX_SECTIONS] = std::array::from_fn(|i| 0.5 * (angles[0][i] + angles[1][i]));
        let d_mid = self.place(p, &mid);
        let hinges = self.chain.hinge_positions(&mid, j);
        let mut gradient = [0.0; MAX_SECTIONS];
        for i in 0..=j {
            gradient[i] = force.dot(&self.chain.axis.cross(&(d_mid - hinges[i])));
        }
        let change: [f64; MAX_SECTIONS] = std::array::from_fn(|i| angles[1][i] - angles[0][i]);
        let change2: f64 = change[..=j].iter().map(|c| c * c).sum();
        let along: f64 = (0..=j).map(|i| gradient[i] * change[i]).sum();
        let difference = force.dot(&(self.place(p, &angles[1]) - self.place(p, &angles[0])));
        let mismatch = difference - along;
        let noise = 64.0 * f64::EPSILON * force.norm() * (1.0 + d_mid.norm());
        if change2 > 0.0 && mismatch.abs() > noise {
            for i in 0..=j {
                gradient[i] += mismatch / change2 * change[i];
            }
        }
        gradient
    }

    /// Adds `evaluate`'s residual at the unknowns `base` and, with `sink`, its tangent by central differences
    /// (steps `h` on the position, [`ROTATION_STEP`] on the rotation and the angles); returns the evaluation
    /// at `base`.
    fn add(
        &self,
        evaluate: &dyn Fn(&[f64; MAX_UNKNOWNS]) -> Evaluation,
        base: &[f64; MAX_UNKNOWNS],
        h: f64,
        residual: &mut [f64],
        sink: Option<&mut dyn EntrySink>,
    ) -> Evaluation {
        let evaluation = evaluate(base);
        let unknowns = self.unknowns();
        for i in 0..unknowns {
            residual[self.dof(i)] += evaluation.residual[i];
        }
        if let Some(sink) = sink {
            for j in 0..unknowns {
                let step = if j < 3 { h } else { ROTATION_STEP };
                let (mut plus, mut minus) = (*base, *base);
                plus[j] += step;
                minus[j] -= step;
                let (fp, fm) = (evaluate(&plus).residual, evaluate(&minus).residual);
                for i in 0..unknowns {
                    let value = (fp[i] - fm[i]) / (2.0 * step);
                    if value != 0.0 {
                        sink.add_entry(self.dof(i), self.dof(j), value);
                    }
                }
            }
        }
        evaluation
    }
}

#[cfg(test)]
pub(crate) mod tests {
    use crate::environment::sea::Sea;
    use crate::model::Model;
    use crate::rod::{section::Section, Rod};
    use crate::vessel::articulation::{Articulation, StingerSection};
    use crate::vessel::lay::{stinger_rollers, LayEquipment};
    use crate::vessel::rigid_body::Vessel;
    use nalgebra::{Vector3, Vector6};

    /// A 0.6 m × 30 mm pipe in 150 m of water, held by an OSV's tensioner over a 100 m-radius, 80 m stinger of
    /// 12 rollers whose last 50 m are two hinged sections of stiffness 1e6 N·m/rad, in a 0.5 m/s current.
    pub(crate) fn articulated_s_lay() -> Model {
        let section = Section::pipe(0.6, 0.03, 7850.0, 207e9, 0.3, 1.0, [0.0, 1.0], [0.0, 1.0])
            .expect("pipe");
        let rod = Rod::straight(Vector3::zeros(), Vector3::new(700.0, 0.0, 0.0), 70, section)
            .expect("rod");
        let profile =
            crate::environment::current::CurrentProfile::Uniform(Vector3::new(0.3, 0.4, 0.0));
        let current = crate::environment::current::Current::new(profile, 0.0).expect("current");
        let sea = Sea::new(150.0, 1025.0, Some(current), None).expect("sea");
        let mut model = Model::new(rod, Some(sea), 9.81).expect("model");
        model.pin("A", None).expect("pin");
        let (radius, origin) = (100.0, Vector3::new(-40.0, 0.0, -6.0));
        let rollers = stinger_rollers(radius, 80.0, 12, origin, 0.0, 0.25).expect("stinger");
        let hinged = StingerSection::new(25.0, 3e4, 2e5, 1e6, [-0.5, 0.5], 20.0).expect("section");
        let articulation =
            Articulation::new(radius, origin, 0.0, 30.0, vec![hinged; 2]).expect("sections");
        let mut lay =
            LayEquipment::s_lay(Vector3::new(10.0, 0.0, -6.3), rollers, 1e7).expect("lay");
        lay.articulation = Some(articulation);
        lay.assign_sections();
        let eta = Vector6::new(600.0, 0.0, -150.0, 0.0, 0.0, 0.0);
        model
            .attach_vessel(
                "B",
                Vessel::osv(),
                eta,
                Vector3::zeros(),
                None,
                vec![],
                Some(lay),
            )
            .expect("vessel");
        model
    }
}
