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
use nalgebra::Vector3;

/// The plastic state of a rod's elements.
#[derive(Debug, Clone, PartialEq)]
pub struct PlasticState {
    /// Each segment's wall fibres, None where it does not yield.
    sections: Vec<Option<FibreSection>>,
    segment_of: Vec<usize>,
    /// Each element's fibres' plastic strains (empty for an element that does not yield): where evaluations
    /// start from, and after the last one.
    pub start: Vec<Vec<f64>>,
    pub end: Vec<Vec<f64>>,
    /// The energy each element dissipated per unit length in its last evaluation (J/m).
    pub dissipated: Vec<f64>,
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
        let start: Vec<Vec<f64>> = rod
            .segment_of
            .iter()
            .map(|&segment| {
                sections[segment]
                    .as_ref()
                    .map_or_else(Vec::new, |fibres| vec![0.0; fibres.state_size()])
            })
            .collect();
        Some(PlasticState {
            sections,
            segment_of: rod.segment_of.clone(),
            end: start.clone(),
            dissipated: vec![0.0; start.len()],
            start,
        })
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
    /// state and dissipation are kept. `bending_scale` scales its bending (statics' continuation from a
    /// cable). None for an element that does not yield.
    pub fn law(
        &mut self,
        element: usize,
        strain: &Vector3<f64>,
        curvature: &Vector3<f64>,
        bending_scale: f64,
    ) -> Option<SectionLaw> {
        let fibres = self.sections[self.segment_of[element]].as_ref()?;
        let (mut law, dissipated) = fibres.law(
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
        self.dissipated[element] = dissipated;
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

    /// Makes the last evaluation's state the next start.
    pub fn commit(&mut self) {
        self.start.clone_from(&self.end);
    }
}
