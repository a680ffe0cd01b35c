//! SVG figures: a small plotting layer (axes, ticks, legend) and the standard lekalo plots —
//! a curve with its control polygon, data points and knot marks; B-spline basis functions; a
//! knot vector; a surface wireframe in a simple projection (see [`crate::wireframe`]).
//!
//! A [`Figure`] is data (series of polylines or markers in world coordinates); [`Figure::to_svg`]
//! maps it to the page. Figures are deterministic: the same input gives the same bytes.
//!
//! - `figure.rs`: [`Figure`] and what it holds ([`Series`], [`Style`], [`Face`], [`Annotation`],
//!   [`ColorBar`]);
//! - `page.rs`: margins, fonts, the world window and the frame mapping it to the page;
//! - `overlap.rs`: series that hide one another ([`Coincidence`]);
//! - `render.rs`: [`Figure::to_svg`]: axes, series, legend, colour bar;
//! - `ticks.rs`: ticks at round numbers and the numbers shown;
//! - `plots.rs`: the standard plots ([`curve_figure`], [`residual_series`], [`basis_figure`],
//!   [`knots_figure`], [`CurvePlot`]);
//! - `tests.rs`.

mod figure;
mod overlap;
mod page;
mod plots;
mod render;
#[cfg(test)]
mod tests;
mod ticks;

pub use figure::{Annotation, Coincidence, ColorBar, Face, Figure, Series, Style};
pub use plots::{basis_figure, curve_figure, knots_figure, residual_series, CurvePlot};
pub use render::escape;
pub(crate) use ticks::{fmt_tick, nice_ticks};
