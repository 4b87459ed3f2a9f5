//! The plastic state of a rod's yielding elements: each element's wall fibres' plastic strains
//! ([`crate::rod::fibre_section`]), where evaluations start from and where the last one ended.
//!
//! An element of a segment whose section yields ([`crate::rod::section::Section::yields`]) takes its section
//! law from its wall's fibres at its Gauss point, returned from the state `start`; its state after the
//! evaluation goes to `end`, and [`PlasticState::commit`] makes that the next start. Statics evaluates every
//! state from the model's initial state (a proportional, monotonic path from it); a run commits each step.
// Indexing cannot go out of bounds here: segment and element indices of the rod the state was built for.
#![allow(clippy::indexing_slicing)]
use crate::rod::element::SectionLaw;
use crate::rod::fibre_section::FibreSection;
use crate::rod::Rod;
use nalgebra::{UnitQuaternion, Vector3};

/// The plastic state of a rod's elements.
#[derive(Debug, Clone, PartialEq)]
pub struct PlasticState {
    /// Each segment's wall fibres, None where it does not yield.
    sections: Vec<Option<FibreSection>>,
    /// Each segment's fibres' state where the pipe enters the line at the hold point: the unyielded pipe's
    /// zeros, or the state a reel-lay's reeling left ([`PlasticState::enter`]); empty where it does not yield.
    entry: Vec<Vec<f64>>,
    segment_of: Vec<usize>,
    /// Each element's fibres' plastic strains (empty for an element that does not yield): where evaluations
    /// start from, and after the last one.
    pub start: Vec<Vec<f64>>,
    pub end: Vec<Vec<f64>>,
}

impl PlasticState {
    /// The state of `rod` from rest; None if no segment yields.
    pub fn new(rod: &Rod) -> Option<Self> {
        let sections: Vec<Option<FibreSection>> = rod
            .sections
            .iter()
            .map(|s| {
                s.yields()
                    .then(|| s.fibre_section().and_then(|fibres| fibres.ok()))
                    .flatten()
            })
            .collect();
        if sections.iter().all(Option::is_none) {
            return None;
        }
        let entry: Vec<Vec<f64>> = sections
            .iter()
            .map(|fibres| {
                fibres
                    .as_ref()
                    .map_or_else(Vec::new, |fibres| vec![0.0; fibres.state_size()])
            })
            .collect();
        let start: Vec<Vec<f64>> = rod
            .segment_of
            .iter()
            .map(|&segment| entry[segment].clone())
            .collect();
        Some(PlasticState {
            sections,
            entry,
            segment_of: rod.segment_of.clone(),
            end: start.clone(),
            start,
        })
    }

    /// Makes the pipe enter the line in the state `entry` gives each yielding segment's fibres (a reel-lay's
    /// reeling, [`crate::rod::reeling::entry_state`]): the entry of the steady lay's history ([`Self::march`])
    /// and every element's state from rest.
    pub fn enter(&mut self, entry: impl Fn(&FibreSection) -> Vec<f64>) {
        for (state, fibres) in self.entry.iter_mut().zip(&self.sections) {
            if let Some(fibres) = fibres {
                *state = entry(fibres);
            }
        }
        for (e, start) in self.start.iter_mut().enumerate() {
            start.clone_from(&self.entry[self.segment_of[e]]);
        }
        self.end.clone_from(&self.start);
    }

    /// Makes `starts` (each element's fibres' state, as a run keeps them) where evaluations start from; an
    /// element whose state does not fit its fibres keeps its own.
    pub fn start_from(&mut self, starts: &[Vec<f64>]) {
        for (start, given) in self.start.iter_mut().zip(starts) {
            if start.len() == given.len() {
                start.copy_from_slice(given);
            }
        }
        self.end.clone_from(&self.start);
    }

    /// The state segment `segment`'s pipe enters the line in (empty where it does not yield).
    pub fn entry(&self, segment: usize) -> &[f64] {
        &self.entry[segment]
    }

    /// Element `element`'s wall fibres, if it yields.
    pub fn fibres(&self, element: usize) -> Option<&FibreSection> {
        self.sections[self.segment_of[element]].as_ref()
    }

    /// Whether element `element` yields.
    pub fn yields(&self, element: usize) -> bool {
        self.sections[self.segment_of[element]].is_some()
    }

    /// Element `element`'s section law at the strain and curvature changes, from its start state; its end
    /// state is kept. `bending_scale` scales its bending (statics' continuation from a
    /// cable). None for an element that does not yield.
    pub fn law(
        &mut self,
        element: usize,
        strain: &Vector3<f64>,
        curvature: &Vector3<f64>,
        bending_scale: f64,
    ) -> Option<SectionLaw> {
        let fibres = self.sections[self.segment_of[element]].as_ref()?;
        let (mut law, _) = fibres.law(
            strain,
            curvature,
            &self.start[element],
            &mut self.end[element],
        );
        if bending_scale != 1.0 {
            for row in 4..6 {
                law.moment[row - 3] *= bending_scale;
                for column in 0..6 {
                    law.stiffness[(row, column)] *= bending_scale;
                }
            }
        }
        Some(law)
    }

    /// The largest plastic strain over element `element`'s wall fibres at the strain and curvature changes
    /// from its start state (0 for an element that does not yield).
    pub fn largest_plastic_strain(
        &self,
        element: usize,
        strain: &Vector3<f64>,
        curvature: &Vector3<f64>,
    ) -> f64 {
        self.sections[self.segment_of[element]]
            .as_ref()
            .map_or(0.0, |fibres| {
                fibres.largest_plastic_strain(
                    &Vector3::new(strain.x, curvature.y, curvature.z),
                    &self.start[element],
                )
            })
    }

    /// The steady lay's history: every material point of the pipe has come from the hold point at node
    /// `hold` (an end) through the configuration (`positions`, `rotations`), so each element's fibres start from
    /// the state its upstream neighbour (toward the hold) ended with, the first from the entry state (the
    /// unyielded pipe, or the reeled one), and end with its own strains. Sets the starts and ends so.
    pub fn march(
        &mut self,
        rod: &Rod,
        positions: &[Vector3<f64>],
        rotations: &[UnitQuaternion<f64>],
        hold: usize,
    ) {
        let elements = rod.element_count();
        let order: Vec<usize> = if hold == 0 {
            (0..elements).collect()
        } else {
            (0..elements).rev().collect()
        };
        let mut upstream: Option<usize> = None;
        for &e in &order {
            if !self.yields(e) {
                upstream = None;
                continue;
            }
            match upstream.filter(|&u| self.end[u].len() == self.start[e].len()) {
                Some(u) => self.start[e].copy_from_slice(&self.end[u]),
                None => self.start[e].clone_from(&self.entry[self.segment_of[e]]),
            }
            let (strain, curvature) = rod.strain_changes(e, positions, rotations);
            self.law(e, &strain, &curvature, 1.0);
            upstream = Some(e);
        }
    }

    /// Makes the last evaluation's state the next start.
    pub fn commit(&mut self) {
        self.start.clone_from(&self.end);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rod::material::Material;
    use crate::rod::section::Section;
    use crate::so3::exp_quat;

    /// A pipe of the thin elastic–perfectly plastic tube whose first half (from the hold at node 0) is bent to
    /// 1.8 κ_y and whose second half is straight again (straightening it unloads elastically: less than 2 κ_y):
    /// marched from the hold, the straight half keeps the residual curvature κ − M(κ)/EI of the thin tube's
    /// closed form, and its plastic strain.
    #[test]
    fn a_pipe_straightened_after_a_bend_keeps_the_closed_form_residual_curvature() {
        let (d, t, e, fy) = (0.4, 0.002, 200e9, 400e6);
        let mut section = Section::pipe(d, t, 7850.0, e, 0.3, 0.0, [0.0, 1.0], [0.0, 1.0]).unwrap();
        if let Some(wall) = section.wall.as_mut() {
            wall.material = Some(Material::elastic_perfectly_plastic(e, fy).unwrap());
        }
        let rod =
            Rod::straight(Vector3::zeros(), Vector3::new(10.0, 0.0, 0.0), 20, section).unwrap();
        let a = 0.5 * (d - t);
        let kappa_y = fy / (e * a);
        let inertia = std::f64::consts::PI / 64.0 * (d.powi(4) - (d - 2.0 * t).powi(4));
        let kappa = 1.8 * kappa_y;
        // Nodes 0..=10 on an arc about e2, then straight along its end tangent.
        let (mut positions, mut rotations) =
            (vec![Vector3::zeros()], vec![exp_quat(&Vector3::zeros())]);
        for node in 1..=20 {
            let angle = kappa * 0.5 * (node.min(10) as f64);
            let previous = (
                kappa * 0.5 * ((node - 1).min(10) as f64),
                positions[node - 1],
            );
            let chord = if node <= 10 {
                // The chord of an arc of 0.5 m, along the mean of its ends' tangents.
                let mid = 0.5 * (previous.0 + angle);
                2.0 * (0.25 * kappa).sin() / kappa * Vector3::new(mid.cos(), 0.0, -mid.sin())
            } else {
                0.5 * Vector3::new(angle.cos(), 0.0, -angle.sin())
            };
            positions.push(previous.1 + chord);
            rotations.push(exp_quat(&Vector3::new(0.0, angle, 0.0)));
        }
        let mut state = PlasticState::new(&rod).unwrap();
        state.march(&rod, &positions, &rotations, 0);
        state.commit();
        let (strain, curvature) = rod.strain_changes(15, &positions, &rotations);
        let moment = state.law(15, &strain, &curvature, 1.0).unwrap().moment;
        let residual = (curvature.y - moment.y / (e * inertia)).abs();
        let beta = (1.0 / 1.8f64).asin();
        let ratio = 4.0 / std::f64::consts::PI
            * (1.8 * (0.5 * beta - 0.25 * (2.0 * beta).sin()) + beta.cos());
        let expected = kappa - ratio * kappa_y;
        println!(
            "residual curvature {:.6} κ_y, closed form {:.6} κ_y",
            residual / kappa_y,
            expected / kappa_y
        );
        assert!(
            (residual / expected - 1.0).abs() < 2e-3,
            "{residual} vs {expected}"
        );
        assert!(state.largest_plastic_strain(15, &strain, &curvature) > 0.0);
    }
}
