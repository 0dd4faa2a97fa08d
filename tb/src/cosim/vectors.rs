//! The regression vectors' transactions as co-simulation stimulus: each unit with vectors
//! (`golden/vectors/`, [`crate::vectors`]) and a twin, in the configuration its vectors were
//! made in, driven with their inputs one transaction per cycle, after reset and followed by
//! idle cycles until the last result has left the pipeline. The RTL then meets exactly the
//! transactions whose outputs the bit-accuracy regression pins.

use super::{BlendAdjustCosim, MipmapCosim, PipelineCosim};
use crate::vectors::{mipmap_frame, mipmap_params, normal_samples, MIPMAP_SCANS, NORMAL_GROUPS};
use units::bump::blend_adjust_153::BlendAdjustParams;
use units::bump::params::BumpParams;
use verif::cosim::{Directed, RESET_CYCLES};

/// Idle cycles after the last transaction: longer than any twin's latency.
const DRAIN: usize = 16;

/// `rows` of `width` inputs, after reset and before the drain (both all zero: not valid).
fn framed(width: usize, rows: impl IntoIterator<Item = Vec<u64>>) -> Vec<Vec<u64>> {
    let idle = || vec![0; width];
    let mut v: Vec<Vec<u64>> = (0..RESET_CYCLES).map(|_| idle()).collect();
    v.extend(rows);
    v.extend((0..DRAIN).map(|_| idle()));
    v
}

/// Unit 153, F = 8, combinational: every `u` in both modes (the vectors' inputs).
pub fn blend_adjust() -> Directed {
    let v = crate::vectors::blend_adjust();
    let rows = v.rows.iter().map(|(i, _)| vec![1, i[0], i[1], i[2]]);
    Directed {
        label: "vectors".into(),
        unit: Box::new(BlendAdjustCosim(BlendAdjustParams {
            frac_bits: 8,
            registered: false,
        })),
        stimulus: framed(4, rows),
    }
}

/// The FIG. 7 pipeline on each built-in map of the vectors, its 128 samples back to back.
pub fn pipeline() -> Result<Vec<Directed>, String> {
    NORMAL_GROUPS
        .iter()
        .map(|&(filter, map)| {
            let params = BumpParams {
                filter,
                ..BumpParams::default()
            };
            let m = crate::maps::builtin(map, 16, 16, params.texel_fmt())?;
            let pw = params.pos_fmt().width();
            let mask = |x: i64| (x as u64) & (u64::MAX >> (64 - pw));
            let rows = normal_samples()
                .iter()
                .map(|s| {
                    let r = crate::runs::normals::quantise(&params, s)?;
                    Ok(vec![1, mask(r.u), mask(r.v), r.scale, r.lod])
                })
                .collect::<Result<Vec<_>, String>>()?;
            Ok(Directed {
                label: format!("vectors-{filter}-{map}"),
                unit: Box::new(PipelineCosim { params, map: m }),
                stimulus: framed(5, rows),
            })
        })
        .collect()
}

/// The mipmap generator on the vectors' 16x8 frame, interlaced and progressive.
pub fn mipmap() -> Vec<Directed> {
    let frame = mipmap_frame();
    MIPMAP_SCANS
        .iter()
        .map(|&scan| {
            let params = mipmap_params(scan);
            let rows = crate::runs::mipmap::video_stream(&params, &frame)
                .into_iter()
                .map(|t| vec![1, u64::from(t.texel), u64::from(t.sof)]);
            Directed {
                label: format!("vectors-{scan:?}").to_lowercase(),
                unit: Box::new(MipmapCosim::new(params)),
                stimulus: framed(3, rows),
            }
        })
        .collect()
}
