//! The paper's experiments (Section V) as test problems, shared by the unit
//! tests and the criterion benches. The Python package's
//! `tcarod.experiments` holds the same fixtures with their published data.

use crate::material::Material;
use crate::tca::{Chirality, Tca};

/// Fig. 5 TCA, `threads` = 3 or 4 (NOTES.md section 1: `l` and `L` swapped in
/// the paper's text; `L = 110 mm` coiled, `l = 497 / 471 mm` fibre).
pub fn fig5_tca(threads: u32) -> Tca {
    let (l, turns, d) = match threads {
        3 => (0.497, 300.0, 2.0e-3),
        4 => (0.471, 259.0, 2.13e-3),
        _ => panic!("Fig. 5 has three- and four-thread TCAs only"),
    };
    Tca::new(l, 0.110, d, turns, Chirality::Extension, Material::silver_coated_nylon())
        .expect("Fig. 5 TCA is valid")
}
