//! Image buffers and views, RGBA input, and image files.

mod buffer;
mod io;
mod rgba;

pub use buffer::{check_dimensions, Image, ImageView, MAX_PIXELS, MAX_SIDE};
pub use io::{
    decode_rgba, read_disparity_png, read_rgba, write_disparity_png, write_gray_png,
    write_rgba_png, RgbaFrame,
};
pub use rgba::{check_rgba, gray_to_rgba, luma, rgba_to_gray, rgba_to_gray_rows};
