//! What defines a model, part by part, as a SHA-256 of its full description: a checkpoint stores it so that
//! a resume can tell whether it continues the model it was saved from, and name the part that differs.
//!
//! Each part's description is its `Debug` text (numbers in their shortest exact form), so a fingerprint
//! changes with any value of the part. A function of time (a reference, a pay-out speed, a point load's
//! scale) is described as such, not by what it computes.
use crate::model::Model;
use sha2::{Digest, Sha256};

/// The parts of a model a fingerprint names.
pub const PARTS: [&str; 10] = [
    "line",
    "sea",
    "gravity",
    "supports",
    "point_loads",
    "attachments",
    "pay_out",
    "vessel",
    "controller",
    "environment",
];

/// The SHA-256 of a description, in hexadecimal.
fn digest(description: &str) -> String {
    Sha256::digest(description.as_bytes())
        .iter()
        .map(|byte| format!("{byte:02x}"))
        .collect()
}

impl Model {
    /// Each part of [`PARTS`] with the SHA-256 of its description.
    pub fn fingerprint(&self) -> Vec<(&'static str, String)> {
        let vessel = self.vessel.as_ref();
        let descriptions = [
            format!("{:?}", self.rod),
            format!("{:?}", self.sea),
            format!("{:?}", self.gravity),
            format!("{:?}", self.supports),
            format!("{:?}", self.point_loads),
            format!("{:?}", self.attachments),
            format!("{:?}", self.pay_out),
            format!(
                "{:?}",
                vessel.map(|a| (
                    a.node,
                    &a.vessel,
                    a.angle,
                    a.eta,
                    a.surface,
                    &a.lay,
                    &a.winch,
                    a.hull_loads
                ))
            ),
            format!("{:?}", vessel.map(|a| &a.controller)),
            format!("{:?}", vessel.map(|a| &a.environment)),
        ];
        PARTS
            .iter()
            .zip(descriptions)
            .map(|(part, description)| (*part, digest(&description)))
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use crate::model::Model;
    use crate::rod::section::Section;
    use crate::rod::Rod;
    use nalgebra::Vector3;

    fn model(end: f64) -> Model {
        let section = Section::pipe(0.3, 0.02, 7850.0, 207e9, 0.3, 1025.0, [0.0; 2], [0.0; 2])
            .expect("section");
        let rod =
            Rod::straight(Vector3::zeros(), Vector3::new(end, 0.0, 0.0), 4, section).expect("rod");
        Model::new(rod, None, 9.81).expect("model")
    }

    /// The same model gives the same fingerprint; moving a node or a support changes only its part.
    #[test]
    fn a_change_shows_in_its_part_only() {
        let a = model(100.0).fingerprint();
        assert_eq!(a, model(100.0).fingerprint());
        assert_eq!(a[0].1.len(), 64);
        let longer = model(100.000001).fingerprint();
        let differing: Vec<&str> = a
            .iter()
            .zip(&longer)
            .filter(|(x, y)| x.1 != y.1)
            .map(|(x, _)| x.0)
            .collect();
        assert_eq!(differing, ["line"]);
        let mut pinned = model(100.0);
        pinned.pin("A", None).expect("pin");
        let differing: Vec<&str> = a
            .iter()
            .zip(&pinned.fingerprint())
            .filter(|(x, y)| x.1 != y.1)
            .map(|(x, _)| x.0)
            .collect();
        assert_eq!(differing, ["supports"]);
    }
}
