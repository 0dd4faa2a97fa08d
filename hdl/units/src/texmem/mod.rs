//! The texture memory path of Schilling & Knittel's Figure 6, the low-cost texture mapping
//! unit 602, one file per unit: DRAM 604, control unit 607, CCC decode 608/610/612, cache 614,
//! colour extract 618, bilinear interpolator 622; the texture layouts in DRAM; the unit 602
//! that wires them.

pub mod bilinear_622;
pub mod cache_614;
pub mod ccc_decode_608;
pub mod control_607;
pub mod dram_604;
pub mod extract_618;
pub mod layout;
pub mod texture_unit_602;
