//! Figures: the SVG plotting layer and the standard plots, surfaces and wireframes, colours,
//! text layout, the figure check, and PNG rendering.
//!
//! - `svg/`: figures, pages, overlaps, rendering, the standard plots (a folder);
//! - `surface_plot.rs`: surfaces coloured by a field, with a colour bar;
//! - `wireframe.rs`: wireframes of surfaces in a projection;
//! - `palette.rs`: colours, dashes and markers;
//! - `layout.rs`: text extents and legend placement;
//! - `figure_check.rs`: the checks of a figure as a reader looks at it;
//! - `png.rs`: PNG by resvg.

pub(crate) mod figure_check;
pub(crate) mod layout;
pub(crate) mod palette;
pub(crate) mod png;
pub(crate) mod surface_plot;
pub(crate) mod svg;
pub(crate) mod wireframe;
