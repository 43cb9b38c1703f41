//! The linearisation of [`MultipleShooting`]: the residual with the exact
//! Jacobian blocks `D_k`, `E_k` of each segment (tangents of the discrete
//! RK4 map, [`crate::rod::IvpSpec::integrate_stretch_tangent`]), their
//! staircase factorisation ([`crate::solve::abd`]) and the dense Jacobian.

use nalgebra::DMatrix;

use super::*;

impl MultipleShooting<'_> {
    /// The residual at `x` into `f` and the Jacobian blocks `D_k`, `E_k`
    /// (exact: tangents of the discrete map), kept for
    /// [`MultipleShooting::dense_jacobian`] and the staircase solve.
    pub fn linearise(&mut self, x: &[f64], f: &mut [f64]) -> Result<()> {
        let (m, na, len) = (self.segments(), self.na(), self.robot.body.length);
        let (rows, cols) = (self.rows(), self.cols());
        self.d = (0..m).map(|k| DMatrix::zeros(rows[k], cols[k])).collect();
        self.e = (0..m.saturating_sub(1))
            .map(|k| DMatrix::zeros(rows[k], cols[k + 1]))
            .collect();
        let mut row = 0;
        self.tip = None;
        let states = self.block_states(x)?;
        for (k, cur) in states.iter().enumerate() {
            let (dirs, seeds) = self.seeds(x, k, cur);
            let spec = self.spec(&cur.tau);
            let tan = spec.integrate_stretch_tangent(self.stretch(k), &cur.y, &seeds)?;
            // (a segment's share of one tangent IVP over the whole grid)
            let share = (self.bounds[k + 1] - self.bounds[k]) as f64 / self.tip() as f64;
            self.work += share * (1.0 + dirs as f64 / 8.0);
            let next = states.get(k + 1).map(|s| &s.y[..]);
            row += self.segment_rows(x, (k, cur), &tan.ivp, next, &mut f[row..]);
            let dcol = if k == 0 { 6 } else { 12 + na };
            let col_of = |c: usize| direction_column(k, na, c);
            let mut own = match next {
                Some(y) => {
                    self.continuity_blocks(k, &tan, y, x);
                    interior_len(na)
                }
                None => {
                    self.tip = Some((tan.ivp.tip.clone(), Some(self.tip_tangent(k, &tan))));
                    let (fs, ms) = residual_scales(self.robot);
                    for j in 0..3 {
                        for c in 0..dirs {
                            self.d[k][(j, col_of(c))] = tan.tip_force_residual[(j, c)] * fs;
                            self.d[k][(3 + j, col_of(c))] = tan.tip_moment_residual[(j, c)] * ms;
                        }
                    }
                    6
                }
            };
            for i in (0..na).filter(|&i| self.ends_in[i] == k) {
                for c in 0..dirs {
                    self.d[k][(own, col_of(c))] = tan.elongation[(i, c)] / len;
                }
                if k > 0 {
                    self.d[k][(own, 12 + i)] += 1.0;
                }
                self.d[k][(own, dcol + i)] -= cur.dd[i];
                own += 1;
            }
        }
        Ok(())
    }

    /// The tip position's derivatives \[m\] with respect to block `k`'s
    /// (the last block's) scaled unknowns, from its segment's tangent IVP
    /// `tan` (see [`MultipleShooting::tip_state`]).
    fn tip_tangent(&self, k: usize, tan: &crate::rod::TangentIvp) -> DMatrix<f64> {
        let (na, len) = (self.na(), self.robot.body.length);
        let mut g = DMatrix::zeros(3, self.cols()[k]);
        for c in 0..tan.tip.ncols() {
            for j in 0..3 {
                g[(j, direction_column(k, na, c))] = tan.tip[(j, c)];
            }
        }
        if k > 0 {
            for j in 0..3 {
                g[(j, j)] += len;
            }
        }
        g
    }

    /// The seed directions of segment `k`'s tangent IVP from its block
    /// state `st`: block 0's `nu`, `L omega` and `sigma`; an interior
    /// block's `theta`, `nu`, `L omega` and `sigma` (its `p` and `delta`
    /// enter nothing but themselves). Returns their number and the seeds.
    fn seeds(&self, x: &[f64], k: usize, st: &BlockState) -> (usize, TangentSeeds) {
        let (na, len) = (self.na(), self.robot.body.length);
        let n = BASE_STATES + na;
        let (lead, strains_at) = if k == 0 { (0, 0) } else { (3, 3) };
        let dirs = lead + 6 + na;
        let mut seeds = TangentSeeds::zeros(na, dirs);
        let mut s0 = DMatrix::zeros(n, dirs);
        if k > 0 {
            let o = self.offset(k);
            let theta = Vector3::new(x[o + 3], x[o + 4], x[o + 5]);
            for (j, dq) in dexp_half(&theta).iter().enumerate() {
                let dq = self.charts[k] * dq;
                for (r, v) in [dq.w, dq.i, dq.j, dq.k].into_iter().enumerate() {
                    s0[(3 + r, j)] = v;
                }
            }
        }
        for j in 0..3 {
            s0[(7 + j, strains_at + j)] = 1.0;
            s0[(10 + j, strains_at + 3 + j)] = 1.0 / len;
        }
        for i in 0..na {
            seeds.tensions[(i, lead + 6 + i)] = st.slope[i];
        }
        seeds.state0 = Some(s0);
        (dirs, seeds)
    }

    /// `D_k` and `E_k` of the continuity rows of segment `k` from its
    /// tangent IVP `tan` (directions as [`MultipleShooting::seeds`]) and
    /// the next block's state `start`.
    fn continuity_blocks(
        &mut self,
        k: usize,
        tan: &crate::rod::TangentIvp,
        start: &[f64],
        x: &[f64],
    ) {
        let (na, len) = (self.na(), self.robot.body.length);
        let end = &tan.ivp.tip;
        let qb = Quaternion::new(start[3], start[4], start[5], start[6]);
        let e = qb.conjugate() * end.q;
        let sgn = if e.w < 0.0 { -2.0 } else { 2.0 };
        let dcol = if k == 0 { 6 } else { 12 + na };
        let d = &mut self.d[k];
        for c in 0..tan.tip.ncols() {
            let col = direction_column(k, na, c);
            let t = tan.tip.column(c);
            let dq = qb.conjugate() * Quaternion::new(t[3], t[4], t[5], t[6]);
            for j in 0..3 {
                d[(j, col)] = t[j] / len;
                d[(3 + j, col)] = sgn * [dq.i, dq.j, dq.k][j];
                d[(6 + j, col)] = t[7 + j];
                d[(9 + j, col)] = t[10 + j] * len;
            }
            for i in 0..na {
                d[(12 + i, col)] = t[BASE_STATES + i] / len;
            }
        }
        if k > 0 {
            for j in 0..3 {
                d[(j, j)] += 1.0;
            }
            for i in 0..na {
                d[(12 + i, 12 + i)] += 1.0;
            }
        }
        for i in 0..na {
            d[(12 + na + i, dcol + i)] = 1.0;
        }
        // the next block: minus its state, and the defect's rotation term
        let o = self.offset(k + 1);
        let eb = &mut self.e[k];
        let theta = Vector3::new(x[o + 3], x[o + 4], x[o + 5]);
        for (j, dexp) in dexp_half(&theta).iter().enumerate() {
            let dqb = self.charts[k + 1] * dexp;
            let de = dqb.conjugate() * end.q;
            for (r, v) in [de.i, de.j, de.k].into_iter().enumerate() {
                eb[(3 + r, 3 + j)] = sgn * v;
            }
        }
        for j in 0..3 {
            eb[(j, j)] = -1.0;
            eb[(6 + j, 6 + j)] = -1.0;
            eb[(9 + j, 9 + j)] = -1.0;
        }
        for i in 0..2 * na {
            eb[(12 + i, 12 + i)] = -1.0;
        }
    }

    /// A staircase of this system's shape, for [`MultipleShooting::factorise`].
    pub(crate) fn staircase(&self) -> Result<crate::solve::abd::Staircase> {
        let shape = crate::solve::abd::Shape {
            rows: self.rows(),
            cols: self.cols(),
        };
        crate::solve::abd::Staircase::new(shape)
    }

    /// The Jacobian blocks of the last linearisation factorised in `lu` (of
    /// this system's shape); whether it was found singular.
    pub(crate) fn factorise(&self, lu: &mut crate::solve::abd::Staircase) -> bool {
        for (k, dk) in self.d.iter().enumerate() {
            lu.d_mut(k).copy_from(dk);
        }
        for (k, ek) in self.e.iter().enumerate() {
            lu.e_mut(k).copy_from(ek);
        }
        lu.factorise().is_err()
    }

    /// The Jacobian assembled dense (for checks and small systems).
    pub fn dense_jacobian(&self) -> DMatrix<f64> {
        let (rows, cols) = (self.rows(), self.cols());
        let n = self.dim();
        let mut j = DMatrix::zeros(n, n);
        let (mut r0, mut c0) = (0, 0);
        for k in 0..self.segments() {
            j.view_mut((r0, c0), (rows[k], cols[k]))
                .copy_from(&self.d[k]);
            if k + 1 < self.segments() {
                j.view_mut((r0, c0 + cols[k]), (rows[k], cols[k + 1]))
                    .copy_from(&self.e[k]);
            }
            r0 += rows[k];
            c0 += cols[k];
        }
        j
    }
}
