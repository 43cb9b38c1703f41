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
use crate::shooting::{solve_tip, Loads, SolveOptions, TipSolution};
use crate::solve::cancel;

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
}

impl Default for BatchOptions {
    fn default() -> Self {
        BatchOptions {
            solve: SolveOptions::default(),
            chunk_size: 256,
            threads: 0,
            warm: true,
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
    /// Newton iterations of each solve.
    pub iterations: Vec<u32>,
    /// IVPs integrated by each solve.
    pub evaluations: Vec<u32>,
    /// Whether each solve converged.
    pub converged: Vec<bool>,
}

impl BatchOutput {
    fn with_len(n: usize, n_actuators: usize) -> Self {
        BatchOutput {
            tip_positions: vec![[f64::NAN; 3]; n],
            tip_rotations: vec![[f64::NAN; 9]; n],
            tensions: vec![f64::NAN; n * n_actuators],
            iterations: vec![0; n],
            evaluations: vec![0; n],
            converged: vec![false; n],
        }
    }
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
    robot.validate()?;
    opts.validate()?;
    let na = robot.actuators.len();
    let n = batch_rows(robot, inputs, wrenches)?;
    let mut out = BatchOutput::with_len(n, na);
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
        if solve_chunk(robot, inputs, wrenches, opts, first, chunk).is_err() {
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
    let cs = chunk_size;
    let n_chunks = out.converged.len().div_ceil(cs);
    // the tensions of each chunk (empty slices without actuators)
    let tensions: Vec<&mut [f64]> = if na == 0 {
        (0..n_chunks).map(|_| Default::default()).collect()
    } else {
        out.tensions.chunks_mut(cs * na).collect()
    };
    out.tip_positions
        .chunks_mut(cs)
        .zip(out.tip_rotations.chunks_mut(cs))
        .zip(tensions)
        .zip(out.iterations.chunks_mut(cs))
        .zip(out.evaluations.chunks_mut(cs))
        .zip(out.converged.chunks_mut(cs))
        .enumerate()
        .map(|(c, (((((pos, rot), tensions), iters), evals), ok))| {
            let chunk = ChunkOut {
                pos,
                rot,
                tensions,
                iters,
                evals,
                ok,
            };
            Mutex::new(Some((c, chunk)))
        })
        .collect()
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
    out: ChunkOut<'_>,
) -> Result<()> {
    let ChunkOut {
        pos,
        rot,
        tensions,
        iters,
        evals,
        ok,
    } = out;
    let na = robot.actuators.len();
    let base = Loads::of(robot);
    let mut warm: Option<TipSolution> = None;
    for j in 0..pos.len() {
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
        match solve_tip(
            robot,
            q,
            &loads,
            &opts.solve,
            if opts.warm { warm.as_ref() } else { None },
        ) {
            Ok(s) => {
                pos[j] = [s.position.x, s.position.y, s.position.z];
                for a in 0..3 {
                    for b in 0..3 {
                        rot[j][3 * a + b] = s.rotation[(a, b)];
                    }
                }
                tensions[j * na..(j + 1) * na].copy_from_slice(&s.tensions);
                iters[j] = s.iterations as u32;
                evals[j] = s.evaluations as u32;
                ok[j] = true;
                warm = Some(s);
            }
            Err(Error::Interrupted) => return Err(Error::Interrupted),
            Err(_) => {
                warm = None;
            }
        }
    }
    Ok(())
}
