//! Tangents of one equilibrium at every node, `Y = d w~(s)/d z` and
//! `H = d (p/L, theta)(s)/d z`: exact from one recorded tangent IVP, or by
//! forward differences of recorded IVPs (a cross-check).

use nalgebra::{DMatrix, Matrix3, Quaternion, UnitQuaternion, Vector3, Vector6};

use super::march::March;
use super::Equilibrium;
use crate::error::{Error, Result};
use crate::rod::{rot, FlatNodes, Grid, IvpResult, Robot, RodState, TangentNodes, TangentSeeds};
use crate::shooting::{base_strains, residual_scales, Loads, Shot, Solution};

/// Tangents of one equilibrium: at every node the frozen-tension columns
/// (the six base strains) `Y_k`, `H_k`; at the tip all `nz` columns when the
/// actuator directions were integrated, and the actuator consistency rows
/// `E = d (delta_i(L) - delta_i)/L / d z` (`na x nz`; `na x 0` if not).
/// The node matrices are [`Cols6`] (flat, on the stack, by columns).
///
/// The columns are those of the stabilised march ([`super::march`]): the
/// true tangents times an invertible factor, the same at every column of a
/// node; `ldet` holds `ln |det|` of the true columns' factor over the
/// carried ones at each node (zero where the march left them alone), and
/// `e` is the consistency `E'` of the carried columns. `carried` is false
/// when no column was ever re-orthonormalised (the plain tangents).
pub(super) struct Tangents {
    pub s: Vec<f64>,
    pub y: Vec<Cols6>,
    pub h: Vec<Cols6>,
    pub y_tip: DMatrix<f64>,
    pub h_tip: DMatrix<f64>,
    pub e: DMatrix<f64>,
    pub ldet: Vec<f64>,
    pub carried: bool,
}

/// A 6 x 6 matrix by columns: `m[j]` is column `j` (the tangent along
/// direction `j`), so the scan's products `H^T Y` are dot products of
/// contiguous columns.
pub(super) type Cols6 = [[f64; 6]; 6];

/// A string crossing a node: `(actuator, r, unit tangent t, |p_b|, tau)`.
type Crossing = (usize, Vector3<f64>, Vector3<f64>, f64, f64);

/// What a node's tangent columns need besides the column itself: rotation,
/// quaternion, total body-frame wrench and each crossing string's geometry.
struct NodeFrame {
    q: Quaternion<f64>,
    rm: Matrix3<f64>,
    rn: Vector3<f64>,
    rmm: Vector3<f64>,
    /// The strings crossing the node.
    strings: Vec<Crossing>,
}

/// True if actuator `a` crosses the section at `s` (at an interior anchor
/// the recorded state is the one after the anchor loads; at the tip the one
/// before, so a string ending there still counts).
fn crosses(a: &crate::rod::Actuator, s: f64, len: f64) -> bool {
    let tol = 1e-12 * len;
    let at_tip = s >= len - tol;
    a.s_start <= s + tol && (a.s_end > s + tol || (at_tip && a.s_end >= len - tol))
}

/// The frame of the node at `s` with state `y`, reusing `strings`' storage.
fn frame(
    robot: &Robot,
    c: &Consts,
    tau: &[f64],
    s: f64,
    y: &[f64],
    mut strings: Vec<Crossing>,
) -> NodeFrame {
    let b = &robot.body;
    let (kse, kbt) = (c.kse, c.kbt);
    let q = Quaternion::new(y[3], y[4], y[5], y[6]);
    let rm = rot(&q);
    let v = Vector3::new(y[7], y[8], y[9]);
    let u = Vector3::new(y[10], y[11], y[12]);
    let mut nb = kse * (v - b.nu_star);
    let mut mb = kbt * (u - b.omega_star);
    strings.clear();
    for (i, a) in robot.actuators.iter().enumerate() {
        if !crosses(a, s, b.length) {
            continue;
        }
        let (r, rp, _) = a.routing.eval(s);
        let pb = v + u.cross(&r) + rp;
        let nrm = pb.norm();
        let tt = pb / nrm;
        nb += tt * tau[i];
        mb += r.cross(&tt) * tau[i];
        strings.push((i, r, tt, nrm, tau[i]));
    }
    NodeFrame {
        q,
        rm,
        rn: rm * nb,
        rmm: rm * mb,
        strings,
    }
}

/// Body constants used by every column.
struct Consts {
    kse: Matrix3<f64>,
    kbt: Matrix3<f64>,
    fs: f64,
    ms: f64,
    len: f64,
}

/// One tangent column: `(d w~, d (p/L, theta))` along direction `j` whose
/// state tangent is `t` and tension derivative `dtau` (`d tau_i / d z_j`).
fn column(
    c: &Consts,
    f: &NodeFrame,
    t: &[f64],
    dtau: &DMatrix<f64>,
    j: usize,
) -> (Vector6<f64>, Vector6<f64>) {
    let (kse, kbt) = (c.kse, c.kbt);
    let dp = Vector3::new(t[0], t[1], t[2]);
    let dv = Vector3::new(t[7], t[8], t[9]);
    let du = Vector3::new(t[10], t[11], t[12]);
    let mut dnb = kse * dv;
    let mut dmb = kbt * du;
    for &(i, r, tt, nrm, tau) in &f.strings {
        // d pb = d v + d u x r; d t = (I - t t^T) d pb / |pb|
        let dpb = dv + du.cross(&r);
        let dt = (dpb - tt * tt.dot(&dpb)) / nrm;
        let df = dt * tau + tt * dtau[(i, j)];
        dnb += df;
        dmb += r.cross(&df);
    }
    // rotation tangent: d q = (theta/2) (x) q  =>  theta = 2 vec(d q (x) q*)
    let w = Quaternion::new(t[3], t[4], t[5], t[6]) * f.q.conjugate() * 2.0;
    let th = Vector3::new(w.i, w.j, w.k);
    // world wrench w = R (nb, mb): d w = theta x R nb + R d nb
    let dn = (f.rm * dnb + th.cross(&f.rn)) * c.fs;
    let dm = (f.rm * dmb + th.cross(&f.rmm)) * c.ms;
    let dh = dp / c.len;
    (
        Vector6::new(dn.x, dn.y, dn.z, dm.x, dm.y, dm.z),
        Vector6::new(dh.x, dh.y, dh.z, th.x, th.y, th.z),
    )
}

/// One value per frozen-tension direction (the six base strains).
type Lanes = [f64; 6];
/// A 3-vector of [`Lanes`].
type V3L = [Lanes; 3];

fn lanes(f: impl FnMut(usize) -> f64) -> Lanes {
    std::array::from_fn(f)
}

/// `m v` for each lane.
fn mat_lanes(m: &Matrix3<f64>, v: &V3L) -> V3L {
    std::array::from_fn(|i| {
        lanes(|l| m[(i, 0)] * v[0][l] + m[(i, 1)] * v[1][l] + m[(i, 2)] * v[2][l])
    })
}

/// `a x b` for lanes `a` and a fixed vector `b`.
fn cross_lanes(a: &V3L, b: &Vector3<f64>) -> V3L {
    [
        lanes(|l| a[1][l] * b.z - a[2][l] * b.y),
        lanes(|l| a[2][l] * b.x - a[0][l] * b.z),
        lanes(|l| a[0][l] * b.y - a[1][l] * b.x),
    ]
}

/// The six frozen-tension columns of a node at once ([`column`] along the
/// base strains, whose tension derivatives are zero), lane by lane: the
/// same arithmetic on arrays of six, which the compiler vectorises.
/// `t`: the node's tangents, `ns` states per direction.
fn frozen_columns(c: &Consts, f: &NodeFrame, t: &[f64], ns: usize) -> (Cols6, Cols6) {
    let g = |k: usize| lanes(|l| t[l * ns + k]);
    let dp = [g(0), g(1), g(2)];
    let dq = [g(3), g(4), g(5), g(6)];
    let dv = [g(7), g(8), g(9)];
    let du = [g(10), g(11), g(12)];
    let mut dnb = mat_lanes(&c.kse, &dv);
    let mut dmb = mat_lanes(&c.kbt, &du);
    for &(_, r, tt, nrm, tau) in &f.strings {
        // d pb = d v + d u x r; d t = (I - t t^T) d pb / |pb|; d f = d t tau
        let ur = cross_lanes(&du, &r);
        let dpb: V3L = std::array::from_fn(|k| lanes(|l| dv[k][l] + ur[k][l]));
        let tp = lanes(|l| tt.x * dpb[0][l] + tt.y * dpb[1][l] + tt.z * dpb[2][l]);
        let df: V3L = std::array::from_fn(|k| lanes(|l| (dpb[k][l] - tt[k] * tp[l]) / nrm * tau));
        // r x d f = -(d f x r)
        let rf = cross_lanes(&df, &r);
        for k in 0..3 {
            for l in 0..6 {
                dnb[k][l] += df[k][l];
                dmb[k][l] -= rf[k][l];
            }
        }
    }
    // theta = 2 vec(d q (x) q*), q = (w, x, y, z)
    let (w, x, y, z) = (f.q.w, f.q.i, f.q.j, f.q.k);
    let th: V3L = [
        lanes(|l| 2.0 * (-dq[0][l] * x + dq[1][l] * w - dq[2][l] * z + dq[3][l] * y)),
        lanes(|l| 2.0 * (-dq[0][l] * y + dq[1][l] * z + dq[2][l] * w - dq[3][l] * x)),
        lanes(|l| 2.0 * (-dq[0][l] * z - dq[1][l] * y + dq[2][l] * x + dq[3][l] * w)),
    ];
    // d w = theta x R nb + R d nb (scaled)
    let (rdn, rdm) = (mat_lanes(&f.rm, &dnb), mat_lanes(&f.rm, &dmb));
    let (tn, tm) = (cross_lanes(&th, &f.rn), cross_lanes(&th, &f.rmm));
    let mut y = [[0.0; 6]; 6];
    let mut h = [[0.0; 6]; 6];
    for l in 0..6 {
        for k in 0..3 {
            y[l][k] = (rdn[k][l] + tn[k][l]) * c.fs;
            y[l][3 + k] = (rdm[k][l] + tm[k][l]) * c.ms;
            h[l][k] = dp[k][l] / c.len;
            h[l][3 + k] = th[k][l];
        }
    }
    (y, h)
}

/// Seeds of the tangent IVP along the scaled unknowns `z_0 .. z_nz`
/// (`nz` = 6: the base strains only; `6 + N`: the elongation guesses too),
/// the tensions and `d tau_i / d z_j` (`N x nz`). `tau`: the tensions \[N\]
/// if already known (the shooting residual's, [`crate::shooting::tensions`]).
fn seeds(
    robot: &Robot,
    eq: &Equilibrium<'_>,
    nz: usize,
    tau: Option<&[f64]>,
) -> Result<(TangentSeeds, Vec<f64>, DMatrix<f64>)> {
    let na = robot.actuators.len();
    let len = robot.body.length;
    let mut seeds = TangentSeeds::zeros(na, nz);
    for k in 0..3 {
        seeds.nu0[(k, k)] = 1.0;
        seeds.omega0[(k, 3 + k)] = 1.0 / len;
    }
    let mut out = Vec::with_capacity(na);
    let mut dtau = DMatrix::zeros(na, nz);
    for (i, a) in robot.actuators.iter().enumerate() {
        let (t, dt_de, _) = a
            .law
            .tension_derivatives(eq.unknowns[6 + i] * len, eq.inputs[i])?;
        out.push(tau.map_or(t, |tau| tau[i]));
        if nz > 6 {
            seeds.tensions[(i, 6 + i)] = dt_de * len;
            dtau[(i, 6 + i)] = dt_de * len;
        }
    }
    Ok((seeds, out, dtau))
}

/// One recorded tangent IVP at an equilibrium, before its nodes are turned
/// into [`Tangents`] ([`tangents_of`]): the recorded nodes, the tip
/// elongation tangents, the tensions \[N\] and `d tau_i / d z_j`, as
/// carried by the stabilised march ([`super::march`]).
pub(crate) struct Pass {
    nodes: TangentNodes,
    elongation: DMatrix<f64>,
    pub tau: Vec<f64>,
    dtau: DMatrix<f64>,
    /// Whether the `N` actuator directions were integrated.
    actuators: bool,
    /// `ln |det|` of the true columns' factor over the carried ones, per node.
    ldet: Vec<f64>,
    /// The actuator part `P dz'` of the carried columns (`N x nz`; `[0 I]`
    /// for the plain ones).
    pdz: DMatrix<f64>,
    /// Re-orthonormalisations done.
    pub(super) reorthonormalised: usize,
}

/// The tangent IVP of the verdict along the six base strains and, if
/// `actuators`, the `N` actuator elongation guesses too, every node
/// recorded (states and tangents; the IVP's nodes are the states,
/// [`Pass::ivp_nodes`]); with the IVP itself (no node list).
/// `tau`: the tensions, if known (else from the force laws). The columns
/// are re-orthonormalised where their spread passes `bound`
/// ([`super::march::GROWTH_BOUND`]; infinite: the plain pass).
pub(super) fn integrate_pass(
    robot: &Robot,
    eq: &Equilibrium<'_>,
    actuators: bool,
    tau: Option<&[f64]>,
    bound: f64,
) -> Result<(Pass, IvpResult)> {
    let na = robot.actuators.len();
    let nz = if actuators { 6 + na } else { 6 };
    let (seeds, tau, dtau) = seeds(robot, eq, nz, tau)?;
    let spec = eq.loads.ivp(robot, &tau, eq.steps);
    let len = robot.body.length;
    let (v0, u0) = base_strains(eq.unknowns, len);
    let n = robot.n_states();
    let mut march = March::new(bound, n, nz, len, actuators);
    if let Some(sol) = eq.along {
        check_grid(robot, sol, eq.steps)?;
    }
    let tan = spec.integrate_tangent_hooked(&v0, &u0, &seeds, &mut |i, y, c, m| {
        if let Some(sol) = eq.along {
            restart(y, sol, i);
        }
        march.at_node(i, c, m)
    })?;
    let nodes = tan.nodes.len();
    // (more directions than one pass holds: the hook was never called)
    march.ldet.resize(nodes, 0.0);
    let pdz = if actuators {
        DMatrix::from_column_slice(march.na, nz, &march.pdz)
    } else {
        DMatrix::zeros(na, 0)
    };
    let pass = Pass {
        nodes: tan.nodes,
        elongation: tan.elongation,
        tau,
        dtau,
        actuators,
        ldet: march.ldet,
        pdz,
        reorthonormalised: march.count,
    };
    Ok((pass, tan.ivp))
}

/// `sol` is recorded on the grid of `steps` steps (one state per node of
/// the pass).
fn check_grid(robot: &Robot, sol: &Solution, steps: usize) -> Result<()> {
    let nodes = Grid::new(robot, steps).tip() + 1;
    if sol.steps != steps || sol.s.len() != nodes {
        return Err(Error::input(
            "solution",
            format!("a solution on the grid of {steps} steps ({nodes} nodes)"),
        ));
    }
    Ok(())
}

/// Continue the pass at node `k` from the recorded state of `sol` there
/// (position, the rotation's quaternion, strains, elongations) instead of
/// its own `y`. Where the pass is on the recorded state already (positions,
/// strains and elongations equal, as on a solution of this very IVP) it
/// goes on from its own: the recorded rotation is a matrix, and reading it
/// back as a quaternion would cost a rounding error (and the work of the
/// conversion), so the verdict of such a solution stays its IVP's bit for
/// bit. The quaternion's sign is `y`'s (`q` and `-q` are one rotation, and
/// the tangent lanes are those of `y`'s sign).
fn restart(y: &mut [f64], sol: &Solution, k: usize) {
    let (p, v, u) = (&sol.positions[k], &sol.nu[k], &sol.omega[k]);
    let delta = sol.elongation_profile.row(k);
    let others = (p.iter().chain(v.iter()).chain(u.iter())).chain(delta.iter());
    let own = (y[0..3].iter()).chain(&y[7..]);
    if own.zip(others).all(|(a, b)| a == b) {
        return;
    }
    let q = UnitQuaternion::from_matrix(&sol.rotations[k]);
    let dot = y[3] * q.w + y[4] * q.i + y[5] * q.j + y[6] * q.k;
    let sign = if dot < 0.0 { -1.0 } else { 1.0 };
    y[0..3].copy_from_slice(p.as_slice());
    y[3..7].copy_from_slice(&[q.w, q.i, q.j, q.k].map(|x| sign * x));
    let rest = v.iter().chain(u.iter()).chain(delta.iter());
    for (x, r) in y[7..].iter_mut().zip(rest) {
        *x = *r;
    }
}

impl Pass {
    /// The IVP's nodes (the recorded states), flat: what assembles a
    /// [`Solution`] without another IVP or a node-by-node copy.
    pub(crate) fn ivp_nodes(&self) -> FlatNodes {
        self.nodes.to_flat()
    }
}

/// The tangents at every node of a recorded pass.
pub(super) fn tangents_of(robot: &Robot, pass: &Pass) -> Tangents {
    let na = robot.actuators.len();
    let nz = if pass.actuators { 6 + na } else { 6 };
    let len = robot.body.length;
    let (fs, ms) = residual_scales(robot);
    let (kse, kbt) = robot.body.stiffness();
    let c = Consts {
        kse,
        kbt,
        fs,
        ms,
        len,
    };
    // the carried columns' tension tangents: d tau_i / d delta_i times
    // their actuator part (P dz = [0 I], dtau itself, for the plain ones)
    let carried_dtau;
    let dtau = if pass.reorthonormalised > 0 && pass.actuators {
        carried_dtau = DMatrix::from_fn(na, nz, |i, j| pass.dtau[(i, 6 + i)] * pass.pdz[(i, j)]);
        &carried_dtau
    } else {
        &pass.dtau
    };
    let tau = &pass.tau;
    let k = pass.nodes.len();
    let mut out = Tangents {
        s: Vec::with_capacity(k),
        y: Vec::with_capacity(k),
        h: Vec::with_capacity(k),
        y_tip: DMatrix::zeros(6, nz),
        h_tip: DMatrix::zeros(6, nz),
        e: DMatrix::zeros(na, if pass.actuators { nz } else { 0 }),
        ldet: pass.ldet.clone(),
        carried: pass.reorthonormalised > 0,
    };
    let mut strings = Vec::with_capacity(na);
    let ns = robot.n_states();
    for (n, node) in pass.nodes.iter().enumerate() {
        let f = frame(robot, &c, tau, node.s, node.state, strings);
        let tip = n + 1 == k;
        if !tip {
            let (y, h) = frozen_columns(&c, &f, node.tangent, ns);
            out.s.push(node.s);
            out.y.push(y);
            out.h.push(h);
            strings = f.strings;
            continue;
        }
        let (mut y, mut h) = ([[0.0; 6]; 6], [[0.0; 6]; 6]);
        for j in 0..nz {
            let (dy, dh) = column(&c, &f, &node.tangent[j * ns..(j + 1) * ns], dtau, j);
            if j < 6 {
                y[j].copy_from_slice(dy.as_slice());
                h[j].copy_from_slice(dh.as_slice());
            }
            out.y_tip.set_column(j, &dy);
            out.h_tip.set_column(j, &dh);
        }
        out.s.push(node.s);
        out.y.push(y);
        out.h.push(h);
        strings = f.strings;
    }
    if pass.actuators {
        for i in 0..na {
            for j in 0..nz {
                // E' = d delta'(L) / L - P dz' (P dz = [0 I] when plain)
                out.e[(i, j)] = pass.elongation[(i, j)] / len - pass.pdz[(i, j)];
            }
        }
    }
    out
}

/// Exact tangents from one recorded tangent IVP ([`integrate_pass`]); with
/// them the IVP itself, the tensions \[N\] and, if `profile`, the IVP's
/// nodes ([`Pass::ivp_nodes`]).
pub(super) fn exact_tangents(
    robot: &Robot,
    eq: &Equilibrium<'_>,
    actuators: bool,
    profile: bool,
    bound: f64,
) -> Result<(Tangents, IvpResult, Vec<f64>, Option<FlatNodes>)> {
    let (pass, ivp) = integrate_pass(robot, eq, actuators, None, bound)?;
    let nodes = profile.then(|| pass.ivp_nodes());
    Ok((tangents_of(robot, &pass), ivp, pass.tau, nodes))
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
/// plus every string crossing `s`.
fn wrench(robot: &Robot, tau: &[f64], s: f64, st: &RodState) -> (Vector3<f64>, Vector3<f64>) {
    let b = &robot.body;
    let (kse, kbt) = b.stiffness();
    let rm = st.rotation();
    let mut n = kse * (st.v - b.nu_star);
    let mut m = kbt * (st.u - b.omega_star);
    for (i, a) in robot.actuators.iter().enumerate() {
        if crosses(a, s, b.length) {
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
    let (resid, ivp, tau) = Shot::new(robot, inputs, loads, steps).residual(x, true)?;
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

/// Forward-difference tangents from `1 + nz` recorded IVPs (all `6 + N`
/// directions; a cross-check of [`exact_tangents`]).
pub(super) fn fd_tangents(robot: &Robot, sol: &Solution) -> Result<Tangents> {
    let na = robot.actuators.len();
    let nz = 6 + na;
    let len = robot.body.length;
    let (fs, ms) = residual_scales(robot);
    let x = &sol.unknowns;
    let base = profile(robot, &sol.inputs, &sol.loads, x, sol.steps)?;
    let nodes = base.p.len();
    let mut y = vec![DMatrix::zeros(6, nz); nodes];
    let mut h = vec![DMatrix::zeros(6, nz); nodes];
    let mut e = DMatrix::zeros(na, nz);
    let h0 = f64::EPSILON.sqrt();
    for j in 0..nz {
        let mut xp = x.clone();
        let step = h0 * x[j].abs().max(1.0);
        xp[j] += step;
        let step = xp[j] - x[j];
        let pp = profile(robot, &sol.inputs, &sol.loads, &xp, sol.steps)?;
        for k in 0..nodes {
            let dn = (pp.n[k] - base.n[k]) * (fs / step);
            let dm = (pp.m[k] - base.m[k]) * (ms / step);
            let dp = (pp.p[k] - base.p[k]) / (len * step);
            let th = vee_skew(&(pp.r[k] * base.r[k].transpose())) / step;
            for i in 0..3 {
                y[k][(i, j)] = dn[i];
                y[k][(3 + i, j)] = dm[i];
                h[k][(i, j)] = dp[i];
                h[k][(3 + i, j)] = th[i];
            }
        }
        for i in 0..na {
            e[(i, j)] = (pp.resid[6 + i] - base.resid[6 + i]) / step;
        }
    }
    let m6 =
        |m: &DMatrix<f64>| -> Cols6 { std::array::from_fn(|j| std::array::from_fn(|i| m[(i, j)])) };
    Ok(Tangents {
        ldet: vec![0.0; sol.s.len()],
        carried: false,
        s: sol.s.clone(),
        y: y.iter().map(m6).collect(),
        h: h.iter().map(m6).collect(),
        y_tip: y.pop().unwrap_or_else(|| DMatrix::zeros(6, nz)),
        h_tip: h.pop().unwrap_or_else(|| DMatrix::zeros(6, nz)),
        e,
    })
}
