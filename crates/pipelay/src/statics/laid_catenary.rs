//! Irvine's elastic catenary extended to a seabed: a cable whose end A lies on a horizontal seabed through A
//! rests on it from A to a touchdown point, where its tangent is horizontal, and hangs from there to B.
//!
//! With H the horizontal tension, L_s the suspended (unstretched) length, w the weight and EA the axial
//! stiffness, the suspended part is Irvine's catenary (eqs. 2.33–2.34) with zero vertical tension at the
//! touchdown:
//!
//! ```text
//! x_s = H L_s/EA + (H/w) asinh(w L_s/H),     z_s = w L_s²/(2EA) + (√(H² + (w L_s)²) − H)/w,
//! ```
//!
//! and the laid part, L_b = L − L_s long, carries T(s) = max(0, H − μw(L_b − s)) (axial friction μ fully
//! mobilised against the stretch, as in MoorPy; T = H without friction) and stretches by ∫T/EA. The closure
//! x_laid + x_s = span, z_s = rise is solved by nested bisection: for a given L_s the rise fixes H (z_s falls
//! as H grows), and the span then grows with L_s. The statics start the pipe from this shape when it rests
//! on the seabed ([`crate::statics::solve`]).
use super::catenary::{asinh_diff, tension_diff};
use nalgebra::Vector3;

/// A cable lying on the seabed from A and hanging to B.
#[derive(Debug, Clone, PartialEq)]
pub struct LaidCatenary {
    a: Vector3<f64>,
    /// Unit horizontal direction from A towards B.
    direction: Vector3<f64>,
    /// Horizontal tension H (N).
    pub horizontal: f64,
    /// Unstretched length on the seabed, from A to the touchdown (m).
    pub laid_length: f64,
    weight: f64,
    ea: f64,
    /// Axial friction coefficient μ on the laid part.
    friction: f64,
}

/// ∫₀^s T(u) du on a laid part of length `laid` with T(u) = max(0, H − f (laid − u)) (f = μw, N/m).
fn laid_tension_integral(h: f64, f: f64, laid: f64, s: f64) -> f64 {
    if f <= 0.0 {
        return h * s;
    }
    let start = (laid - h / f).max(0.0);
    if s <= start {
        return 0.0;
    }
    (h - f * laid) * (s - start) + 0.5 * f * (s * s - start * start)
}

/// Bisection of a monotonic `f` on [lo, hi] for its zero (f(lo), f(hi) of opposite signs), to round-off.
fn bisect(mut lo: f64, mut hi: f64, f: impl Fn(f64) -> f64) -> f64 {
    let rising = f(hi) > f(lo);
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            break;
        }
        if (f(mid) > 0.0) == rising {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    0.5 * (lo + hi)
}

impl LaidCatenary {
    /// The cable of unstretched `length`, weight `weight` (N/m), axial stiffness `ea` (N) and axial seabed
    /// friction `friction` from A on the seabed to B above it; `None` when it does not reach the seabed (or
    /// cannot reach B).
    pub fn solve(
        a: Vector3<f64>,
        b: Vector3<f64>,
        length: f64,
        weight: f64,
        ea: f64,
        friction: f64,
    ) -> Option<Self> {
        let chord = b - a;
        let span = chord.xy().norm();
        let rise = -chord.z;
        if !(span > 0.0 && rise > 0.0 && weight > 0.0 && ea > 0.0 && length > 0.0) {
            return None;
        }
        let height = |h: f64, suspended: f64| {
            let ws = weight * suspended;
            weight * suspended * suspended / (2.0 * ea) + tension_diff(h, 0.0, ws) / weight
        };
        let span_of = |h: f64, suspended: f64| {
            h * suspended / ea
                + h / weight * asinh_diff(h, 0.0, weight * suspended)
                + (length - suspended)
                + laid_tension_integral(
                    h,
                    friction * weight,
                    length - suspended,
                    length - suspended,
                ) / ea
        };
        // H that lifts `suspended` metres of cable to the rise; None if even a vertical cable is too short.
        let tension_for = |suspended: f64| -> Option<f64> {
            if height(1e-12 * weight * length, suspended) <= rise {
                return None;
            }
            let mut hi = weight * length;
            while height(hi, suspended) > rise {
                hi *= 2.0;
                if hi > 1e30 {
                    return None;
                }
            }
            Some(bisect(1e-12 * weight * length, hi, |h| {
                height(h, suspended) - rise
            }))
        };
        // The shortest suspended length that reaches the rise, and the span at the longest (all hanging).
        let shortest = bisect(0.0, length, |s| s + weight * s * s / (2.0 * ea) - rise);
        let h_full = tension_for(length)?;
        if span_of(h_full, length) < span {
            return None; // the cable lifts off A: no laid part
        }
        let suspended = bisect(shortest * (1.0 + 1e-9), length, |s| {
            tension_for(s).map_or(-span, |h| span_of(h, s) - span)
        });
        let horizontal = tension_for(suspended)?;
        Some(LaidCatenary {
            a,
            direction: Vector3::new(chord.x, chord.y, 0.0) / span,
            horizontal,
            laid_length: length - suspended,
            weight,
            ea,
            friction,
        })
    }

    /// Point at unstretched arc length s from A (m, in e).
    pub fn position(&self, s: f64) -> Vector3<f64> {
        let h = self.horizontal;
        let laid = self.laid_length.min(s);
        let stretch = laid_tension_integral(h, self.friction * self.weight, self.laid_length, laid);
        let mut point = self.a + self.direction * (laid + stretch / self.ea);
        if s > self.laid_length {
            let t = s - self.laid_length;
            let ws = self.weight * t;
            let x = h * t / self.ea + h / self.weight * asinh_diff(h, 0.0, ws);
            let z = self.weight * t * t / (2.0 * self.ea) + tension_diff(h, 0.0, ws) / self.weight;
            point += self.direction * x - Vector3::z() * z;
        }
        point
    }

    /// Unit tangent at arc length s, from A towards B.
    pub fn tangent(&self, s: f64) -> Vector3<f64> {
        let vertical = self.weight * (s - self.laid_length).max(0.0);
        (self.direction * self.horizontal - Vector3::z() * vertical).normalize()
    }

    /// Tension at arc length s (N).
    pub fn tension(&self, s: f64) -> f64 {
        if s < self.laid_length {
            return (self.horizontal - self.friction * self.weight * (self.laid_length - s))
                .max(0.0);
        }
        self.horizontal.hypot(self.weight * (s - self.laid_length))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Closure at B, the touchdown on the seabed with a horizontal tangent, and the suspended part's
    /// equilibrium: the vertical tension at B carries the suspended weight.
    #[test]
    fn closes_at_b_and_carries_the_suspended_weight() {
        let (a, b) = (Vector3::zeros(), Vector3::new(1200.0, 0.0, -800.0));
        let (length, w, ea) = (1600.0, 1846.0, 5.4e9);
        let c = LaidCatenary::solve(a, b, length, w, ea, 0.0).expect("a laid part");
        assert!(
            (c.position(length) - b).norm() < 1e-6,
            "{}",
            c.position(length)
        );
        let touchdown = c.position(c.laid_length);
        assert!(touchdown.z.abs() < 1e-12 && c.tangent(c.laid_length).z.abs() < 1e-12);
        let top = c.tangent(length) * c.tension(length);
        let suspended = length - c.laid_length;
        assert!((-top.z - w * suspended).abs() < 1e-9 * w * suspended);
        // The stretch is the tension over EA: finite differences of the position.
        let s = 1000.0;
        let stretch = (c.position(s + 1e-3) - c.position(s - 1e-3)).norm() / 2e-3;
        assert!((stretch - 1.0 - c.tension(s) / ea).abs() < 1e-8);
        // Taut: no laid part.
        assert!(LaidCatenary::solve(a, b, 1300.0, w, ea, 0.0).is_none());
        // With friction the laid part's tension falls by μw per metre towards A, and B still closes.
        let c = LaidCatenary::solve(a, b, length, w, ea, 0.5).expect("a laid part");
        assert!((c.position(length) - b).norm() < 1e-6);
        let s = c.laid_length - 10.0;
        assert!((c.tension(c.laid_length) - c.tension(s) - 0.5 * w * 10.0).abs() < 1e-6);
        let stretch = (c.position(s + 1e-3) - c.position(s - 1e-3)).norm() / 2e-3;
        assert!((stretch - 1.0 - c.tension(s) / ea).abs() < 1e-8);
    }
}
