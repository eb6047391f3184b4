//! Lane paint lies on the road: a ridge pixel counts as a marking only when the road beside it
//! is grey and darker than the paint.
//!
//! Asphalt and concrete are nearly colourless and darker than their paint; the bright ridges a
//! line detector also finds off the road are not on such ground: white-painted tree trunks
//! stand in foliage, the highlights of a red car in its paint, a gap of grey sky between trunks
//! among more sky. A ridge pixel at working column x with marking intensity m(x) is kept when,
//! at x - d or at x + d for one d of [`SIDE_OFFSETS`] working pixels, the saturation (see
//! [`super::marking_image`]) is at most [`MAX_ROAD_SATURATION`] and m is below m(x) by at
//! least `min_contrast`: one such place is enough, so a road's edge line with grass beyond it
//! stays, and so does a line near the horizon of a small frame whose neighbour is close. The
//! nearest offset lies on the paint of a wide marking (not darker) and the farthest beyond
//! the widest half-width the ridge filter looks at ([`super::ridges::SCALES`]).

use super::ridges::RidgePixel;
use crate::image::Image;

/// Largest saturation (0-255) of grey road.
pub const MAX_ROAD_SATURATION: u8 = 40;
/// Distances from a ridge pixel to where its sides are sampled, working pixels.
pub const SIDE_OFFSETS: [usize; 3] = [3, 6, 12];

/// Keeps the pixels of `pixels` with a side of grey road (see the module docs) in the marking
/// intensity `m` and its `saturation`.
pub fn keep_on_grey_road(
    pixels: &mut Vec<RidgePixel>,
    m: &Image<u8>,
    saturation: &Image<u8>,
    min_contrast: i32,
) {
    let w = saturation.width();
    pixels.retain(|p| {
        let (x, y) = (p.x as usize, p.y as usize);
        let ridge = m.get(x, y) as i32;
        let road = |x: usize| {
            saturation.get(x, y) <= MAX_ROAD_SATURATION
                && ridge - m.get(x, y) as i32 >= min_contrast
        };
        SIDE_OFFSETS
            .iter()
            .any(|&d| (x >= d && road(x - d)) || (x + d < w && road(x + d)))
    });
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ridges_beside_colour_or_brighter_ground_are_dropped() {
        // Columns 0-29 grey road (intensity 80), 30-59 foliage (saturated), 60-89 grey sky
        // (intensity 200), 90-119 road again with a neighbouring marking at column 112; every
        // ridge pixel at intensity 190.
        let (mut m, mut sat) = (Image::new(120, 1).unwrap(), Image::new(120, 1).unwrap());
        for x in 0..120 {
            m.set(x, 0, [80, 60, 200, 80][x / 30]);
            sat.set(x, 0, [10, 120, 5, 10][x / 30]);
        }
        m.set(112, 0, 190);
        let px = |x: u16| RidgePixel {
            x,
            y: 0,
            contrast: 50,
        };
        let mut pixels = vec![px(5), px(20), px(36), px(45), px(65), px(70), px(100)];
        for p in &pixels {
            m.set(p.x as usize, 0, 190);
        }
        keep_on_grey_road(&mut pixels, &m, &sat, 12);
        let kept: Vec<u16> = pixels.iter().map(|p| p.x).collect();
        // 5: road on its right; 20: road on its left; 36: road at x 24 (a road's edge line
        // with grass beyond); 45: foliage on both sides; 65, 70: grey sky as bright as the
        // ridge or brighter; 100: sky 12 to the left and the neighbour's paint 12 to the
        // right, but road 3 and 6 away.
        assert_eq!(kept, vec![5, 20, 36, 100]);
    }
}
