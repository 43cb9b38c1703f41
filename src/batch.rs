//! Many forward solves in one call: rows of actuator inputs (and optionally
//! tip loads), split into fixed chunks that are solved in parallel across
//! threads, each chunk in order with warm starts along it.
//!
//! The chunking is fixed by `chunk_size` alone (not by the thread count), and
//! a warm-start chain restarts at every chunk, so the results do not depend
//! on the number of threads or on how chunks are spread over machines.

use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};

use nalgebra::Vector3;

use crate::error::{Error, Result};
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
    opts.solve.validate()?;
    let na = robot.actuators.len();
    if opts.chunk_size == 0 {
        return Err(Error::param("chunk_size", 0.0, ">= 1"));
    }
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
    let mut out = BatchOutput::with_len(n, na);
    let cs = opts.chunk_size;
    let n_chunks = n.div_ceil(cs);
    // the tensions of each chunk (empty slices without actuators)
    let tensions: Vec<&mut [f64]> = if na == 0 {
        (0..n_chunks).map(|_| Default::default()).collect()
    } else {
        out.tensions.chunks_mut(cs * na).collect()
    };
    // One work item per chunk: its index and its disjoint slices of the output.
    let items: Vec<std::sync::Mutex<Option<(usize, ChunkOut<'_>)>>> = out
        .tip_positions
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
            std::sync::Mutex::new(Some((c, chunk)))
        })
        .collect();
    let next = AtomicUsize::new(0);
    // cancellation: workers poll `stop` (set by whoever sees the caller's
    // cancel check fire, see `crate::solve::cancel`)
    let stop = AtomicBool::new(false);
    let running = AtomicUsize::new(0);
    let work = || loop {
        if stop.load(Ordering::Relaxed) {
            break;
        }
        let c = next.fetch_add(1, Ordering::Relaxed);
        if c >= n_chunks {
            break;
        }
        let (c, chunk) = items[c]
            .lock()
            .expect("no panics while held")
            .take()
            .expect("each chunk once");
        if solve_chunk(robot, inputs, wrenches, opts, c * cs, chunk).is_err() {
            stop.store(true, Ordering::Relaxed);
        }
    };
    let threads = thread_count(opts.threads).min(n_chunks.max(1));
    if threads <= 1 {
        work();
    } else {
        let flag = || stop.load(Ordering::Relaxed);
        std::thread::scope(|s| {
            for _ in 0..threads {
                running.fetch_add(1, Ordering::SeqCst);
                s.spawn(|| {
                    cancel::interruptible(&flag, work);
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
    if stop.load(Ordering::Relaxed) {
        return Err(Error::Interrupted);
    }
    Ok(out)
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
