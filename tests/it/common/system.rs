//! Checks on a system of lines: its scene's refusals and its 6×6
//! stiffness (docs/theory.md §17.3).

use riser::math::{M6, V3};
use riser::scene::SceneError;
use riser::scene::system::SystemScene;
use riser::sim::system::{SystemStatics, perturbed_pose};

/// −∂(F, M)/∂(pose) by central differences of `solve` (the system's
/// statics at a pose): ±h m in translation and ±h_r rad of global rotation
/// vector about `pose`.
pub fn finite_difference_stiffness(pose: &[f64; 6], h: f64, hr: f64, solve: impl Fn(&[f64; 6]) -> SystemStatics) -> M6 {
    let mut k = M6::zeros();
    for j in 0..6 {
        let e = |s: f64| {
            let (mut du, mut dth) = (V3::zeros(), V3::zeros());
            if j < 3 {
                du[j] = s * h;
            } else {
                dth[j - 3] = s * hr;
            }
            let st = solve(&perturbed_pose(pose, du, dth));
            [st.force.x, st.force.y, st.force.z, st.moment.x, st.moment.y, st.moment.z]
        };
        let (p, m) = (e(1.0), e(-1.0));
        let step = if j < 3 { h } else { hr };
        for i in 0..6 {
            k[(i, j)] = -(p[i] - m[i]) / (2.0 * step);
        }
    }
    k
}

/// The largest error of each 3×3 block relative to the block's largest entry.
pub fn block_errors(k: &M6, fd: &M6) -> [f64; 4] {
    let mut out = [0.0; 4];
    for (b, (r, c)) in [(0, 0), (0, 3), (3, 0), (3, 3)].into_iter().enumerate() {
        let kb = k.fixed_view::<3, 3>(r, c);
        let fb = fd.fixed_view::<3, 3>(r, c);
        out[b] = (kb - fb).amax() / kb.amax().max(fb.amax());
    }
    out
}

/// The (field, message) pairs a system scene `text` is refused with
/// (panics if it is accepted or fails otherwise).
pub fn invalid(text: &str) -> Vec<(String, String)> {
    match SystemScene::from_toml(text, "test") {
        Err(SceneError::Invalid(es)) => es.into_iter().map(|e| (e.field, e.message)).collect(),
        other => panic!("expected invalid, got {other:?}"),
    }
}

/// Whether `errs` refuses `field` with a message containing `words`.
pub fn has(errs: &[(String, String)], field: &str, words: &str) -> bool {
    errs.iter().any(|(f, m)| f == field && m.contains(words))
}
