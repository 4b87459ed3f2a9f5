//! The rod: its stress-free reference (nodes, nodal frames, elements) and the element it is made of: the
//! cross-section ([`section`]), the element's statics ([`element`]) and its energy–momentum step
//! ([`dynamic_element`]), and the bodies attached at points of it ([`attachment`]).
//!
//! May use: the basics (rotations, errors, memory).
// Indexing cannot go out of bounds here: Node and element indices of the rod this module builds (nodes.len() = elements + 1, checked at construction).
#![allow(clippy::indexing_slicing)]
pub mod attachment;
pub mod dynamic_element;
pub mod element;
pub mod section;

use crate::error::{finite, Error, Result};
use crate::rod::section::Section;
use crate::so3::{minimal_rotation, quat_from_matrix};
use element::ElementReference;
use nalgebra::{UnitQuaternion, Vector3};

/// A rod in its stress-free reference configuration.
#[derive(Debug, Clone)]
pub struct Rod {
    /// Reference node positions X_a (m), `elements + 1` of them.
    pub nodes: Vec<Vector3<f64>>,
    /// Reference nodal frames R_a⁰ (t1 along the centreline).
    pub frames: Vec<UnitQuaternion<f64>>,
    /// Per-element reference data.
    pub elements: Vec<ElementReference>,
    /// The cross-section, the same along the rod.
    pub section: Section,
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
        Ok(Self::with_frames(nodes, frames, section))
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
        Rod {
            nodes,
            frames,
            elements,
            section,
        }
    }

    /// Number of elements n.
    pub fn element_count(&self) -> usize {
        self.elements.len()
    }

    /// Number of nodes n + 1.
    pub fn node_count(&self) -> usize {
        self.nodes.len()
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
    }

    /// Joins elements `element` and `element + 1` into one by removing the node between them; the joined
    /// element has their summed length and the length-weighted mean reference strains.
    pub fn join_elements(&mut self, element: usize) {
        let (first, second) = (self.elements[element], self.elements[element + 1]);
        let length = first.length + second.length;
        let mean =
            |x: Vector3<f64>, y: Vector3<f64>| (x * first.length + y * second.length) / length;
        self.elements[element] = ElementReference {
            length,
            strain: mean(first.strain, second.strain),
            curvature: mean(first.curvature, second.curvature),
        };
        self.elements.remove(element + 1);
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
