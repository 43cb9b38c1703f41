//! Elastic stability of a shooting equilibrium (beyond the paper; issue 16).
//!
//! # Criterion
//!
//! Till and Rucker ("Elastic Stability of Cosserat Rods and Parallel
//! Continuum Robots", IEEE T-RO 2017) test an equilibrium of a rod with a
//! fixed base and a free (natural) tip under conservative loads by Jacobi's
//! conjugate-point condition: it is stable iff the tangent map from the base
//! unknowns to the wrench at `s`,
//!
//! `Y(s) = d(n, m)(s) / d(n(0), m(0))`                                  (S1)
//!
//! is non-singular for every `s` in `(0, L]`: at a zero of `det Y(s)` the
//! truncated rod `[0, s]` under the same dead loads admits a neutral
//! perturbation. We carry the positions and rotations along too,
//! `H(s) = d(p, theta)(s) / d(n(0), m(0))` (`delta R R^T = [theta]x`), and use
//! the tip stiffness of the truncated rod
//!
//! `K(s) = Y(s) H(s)^-1`                                                (S2)
//!
//! (dimensionless: forces by `L^2/EI`, moments by `L/EI`, displacements by
//! `L`). `K(0+)` is positive definite (it grows like `1/s`); an eigenvalue
//! of `K` passes through zero exactly where `det Y` does. Testing the smallest
//! eigenvalue of the symmetric part of `K(s)` on the nodes, instead of the
//! sign of `det Y`, also catches the double roots of symmetric sections
//! (a round column buckles in two planes at once and `det Y` touches zero
//! without changing sign).
//!
//! # Extensions
//!
//! * Strings with a fixed tension (constant-tension tendons) add the
//!   string-length integrand `tau |p_i'|` to a local Lagrangian: (S1)-(S2)
//!   hold with the total wrench (body plus the strings crossing `s`). The
//!   tangent is taken with the tensions frozen.
//! * Tensions that depend on strain (TCA law, coil contact, linear tendon)
//!   add `sum_i k_i (d Lambda_i)^2 >= 0` to the second variation, with
//!   `k_i = d tau_i / d delta_i` and `Lambda_i` the actuator length, a
//!   non-local term. The Morse index of the second variation is then the
//!   number of Dirichlet conjugate points of the frozen-tension problem
//!   (zeros of `det H(s)` in `(0, L)`; none for a stable rod) plus the number
//!   of negative eigenvalues of the full tip stiffness
//!
//!   `K_full = Y_z Z (H_z Z)^-1`                                        (S3)
//!
//!   where `z = (v(0), u(0), delta_i)` are all shooting unknowns and the
//!   columns of `Z` span the `z` that keep every actuator consistent
//!   (`d(delta_i(L) - delta_i) = 0`): the tip stiffness with the actuator
//!   springs in. With constant tensions (S3) is `K(L)`.
//! * Dead loads (gravity, distributed and tip force) enter the wrench
//!   balance only; a world-fixed tip moment is not conservative in 3-D and
//!   is treated like a dead load (its non-symmetric part is dropped with the
//!   antisymmetric part of `K`).
//! * A blocked tip (mixed boundary condition: tip translation along some
//!   world directions held, contact force a Lagrange multiplier) restricts
//!   the tip variations: the index is that of (S3) restricted to the
//!   complement of the blocked directions.
//!
//! # Margin
//!
//! The smallest eigenvalue of the symmetric part of the dimensionless tip
//! stiffness at the tip: (S2) at `s = L` (free tip, no strain-dependent
//! actuator), or (S3) restricted to the free directions.
//! Positive iff stable (above `-NEUTRAL`: neutral symmetry modes count as
//! stable); it passes through zero at a buckling load or a fold.
//! If a conjugate point lies inside the body it is at most `-(L - s_c)/L`
//! (continuous at a first conjugate point reaching the tip). Along `s` only
//! positive definiteness is tested (Cholesky), to keep the verdict cheap.
//!
//! # Cost
//!
//! One tangent integration (the IVP with its exact variational equations
//! along the `6 + N` shooting unknowns, `shooting::shoot_jacobian`) gives
//! every node's `Y`, `H` and the actuator rows; [`stability_fd`] does the
//! same from `7 + N` recorded IVPs by forward differences (a cross-check).

use nalgebra::{DMatrix, DVector, Matrix3, Matrix6, Quaternion, SymmetricEigen, Vector3};

use crate::error::{Error, Result};
use crate::rod::{rot, Robot, RodState};
use crate::shooting::{residual_scales, shoot, shoot_jacobian, Loads, Solution};

/// Margins above `-NEUTRAL` count as stable: a symmetry leaves a neutral
/// mode (a buckled round column can turn about the vertical at no cost, so
/// its smallest tip stiffness is zero up to the ~1e-10 noise of the
/// finite-difference tangents).
pub const NEUTRAL: f64 = 1e-6;

/// Stability verdict of one equilibrium.
#[derive(Debug, Clone)]
pub struct Stability {
    /// True if the equilibrium is a strict local minimum of the energy.
    pub stable: bool,
    /// Smallest eigenvalue of the symmetric dimensionless tip stiffness
    /// (see the module docs); > 0 iff stable.
    pub margin: f64,
    /// Arc length \[m\] of the first conjugate point of the frozen-tension
    /// problem (first node where (S2) is no longer positive definite), if any.
    pub conjugate_point: Option<f64>,
    /// Arc length \[m\] of the nodes.
    pub s: Vec<f64>,
    /// Till and Rucker's determinant (S1) normalised to 1 at the base,
    /// `det(Y(s) Y(0)^-1)`, at each node (frozen tensions).
    pub determinant: Vec<f64>,
    /// At the tip node, the smallest eigenvalue of the symmetric part of
    /// (S2); at the other nodes `+1` where it is positive definite (above
    /// `-NEUTRAL`) and `-1` where not (a Cholesky test: no eigenvalue is
    /// computed there); the base node, where `K` is infinite, carries `+inf`.
    pub min_stiffness: Vec<f64>,
    /// Integrations for the verdict: 1 tangent IVP ([`stability`]) or
    /// `7 + N` IVPs ([`stability_fd`]).
    pub evaluations: usize,
    /// Softest tip mode: unit eigenvector `(p / L, theta)` (world frame) of
    /// the smallest eigenvalue of the symmetric tip stiffness at `s = L`
    /// (zeros if the stiffness is undefined).
    pub mode: [f64; 6],
}

/// Data of one recorded IVP at each node: position, rotation, total wrench.
struct Profile {
    p: Vec<Vector3<f64>>,
    r: Vec<Matrix3<f64>>,
    n: Vec<Vector3<f64>>,
    m: Vec<Vector3<f64>>,
    resid: Vec<f64>,
}

/// Total wrench (world frame) across the section at node `s`: body stress
/// plus every string crossing `s` (at an interior anchor the recorded state
/// is the one after the anchor loads; at the tip the one before).
fn wrench(robot: &Robot, tau: &[f64], s: f64, st: &RodState) -> (Vector3<f64>, Vector3<f64>) {
    let b = &robot.body;
    let (kse, kbt) = b.stiffness();
    let len = b.length;
    let tol = 1e-12 * len;
    let rm = st.rotation();
    let mut n = kse * (st.v - b.nu_star);
    let mut m = kbt * (st.u - b.omega_star);
    let at_tip = s >= len - tol;
    for (i, a) in robot.actuators.iter().enumerate() {
        let crosses =
            a.s_start <= s + tol && (a.s_end > s + tol || (at_tip && a.s_end >= len - tol));
        if crosses {
            let (r, rp, _) = a.routing.eval(s);
            let pb = st.v + st.u.cross(&r) + rp;
            let t = pb / pb.norm() * tau[i];
            n += t;
            m += r.cross(&t);
        }
    }
    (rm * n, rm * m)
}

fn profile(
    robot: &Robot,
    inputs: &[f64],
    loads: &Loads,
    x: &[f64],
    steps: usize,
) -> Result<Profile> {
    let (resid, ivp, tau) = shoot(robot, inputs, loads, x, steps, true)?;
    let k = ivp.nodes.len();
    let mut pr = Profile {
        p: Vec::with_capacity(k),
        r: Vec::with_capacity(k),
        n: Vec::with_capacity(k),
        m: Vec::with_capacity(k),
        resid,
    };
    for (s, st) in &ivp.nodes {
        let (n, m) = wrench(robot, &tau, *s, st);
        pr.p.push(st.p);
        pr.r.push(st.rotation());
        pr.n.push(n);
        pr.m.push(m);
    }
    Ok(pr)
}

/// Axial vector of the skew part of `a`.
fn vee_skew(a: &Matrix3<f64>) -> Vector3<f64> {
    Vector3::new(
        a[(2, 1)] - a[(1, 2)],
        a[(0, 2)] - a[(2, 0)],
        a[(1, 0)] - a[(0, 1)],
    ) * 0.5
}

/// Smallest eigenvalue of the symmetric part of a square matrix.
fn min_sym_eig(k: &DMatrix<f64>) -> f64 {
    min_sym_pair(k).0
}

/// Smallest eigenvalue of the symmetric part and its unit eigenvector.
fn min_sym_pair(k: &DMatrix<f64>) -> (f64, DVector<f64>) {
    let sym = (k + k.transpose()) * 0.5;
    let e = SymmetricEigen::new(sym);
    let (i, _) =
        e.eigenvalues.iter().enumerate().fold(
            (0, f64::INFINITY),
            |a, (i, &v)| if v < a.1 { (i, v) } else { a },
        );
    (e.eigenvalues[i], e.eigenvectors.column(i).into_owned())
}

/// Stiffness of each actuator's law, `d tau / d delta` [N/m], at the solution.
fn actuator_stiffness(robot: &Robot, sol: &Solution) -> Result<Vec<f64>> {
    let len = robot.body.length;
    robot
        .actuators
        .iter()
        .enumerate()
        .map(|(i, a)| {
            let d = sol.elongations[i];
            let h = 1e-9 * len;
            let tp = a.law.tension(d + h, sol.inputs[i])?;
            let tm = a.law.tension(d - h, sol.inputs[i])?;
            Ok((tp - tm) / (2.0 * h))
        })
        .collect()
}

/// Tangents of one equilibrium at every node: `Y~_k = d w~(s_k)/d z`,
/// `H~_k = d (p/L, theta)(s_k)/d z` (`6 x nz` each), and the actuator
/// consistency rows `E = d (delta_i(L) - delta_i)/L / d z` (`na x nz`).
struct Tangents {
    s: Vec<f64>,
    y: Vec<DMatrix<f64>>,
    h: Vec<DMatrix<f64>>,
    e: DMatrix<f64>,
}

/// Exact tangents from one tangent IVP (`shoot_jacobian` with recorded nodes).
fn exact_tangents(robot: &Robot, sol: &Solution) -> Result<Tangents> {
    let na = robot.actuators.len();
    let nz = 6 + na;
    let b = &robot.body;
    let len = b.length;
    let tol = 1e-12 * len;
    let (kse, kbt) = b.stiffness();
    let (fs, ms) = residual_scales(robot);
    let (_, jac, tan, tau) = shoot_jacobian(
        robot,
        &sol.inputs,
        &sol.loads,
        &sol.unknowns,
        sol.steps,
        true,
    )?;
    // d tau / d z: only through the actuator's own elongation guess
    let mut dtau = DMatrix::zeros(na, nz);
    for (i, a) in robot.actuators.iter().enumerate() {
        let (_, dt_de, _) = a
            .law
            .tension_derivatives(sol.unknowns[6 + i] * len, sol.inputs[i])?;
        dtau[(i, 6 + i)] = dt_de * len;
    }
    let mut out = Tangents {
        s: vec![],
        y: vec![],
        h: vec![],
        e: jac.rows(6, na).into_owned(),
    };
    for node in &tan.nodes {
        let sk = node.s;
        let y = &node.state;
        let t = &node.tangent;
        let q = Quaternion::new(y[3], y[4], y[5], y[6]);
        let rm = rot(&q);
        let v = Vector3::new(y[7], y[8], y[9]);
        let u = Vector3::new(y[10], y[11], y[12]);
        // body-frame wrench and its tangent
        let mut nb = kse * (v - b.nu_star);
        let mut mb = kbt * (u - b.omega_star);
        let mut dnb = kse * t.rows(7, 3);
        let mut dmb = kbt * t.rows(10, 3);
        let at_tip = sk >= len - tol;
        for (i, a) in robot.actuators.iter().enumerate() {
            if !(a.s_start <= sk + tol && (a.s_end > sk + tol || (at_tip && a.s_end >= len - tol)))
            {
                continue;
            }
            let (r, rp, _) = a.routing.eval(sk);
            let pb = v + u.cross(&r) + rp;
            let nrm = pb.norm();
            let tt = pb / nrm;
            // d pb = d v + d u x r = d v - [r]x d u
            let dpb = t.rows(7, 3) - r.cross_matrix() * t.rows(10, 3);
            let dt = (Matrix3::identity() - tt * tt.transpose()) / nrm * dpb;
            let df = dt * tau[i] + tt * dtau.row(i);
            nb += tt * tau[i];
            mb += r.cross(&tt) * tau[i];
            dnb += &df;
            dmb += r.cross_matrix() * df;
        }
        // rotation tangent: d q = (theta/2) (x) q  =>  theta = 2 vec(d q (x) q*)
        let mut th = DMatrix::zeros(3, nz);
        for j in 0..nz {
            let dq = Quaternion::new(t[(3, j)], t[(4, j)], t[(5, j)], t[(6, j)]);
            let w = dq * q.conjugate() * 2.0;
            th[(0, j)] = w.i;
            th[(1, j)] = w.j;
            th[(2, j)] = w.k;
        }
        // world wrench w = R (nb, mb): d w = [theta]x R nb + R d nb
        let rn = rm * nb;
        let rmm = rm * mb;
        let dn = (rm * dnb - rn.cross_matrix() * &th) * fs;
        let dm = (rm * dmb - rmm.cross_matrix() * &th) * ms;
        let mut yk = DMatrix::zeros(6, nz);
        yk.rows_mut(0, 3).copy_from(&dn);
        yk.rows_mut(3, 3).copy_from(&dm);
        let mut hk = DMatrix::zeros(6, nz);
        hk.rows_mut(0, 3).copy_from(&(t.rows(0, 3) / len));
        hk.rows_mut(3, 3).copy_from(&th);
        out.s.push(sk);
        out.y.push(yk);
        out.h.push(hk);
    }
    Ok(out)
}

/// Forward-difference tangents from `1 + nz` recorded IVPs (a cross-check
/// of [`exact_tangents`]).
fn fd_tangents(robot: &Robot, sol: &Solution) -> Result<Tangents> {
    let na = robot.actuators.len();
    let nz = 6 + na;
    let len = robot.body.length;
    let (fs, ms) = residual_scales(robot);
    let x = &sol.unknowns;
    let base = profile(robot, &sol.inputs, &sol.loads, x, sol.steps)?;
    let nodes = base.p.len();
    let mut out = Tangents {
        s: sol.s.clone(),
        y: vec![DMatrix::zeros(6, nz); nodes],
        h: vec![DMatrix::zeros(6, nz); nodes],
        e: DMatrix::zeros(na, nz),
    };
    let h0 = f64::EPSILON.sqrt();
    for j in 0..nz {
        let mut xp = x.clone();
        let h = h0 * x[j].abs().max(1.0);
        xp[j] += h;
        let h = xp[j] - x[j];
        let pp = profile(robot, &sol.inputs, &sol.loads, &xp, sol.steps)?;
        for k in 0..nodes {
            let dn = (pp.n[k] - base.n[k]) * (fs / h);
            let dm = (pp.m[k] - base.m[k]) * (ms / h);
            let dp = (pp.p[k] - base.p[k]) / (len * h);
            let th = vee_skew(&(pp.r[k] * base.r[k].transpose())) / h;
            for i in 0..3 {
                out.y[k][(i, j)] = dn[i];
                out.y[k][(3 + i, j)] = dm[i];
                out.h[k][(i, j)] = dp[i];
                out.h[k][(3 + i, j)] = th[i];
            }
        }
        for i in 0..na {
            out.e[(i, j)] = (pp.resid[6 + i] - base.resid[6 + i]) / h;
        }
    }
    Ok(out)
}

fn check(robot: &Robot, sol: &Solution, blocked: &[Vector3<f64>]) -> Result<()> {
    robot.validate()?;
    let na = robot.actuators.len();
    if sol.unknowns.len() != 6 + na || sol.inputs.len() != na {
        return Err(Error::input(
            "solution",
            format!(
                "solution of a robot with {} actuators, this one has {na}",
                sol.inputs.len()
            ),
        ));
    }
    for (j, b) in blocked.iter().enumerate() {
        if !(b.iter().all(|v| v.is_finite()) && b.norm() > 0.0) {
            return Err(Error::input(
                &format!("blocked[{j}]"),
                "must be a finite non-zero vector",
            ));
        }
    }
    Ok(())
}

/// Stability of the equilibrium `sol` of `robot` (see the module docs), from
/// one tangent integration (`6 + N` directions).
/// `blocked`: world directions along which the tip translation is held (a
/// blocked-tip solution's block normal); empty for a free tip.
pub fn stability(robot: &Robot, sol: &Solution, blocked: &[Vector3<f64>]) -> Result<Stability> {
    check(robot, sol, blocked)?;
    let t = exact_tangents(robot, sol)?;
    verdict(robot, sol, blocked, t, 1)
}

/// [`stability`] from forward-difference tangents (`7 + N` IVPs); for
/// cross-checks.
pub fn stability_fd(robot: &Robot, sol: &Solution, blocked: &[Vector3<f64>]) -> Result<Stability> {
    check(robot, sol, blocked)?;
    let t = fd_tangents(robot, sol)?;
    verdict(robot, sol, blocked, t, 7 + robot.actuators.len())
}

fn verdict(
    robot: &Robot,
    sol: &Solution,
    blocked: &[Vector3<f64>],
    t: Tangents,
    evaluations: usize,
) -> Result<Stability> {
    let na = robot.actuators.len();
    let nz = 6 + na;
    let len = robot.body.length;
    let nodes = t.s.len();
    let s_nodes = t.s.clone();
    // frozen-tension scan with fixed-size 6 x 6 algebra: the determinant
    // (S1), the Dirichlet test (det H) and positive definiteness of (S2) by
    // Cholesky (an eigenvalue is computed at the tip only)
    let m6 = |m: &DMatrix<f64>| Matrix6::from_fn(|i, j| m[(i, j)]);
    let y0inv = m6(&t.y[0]).try_inverse();
    let mut determinant = Vec::with_capacity(nodes);
    let mut min_stiffness = Vec::with_capacity(nodes);
    let mut conjugate: Option<f64> = None;
    let mut dirichlet: Option<f64> = None;
    let mut hdet_sign = 0.0;
    for (k, &sk) in s_nodes.iter().enumerate() {
        let y = m6(&t.y[k]);
        determinant.push(match &y0inv {
            Some(yi) => (y * yi).determinant(),
            None => f64::NAN,
        });
        if k == 0 || sk <= 0.0 {
            min_stiffness.push(f64::INFINITY);
            continue;
        }
        let h = m6(&t.h[k]);
        let hd = h.determinant();
        if hdet_sign == 0.0 {
            hdet_sign = hd.signum();
        } else if dirichlet.is_none() && hd * hdet_sign <= 0.0 {
            dirichlet = Some(sk);
        }
        let pd = match h.try_inverse() {
            Some(hi) => {
                let kk = y * hi;
                let sym = (kk + kk.transpose()) * 0.5 + Matrix6::identity() * NEUTRAL;
                sym.cholesky().is_some()
            }
            None => false,
        };
        if conjugate.is_none() && !pd {
            conjugate = Some(sk);
        }
        min_stiffness.push(if pd { 1.0 } else { -1.0 });
    }
    // min_stiffness: the smallest eigenvalue at the tip, the sign of the
    // Cholesky test elsewhere
    if nodes > 1 {
        if let Some(hi) = m6(&t.h[nodes - 1]).try_inverse() {
            let kk = DMatrix::from_fn(6, 6, |i, j| (m6(&t.y[nodes - 1]) * hi)[(i, j)]);
            min_stiffness[nodes - 1] = min_sym_eig(&kk);
        }
    }
    let kk = actuator_stiffness(robot, sol)?;
    let springy = kk.iter().any(|k| k.abs() > 0.0);
    let frozen = !springy && blocked.is_empty();
    let last = nodes - 1;
    let mut mode = [0.0; 6];
    let mut out = Stability {
        stable: false,
        margin: f64::NEG_INFINITY,
        conjugate_point: conjugate,
        s: s_nodes,
        determinant,
        min_stiffness,
        evaluations,
        mode,
    };
    if frozen {
        let m = out.min_stiffness[last];
        if let Some(hi) = t.h[last].columns(0, 6).into_owned().try_inverse() {
            let (_, v) = min_sym_pair(&(t.y[last].columns(0, 6).into_owned() * hi));
            mode.copy_from_slice(v.as_slice());
        }
        out.stable = conjugate.is_none();
        out.margin = match conjugate {
            Some(sc) => m.min(-(len - sc) / len),
            None => m,
        };
        out.mode = mode;
        return Ok(out);
    }
    // basis of the consistent z: d delta = -E_d^-1 E_x dx
    let z = if na == 0 {
        DMatrix::identity(6, 6)
    } else {
        let ex = t.e.columns(0, 6).into_owned();
        let ed = t.e.columns(6, na).into_owned();
        let Some(edi) = ed.try_inverse() else {
            return Ok(out);
        };
        let mut z = DMatrix::zeros(nz, 6);
        z.view_mut((0, 0), (6, 6))
            .copy_from(&DMatrix::identity(6, 6));
        z.view_mut((6, 0), (na, 6)).copy_from(&(-edi * ex));
        z
    };
    let Some(hi) = (&t.h[last] * &z).try_inverse() else {
        return Ok(out);
    };
    let kfull = &t.y[last] * &z * hi;
    // restrict to tip variations orthogonal to the blocked directions
    let basis: Vec<DVector<f64>> = blocked
        .iter()
        .map(|b| {
            let mut v = DVector::zeros(6);
            v.rows_mut(0, 3).copy_from(&(b / b.norm()));
            v
        })
        .collect();
    let q = complement(&basis);
    let kr = q.transpose() * kfull * &q;
    let (mut m, v) = min_sym_pair(&kr);
    mode.copy_from_slice((&q * v).as_slice());
    if let Some(sd) = dirichlet {
        m = m.min(-(len - sd) / len);
    }
    out.stable = dirichlet.is_none() && m > -NEUTRAL;
    out.margin = m;
    out.mode = mode;
    Ok(out)
}

/// Orthonormal basis (columns) of the complement in R^6 of the span of `vs`.
fn complement(vs: &[DVector<f64>]) -> DMatrix<f64> {
    if vs.is_empty() {
        return DMatrix::identity(6, 6);
    }
    let a = DMatrix::from_columns(vs);
    let svd = a.clone().svd(true, false);
    let u = svd.u.expect("requested");
    let rank = svd.singular_values.iter().filter(|&&x| x > 1e-12).count();
    // full U: complete the basis by Gram-Schmidt on the unit vectors
    let mut cols: Vec<DVector<f64>> = (0..rank).map(|j| u.column(j).into_owned()).collect();
    let mut out = Vec::new();
    for e in 0..6 {
        let mut v = DVector::zeros(6);
        v[e] = 1.0;
        for c in &cols {
            let d = c.dot(&v);
            v -= c * d;
        }
        let n = v.norm();
        if n > 1e-8 {
            v /= n;
            cols.push(v.clone());
            out.push(v);
        }
        if cols.len() == 6 {
            break;
        }
    }
    DMatrix::from_columns(&out)
}
