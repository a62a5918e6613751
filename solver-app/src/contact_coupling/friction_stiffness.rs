//! The friction's stiffness in the preconditioners of Newton's method:
//! the linearisation of the Coulomb return map (eqs. 4.20–4.22) by the
//! face's state, sticking or slipping.
use contact_force::{FrictionState, SurfaceContact};
use fv_mesh::{Tensor, Vector};

/// The friction's tangential stiffness per area of face `i` (normal `n`)
/// in the preconditioners' linearisation. Sticking (eq. 4.21): the
/// tangential penalty, ε_t (I − n⊗n). Slipping (eq. 4.22): the derivative
/// of the return map, ε_t μp/|t_trial| (I − n⊗n − ŝ⊗ŝ) across the slip
/// direction ŝ = t_t/|t_t| and nothing along it; |t_trial| is taken as
/// ε_t|Δg_t| (exact where the increment starts without tangential
/// traction; otherwise an estimate, the trial traction also carrying the
/// elastic slip of earlier increments and the contact fraction, held to
/// at most the sticking spring).
/// A slipping face given the sticking spring makes the preconditioner
/// hold tangentially what the residual lets slide: a J2 block upset by a
/// rough rigid platen (μ = 0.1, plane strain 20 × 10), whose top slips
/// over most of its width, needed 258 Newton and 3,665 Krylov iterations
/// in 10 increments, 185 and 1,748 with this (and
/// [`friction_normal_coupling`]). Against a rigid body only: between two
/// deformable bodies the preconditioners keep the sticking spring, which
/// also holds the soft sliding mode of a frictional pair (curved beams
/// μ = 0.3: at most 38 Newton iterations in an increment with it, 52–71
/// without; docs/newton-krylov.md, "Friction in the preconditioners").
pub fn friction_stiffness(contact: &SurfaceContact, i: usize, n: &Vector, eps_t: f64) -> Tensor {
    let nn = n * n.transpose();
    let across = Tensor::identity() - nn;
    if eps_t <= 0.0 {
        return Tensor::zeros();
    }
    let slipping = contact.friction_state.get(i) == Some(&FrictionState::Slip);
    if !slipping {
        return across * eps_t;
    }
    let t = contact.tangential_traction[i];
    let slip = contact.slip[i].norm();
    let (tn, st) = (t.norm(), slip * eps_t);
    if !(tn > 0.0) || !(st > 0.0) {
        return across * eps_t;
    }
    let s = t / tn;
    (across - s * s.transpose()) * (eps_t * (tn / st).min(1.0))
}

/// How a slipping face's friction follows its normal gap, per area: the
/// traction t = ε_n g (n − μŝ) of eqs. 4.11 and 4.22 gives the spring
/// ε_n (n − μŝ) ⊗ n, whose friction part is −ε_n (t_t / p) ⊗ n (μŝ = t_t/p).
/// Not symmetric: the assembled Jacobian takes it, the segregated operator
/// (a diagonal per component) cannot. Zero where the face sticks or is open.
pub fn friction_normal_coupling(
    contact: &SurfaceContact,
    i: usize,
    n: &Vector,
    eps_n: f64,
) -> Tensor {
    let slipping = contact.friction_state.get(i) == Some(&FrictionState::Slip);
    let p = contact.pressure.get(i).copied().unwrap_or(0.0);
    if !slipping || !(p > 0.0) {
        return Tensor::zeros();
    }
    (contact.tangential_traction[i] / p) * n.transpose() * (-eps_n)
}

#[cfg(test)]
mod tests {
    use super::*;
    use contact_force::face_friction;

    /// One face, pressed by `p`, with the friction `face_friction` gives
    /// for the increment's slip `du` (no earlier slip, full contact).
    fn face(n: &Vector, p: f64, du: &Vector, eps_t: f64, mu: f64) -> SurfaceContact {
        let f = face_friction(n, p, 1.0, du, &Vector::zeros(), &Vector::zeros(), eps_t, mu);
        SurfaceContact {
            normal_traction: vec![-n * p],
            tangential_traction: vec![f.traction],
            pressure: vec![p],
            gap: vec![-p / 1e3],
            contact_fraction: vec![1.0],
            slip: vec![f.slip],
            friction_state: vec![f.state],
        }
    }

    /// −∂t_t/∂Δu along `v` by central differences of the return map.
    fn numerical(n: &Vector, p: f64, du: &Vector, v: &Vector, eps_t: f64, mu: f64) -> Vector {
        let h = 1e-7 * du.norm().max(1e-3);
        let t = |d: &Vector| {
            face_friction(n, p, 1.0, d, &Vector::zeros(), &Vector::zeros(), eps_t, mu).traction
        };
        -(t(&(du + v * h)) - t(&(du - v * h))) / (2.0 * h)
    }

    #[test]
    fn the_stiffness_is_the_return_maps_derivative_sticking_and_slipping() {
        let n = Vector::new(0.0, 0.0, 1.0);
        let (eps_t, mu, p) = (1e4, 0.3, 10.0);
        // sticking: |ε_t Δg| = 1 < μp = 3; slipping: 20 > 3
        for du in [
            Vector::new(1e-4, 0.0, 0.0),
            Vector::new(1.6e-3, 1.2e-3, 0.0),
        ] {
            let c = face(&n, p, &du, eps_t, mu);
            let k = friction_stiffness(&c, 0, &n, eps_t);
            for v in [Vector::new(1.0, 0.0, 0.0), Vector::new(0.0, 1.0, 0.0)] {
                let expected = numerical(&n, p, &du, &v, eps_t, mu);
                let got = k * v;
                assert!(
                    (got - expected).norm() <= 1e-5 * eps_t,
                    "{:?}: K v = {got:?}, finite differences {expected:?}",
                    c.friction_state[0]
                );
            }
        }
    }

    #[test]
    fn the_normal_coupling_is_the_derivative_along_the_gap() {
        // t_t = μ p ŝ with p = −ε_n g: ∂t_t/∂g = −μ ε_n ŝ. The face's
        // outward normal points at the other surface: moving the face by
        // +n deepens the gap by 1, and p grows by ε_n
        let n = Vector::new(0.0, 0.0, 1.0);
        let (eps_n, eps_t, mu, p) = (1e3, 1e4, 0.3, 10.0);
        let du = Vector::new(1.6e-3, 1.2e-3, 0.0);
        let c = face(&n, p, &du, eps_t, mu);
        let k = friction_normal_coupling(&c, 0, &n, eps_n);
        let h = 1e-6;
        let t = |p: f64| {
            face_friction(
                &n,
                p,
                1.0,
                &du,
                &Vector::zeros(),
                &Vector::zeros(),
                eps_t,
                mu,
            )
            .traction
        };
        let dt_du = (t(p + eps_n * h) - t(p - eps_n * h)) / (2.0 * h);
        // K n is −∂t/∂u along n; |∂t_t/∂u| = μ ε_n = 300
        let got = k * n;
        assert!(
            (got + dt_du).norm() <= 1e-6 * eps_n,
            "{got:?} against {:?}",
            -dt_du
        );
        assert!((got.norm() - mu * eps_n).abs() < 1e-9 * eps_n, "{got:?}");
        let stuck = face(&n, p, &Vector::new(1e-4, 0.0, 0.0), eps_t, mu);
        assert_eq!(
            friction_normal_coupling(&stuck, 0, &n, eps_n),
            Tensor::zeros()
        );
    }
}
