//! The scene renderer: ray casting through the project's own camera model.
//!
//! For every pixel the undistorted viewing direction n = (x_n, y_n, 1) (camera frame) is
//! computed once; per frame it is rotated into the vehicle frame, r = R^T n, with the camera
//! of that frame (calibrated pitch and height plus the body oscillation of the pose). The
//! ray C + t r, C = (0, 0, h) (shifted by the baseline along the camera's X axis for the right
//! camera of a stereo pair), meets the road surface z = C_V x^2 / 2 (Danescu eq. 4 in the
//! vehicle frame) where
//!
//! ```text
//! (C_V r_x^2 / 2) t^2 - r_z t - h = 0     (smallest positive root; t = h / -r_z when C_V = 0)
//! ```
//!
//! and t is also the hit's depth Z along the optical axis (n has unit Z), so the exact
//! disparity of a left pixel is f_x B / t. Vehicles are boxes tested with the slab method and
//! win when nearer. A road hit (X, Y) becomes road coordinates (s, d) by Newton steps on a
//! per-frame table of the reference line in the vehicle frame (every 0.5 m, linear
//! interpolation: < 0.4 mm off on a 100 m radius), seeded with the neighbouring pixel's s.
//! The pixel's footprint on the road anti-aliases the markings: along the road
//! f_s = X^2 / (f_y h) (one image row), across f_d = X / f_x + |Y / X| f_s (one column, plus
//! the lateral drift of a row step on rays that converge to the vanishing point). Appearance effects follow in [`super::appearance`].

use super::appearance::value_noise;
use super::ego::Pose;
use super::kerbs::Raised;
use super::road::Road;
use super::scene::{SceneConfig, Shadow};
use crate::camera::Camera;
use crate::error::Result;
use crate::math;

/// Farthest road distance rendered, metres (beyond: haze at the horizon).
pub const MAX_RANGE_M: f64 = 300.0;
const TABLE_STEP: f64 = 0.5;
const TABLE_BEHIND: f64 = 10.0;

/// One reference-line sample in the vehicle frame.
#[derive(Debug, Clone, Copy, Default)]
pub(super) struct LocalSample {
    x: f64,
    y: f64,
    c: f64,
    s: f64,
    curvature: f64,
}

/// A vehicle box in the vehicle frame.
#[derive(Debug, Clone, Copy)]
struct BoxNow {
    centre: [f64; 3],
    cos: f64,
    sin: f64,
    half: [f64; 3],
    rgb: [f32; 3],
    /// Bounds of the box's image in normalised coordinates [x_min, x_max, y_min, y_max]
    /// (rays outside cannot hit it; infinite when the box reaches behind the camera).
    bounds: [f64; 4],
}

/// What a camera ray hit.
#[derive(Debug, Clone, Copy)]
pub(super) enum Hit {
    Sky,
    Road {
        x: f64,
        y: f64,
        depth: f64,
    },
    Vehicle {
        index: usize,
        local: [f64; 3],
        normal: usize,
        depth: f64,
    },
}

/// Per-frame state of the renderer, built before the pixel loop.
pub(super) struct FrameGeometry {
    /// Rotation road->camera (rows: camera axes in the vehicle frame).
    rt: [[f64; 3]; 3],
    origin: [f64; 3],
    table: Vec<LocalSample>,
    table_s0: f64,
    boxes: Vec<BoxNow>,
    c_v: f64,
}

impl FrameGeometry {
    /// Builds the frame's camera rotation, reference-line table and vehicle boxes.
    pub(super) fn new(
        config: &SceneConfig,
        road: &Road,
        camera: &Camera,
        pose: Pose,
        baseline: f64,
        table: &mut Vec<LocalSample>,
    ) -> Result<Self> {
        let mut file = camera.to_file();
        file.pitch_deg += math::rad_to_deg(pose.pitch_offset);
        file.height_m += pose.height_offset;
        let cam = Camera::from_file(&file)?;
        let r = cam.rotation();
        let rt = [
            [r[(0, 0)], r[(0, 1)], r[(0, 2)]],
            [r[(1, 0)], r[(1, 1)], r[(1, 2)]],
            [r[(2, 0)], r[(2, 1)], r[(2, 2)]],
        ];
        // Camera X axis in the vehicle frame is the first row of R.
        let origin = [
            baseline * rt[0][0],
            baseline * rt[0][1],
            file.height_m + baseline * rt[0][2],
        ];
        let (ch, sh) = (math::cos(pose.heading), math::sin(pose.heading));
        let to_vehicle = |p: [f64; 2]| {
            let (dx, dy) = (p[0] - pose.position[0], p[1] - pose.position[1]);
            [dx * ch + dy * sh, -dx * sh + dy * ch]
        };
        table.clear();
        let s0 = pose.s - TABLE_BEHIND;
        let n = ((MAX_RANGE_M * 1.3 + TABLE_BEHIND) / TABLE_STEP) as usize;
        for i in 0..=n {
            let s = s0 + i as f64 * TABLE_STEP;
            let a = road.at(s);
            let [x, y] = to_vehicle([a.x, a.y]);
            let rel = a.heading - pose.heading;
            table.push(LocalSample {
                x,
                y,
                c: math::cos(rel),
                s: math::sin(rel),
                curvature: a.curvature,
            });
        }
        let boxes: Vec<BoxNow> = config
            .vehicles
            .iter()
            .map(|v| {
                let s_mid = v.start_s + v.speed_mps * pose.t + v.size_m[0] / 2.0;
                let d = road.lane_centre(v.lane, s_mid) + v.offset_m;
                let [x, y] = to_vehicle(road.point(s_mid, d));
                let rel = road.at(s_mid).heading - pose.heading;
                let z = config.vertical.curvature * x * x / 2.0;
                BoxNow {
                    centre: [x, y, z + v.size_m[2] / 2.0],
                    cos: math::cos(rel),
                    sin: math::sin(rel),
                    half: [v.size_m[0] / 2.0, v.size_m[1] / 2.0, v.size_m[2] / 2.0],
                    rgb: [v.rgb[0] as f32, v.rgb[1] as f32, v.rgb[2] as f32],
                    bounds: [
                        f64::NEG_INFINITY,
                        f64::INFINITY,
                        f64::NEG_INFINITY,
                        f64::INFINITY,
                    ],
                }
            })
            .collect();
        let mut boxes: Vec<BoxNow> = boxes;
        for b in &mut boxes {
            b.bounds = image_bounds(b, &rt, origin);
        }
        Ok(Self {
            rt,
            origin,
            table: std::mem::take(table),
            table_s0: s0,
            boxes,
            c_v: config.vertical.curvature,
        })
    }

    /// Gives the table buffer back for reuse.
    pub(super) fn into_table(self) -> Vec<LocalSample> {
        self.table
    }

    /// The vehicle-frame direction r = R^T n of the ray of normalised direction (x_n, y_n, 1).
    fn direction(&self, xn: f64, yn: f64) -> [f64; 3] {
        let rt = &self.rt;
        [
            rt[0][0] * xn + rt[1][0] * yn + rt[2][0],
            rt[0][1] * xn + rt[1][1] * yn + rt[2][1],
            rt[0][2] * xn + rt[1][2] * yn + rt[2][2],
        ]
    }

    /// The vehicle-frame point C + t r of the ray (x_n, y_n, 1).
    pub(super) fn point_at(&self, xn: f64, yn: f64, t: f64) -> [f64; 3] {
        let (o, r) = (self.origin, self.direction(xn, yn));
        [o[0] + t * r[0], o[1] + t * r[1], o[2] + t * r[2]]
    }

    /// Height of the road surface at `x` ahead (the vertical curve z = C_V x^2 / 2).
    pub(super) fn surface_height(&self, x: f64) -> f64 {
        self.c_v * x * x / 2.0
    }

    /// Where the ray (x_n, y_n, 1) meets the road surface raised by `height`: vehicle-frame
    /// x, y and the depth t; `None` when it does not (or beyond the rendered range).
    pub(super) fn cast_surface(&self, xn: f64, yn: f64, height: f64) -> Option<[f64; 3]> {
        let (o, r) = (self.origin, self.direction(xn, yn));
        let t = road_hit([o[0], o[1], o[2] - height], r, self.c_v)?;
        let x = o[0] + t * r[0];
        (x <= MAX_RANGE_M).then(|| [x, o[1] + t * r[1], t])
    }

    /// Casts the ray of normalised direction (x_n, y_n, 1).
    pub(super) fn cast(&self, xn: f64, yn: f64) -> Hit {
        let r = self.direction(xn, yn);
        let o = self.origin;
        let mut best = match road_hit(o, r, self.c_v) {
            Some(t) if o[0] + t * r[0] <= MAX_RANGE_M => Hit::Road {
                x: o[0] + t * r[0],
                y: o[1] + t * r[1],
                depth: t,
            },
            _ => Hit::Sky,
        };
        let mut nearest = match best {
            Hit::Road { depth, .. } => depth,
            _ => f64::INFINITY,
        };
        for (index, b) in self.boxes.iter().enumerate() {
            let [x0, x1, y0, y1] = b.bounds;
            if xn < x0 || xn > x1 || yn < y0 || yn > y1 {
                continue;
            }
            if let Some((t, local, normal)) = box_hit(b, o, r) {
                if t < nearest {
                    nearest = t;
                    best = Hit::Vehicle {
                        index,
                        local,
                        normal,
                        depth: t,
                    };
                }
            }
        }
        best
    }

    /// Road coordinates (s, d) of the vehicle-frame road point (x, y), Newton from `s_guess`.
    pub(super) fn locate(&self, x: f64, y: f64, s_guess: f64) -> (f64, f64) {
        let mut s = s_guess;
        let mut across = 0.0;
        let last = self.table.len() - 2;
        for _ in 0..4 {
            let k = crate::math::clamp((s - self.table_s0) / TABLE_STEP, 0.0, last as f64);
            let i = (k as usize).min(last);
            let f = k - i as f64;
            let (a, b) = (self.table[i], self.table[i + 1]);
            let lerp = |p: f64, q: f64| p + (q - p) * f;
            let (px, py, c, sn) = (
                lerp(a.x, b.x),
                lerp(a.y, b.y),
                lerp(a.c, b.c),
                lerp(a.s, b.s),
            );
            let (dx, dy) = (x - px, y - py);
            let along = dx * c + dy * sn;
            across = -dx * sn + dy * c;
            s += along / (1.0 - a.curvature * across).max(0.1);
            if along.abs() < 1e-4 {
                break;
            }
        }
        (s, across)
    }

    /// The vehicle box `index` (for shading): colour and half sizes.
    pub(super) fn vehicle(&self, index: usize) -> ([f32; 3], [f64; 3]) {
        (self.boxes[index].rgb, self.boxes[index].half)
    }

    /// Whether the road point (x, y) (vehicle frame) lies under a vehicle's shadow.
    pub(super) fn under_vehicle(&self, x: f64, y: f64) -> f32 {
        let mut light = 1.0f32;
        for b in &self.boxes {
            let (dx, dy) = (x - b.centre[0], y - b.centre[1]);
            let (lx, ly) = (dx * b.cos + dy * b.sin, -dx * b.sin + dy * b.cos);
            // A soft shadow 0.25 m wider than the car, strongest underneath.
            let ex = (lx.abs() - b.half[0] - 0.1).max(0.0);
            let ey = (ly.abs() - b.half[1] - 0.1).max(0.0);
            let dist = (ex * ex + ey * ey).sqrt();
            if dist < 0.3 {
                light = light.min(0.35 + (dist / 0.3) as f32 * 0.65);
            }
        }
        light
    }
}

/// The normalised image bounds of a box seen from `origin` with rotation `rt` (rows: camera
/// axes in the vehicle frame); unbounded when a corner is not in front of the camera.
fn image_bounds(b: &BoxNow, rt: &[[f64; 3]; 3], origin: [f64; 3]) -> [f64; 4] {
    let mut out = [
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::INFINITY,
        f64::NEG_INFINITY,
    ];
    for corner in 0..8 {
        let sign = |bit: usize| if corner >> bit & 1 == 1 { 1.0 } else { -1.0 };
        let (lx, ly, lz) = (
            sign(0) * b.half[0],
            sign(1) * b.half[1],
            sign(2) * b.half[2],
        );
        let p = [
            b.centre[0] + lx * b.cos - ly * b.sin - origin[0],
            b.centre[1] + lx * b.sin + ly * b.cos - origin[1],
            b.centre[2] + lz - origin[2],
        ];
        let cam = |row: &[f64; 3]| row[0] * p[0] + row[1] * p[1] + row[2] * p[2];
        let (x, y, z) = (cam(&rt[0]), cam(&rt[1]), cam(&rt[2]));
        if z <= 1e-6 {
            return [
                f64::NEG_INFINITY,
                f64::INFINITY,
                f64::NEG_INFINITY,
                f64::INFINITY,
            ];
        }
        out = [
            out[0].min(x / z),
            out[1].max(x / z),
            out[2].min(y / z),
            out[3].max(y / z),
        ];
    }
    // A small margin for rounding.
    [out[0] - 1e-6, out[1] + 1e-6, out[2] - 1e-6, out[3] + 1e-6]
}

/// Smallest positive t with C + t r on the surface z = c_v x^2 / 2.
fn road_hit(o: [f64; 3], r: [f64; 3], c_v: f64) -> Option<f64> {
    // (o_z + t r_z) = c_v (o_x + t r_x)^2 / 2.
    let a = c_v * r[0] * r[0] / 2.0;
    let b = c_v * o[0] * r[0] - r[2];
    let c = c_v * o[0] * o[0] / 2.0 - o[2];
    if a.abs() < 1e-15 {
        return (b > 1e-12).then(|| -c / b);
    }
    let disc = b * b - 4.0 * a * c;
    if disc < 0.0 {
        return None;
    }
    let sq = disc.sqrt();
    // Numerically stable roots.
    let q = -0.5 * (b + b.signum() * sq);
    let (t1, t2) = (q / a, if q != 0.0 { c / q } else { f64::INFINITY });
    [t1, t2]
        .into_iter()
        .filter(|t| *t > 1e-9)
        .fold(None, |m: Option<f64>, t| Some(m.map_or(t, |m| m.min(t))))
}

/// Slab test of the ray against a box: distance, hit point in box coordinates, and which face
/// (0: x, 1: y, 2: z) it entered through.
fn box_hit(b: &BoxNow, o: [f64; 3], r: [f64; 3]) -> Option<(f64, [f64; 3], usize)> {
    let d = [o[0] - b.centre[0], o[1] - b.centre[1], o[2] - b.centre[2]];
    let lo = [
        d[0] * b.cos + d[1] * b.sin,
        -d[0] * b.sin + d[1] * b.cos,
        d[2],
    ];
    let lr = [
        r[0] * b.cos + r[1] * b.sin,
        -r[0] * b.sin + r[1] * b.cos,
        r[2],
    ];
    let (mut t0, mut t1, mut face) = (0.0f64, f64::INFINITY, 0usize);
    for k in 0..3 {
        if lr[k].abs() < 1e-12 {
            if lo[k].abs() > b.half[k] {
                return None;
            }
            continue;
        }
        let (mut a, mut c) = ((-b.half[k] - lo[k]) / lr[k], (b.half[k] - lo[k]) / lr[k]);
        if a > c {
            std::mem::swap(&mut a, &mut c);
        }
        if a > t0 {
            t0 = a;
            face = k;
        }
        t1 = t1.min(c);
        if t0 > t1 {
            return None;
        }
    }
    (t0 > 1e-9).then(|| {
        (
            t0,
            [lo[0] + t0 * lr[0], lo[1] + t0 * lr[1], lo[2] + t0 * lr[2]],
            face,
        )
    })
}

/// Shades a road point, `raised`: what of a kerb it is on. `fd`, `fs`: footprint across and
/// along, metres.
#[allow(clippy::too_many_arguments)]
pub(super) fn shade_road(
    config: &SceneConfig,
    road: &Road,
    s: f64,
    d: f64,
    raised: Raised,
    fd: f64,
    fs: f64,
    seed: u64,
) -> [f32; 3] {
    let a = &config.appearance;
    let lanes = road.lanes();
    // Road edges: the outermost existing lanes' outer boundaries, plus a 0.4 m shoulder.
    let first = (0..lanes).find(|&i| road.lane_exists(i, s)).unwrap_or(0);
    let last = (0..lanes)
        .rev()
        .find(|&i| road.lane_exists(i, s))
        .unwrap_or(lanes - 1);
    let (left_edge, right_edge) = (
        road.boundary_offset(first, s) + 0.4,
        road.boundary_offset(last + 1, s) - 0.4,
    );
    let noise = |scale: f64, salt: u64| value_noise(seed ^ salt, s * scale, d * scale) as f32;
    // Texture finer than the pixel footprint would shimmer: fade it out with distance.
    let fine = (0.1 / fd).min(1.0) as f32;
    let mut rgb = if raised == Raised::Pavement {
        // Concrete paving slabs 1.2 m long with dark joints.
        let n = (noise(10.0, 31) - 0.5) * fine + (noise(0.8, 32) - 0.5) * 0.6;
        let joint = super::markings::interval(s.rem_euclid(1.2) - 0.6, 0.015, fs);
        let g = (150.0 + 28.0 * n) * (1.0 - 0.35 * joint);
        [g, g * 0.99, g * 0.96]
    } else if d > left_edge || d < right_edge {
        // Verge: dry grass and gravel.
        let n = noise(3.0, 11) * fine + 0.5 * (1.0 - fine);
        let m = noise(0.4, 12);
        [
            80.0 + 40.0 * n + 20.0 * m,
            90.0 + 30.0 * n + 15.0 * m,
            50.0 + 20.0 * n,
        ]
    } else {
        let t = (noise(12.0, 1) - 0.5) * fine + (noise(1.5, 2) - 0.5) * 0.8;
        let mut g = a.asphalt as f32 + t * a.texture as f32;
        if a.patches > 0.0 {
            // Repair patches: blobs of darker asphalt where a coarse noise is low.
            let p = noise(0.25, 3);
            g *= 1.0 - 0.22 * ((a.patches as f32 - p) * 40.0).clamp(0.0, 1.0);
        }
        if a.seam_period_m > 0.0 {
            let seam = super::markings::interval(s.rem_euclid(a.seam_period_m) - 0.05, 0.04, fs);
            g *= 1.0 - 0.45 * seam;
        }
        [g, g, g * 1.02]
    };
    let m = config.markings.coverage(road, s, d, fd, fs);
    // Road paint is retroreflective: at night it returns more of the headlights' light.
    let gain = if a.night { 1.8 } else { 1.0 };
    blend(&mut rgb, m.rgb.map(|c| c * gain), m.alpha);
    if raised == Raised::Kerbstone {
        // Weathered concrete.
        let n = 1.0 + 0.12 * (noise(14.0, 33) - 0.5) * fine;
        rgb = rgb.map(|c| c * n);
    }
    for p in &config.road_paint {
        let along = super::markings::interval(s - (p.s + p.size_m[0] / 2.0), p.size_m[0] / 2.0, fs);
        let across = super::markings::interval(d - p.d, p.size_m[1] / 2.0, fd);
        blend(&mut rgb, [220.0, 220.0, 215.0], along * across * 0.9);
    }
    let mut light = 1.0f32;
    for sh in &config.shadows {
        match *sh {
            Shadow::Band {
                from_s,
                to_s,
                light: l,
            } => {
                if s >= from_s && s < to_s {
                    light = light.min(l as f32);
                }
            }
            Shadow::Trees {
                from_s,
                to_s,
                left,
                reach_m,
                light: l,
            } => {
                if s >= from_s && s < to_s {
                    let edge = if left { left_edge } else { right_edge };
                    let inside = if left { edge - d } else { d - edge };
                    // Crowns of a few metres whose reach into the road varies, dappled by
                    // finer gaps in the leaves; edges softened over 0.3 m.
                    let reach = reach_m * (0.3 + 0.7 * value_noise(seed ^ 21, s / 6.0, 0.0));
                    let crown = ((reach - inside) / 0.3).clamp(0.0, 1.0) as f32;
                    let leaves = ((value_noise(seed ^ 22, s * 0.8, d * 0.8) - 0.3) * 5.0)
                        .clamp(0.0, 1.0) as f32;
                    let k = crown * leaves;
                    light = light.min(1.0 - k * (1.0 - l as f32));
                }
            }
        }
    }
    for c in rgb.iter_mut() {
        *c *= light;
    }
    rgb
}

/// Shades a kerb's vertical face (facing the road, in its own shadow) at `height` above the
/// road, `s` along it.
pub(super) fn shade_kerb_face(s: f64, height: f64, seed: u64) -> [f32; 3] {
    let n = value_noise(seed ^ 34, s * 14.0, height * 14.0) as f32;
    let g = 128.0 + 16.0 * (n - 0.5);
    [g, g * 0.99, g * 0.95]
}

/// Alpha-blends `with` over `rgb`.
pub(super) fn blend(rgb: &mut [f32; 3], with: [f32; 3], alpha: f32) {
    for k in 0..3 {
        rgb[k] += (with[k] - rgb[k]) * alpha;
    }
}

/// Shades a vehicle hit: body colour by face, dark glass in the upper part, dark wheels band.
pub(super) fn shade_vehicle(
    rgb: [f32; 3],
    half: [f64; 3],
    local: [f64; 3],
    face: usize,
) -> [f32; 3] {
    let shade = [0.8f32, 0.65, 1.0][face];
    let z = local[2] + half[2];
    if z < 0.35 {
        return [25.0, 25.0, 28.0];
    }
    if face == 0 && z > half[2] * 2.0 * 0.55 {
        return [40.0, 45.0, 55.0];
    }
    if face == 0 && z > 0.7 && z < 0.9 && local[1].abs() > half[1] * 0.6 {
        return [200.0, 30.0, 30.0]; // tail lights
    }
    [rgb[0] * shade, rgb[1] * shade, rgb[2] * shade]
}

/// Sky colour at normalised image height `v` (0 top .. 1 bottom).
pub(super) fn sky(v: f32, night: bool) -> [f32; 3] {
    if night {
        [10.0, 12.0, 20.0]
    } else {
        let k = v.clamp(0.0, 1.0);
        [140.0 + 60.0 * k, 170.0 + 45.0 * k, 210.0 + 25.0 * k]
    }
}

/// Distance haze: blends towards the horizon colour.
pub(super) fn haze(rgb: &mut [f32; 3], x: f64, night: bool) {
    let k = ((x / MAX_RANGE_M) as f32).clamp(0.0, 1.0);
    let far = if night {
        [8.0, 9.0, 14.0]
    } else {
        [185.0, 195.0, 205.0]
    };
    blend(rgb, far, k * k);
}

/// Night lighting of a road point: ambient plus two headlight beams.
pub(super) fn night_light(x: f64, y: f64) -> f32 {
    if x <= 0.0 {
        return 0.06;
    }
    let spread = (y / (x * 0.35 + 1.5)).abs();
    let beam = (1.0 - spread).clamp(0.0, 1.0) / (1.0 + (x / 30.0) * (x / 30.0));
    0.06 + 0.9 * beam as f32
}
