//! Pictures of a tracker's cues after a frame, for the views that explain it.

/// A picture of one of a tracker's cues after the last frame, in road coordinates, for the
/// views that explain a tracker (Adachi's vote histogram, Lee's likelihood map, ...).
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
#[serde(tag = "kind", rename_all = "kebab-case")]
pub enum Layer {
    /// Values over bins of one road axis: bin k covers [start + k step, start + (k + 1) step).
    Histogram {
        /// What the values are.
        name: String,
        /// The axis, e.g. `rho (m, positive right)`.
        axis: String,
        /// Start of bin 0, metres.
        start: f64,
        /// Bin size, metres.
        step: f64,
        /// One value per bin.
        values: Vec<f32>,
    },
    /// Values on a road-plane grid of square cells: row r spans x in [x0 + r cell, x0 +
    /// (r + 1) cell), column c spans y in (y0 - (c + 1) cell, y0 - c cell] (columns run from
    /// left to right as seen from the car); `values[r * width + c]`.
    Grid {
        /// What the values are.
        name: String,
        /// Columns.
        width: usize,
        /// Rows.
        height: usize,
        /// Near edge of row 0, metres ahead.
        x0: f64,
        /// Left edge of column 0, metres (y left).
        y0: f64,
        /// Cell size, metres.
        cell: f64,
        /// One value per cell.
        values: Vec<f32>,
    },
    /// Values on a plane other than the road, row 0 at the bottom of the axes.
    Plane {
        /// What the values are.
        name: String,
        /// Columns.
        width: usize,
        /// Rows.
        height: usize,
        /// Where the rows and columns are.
        #[serde(flatten)]
        axes: PlaneAxes,
        /// One value per cell.
        values: Vec<f32>,
    },
}

/// A layer of values on a plane other than the road (e.g. Danescu's lateral density image):
/// column c is at `x0 + (c + 0.5) dx` on the x axis, row r at `y0 + (r + 0.5) dy` on the y axis;
/// `values[r * width + c]`. Part of [`Layer::Plane`].
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct PlaneAxes {
    /// The x axis, e.g. `Z (m, ahead)`.
    pub x_axis: String,
    /// Start of column 0.
    pub x0: f64,
    /// Column size.
    pub dx: f64,
    /// The y axis, e.g. `Y (m, up)`.
    pub y_axis: String,
    /// Start of row 0.
    pub y0: f64,
    /// Row size.
    pub dy: f64,
}
