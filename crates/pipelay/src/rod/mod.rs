//! The rod: its stress-free reference (nodes, nodal frames, elements) made of consecutive segments, each with
//! its own cross-section ([`section`]); the rod element's statics ([`element`]) and energy–momentum step
//! ([`dynamic_element`]); the cable element of segments without bending stiffness ([`cable`]); and the bodies
//! attached at points of it ([`attachment`]).
//!
//! May use: the basics (rotations, errors, memory).
// Indexing cannot go out of bounds here: Node and element indices of the rod this module builds (nodes.len() = elements + 1, checked at construction).
#![allow(clippy::indexing_slicing)]
pub mod attachment;
pub mod cable;
pub mod dynamic_element;
pub mod element;
pub mod fibre_section;
pub mod material;
pub mod plastic_state;
pub mod reeling;
pub mod section;

use crate::error::{finite, Error, Result};
use crate::rod::section::Section;
use crate::so3::{minimal_rotation, quat_from_matrix};
use element::ElementReference;
use nalgebra::{UnitQuaternion, Vector3};

/// The longest line a rod may be (m): beyond it the nodes' coordinates lose the precision that tells them
/// apart (1e8 m is 2500 times round the Earth).
pub const LONGEST_LINE: f64 = 1e8;

/// A rod in its stress-free reference configuration.
#[derive(Debug, Clone)]
pub struct Rod {
    /// Reference node positions X_a (m), `elements + 1` of them.
    pub nodes: Vec<Vector3<f64>>,
    /// Reference nodal frames R_a⁰ (t1 along the centreline).
    pub frames: Vec<UnitQuaternion<f64>>,
    /// Per-element reference data.
    pub elements: Vec<ElementReference>,
    /// The cross-section of each segment, from end A.
    pub sections: Vec<Section>,
    /// The segment each element belongs to (an index into `sections`; a pay-out feed adds sections that the
    /// elements it pays out take).
    pub segment_of: Vec<usize>,
}

/// One segment of a line: its unstretched length (m), its section and its number of elements.
#[derive(Debug, Clone)]
pub struct Segment {
    pub length: f64,
    pub section: Section,
    pub elements: usize,
}

impl Segment {
    /// Checks the segment: a finite length > 0 and at least one element, named `prefix` + the field.
    pub fn check(&self, prefix: &str) -> Result<()> {
        finite(&format!("{prefix}length"), &[self.length])?;
        if self.length <= 0.0 {
            return Err(Error::input(
                format!("{prefix}length"),
                self.length,
                "must be > 0 m",
            ));
        }
        if self.elements == 0 {
            return Err(Error::input(
                format!("{prefix}elements"),
                self.elements,
                "must be an integer >= 1",
            ));
        }
        Ok(())
    }
}

impl Rod {
    /// A rod through `nodes` (a polyline). Nodal frames: t1 along the average of the adjacent chords;
    /// the first frame is the smallest rotation of e1 onto t1, the others follow by parallel transport.
    pub fn new(nodes: Vec<Vector3<f64>>, section: Section) -> Result<Self> {
        if nodes.len() < 2 {
            return Err(Error::input(
                "nodes",
                format!("{} node(s)", nodes.len()),
                "need at least 2 nodes (1 element)",
            ));
        }
        for node in &nodes {
            finite("nodes", node.as_slice())?;
        }
        let count = nodes.len();
        crate::memory::check(
            "nodes",
            format!("{count} nodes"),
            count as f64 * crate::memory::ROD_BYTES_PER_ELEMENT,
            "the rod's reference",
        )?;
        let mut chords = crate::memory::vec_with_capacity(count - 1, "the rod's chords")?;
        for (i, pair) in nodes.windows(2).enumerate() {
            let chord = pair[1] - pair[0];
            let length = chord.norm();
            let scale = pair[0].norm().max(pair[1].norm()).max(1.0);
            if length <= 1e-12 * scale {
                return Err(Error::input(
                    "nodes",
                    format!(
                        "nodes {i} and {} coincide at {:?}",
                        i + 1,
                        pair[0].as_slice()
                    ),
                    "consecutive nodes must be distinct",
                ));
            }
            chords.push(chord / length);
        }
        let tangents: Vec<Vector3<f64>> = (0..nodes.len())
            .map(|a| {
                let before = if a > 0 { chords[a - 1] } else { chords[0] };
                let after = chords.get(a).copied().unwrap_or(before);
                let sum = before + after;
                // A reversal of direction (sum ≈ 0) keeps the incoming chord.
                if sum.norm() > 1e-8 {
                    sum.normalize()
                } else {
                    before
                }
            })
            .collect();
        let mut frames = crate::memory::vec_with_capacity(count, "the rod's frames")?;
        let mut frame = minimal_rotation(&Vector3::x(), &tangents[0]);
        frames.push(quat_from_matrix(&frame));
        for pair in tangents.windows(2) {
            frame = minimal_rotation(&pair[0], &pair[1]) * frame;
            frames.push(quat_from_matrix(&frame));
        }
        let mut rod = Self::with_frames(nodes, frames, section);
        rod.unstrain_cables();
        Ok(rod)
    }

    /// A straight rod of `elements` equal elements from `start` to `end`.
    pub fn straight(
        start: Vector3<f64>,
        end: Vector3<f64>,
        elements: usize,
        section: Section,
    ) -> Result<Self> {
        if elements == 0 {
            return Err(Error::input(
                "elements",
                elements,
                "must be an integer >= 1",
            ));
        }
        finite("start", start.as_slice())?;
        finite("end", end.as_slice())?;
        let span = (end - start).amax();
        if span > LONGEST_LINE {
            return Err(Error::input(
                "end",
                format!("{:?}, {span:e} m from start", end.as_slice()),
                format!("must make a line of at most {LONGEST_LINE:e} m"),
            ));
        }
        if (end - start).norm() <= 1e-12 * start.norm().max(end.norm()).max(1.0) {
            return Err(Error::input(
                "end",
                format!("{:?}, the same point as start", end.as_slice()),
                "must differ from start",
            ));
        }
        crate::memory::check(
            "elements",
            elements,
            elements as f64 * crate::memory::ROD_BYTES_PER_ELEMENT,
            "the rod's reference",
        )?;
        let mut nodes = crate::memory::vec_with_capacity(elements + 1, "the rod's nodes")?;
        nodes.extend((0..=elements).map(|i| start + (end - start) * (i as f64 / elements as f64)));
        Self::new(nodes, section)
    }

    fn with_frames(
        nodes: Vec<Vector3<f64>>,
        frames: Vec<UnitQuaternion<f64>>,
        section: Section,
    ) -> Self {
        let elements = (0..nodes.len() - 1)
            .map(|e| {
                ElementReference::new(
                    &nodes[e],
                    &nodes[e + 1],
                    &frames[e],
                    &frames[e + 1],
                    (nodes[e + 1] - nodes[e]).norm(),
                )
            })
            .collect();
        let segment_of = vec![0; nodes.len() - 1];
        Rod {
            nodes,
            frames,
            elements,
            sections: vec![section],
            segment_of,
        }
    }

    /// A straight line of consecutive `segments` from `start` along `direction`, continuous at the joints
    /// (each joint is a node of both segments); each segment is divided into its own equal elements.
    pub fn segments(
        start: Vector3<f64>,
        direction: Vector3<f64>,
        segments: &[Segment],
    ) -> Result<Self> {
        finite("start", start.as_slice())?;
        finite("direction", direction.as_slice())?;
        if direction.norm() == 0.0 {
            return Err(Error::input(
                "direction",
                format!("{:?}", direction.as_slice()),
                "must be a non-zero vector",
            ));
        }
        let Some(first) = segments.first() else {
            return Err(Error::input(
                "segments",
                "an empty list",
                "need at least one segment",
            ));
        };
        let axis = direction.normalize();
        let length: f64 = segments.iter().map(|s| s.length.abs()).sum();
        if length > LONGEST_LINE {
            return Err(Error::input(
                "segments",
                format!("segments of {length:e} m in all"),
                format!("must make a line of at most {LONGEST_LINE:e} m"),
            ));
        }
        let total: usize = segments.iter().map(|s| s.elements).sum();
        crate::memory::check(
            "segments",
            format!("{total} elements"),
            total as f64 * crate::memory::ROD_BYTES_PER_ELEMENT,
            "the rod's reference",
        )?;
        let mut nodes = crate::memory::vec_with_capacity(total + 1, "the rod's nodes")?;
        let mut segment_of = crate::memory::vec_with_capacity(total, "the rod's segments")?;
        nodes.push(start);
        let mut arc = 0.0;
        for (k, segment) in segments.iter().enumerate() {
            segment.check(&format!("segments[{k}]."))?;
            for i in 1..=segment.elements {
                let s = arc + segment.length * (i as f64 / segment.elements as f64);
                nodes.push(start + axis * s);
                segment_of.push(k);
            }
            arc += segment.length;
        }
        let mut rod = Self::new(nodes, first.section.clone())?;
        rod.sections = segments.iter().map(|s| s.section.clone()).collect();
        rod.segment_of = segment_of;
        rod.unstrain_cables();
        Ok(rod)
    }

    /// Gives the cable elements zero reference strain and curvature: a cable's stress-free state is its
    /// unstretched length alone (the frames' round-off would otherwise leave a strain of ~1e-16 in it).
    pub fn unstrain_cables(&mut self) {
        for (element, &segment) in self.elements.iter_mut().zip(&self.segment_of) {
            if self.sections[segment].cable {
                element.strain = Vector3::zeros();
                element.curvature = Vector3::zeros();
            }
        }
    }

    /// Element `element`'s changes of strain and curvature from its reference, (Γ − Γ₀, K − K₀), in the
    /// configuration `positions`, `rotations` (the objective element's, [`element::midpoint_frame_and_strains`]).
    pub fn strain_changes(
        &self,
        element: usize,
        positions: &[Vector3<f64>],
        rotations: &[UnitQuaternion<f64>],
    ) -> (Vector3<f64>, Vector3<f64>) {
        let reference = &self.elements[element];
        let (_, strain, curvature) = element::midpoint_frame_and_strains(
            &positions[element],
            &positions[element + 1],
            &rotations[element],
            &rotations[element + 1],
            reference,
        );
        (strain - reference.strain, curvature - reference.curvature)
    }

    /// The section of element `element`.
    pub fn section(&self, element: usize) -> &Section {
        &self.sections[self.segment_of[element]]
    }

    /// Whether every element at node `node` is a cable's: its rotation is then no degree of freedom.
    pub fn is_cable_node(&self, node: usize) -> bool {
        let before = node.checked_sub(1).map(|e| self.section(e).cable);
        let after = (node < self.element_count()).then(|| self.section(node).cable);
        before.unwrap_or(true) && after.unwrap_or(true)
    }

    /// Which nodes are cable nodes ([`Rod::is_cable_node`]).
    pub fn cable_nodes(&self) -> Vec<bool> {
        (0..self.node_count())
            .map(|a| self.is_cable_node(a))
            .collect()
    }

    /// The largest of a section property over the segments (e.g. the axial stiffness, for scales).
    pub fn largest(&self, property: impl Fn(&Section) -> f64) -> f64 {
        self.sections.iter().map(property).fold(0.0, f64::max)
    }

    /// The length-weighted mean of a section property over the elements (e.g. the submerged weight, for the
    /// statics' catenary start).
    pub fn mean(&self, property: impl Fn(&Section) -> f64) -> f64 {
        let total = self.length();
        self.elements
            .iter()
            .zip(&self.segment_of)
            .map(|(e, &k)| e.length * property(&self.sections[k]))
            .sum::<f64>()
            / total
    }

    /// Number of elements n.
    pub fn element_count(&self) -> usize {
        self.elements.len()
    }

    /// Number of nodes n + 1.
    pub fn node_count(&self) -> usize {
        self.nodes.len()
    }

    /// The shortest element's reference length (m).
    pub fn shortest_element(&self) -> f64 {
        self.elements
            .iter()
            .map(|e| e.length)
            .fold(f64::INFINITY, f64::min)
    }

    /// Total reference length (m).
    pub fn length(&self) -> f64 {
        self.elements.iter().map(|e| e.length).sum()
    }

    /// Splits element `element` at a fraction `fraction` ∈ (0, 1) of its length from its first node: a node
    /// is inserted at index `element + 1`, on the element's reference chord, with the geodesic frame between
    /// its ends; both halves keep the element's reference strains (Γ0, K0 are per length).
    pub fn split_element(&mut self, element: usize, fraction: f64) {
        let parent = self.elements[element];
        let (a, b) = (element, element + 1);
        let node = self.nodes[a] + (self.nodes[b] - self.nodes[a]) * fraction;
        let frame = self.frames[a].slerp(&self.frames[b], fraction);
        let first = ElementReference {
            length: fraction * parent.length,
            ..parent
        };
        let second = ElementReference {
            length: (1.0 - fraction) * parent.length,
            ..parent
        };
        self.nodes.insert(b, node);
        self.frames.insert(b, frame);
        self.elements[element] = first;
        self.elements.insert(element + 1, second);
        self.segment_of
            .insert(element + 1, self.segment_of[element]);
    }

    /// Joins elements `element` and `element + 1` into one by removing the node between them; the joined
    /// element has their summed length, the length-weighted mean reference strains and the segment of the
    /// first (`keep` = 0) or the second (`keep` = 1).
    pub fn join_elements(&mut self, element: usize, keep: usize) {
        let (first, second) = (self.elements[element], self.elements[element + 1]);
        let length = first.length + second.length;
        let mean =
            |x: Vector3<f64>, y: Vector3<f64>| (x * first.length + y * second.length) / length;
        self.elements[element] = ElementReference {
            length,
            strain: mean(first.strain, second.strain),
            curvature: mean(first.curvature, second.curvature),
        };
        self.segment_of[element] = self.segment_of[element + keep.min(1)];
        self.elements.remove(element + 1);
        self.segment_of.remove(element + 1);
        self.nodes.remove(element + 1);
        self.frames.remove(element + 1);
    }

    /// Each node's arc length from end A along the reference (n + 1 values, m).
    pub fn arc_lengths(&self) -> Vec<f64> {
        std::iter::once(0.0)
            .chain(self.elements.iter().scan(0.0, |arc, e| {
                *arc += e.length;
                Some(*arc)
            }))
            .collect()
    }
}

/// The unit mean of the chords at node `node` of `positions` (a polyline): the direction of a node without a
/// rotation of its own.
pub fn chord_axis(positions: &[Vector3<f64>], node: usize) -> Vector3<f64> {
    let before = node
        .checked_sub(1)
        .map(|a| (positions[node] - positions[a]).normalize());
    let after = positions
        .get(node + 1)
        .map(|b| (b - positions[node]).normalize());
    let sum = before.unwrap_or(Vector3::zeros()) + after.unwrap_or(Vector3::zeros());
    if sum.norm() > 1e-8 {
        sum.normalize()
    } else {
        before.or(after).unwrap_or(Vector3::x())
    }
}
