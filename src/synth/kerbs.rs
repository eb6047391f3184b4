//! Kerbs in 3-D. A road-edge boundary styled [`Pattern::Curb`] is the foot of a kerb's
//! inner face: everything beyond it on that side (the kerbstone, [`CURB_WIDTH_M`] wide, then
//! the pavement) is raised by h_k = [`MarkingConfig::curb_height_m`] above the road surface.
//!
//! A camera ray that met the ground z = C_V x^2 / 2 at P_0 = C + t_0 r, beyond a face (its
//! lateral offset d_0 past the face's d_f), met the raised surface z = h_k + C_V x^2 / 2 at
//! P_1 = C + t_1 r first. If P_1 is past the face too, P_1 is the hit: the ray is above h_k
//! for every t < t_1, so nothing raised can be hit earlier. Otherwise the ray went down the
//! face between the two points, at
//!
//! ```text
//! t_f = t_1 + (t_0 - t_1) (d_f - d_1) / (d_0 - d_1)
//! ```
//!
//! (d is linear in t over the few metres from P_1 to P_0 up to the road's curvature: well
//! under a millimetre on a 100 m radius). Rays that cross a kerb and come back down onto the
//! road (a chord through the inside of a sharp bend) and vehicles standing on a pavement are
//! not modelled.
//!
//! [`Pattern::Curb`]: super::markings::Pattern::Curb
//! [`MarkingConfig::curb_height_m`]: super::markings::MarkingConfig::curb_height_m

use super::markings::{MarkingConfig, Pattern, CURB_WIDTH_M};
use super::render::FrameGeometry;
use super::road::Road;

/// Which part of the scene's surface a road ray ends on.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Surface {
    /// Vehicle-frame position, metres.
    pub x: f64,
    /// Vehicle-frame position, metres.
    pub y: f64,
    /// Distance along the optical axis, metres.
    pub depth: f64,
    /// Road coordinates.
    pub s: f64,
    /// Road coordinates.
    pub d: f64,
    /// Height above the road surface, metres (0 on the road, h_k on a kerb or pavement).
    pub height: f64,
    /// Whether this is a kerb's vertical face.
    pub face: bool,
}

impl Surface {
    /// The ground point `ground` (vehicle-frame x, y and depth) at road coordinates (s, d).
    pub(super) fn ground(ground: [f64; 3], s: f64, d: f64) -> Self {
        Self {
            x: ground[0],
            y: ground[1],
            depth: ground[2],
            s,
            d,
            height: 0.0,
            face: false,
        }
    }
}

/// The lateral offsets of the kerb faces at `s`: the left one (raised where d > face) and the
/// right one (raised where d < face), `None` where that road edge is not a kerb.
pub(super) fn faces(markings: &MarkingConfig, road: &Road, s: f64) -> [Option<f64>; 2] {
    let lanes = road.lanes();
    let Some(first) = (0..lanes).find(|&i| road.lane_exists(i, s)) else {
        return [None, None];
    };
    let last = (0..lanes)
        .rev()
        .find(|&i| road.lane_exists(i, s))
        .unwrap_or(first);
    let kerb = |k: usize| {
        markings
            .style(road, k, s)
            .is_some_and(|st| st.pattern == Pattern::Curb)
            .then(|| road.boundary_offset(k, s))
    };
    [kerb(first), kerb(last + 1)]
}

/// How far `d` is past a kerb face (positive: raised; negative: on the road side), and the
/// face's offset: the face `d` is past, else the nearer face, else the only one; `None`
/// without kerbs.
fn past_face(faces: [Option<f64>; 2], d: f64) -> Option<(f64, f64)> {
    match faces {
        [Some(f), _] if d > f => Some((d - f, f)),
        [_, Some(f)] if d < f => Some((f - d, f)),
        [Some(f), Some(g)] => {
            // Between the faces: the nearer one.
            Some(if f - d < d - g {
                (d - f, f)
            } else {
                (g - d, g)
            })
        }
        [Some(f), None] => Some((d - f, f)),
        [None, Some(g)] => Some((g - d, g)),
        [None, None] => None,
    }
}

/// The surface a road ray of normalised direction (`xn`, `yn`) ends on in a scene with kerbs,
/// given where it met the ground: `ground` (vehicle-frame x, y and depth) at road coordinates
/// (`s`, `d`).
#[allow(clippy::too_many_arguments)]
pub(super) fn surface(
    geo: &FrameGeometry,
    markings: &MarkingConfig,
    road: &Road,
    xn: f64,
    yn: f64,
    ground: [f64; 3],
    s: f64,
    d: f64,
) -> Surface {
    let on_ground = Surface::ground(ground, s, d);
    let height = markings.curb_height_m;
    if height <= 0.0 {
        return on_ground;
    }
    let Some((past, _)) = past_face(faces(markings, road, s), d) else {
        return on_ground;
    };
    if past <= 0.0 {
        return on_ground;
    }
    let Some([x1, y1, t1]) = geo.cast_surface(xn, yn, height) else {
        return on_ground;
    };
    let (s1, d1) = geo.locate(x1, y1, s);
    let Some((past1, face)) = past_face(faces(markings, road, s1), d1) else {
        return on_ground;
    };
    if past1 >= 0.0 {
        return Surface {
            x: x1,
            y: y1,
            depth: t1,
            s: s1,
            d: d1,
            height,
            face: false,
        };
    }
    // Down the face, between P_1 and P_0.
    let k = ((face - d1) / (d - d1)).clamp(0.0, 1.0);
    let t = t1 + (ground[2] - t1) * k;
    let [x, y, z] = geo.point_at(xn, yn, t);
    Surface {
        x,
        y,
        depth: t,
        s: s1 + (s - s1) * k,
        d: face,
        height: crate::math::clamp(z - geo.surface_height(x), 0.0, height),
        face: true,
    }
}

/// What of a kerb (`s`, `d`) is on: the kerbstone's top, the pavement behind it, or neither.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Raised {
    /// Not raised: the road or an unkerbed verge.
    No,
    /// The kerbstone's top, [`CURB_WIDTH_M`] wide.
    Kerbstone,
    /// The pavement behind it.
    Pavement,
}

/// Which raised part, if any, (`s`, `d`) is on.
pub(super) fn raised(markings: &MarkingConfig, road: &Road, s: f64, d: f64) -> Raised {
    match past_face(faces(markings, road, s), d) {
        Some((past, _)) if past > CURB_WIDTH_M => Raised::Pavement,
        Some((past, _)) if past >= 0.0 => Raised::Kerbstone,
        _ => Raised::No,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::synth::render::Hit;
    use crate::synth::{default_camera, scenario, Eye, Scene};

    /// Renders `urban` (kerbs on both sides) with depth and rebuilds every road pixel's 3-D
    /// point from it: the depth must put pixels past a face on the raised surface, pixels
    /// before it on the road, and show each face as a vertical strip standing on its line.
    #[test]
    fn kerbs_and_pavements_stand_at_the_kerb_height_in_the_depth_map() {
        let (w, h) = (320, 240);
        let camera = default_camera(w, h).unwrap();
        let mut scene = Scene::new(scenario("urban").unwrap(), camera.clone(), 1).unwrap();
        let markings = scene.config().markings.clone();
        let hk = markings.curb_height_m;
        assert!(hk > 0.1);
        let (mut rgba, mut depth) = (vec![0; w * h * 4], vec![0.0; w * h]);
        let pose = scene
            .render(30, Eye::Left, &mut rgba, Some(&mut depth))
            .unwrap();
        let mut table = Vec::new();
        let geo = FrameGeometry::new(
            scene.config(),
            scene.road(),
            scene.camera(),
            pose,
            0.0,
            &mut table,
        )
        .unwrap();
        let (mut road, mut raised, mut face, mut face_rows) = (0, 0, 0, [0usize; 2]);
        let mut face_luma = 0.0;
        let mut top_luma = (0.0, 0);
        for v in 0..h {
            let mut sides = [false; 2];
            for u in 0..w {
                let t = depth[v * w + u] as f64;
                if t <= 0.0 {
                    continue;
                }
                let [xn, yn] = camera.pixel_to_normalised(u as f64, v as f64).unwrap();
                let [x, y, z] = geo.point_at(xn, yn, t);
                if x > 25.0 || matches!(geo.cast(xn, yn), Hit::Vehicle { .. }) {
                    continue; // far away, or a parked car
                }
                let (s, d) = geo.locate(x, y, pose.s);
                let Some((past, f)) = past_face(faces(&markings, scene.road(), s), d) else {
                    panic!("urban has kerbs on both sides");
                };
                let luma = rgba[(v * w + u) * 4 + 1] as f64;
                if past > 0.02 {
                    assert!(
                        (z - hk).abs() < 0.005,
                        "({u}, {v}) past the face at z = {z}"
                    );
                    raised += 1;
                    if past > 0.05 && past < CURB_WIDTH_M - 0.05 {
                        top_luma = (top_luma.0 + luma, top_luma.1 + 1);
                    }
                } else if past < -0.02 {
                    assert!(z.abs() < 0.005, "({u}, {v}) on the road at z = {z}");
                    road += 1;
                } else if z > 0.01 && z < hk - 0.01 {
                    assert!(
                        (d - f).abs() < 0.01,
                        "({u}, {v}) on a face at d = {d}, face {f}"
                    );
                    face += 1;
                    face_luma += luma;
                    sides[usize::from(d < 0.0)] = true;
                }
            }
            for k in 0..2 {
                face_rows[k] += usize::from(sides[k]);
            }
        }
        assert!(
            road > 5_000 && raised > 2_000,
            "road {road}, raised {raised}"
        );
        // Both faces are seen over many rows, and darker than the kerbstone's top.
        assert!(face_rows[0] > 20 && face_rows[1] > 20, "{face_rows:?}");
        let (face_luma, top_luma) = (face_luma / face as f64, top_luma.0 / top_luma.1 as f64);
        assert!(face_luma + 20.0 < top_luma, "{face_luma} vs {top_luma}");
    }

    #[test]
    fn the_face_on_a_points_side_decides() {
        // Kerbs at d = 5 (left) and d = -2 (right).
        let both = [Some(5.0), Some(-2.0)];
        assert_eq!(past_face(both, 5.5), Some((0.5, 5.0)));
        assert_eq!(past_face(both, -2.25), Some((0.25, -2.0)));
        // On the road: negative distances to the nearer face.
        assert_eq!(past_face(both, 4.0), Some((-1.0, 5.0)));
        assert_eq!(past_face(both, -1.0), Some((-1.0, -2.0)));
        // One kerb only: always measured against it.
        assert_eq!(past_face([None, Some(-2.0)], 3.0), Some((-5.0, -2.0)));
        assert_eq!(past_face([Some(5.0), None], 7.0), Some((2.0, 5.0)));
        assert_eq!(past_face([None, None], 0.0), None);
    }
}
