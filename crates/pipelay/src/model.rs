//! A model: the rod, the sea, gravity, supports (eqs. 20–21) and point loads.
use crate::error::{finite, non_negative, Error, Result};
use crate::hydro::Sea;
use crate::rod::Rod;
use crate::so3::quat_from_matrix;
use nalgebra::{Matrix3, UnitQuaternion, Vector3};

/// How a node is held.
#[derive(Debug, Clone, PartialEq)]
pub enum SupportKind {
    /// Position and rotation prescribed.
    Clamp {
        position: Vector3<f64>,
        rotation: UnitQuaternion<f64>,
    },
    /// Position prescribed, rotation free.
    Pin { position: Vector3<f64> },
}

/// A support at a node.
#[derive(Debug, Clone, PartialEq)]
pub struct Support {
    pub node: usize,
    pub kind: SupportKind,
}

impl Support {
    /// Prescribed position.
    pub fn position(&self) -> Vector3<f64> {
        match self.kind {
            SupportKind::Clamp { position, .. } | SupportKind::Pin { position } => position,
        }
    }

    /// Prescribed rotation, if any.
    pub fn rotation(&self) -> Option<UnitQuaternion<f64>> {
        match self.kind {
            SupportKind::Clamp { rotation, .. } => Some(rotation),
            SupportKind::Pin { .. } => None,
        }
    }
}

/// A fixed-direction (dead) force and moment at a node.
#[derive(Debug, Clone, PartialEq)]
pub struct PointLoad {
    pub node: usize,
    pub force: Vector3<f64>,
    pub moment: Vector3<f64>,
}

/// The whole model.
#[derive(Debug, Clone)]
pub struct Model {
    pub rod: Rod,
    pub sea: Option<Sea>,
    /// Gravitational acceleration g ≥ 0 (m/s²), acting along +e3.
    pub gravity: f64,
    pub supports: Vec<Support>,
    pub point_loads: Vec<PointLoad>,
}

impl Model {
    /// A free rod, optionally in a sea.
    pub fn new(rod: Rod, sea: Option<Sea>, gravity: f64) -> Result<Self> {
        non_negative("gravity", gravity, "m/s²")?;
        Ok(Model {
            rod,
            sea,
            gravity,
            supports: Vec::new(),
            point_loads: Vec::new(),
        })
    }

    /// The node of a rod end: "A" is node 0 (seabed end), "B" node n (top end).
    pub fn end_node(&self, end: &str) -> Result<usize> {
        match end {
            "A" => Ok(0),
            "B" => Ok(self.rod.element_count()),
            other => Err(Error::input(
                "end",
                format!("{other:?}"),
                "must be \"A\" (node 0) or \"B\" (node n)",
            )),
        }
    }

    /// A node index, Python style: negative counts from the end.
    pub fn node_index(&self, node: i64) -> Result<usize> {
        let count = self.rod.node_count() as i64;
        let index = if node < 0 { node + count } else { node };
        if (0..count).contains(&index) {
            Ok(index as usize)
        } else {
            Err(Error::input(
                "node",
                node,
                format!("must be an index in [-{count}, {})", count),
            ))
        }
    }

    fn add_support(&mut self, node: usize, kind: SupportKind) {
        self.supports.retain(|s| s.node != node);
        self.supports.push(Support { node, kind });
    }

    /// Clamps an end: position and rotation held (default: the reference node and frame).
    pub fn clamp(
        &mut self,
        end: &str,
        position: Option<Vector3<f64>>,
        rotation: Option<Matrix3<f64>>,
    ) -> Result<()> {
        let node = self.end_node(end)?;
        let position = self.checked_position(node, position)?;
        let rotation = match rotation {
            None => self.rod.frames[node],
            Some(r) => {
                finite("rotation", r.as_slice())?;
                let error = (r.transpose() * r - Matrix3::identity()).abs().max();
                if error > 1e-6 || r.determinant() <= 0.0 {
                    return Err(Error::input(
                        "rotation",
                        format!(
                            "a matrix with |RᵀR − I| = {error:.2e}, det = {:.4}",
                            r.determinant()
                        ),
                        "must be a rotation matrix (orthonormal to 1e-6, det = +1)",
                    ));
                }
                quat_from_matrix(&r)
            }
        };
        self.add_support(node, SupportKind::Clamp { position, rotation });
        Ok(())
    }

    /// Pins an end: position held (default: the reference node), rotation free.
    pub fn pin(&mut self, end: &str, position: Option<Vector3<f64>>) -> Result<()> {
        let node = self.end_node(end)?;
        let position = self.checked_position(node, position)?;
        self.add_support(node, SupportKind::Pin { position });
        Ok(())
    }

    fn checked_position(
        &self,
        node: usize,
        position: Option<Vector3<f64>>,
    ) -> Result<Vector3<f64>> {
        match position {
            None => Ok(self.rod.nodes[node]),
            Some(p) => {
                finite("position", p.as_slice())?;
                Ok(p)
            }
        }
    }

    /// Adds a fixed-direction force (N) and moment (N·m) at a node.
    pub fn point_load(
        &mut self,
        node: i64,
        force: Vector3<f64>,
        moment: Vector3<f64>,
    ) -> Result<()> {
        let node = self.node_index(node)?;
        finite("force", force.as_slice())?;
        finite("moment", moment.as_slice())?;
        self.point_loads.push(PointLoad {
            node,
            force,
            moment,
        });
        Ok(())
    }

    /// Submerged weight per unit reference length (N/m, along +e3): (m − ρ_w A_b) g (text under eq. 17).
    pub fn submerged_weight(&self) -> f64 {
        let section = &self.rod.section;
        let buoyancy_mass = self
            .sea
            .as_ref()
            .map_or(0.0, |sea| sea.density * section.displaced_area);
        (section.mass - buoyancy_mass) * self.gravity
    }

    /// Morison drag coefficients k = ½ρ_w C_D d_o (axial, normal), zero without a sea.
    pub fn drag_coefficients(&self) -> (f64, f64) {
        let section = &self.rod.section;
        match &self.sea {
            Some(sea) => {
                let k = 0.5 * sea.density * section.outer_diameter;
                (k * section.drag[0], k * section.drag[1])
            }
            None => (0.0, 0.0),
        }
    }
}
