//! A lay route of legs joined by circular arcs: the path a DP reference follows through waypoints.
//!
//! Through waypoints w_0 … w_m (x, y in e), each interior corner w_k turning by Δ_k (signed, + to the left, from
//! the leg into it to the leg out of it) is cut by the arc of radius R tangent to both legs: it starts
//! T_k = R tan(|Δ_k|/2) before the corner on the leg in and ends T_k after it on the leg out, about the centre
//! R to the turn's side of its start. The path is the legs' remaining straights and the arcs, parametrised by
//! its length s; its heading ψ(s) (the tangent's angle from e1 toward e2) is continuous and its curvature is 0 on
//! the straights and ±1/R on the arcs.
// Indexing cannot go out of bounds here: windows of two, and the waypoints', legs' and corners' own indices.
#![allow(clippy::indexing_slicing)]
use crate::error::{finite, positive, Error, Result};
use nalgebra::Vector2;

/// One piece of the path, from arc length `start` (m) along it.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Piece {
    /// A straight from `from` along the unit `direction`.
    Line {
        start: f64,
        from: Vector2<f64>,
        direction: Vector2<f64>,
    },
    /// An arc about `centre` of radius R, starting at the polar angle `angle` (from the centre) and turning
    /// with `sign` (+1 to the left).
    Arc {
        start: f64,
        centre: Vector2<f64>,
        angle: f64,
        sign: f64,
    },
}

/// The route's path: its pieces in order, the heading at its start, the arcs' radius and its length (m).
#[derive(Debug, Clone, PartialEq)]
pub struct RoutePath {
    pieces: Vec<(Piece, f64)>,
    radius: f64,
    length: f64,
}

/// Where the path is at an arc length: the point (m), the heading ψ (rad) and the curvature dψ/ds (1/m).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PathPoint {
    pub point: Vector2<f64>,
    pub heading: f64,
    pub curvature: f64,
}

impl RoutePath {
    /// The path through `waypoints` (at least two, no two consecutive alike) with its corners cut by arcs of
    /// `radius` (m); an error names `waypoints` or `radius` where a corner's arc does not fit its legs.
    pub fn new(waypoints: &[Vector2<f64>], radius: f64) -> Result<Self> {
        if waypoints.len() < 2 {
            return Err(Error::input(
                "waypoints",
                format!("{} points", waypoints.len()),
                "must hold at least two (x, y) points",
            ));
        }
        for w in waypoints {
            finite("waypoints", w.as_slice())?;
        }
        let directions: Vec<Vector2<f64>> = waypoints
            .windows(2)
            .map(|pair| {
                (pair[1] - pair[0]).try_normalize(1e-9).ok_or_else(|| {
                    Error::input(
                        "waypoints",
                        format!("{:?} twice", pair[0].as_slice()),
                        "must not repeat a point",
                    )
                })
            })
            .collect::<Result<_>>()?;
        let turns: Vec<f64> = directions
            .windows(2)
            .map(|pair| pair[0].perp(&pair[1]).atan2(pair[0].dot(&pair[1])))
            .collect();
        if turns.iter().any(|turn| turn.abs() > 1e-12) {
            positive("radius", radius, "m")?;
        }
        // The length each corner's arc takes off the legs beside it.
        let cut: Vec<f64> = turns
            .iter()
            .map(|turn| radius * (0.5 * turn.abs()).tan())
            .collect();
        let mut pieces = Vec::with_capacity(2 * waypoints.len());
        let mut length = 0.0;
        let mut heading = directions[0].y.atan2(directions[0].x);
        for (k, direction) in directions.iter().enumerate() {
            let leg = (waypoints[k + 1] - waypoints[k]).norm();
            let before = if k == 0 { 0.0 } else { cut[k - 1] };
            let after = cut.get(k).copied().unwrap_or(0.0);
            let straight = leg - before - after;
            if straight < -1e-9 * leg {
                return Err(Error::input(
                    "radius",
                    radius,
                    format!(
                        "is too large for leg {} ({leg:.1} m long): its corners' arcs take {:.1} m of it; \
                         use a radius below {:.1} m or longer legs",
                        k + 1,
                        before + after,
                        radius * leg / (before + after)
                    ),
                ));
            }
            let from = waypoints[k] + before * direction;
            pieces.push((
                Piece::Line {
                    start: length,
                    from,
                    direction: *direction,
                },
                heading,
            ));
            length += straight.max(0.0);
            if let Some(&turn) = turns.get(k) {
                if turn.abs() > 1e-12 {
                    let sign = turn.signum();
                    let arc_start = waypoints[k + 1] - after * direction;
                    let left = Vector2::new(-direction.y, direction.x);
                    let centre = arc_start + sign * radius * left;
                    let offset = arc_start - centre;
                    pieces.push((
                        Piece::Arc {
                            start: length,
                            centre,
                            angle: offset.y.atan2(offset.x),
                            sign,
                        },
                        heading,
                    ));
                    length += radius * turn.abs();
                }
                heading += turn;
            }
        }
        Ok(RoutePath {
            pieces,
            radius,
            length,
        })
    }

    /// The path's length (m).
    pub fn length(&self) -> f64 {
        self.length
    }

    /// Where the path is at arc length `s` (m), clamped to [0, length].
    pub fn at(&self, s: f64) -> PathPoint {
        let s = s.clamp(0.0, self.length);
        let start_of = |piece: &Piece| match piece {
            Piece::Line { start, .. } | Piece::Arc { start, .. } => *start,
        };
        let index = self
            .pieces
            .iter()
            .rposition(|(piece, _)| start_of(piece) <= s)
            .unwrap_or(0);
        let Some((piece, heading)) = self.pieces.get(index) else {
            return PathPoint {
                point: Vector2::zeros(),
                heading: 0.0,
                curvature: 0.0,
            };
        };
        match *piece {
            Piece::Line {
                start,
                from,
                direction,
            } => PathPoint {
                point: from + (s - start) * direction,
                heading: *heading,
                curvature: 0.0,
            },
            Piece::Arc {
                start,
                centre,
                angle,
                sign,
            } => {
                let turned = (s - start) / self.radius;
                let polar = angle + sign * turned;
                PathPoint {
                    point: centre + self.radius * Vector2::new(polar.cos(), polar.sin()),
                    heading: heading + sign * turned,
                    curvature: sign / self.radius,
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// An L of two 100 m legs turning left by 90° with R = 30 m: 70 m straight, a quarter circle about
    /// (70, 30), 70 m straight; the heading turns from 0 to π/2 at 1/R on the arc, continuous throughout.
    #[test]
    fn a_corner_is_cut_by_its_tangent_arc() {
        let waypoints = [
            Vector2::new(0.0, 0.0),
            Vector2::new(100.0, 0.0),
            Vector2::new(100.0, 100.0),
        ];
        let path = RoutePath::new(&waypoints, 30.0).unwrap();
        let quarter = 0.5 * std::f64::consts::PI * 30.0;
        assert!((path.length() - (140.0 + quarter)).abs() < 1e-9);
        let centre = Vector2::new(70.0, 30.0);
        for k in 0..=20 {
            let s = 70.0 + quarter * f64::from(k) / 20.0;
            let at = path.at(s);
            assert!(((at.point - centre).norm() - 30.0).abs() < 1e-9);
            assert!((at.heading - (s - 70.0) / 30.0).abs() < 1e-12);
        }
        assert!((path.at(70.0 + 0.5 * quarter).curvature - 1.0 / 30.0).abs() < 1e-15);
        let end = path.at(1e9);
        assert!((end.point - Vector2::new(100.0, 100.0)).norm() < 1e-9);
        // Continuity: neighbouring points 1 mm apart along the path are 1 mm apart in the plane.
        let mut s = 0.0;
        while s < path.length() - 1e-3 {
            let (a, b) = (path.at(s), path.at(s + 1e-3));
            assert!(((b.point - a.point).norm() - 1e-3).abs() < 1e-9, "{s}");
            assert!((b.heading - a.heading).abs() < 1e-4);
            s += 0.25;
        }
        // A right turn's arc lies to the right.
        let right = RoutePath::new(
            &[waypoints[0], waypoints[1], Vector2::new(100.0, -100.0)],
            30.0,
        )
        .unwrap();
        let middle = right.at(70.0 + 0.5 * quarter);
        assert!((middle.point - Vector2::new(70.0, -30.0)).norm() > 29.99);
        assert!(middle.curvature < 0.0 && right.at(1e9).heading < -1.5);
        assert!(RoutePath::new(&waypoints, 120.0).is_err());
        assert!(RoutePath::new(&waypoints[..1], 30.0).is_err());
    }
}
