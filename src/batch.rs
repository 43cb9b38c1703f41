//! Many forward solves in one call: rows of actuator inputs (and optionally
//! tip loads), split into fixed chunks that are solved in parallel across
//! threads, each chunk in order with warm starts along it.
//!
//! The chunking is fixed by `chunk_size` alone (not by the thread count), and
//! a warm-start chain restarts at every chunk, so the results do not depend
//! on the number of threads or on how chunks are spread over machines.

use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::Mutex;

use nalgebra::Vector3;

use crate::error::{Error, Result};
use crate::limits::{MAX_BATCH_ROWS, MAX_CHUNK, MAX_THREADS};
use crate::rod::Robot;
use crate::shooting::{solve_loaded, Loads, Solution, SolveOptions};
use crate::solve::cancel;
use crate::stability::{stability, Stability};

/// Options of [`solve_batch`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BatchOptions {
    /// Options of each forward solve.
    pub solve: SolveOptions,
    /// Rows per chunk; warm starts run along a chunk.
    pub chunk_size: usize,
    /// Worker threads (0: all available cores).
    pub threads: usize,
    /// Warm-start each row from the previous row of its chunk (else every row is cold).
    pub warm: bool,
    /// Give each converged row its stability verdict ([`crate::stability`],
    /// one tangent integration per row, about as much as a warm solve); off
    /// for hot loops that do not use it.
    pub stability: bool,
}

impl Default for BatchOptions {
    fn default() -> Self {
        BatchOptions {
            solve: SolveOptions::default(),
            chunk_size: 256,
            threads: 0,
            warm: true,
            stability: true,
        }
    }
}

/// Stacked results of [`solve_batch`], one entry per row.
#[derive(Debug, Clone, Default)]
pub struct BatchOutput {
    /// Tip positions \[m\] (NaN where a solve failed).
    pub tip_positions: Vec<[f64; 3]>,
    /// Tip rotations, row-major 3x3 (NaN where a solve failed).
    pub tip_rotations: Vec<[f64; 9]>,
    /// Actuator tensions \[N\], `n_rows x n_actuators` row-major (NaN where
    /// a solve failed).
    pub tensions: Vec<f64>,
    /// Newton iterations of each solve (of a failed one: those it spent).
    pub iterations: Vec<u32>,
    /// IVPs integrated by each solve (of a failed one: those it spent).
    pub evaluations: Vec<u32>,
    /// Whether each solve converged.
    pub converged: Vec<bool>,
    /// Whether each row's equilibrium is stable (`false` where no verdict:
    /// see `margin`).
    pub stable: Vec<bool>,
    /// Stability margin of each row (smallest eigenvalue of the
    /// dimensionless tip stiffness, > 0 iff stable; see
    /// [`crate::stability::Stability::margin`]); NaN where there is no
    /// verdict: the solve or the verdict failed, or `stability` was off.
    pub margin: Vec<f64>,
    /// Shape of each row, filled by [`solve_batch_shapes`] only (empty
    /// otherwise): arc length \[m\] and world position \[m\] of every node,
    /// `[s, x, y, z]`; empty for a row that did not converge.
    pub shapes: Vec<Vec<[f64; 4]>>,
}

impl BatchOutput {
    /// Outputs of `n` rows before any solve (NaN / zero / false). A 2M-row
    /// batch touches ~250 MB here (0.1-0.4 s of page faults), so the filling
    /// polls the cancel check ([`crate::solve::cancel`]) between blocks.
    fn with_len(n: usize, n_actuators: usize) -> Result<Self> {
        Ok(BatchOutput {
            tip_positions: filled(n, [f64::NAN; 3])?,
            tip_rotations: filled(n, [f64::NAN; 9])?,
            tensions: filled(n * n_actuators, f64::NAN)?,
            iterations: filled(n, 0)?,
            evaluations: filled(n, 0)?,
            converged: filled(n, false)?,
            stable: filled(n, false)?,
            margin: filled(n, f64::NAN)?,
            shapes: Vec::new(),
        })
    }
}

/// `vec![value; n]`, filled in blocks of 2^16 with a cancel check between.
fn filled<T: Copy>(n: usize, value: T) -> Result<Vec<T>> {
    const BLOCK: usize = 1 << 16;
    let mut v = Vec::with_capacity(n);
    while v.len() < n {
        cancel::check()?;
        let m = (n - v.len()).min(BLOCK);
        v.resize(v.len() + m, value);
    }
    Ok(v)
}

/// One chunk's disjoint slices of a [`BatchOutput`].
struct ChunkOut<'a> {
    pos: &'a mut [[f64; 3]],
    rot: &'a mut [[f64; 9]],
    /// `rows x n_actuators`, row-major.
    tensions: &'a mut [f64],
    iters: &'a mut [u32],
    evals: &'a mut [u32],
    ok: &'a mut [bool],
    stable: &'a mut [bool],
    margin: &'a mut [f64],
    /// Each row's shape (empty slice: shapes not kept).
    shapes: &'a mut [Vec<[f64; 4]>],
}

impl<'a> ChunkOut<'a> {
    fn whole(out: &'a mut BatchOutput) -> Self {
        ChunkOut {
            pos: &mut out.tip_positions,
            rot: &mut out.tip_rotations,
            tensions: &mut out.tensions,
            iters: &mut out.iterations,
            evals: &mut out.evaluations,
            ok: &mut out.converged,
            stable: &mut out.stable,
            margin: &mut out.margin,
            shapes: &mut out.shapes,
        }
    }

    fn rows(&self) -> usize {
        self.ok.len()
    }

    /// The first `rows` rows (at most all) and the rest.
    fn split(self, rows: usize, na: usize) -> (Self, Self) {
        let k = rows.min(self.rows());
        let (pos, pos2) = self.pos.split_at_mut(k);
        let (rot, rot2) = self.rot.split_at_mut(k);
        let (tensions, tensions2) = self.tensions.split_at_mut(k * na);
        let (iters, iters2) = self.iters.split_at_mut(k);
        let (evals, evals2) = self.evals.split_at_mut(k);
        let (ok, ok2) = self.ok.split_at_mut(k);
        let (stable, stable2) = self.stable.split_at_mut(k);
        let (margin, margin2) = self.margin.split_at_mut(k);
        let (shapes, shapes2) = self.shapes.split_at_mut(k.min(self.shapes.len()));
        (
            ChunkOut {
                pos,
                rot,
                tensions,
                iters,
                evals,
                ok,
                stable,
                margin,
                shapes,
            },
            ChunkOut {
                pos: pos2,
                rot: rot2,
                tensions: tensions2,
                iters: iters2,
                evals: evals2,
                ok: ok2,
                stable: stable2,
                margin: margin2,
                shapes: shapes2,
            },
        )
    }

    /// Row `j` from the converged solve `s` and its verdict, if any.
    fn set(&mut self, j: usize, s: &Solution, verdict: Option<&Stability>) {
        let na = s.tensions.len();
        self.pos[j] = s.tip_position().into();
        let rotation = s.tip_rotation();
        for a in 0..3 {
            for b in 0..3 {
                self.rot[j][3 * a + b] = rotation[(a, b)];
            }
        }
        self.tensions[j * na..(j + 1) * na].copy_from_slice(&s.tensions);
        self.iters[j] = s.iterations as u32;
        self.evals[j] = (s.evaluations + verdict.map_or(0, |v| v.evaluations)) as u32;
        self.ok[j] = true;
        if let Some(v) = verdict {
            self.stable[j] = v.stable;
            self.margin[j] = v.margin;
        }
    }

    /// Row `j` of a solve that failed with `e`: the work it spent
    /// (iterations, IVPs), not zeros, so a row's cost is counted whether it
    /// converged or not.
    fn set_failed(&mut self, j: usize, e: &Error) {
        if let Error::NotConverged {
            iterations,
            evaluations,
            ..
        } = e
        {
            self.iters[j] = *iterations as u32;
            self.evals[j] = *evaluations as u32;
        }
    }
}

/// Number of worker threads for `requested` (0: available parallelism).
pub fn thread_count(requested: usize) -> usize {
    if requested > 0 {
        requested
    } else {
        std::thread::available_parallelism().map_or(1, |n| n.get())
    }
}

impl BatchOptions {
    /// Error unless the options are in range: the solve options,
    /// `1 <= chunk_size <= MAX_CHUNK`, `threads <= MAX_THREADS` (see [`crate::limits`]).
    pub fn validate(&self) -> Result<()> {
        self.solve.validate()?;
        if !(1..=MAX_CHUNK).contains(&self.chunk_size) {
            return Err(Error::param(
                "chunk_size",
                self.chunk_size as f64,
                format!("1 <= chunk_size <= {MAX_CHUNK}"),
            ));
        }
        if self.threads > MAX_THREADS {
            return Err(Error::param(
                "threads",
                self.threads as f64,
                format!("0 <= threads <= {MAX_THREADS}"),
            ));
        }
        Ok(())
    }
}

/// Solve `n = inputs.len() / n_actuators` forward problems: row `k` has
/// inputs `inputs[k * na..(k + 1) * na]` and, if `wrenches` is given, tip
/// force and moment `wrenches[k * 6..(k + 1) * 6]` (world frame, N and N m;
/// else the body's own tip loads).
///
/// Invalid inputs are an error (naming the row) before any work; a solve that
/// does not converge gives `converged = false`, NaN pose and NaN tensions,
/// and the next row of its chunk starts cold.
pub fn solve_batch(
    robot: &Robot,
    inputs: &[f64],
    wrenches: Option<&[f64]>,
    opts: &BatchOptions,
) -> Result<BatchOutput> {
    run_batch(robot, inputs, wrenches, opts, false)
}

/// [`solve_batch`] keeping the shape of every converged row
/// ([`BatchOutput::shapes`]: arc length and centre-line position of each
/// node), rebuilt from its converged unknowns by one more IVP per row
/// (counted in [`BatchOutput::evaluations`]). Memory grows with rows times
/// nodes (32 bytes per node), so a sweep of millions of rows should keep
/// tips only.
pub fn solve_batch_shapes(
    robot: &Robot,
    inputs: &[f64],
    wrenches: Option<&[f64]>,
    opts: &BatchOptions,
) -> Result<BatchOutput> {
    run_batch(robot, inputs, wrenches, opts, true)
}

fn run_batch(
    robot: &Robot,
    inputs: &[f64],
    wrenches: Option<&[f64]>,
    opts: &BatchOptions,
    shapes: bool,
) -> Result<BatchOutput> {
    robot.validate()?;
    opts.validate()?;
    let na = robot.actuators.len();
    let n = batch_rows(robot, inputs, wrenches)?;
    let mut out = BatchOutput::with_len(n, na)?;
    if shapes {
        out.shapes = std::iter::repeat_with(Vec::new).take(n).collect();
    }
    let items = chunk_items(&mut out, opts.chunk_size, na);
    let stop = AtomicBool::new(false);
    let next = AtomicUsize::new(0);
    let work = || loop {
        if stop.load(Ordering::Relaxed) {
            break;
        }
        let c = next.fetch_add(1, Ordering::Relaxed);
        if c >= items.len() {
            break;
        }
        let (c, chunk) = items[c]
            .lock()
            .expect("no panics while held")
            .take()
            .expect("each chunk once");
        let first = c * opts.chunk_size;
        if solve_chunk(robot, inputs, wrenches, opts, first, chunk, shapes).is_err() {
            stop.store(true, Ordering::Relaxed);
        }
    };
    run_workers(
        thread_count(opts.threads).min(items.len().max(1)),
        &stop,
        work,
    );
    if stop.load(Ordering::Relaxed) {
        return Err(Error::Interrupted);
    }
    Ok(out)
}

/// The number of rows of a batch, after checking every row: inputs in whole
/// rows (at most [`MAX_BATCH_ROWS`]), each valid for the robot; wrenches (if
/// given) 6 finite values per row.
fn batch_rows(robot: &Robot, inputs: &[f64], wrenches: Option<&[f64]>) -> Result<usize> {
    let na = robot.actuators.len();
    let n = if na == 0 {
        match wrenches {
            Some(w) => w.len() / 6,
            None => {
                return Err(Error::input(
                    "inputs",
                    "a robot without actuators needs wrenches to set the batch size",
                ))
            }
        }
    } else {
        if inputs.len() % na != 0 {
            return Err(Error::input(
                "inputs",
                format!(
                    "length {} is not a multiple of {na} actuators",
                    inputs.len()
                ),
            ));
        }
        inputs.len() / na
    };
    if n > MAX_BATCH_ROWS {
        return Err(Error::input(
            "inputs",
            format!(
                "{n} rows: at most {MAX_BATCH_ROWS} rows per call (use tcarod.batch.iter_batches)"
            ),
        ));
    }
    if let Some(w) = wrenches {
        if w.len() != 6 * n {
            return Err(Error::input(
                "wrenches",
                format!("expected {n} rows of 6, got {} values", w.len()),
            ));
        }
        for (k, x) in w.iter().enumerate() {
            crate::error::finite(&format!("wrenches[{}, {}]", k / 6, k % 6), *x)?;
        }
    }
    for k in 0..n {
        // a 2M-row batch takes ~0.1-0.3 s to check: stay interruptible
        if k % 4096 == 0 {
            cancel::check()?;
        }
        robot
            .check_inputs(&inputs[k * na..(k + 1) * na])
            .map_err(|e| e.renamed(|name| format!("row {k}: {name}")))?;
    }
    Ok(n)
}

/// One work item per chunk of `chunk_size` rows: its index and its disjoint
/// slices of `out`.
type ChunkItem<'a> = Mutex<Option<(usize, ChunkOut<'a>)>>;

fn chunk_items(out: &mut BatchOutput, chunk_size: usize, na: usize) -> Vec<ChunkItem<'_>> {
    let mut items = Vec::with_capacity(out.converged.len().div_ceil(chunk_size));
    let mut rest = ChunkOut::whole(out);
    while rest.rows() > 0 {
        let (chunk, r) = rest.split(chunk_size, na);
        items.push(Mutex::new(Some((items.len(), chunk))));
        rest = r;
    }
    items
}

/// Run `work` on `threads` threads (inline for one). Workers poll `stop`,
/// which the calling thread sets when its own cancel check fires (see
/// [`crate::solve::cancel`]).
fn run_workers(threads: usize, stop: &AtomicBool, work: impl Fn() + Sync) {
    if threads <= 1 {
        work();
        return;
    }
    let running = AtomicUsize::new(0);
    let flag = || stop.load(Ordering::Relaxed);
    std::thread::scope(|s| {
        for _ in 0..threads {
            running.fetch_add(1, Ordering::SeqCst);
            s.spawn(|| {
                cancel::interruptible(&flag, &work);
                running.fetch_sub(1, Ordering::SeqCst);
            });
        }
        // the calling thread polls its own cancel check for the workers
        while running.load(Ordering::SeqCst) > 0 {
            if cancel::check().is_err() {
                stop.store(true, Ordering::Relaxed);
            }
            std::thread::sleep(std::time::Duration::from_millis(5));
        }
    });
}

fn solve_chunk(
    robot: &Robot,
    inputs: &[f64],
    wrenches: Option<&[f64]>,
    opts: &BatchOptions,
    first: usize,
    mut out: ChunkOut<'_>,
    shapes: bool,
) -> Result<()> {
    let na = robot.actuators.len();
    let base = Loads::of(robot);
    let mut warm: Option<Solution> = None;
    for j in 0..out.rows() {
        let k = first + j;
        let loads = match wrenches {
            Some(w) => {
                let w = &w[k * 6..k * 6 + 6];
                Loads {
                    tip_force: Vector3::new(w[0], w[1], w[2]),
                    tip_moment: Vector3::new(w[3], w[4], w[5]),
                }
            }
            None => base,
        };
        let q = &inputs[k * na..(k + 1) * na];
        cancel::check()?;
        let start = if opts.warm { warm.as_ref() } else { None };
        match solve_loaded(robot, q, &loads, &opts.solve, start) {
            Ok(s) => {
                // a verdict that cannot be computed leaves the row without one (NaN margin)
                let verdict = match opts.stability {
                    true => stability(robot, &s, &[]).ok(),
                    false => None,
                };
                out.set(j, &s, verdict.as_ref());
                if shapes {
                    out.shapes[j] = (s.s.iter().zip(&s.positions))
                        .map(|(s, p)| [*s, p.x, p.y, p.z])
                        .collect();
                }
                warm = Some(s);
            }
            Err(Error::Interrupted) => return Err(Error::Interrupted),
            Err(e) => {
                out.set_failed(j, &e);
                warm = None;
            }
        }
    }
    Ok(())
}
