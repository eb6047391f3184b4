//! The stereo matcher on a real rectified pair, drawn for looking at: the left image on top,
//! the disparity below it (brighter is nearer, black where the matcher gave none), with the
//! share of pixels that got a disparity per quarter of the image height printed.
//! Reads PNG/JPEG, and binary PGM (P5) such as the Karlsruhe pairs.
//! `cargo run --release --example disparity_png -- LEFT RIGHT OUT.png [MAX_DISPARITY]`

use lanepf::image::{read_rgba, rgba_to_gray, write_gray_png, Image};
use lanepf::vision::{DisparityConfig, StereoMatcher};
use std::path::Path;

/// A grey image from a binary PGM with 8-bit samples, or any image the crate decodes.
fn read_gray(path: &str) -> Result<Image<u8>, Box<dyn std::error::Error>> {
    let bytes = std::fs::read(path)?;
    if bytes.starts_with(b"P5") {
        // Header: magic, width, height, maxval, separated by white space and # comments.
        let (mut fields, mut i) = (Vec::new(), 2);
        while fields.len() < 3 {
            match bytes.get(i) {
                Some(b'#') => {
                    while bytes.get(i).is_some_and(|&b| b != b'\n') {
                        i += 1;
                    }
                }
                Some(b) if b.is_ascii_digit() => {
                    let start = i;
                    while bytes.get(i).is_some_and(u8::is_ascii_digit) {
                        i += 1;
                    }
                    fields.push(std::str::from_utf8(&bytes[start..i])?.parse::<usize>()?);
                    continue;
                }
                Some(_) => {}
                None => return Err(format!("{path}: truncated PGM header").into()),
            }
            i += 1;
        }
        let (w, h, max) = (fields[0], fields[1], fields[2]);
        if max > 255 {
            return Err(format!("{path}: 16-bit PGM is not supported").into());
        }
        let data = bytes
            .get(i + 1..i + 1 + w * h)
            .ok_or_else(|| format!("{path}: fewer than {w}x{h} samples"))?;
        return Ok(Image::from_vec(w, h, data.to_vec())?);
    }
    let frame = read_rgba(Path::new(path))?;
    let mut gray = Image::new(frame.width, frame.height)?;
    rgba_to_gray(&frame.data, frame.width, frame.height, &mut gray)?;
    Ok(gray)
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().collect();
    if args.len() < 4 {
        return Err("usage: disparity_png LEFT RIGHT OUT.png [MAX_DISPARITY]".into());
    }
    let (left, right) = (read_gray(&args[1])?, read_gray(&args[2])?);
    let max_disparity = args.get(4).map_or(Ok(128), |s| s.parse())?;
    let (w, h) = (left.width(), left.height());
    let mut matcher = StereoMatcher::new(
        w,
        h,
        DisparityConfig {
            max_disparity,
            ..DisparityConfig::default()
        },
    )?;
    let t0 = std::time::Instant::now();
    matcher.compute(&left.view(), &right.view(), 0)?;
    let ms = t0.elapsed().as_secs_f64() * 1e3;
    let d = matcher.disparity();
    let mut out = Image::<u8>::new(w, 2 * h)?;
    for v in 0..h {
        for u in 0..w {
            out.set(u, v, left.get(u, v));
            let x = d.get(u, v);
            let g = if x > 0.0 {
                (40.0 + 215.0 * x / max_disparity as f32).min(255.0) as u8
            } else {
                0
            };
            out.set(u, h + v, g);
        }
    }
    write_gray_png(Path::new(&args[3]), &out)?;
    print!("{w}x{h}, disparities 0..={max_disparity}, {ms:.0} ms; valid per quarter (top first):");
    for q in 0..4 {
        let rows = q * h / 4..(q + 1) * h / 4;
        let n = rows.len() * w;
        let valid = rows
            .flat_map(|v| (0..w).map(move |u| (u, v)))
            .filter(|&(u, v)| d.get(u, v) > 0.0)
            .count();
        print!(" {:.0} %", 100.0 * valid as f64 / n as f64);
    }
    println!();
    Ok(())
}
