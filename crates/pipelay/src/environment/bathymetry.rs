//! The seabed's shape: its elevation z = b(x, y) in frame e (e3 down, so b grows with depth), flat, a plane
//! or a grid interpolated bilinearly, and the penetration of a point into it.
//!
//! Penetration (positive inside the seabed) of a point p = (x, y, z): δ(p) = (z − b(x, y)) c(x, y), the
//! vertical gap times the cosine of the local slope c = 1/√(1 + |G|²). For a plane G = ∇b and δ is the exact
//! normal distance. For a grid G is the bilinear interpolation of the nodal gradients of b (central
//! differences), so that δ is continuous across cells (∇b of a bilinear surface is not) and a plane given as
//! a grid is the same seabed as the plane. The contact force −k d δ ∇δ then acts along the local normal
//! (b_x, b_y, −1)/√(1 + |∇b|²) up to terms of the order of the penetration times the change of slope.
// Indexing cannot go out of bounds here: Grid indices found by searching the validated, sorted axes (at least 2 points each).
#![allow(clippy::indexing_slicing)]
use crate::error::{finite, Error, Result};
use nalgebra::{Matrix2, Matrix3, Vector2, Vector3};

/// The seabed's shape.
#[derive(Debug, Clone, PartialEq)]
pub enum Bathymetry {
    /// b(x, y) = z + g_x x + g_y y.
    Plane { z: f64, gradient: Vector2<f64> },
    /// Values of b at the nodes of a rectangular grid, interpolated bilinearly and held constant outside it.
    Grid(Grid),
}

/// A rectangular grid of seabed elevations.
#[derive(Debug, Clone, PartialEq)]
pub struct Grid {
    /// Strictly increasing x (m), at least 2.
    pub x: Vec<f64>,
    /// Strictly increasing y (m), at least 2.
    pub y: Vec<f64>,
    /// b at (x_i, y_j), stored at i·ny + j (m).
    pub z: Vec<f64>,
    /// ∂b/∂x and ∂b/∂y at the nodes (central differences, one-sided at the borders).
    slope_x: Vec<f64>,
    slope_y: Vec<f64>,
}

/// The penetration δ of a point and its first and second derivatives with respect to the point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Penetration {
    pub value: f64,
    pub gradient: Vector3<f64>,
    pub hessian: Matrix3<f64>,
}

/// A bilinear interpolant's value, gradient and mixed derivative f_xy at a point.
struct Bilinear {
    value: f64,
    gradient: Vector2<f64>,
    mixed: f64,
}

fn increasing(argument: &str, values: &[f64]) -> Result<()> {
    finite(argument, values)?;
    if values.len() < 2 || values.windows(2).any(|w| w[1] <= w[0]) {
        return Err(Error::input(
            argument,
            format!("{values:?}"),
            "must hold at least 2 strictly increasing coordinates (m)",
        ));
    }
    Ok(())
}

/// Nodal derivative of `values` (a function of `coords`): central differences inside, one-sided at the ends.
fn nodal_derivative(coords: &[f64], value: impl Fn(usize) -> f64, k: usize) -> f64 {
    let last = coords.len() - 1;
    let (lo, hi) = (k.saturating_sub(1), (k + 1).min(last));
    (value(hi) - value(lo)) / (coords[hi] - coords[lo])
}

impl Grid {
    /// The cell of a coordinate and its local coordinate u ∈ [0, 1]; outside the grid the nearest border,
    /// with `inside` false (the interpolant is held constant there).
    fn locate(coords: &[f64], x: f64) -> (usize, f64, bool) {
        let last = coords.len() - 1;
        if x <= coords[0] {
            return (0, 0.0, false);
        }
        if x >= coords[last] {
            return (last - 1, 1.0, false);
        }
        let i = coords
            .partition_point(|&c| c <= x)
            .saturating_sub(1)
            .min(last - 1);
        (i, (x - coords[i]) / (coords[i + 1] - coords[i]), true)
    }

    /// The bilinear interpolant of nodal `values` at (x, y).
    fn interpolate(&self, values: &[f64], x: f64, y: f64) -> Bilinear {
        let ny = self.y.len();
        let (i, u, inside_x) = Self::locate(&self.x, x);
        let (j, v, inside_y) = Self::locate(&self.y, y);
        let (hx, hy) = (self.x[i + 1] - self.x[i], self.y[j + 1] - self.y[j]);
        let f00 = values[i * ny + j];
        let f10 = values[(i + 1) * ny + j];
        let f01 = values[i * ny + j + 1];
        let f11 = values[(i + 1) * ny + j + 1];
        let value =
            f00 * (1.0 - u) * (1.0 - v) + f10 * u * (1.0 - v) + f01 * (1.0 - u) * v + f11 * u * v;
        let fx = ((f10 - f00) * (1.0 - v) + (f11 - f01) * v) / hx;
        let fy = ((f01 - f00) * (1.0 - u) + (f11 - f10) * u) / hy;
        let fxy = (f11 - f10 - f01 + f00) / (hx * hy);
        Bilinear {
            value,
            gradient: Vector2::new(
                if inside_x { fx } else { 0.0 },
                if inside_y { fy } else { 0.0 },
            ),
            mixed: if inside_x && inside_y { fxy } else { 0.0 },
        }
    }
}

impl Bathymetry {
    /// The horizontal plane z = `z`.
    pub fn flat(z: f64) -> Result<Self> {
        Self::plane(z, Vector2::zeros())
    }

    /// The plane b(x, y) = z + g_x x + g_y y (e3 down: a positive g_x deepens along e1).
    pub fn plane(z: f64, gradient: Vector2<f64>) -> Result<Self> {
        finite("z", &[z])?;
        finite("gradient", gradient.as_slice())?;
        Ok(Bathymetry::Plane { z, gradient })
    }

    /// A grid: `x` (nx,), `y` (ny,) strictly increasing, `z` (nx·ny, x-major: z[i·ny + j] at (x_i, y_j)).
    pub fn grid(x: Vec<f64>, y: Vec<f64>, z: Vec<f64>) -> Result<Self> {
        increasing("x", &x)?;
        increasing("y", &y)?;
        if z.len() != x.len() * y.len() {
            return Err(Error::input(
                "z",
                format!("{} values", z.len()),
                format!(
                    "must have shape (len(x), len(y)) = ({}, {})",
                    x.len(),
                    y.len()
                ),
            ));
        }
        finite("z", &z)?;
        let ny = y.len();
        let mut slope_x = vec![0.0; z.len()];
        let mut slope_y = vec![0.0; z.len()];
        for i in 0..x.len() {
            for j in 0..ny {
                slope_x[i * ny + j] = nodal_derivative(&x, |k| z[k * ny + j], i);
                slope_y[i * ny + j] = nodal_derivative(&y, |k| z[i * ny + k], j);
            }
        }
        Ok(Bathymetry::Grid(Grid {
            x,
            y,
            z,
            slope_x,
            slope_y,
        }))
    }

    /// The shallowest seabed elevation over the horizontal points `points` (and, for a grid, its nodes):
    /// the smallest b, since e3 points down.
    pub fn shallowest(&self, points: &[Vector2<f64>]) -> f64 {
        let over_points = points
            .iter()
            .map(|p| self.elevation(p.x, p.y))
            .fold(f64::INFINITY, f64::min);
        match self {
            Bathymetry::Plane { .. } => over_points,
            Bathymetry::Grid(grid) => grid.z.iter().copied().fold(over_points, f64::min),
        }
    }

    /// Whether the seabed is a plane (its penetration is then linear in the position).
    pub fn is_plane(&self) -> bool {
        matches!(self, Bathymetry::Plane { .. })
    }

    /// The seabed elevation b(x, y) (m, e3 down).
    pub fn elevation(&self, x: f64, y: f64) -> f64 {
        match self {
            Bathymetry::Plane { z, gradient } => z + gradient.x * x + gradient.y * y,
            Bathymetry::Grid(grid) => grid.interpolate(&grid.z, x, y).value,
        }
    }

    /// The penetration δ of point p into the seabed (m, positive inside), with its gradient and Hessian.
    pub fn penetration(&self, p: &Vector3<f64>) -> Penetration {
        match self {
            Bathymetry::Plane { z, gradient } => {
                let c = 1.0 / (1.0 + gradient.norm_squared()).sqrt();
                let normal_in = Vector3::new(-gradient.x, -gradient.y, 1.0) * c;
                Penetration {
                    value: (p.z - z - gradient.x * p.x - gradient.y * p.y) * c,
                    gradient: normal_in,
                    hessian: Matrix3::zeros(),
                }
            }
            Bathymetry::Grid(grid) => grid.penetration(p),
        }
    }

    /// Unit normal of the seabed below point p, pointing out of the seabed (into the water): −∇δ/|∇δ|.
    pub fn outward_normal(&self, p: &Vector3<f64>) -> Vector3<f64> {
        -self.penetration(p).gradient.normalize()
    }
}

impl Grid {
    /// δ = g c with g = z − b(x, y) and c = (1 + |G|²)^(−1/2), G the interpolated nodal slopes.
    fn penetration(&self, p: &Vector3<f64>) -> Penetration {
        let b = self.interpolate(&self.z, p.x, p.y);
        let sx = self.interpolate(&self.slope_x, p.x, p.y);
        let sy = self.interpolate(&self.slope_y, p.x, p.y);
        let slope = Vector2::new(sx.value, sy.value);
        // J = ∂G/∂(x, y): rows are ∇G_x and ∇G_y.
        let jacobian = Matrix2::new(sx.gradient.x, sx.gradient.y, sy.gradient.x, sy.gradient.y);
        let c = 1.0 / (1.0 + slope.norm_squared()).sqrt();
        let c3 = c * c * c;
        let jt_g = jacobian.transpose() * slope;
        let grad_c2 = -c3 * jt_g;
        let mixed = Matrix2::new(0.0, 1.0, 1.0, 0.0);
        let hess_c2 = -c3
            * (jacobian.transpose() * jacobian + mixed * (slope.x * sx.mixed + slope.y * sy.mixed))
            + 3.0 * c3 * c * c * jt_g * jt_g.transpose();
        let gap = p.z - b.value;
        let grad_gap = Vector3::new(-b.gradient.x, -b.gradient.y, 1.0);
        let mut hess_gap = Matrix3::zeros();
        hess_gap[(0, 1)] = -b.mixed;
        hess_gap[(1, 0)] = -b.mixed;
        let grad_c = Vector3::new(grad_c2.x, grad_c2.y, 0.0);
        let mut hess_c = Matrix3::zeros();
        hess_c.fixed_view_mut::<2, 2>(0, 0).copy_from(&hess_c2);
        Penetration {
            value: gap * c,
            gradient: grad_gap * c + grad_c * gap,
            hessian: hess_gap * c
                + grad_gap * grad_c.transpose()
                + grad_c * grad_gap.transpose()
                + hess_c * gap,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn wavy_grid() -> Bathymetry {
        let x: Vec<f64> = (0..6).map(|i| -20.0 + 13.0 * i as f64).collect();
        let y: Vec<f64> = (0..5).map(|j| -15.0 + 9.0 * j as f64).collect();
        let mut z = Vec::new();
        for xi in &x {
            for yj in &y {
                z.push(0.05 * xi + 0.3 * (0.1 * xi).sin() * (0.13 * yj).cos() - 0.02 * yj);
            }
        }
        Bathymetry::grid(x, y, z).expect("valid grid")
    }

    /// Gradient and Hessian of the penetration against central differences, inside a cell.
    #[test]
    fn penetration_derivatives_match_finite_differences() {
        let plane = Bathymetry::plane(1.0, Vector2::new(0.1, -0.05)).expect("valid plane");
        for bathymetry in [plane, wavy_grid()] {
            let p = Vector3::new(3.3, -4.1, 0.7);
            let at = bathymetry.penetration(&p);
            let h = 1e-6;
            for k in 0..3 {
                let mut e = Vector3::zeros();
                e[k] = h;
                let (plus, minus) = (
                    bathymetry.penetration(&(p + e)),
                    bathymetry.penetration(&(p - e)),
                );
                let fd = (plus.value - minus.value) / (2.0 * h);
                assert!((fd - at.gradient[k]).abs() < 1e-8, "gradient {k}");
                let fd_h = (plus.gradient - minus.gradient) / (2.0 * h);
                assert!(
                    (fd_h - at.hessian.column(k)).norm() < 1e-7,
                    "hessian column {k}: {fd_h} vs {}",
                    at.hessian.column(k)
                );
            }
        }
    }

    /// A plane given as a grid is the same seabed as the plane; the plane's penetration is the normal distance.
    #[test]
    fn plane_as_grid_is_the_plane() {
        let gradient = Vector2::new(0.12, -0.07);
        let plane = Bathymetry::plane(2.0, gradient).expect("valid plane");
        let x = vec![-50.0, 0.0, 30.0, 100.0];
        let y = vec![-10.0, 5.0, 40.0];
        let z = x
            .iter()
            .flat_map(|xi| {
                y.iter()
                    .map(move |yj| 2.0 + gradient.x * xi + gradient.y * yj)
            })
            .collect();
        let grid = Bathymetry::grid(x, y, z).expect("valid grid");
        for p in [Vector3::new(10.0, 0.0, 3.0), Vector3::new(-20.0, 33.0, 1.0)] {
            let (a, b) = (plane.penetration(&p), grid.penetration(&p));
            assert!((a.value - b.value).abs() < 1e-12);
            assert!((a.gradient - b.gradient).norm() < 1e-12);
        }
        // Normal distance: move p along the unit normal by d, penetration changes by d.
        let p = Vector3::new(4.0, 7.0, 5.0);
        let n = plane.outward_normal(&p);
        let d = 0.37;
        assert!(
            (plane.penetration(&p).value - plane.penetration(&(p + d * n)).value - d).abs() < 1e-12
        );
    }

    #[test]
    fn bad_grids_are_refused() {
        assert!(Bathymetry::grid(vec![0.0, 1.0], vec![0.0, 1.0], vec![0.0; 3]).is_err());
        assert!(Bathymetry::grid(vec![0.0, 0.0], vec![0.0, 1.0], vec![0.0; 4]).is_err());
        assert!(Bathymetry::grid(vec![0.0], vec![0.0, 1.0], vec![0.0; 2]).is_err());
        assert!(Bathymetry::grid(
            vec![0.0, 1.0],
            vec![0.0, 1.0],
            vec![0.0, f64::NAN, 0.0, 0.0]
        )
        .is_err());
        assert!(Bathymetry::plane(f64::INFINITY, Vector2::zeros()).is_err());
    }
}
