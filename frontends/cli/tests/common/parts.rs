//! Render-farm parts made by hand, with pixels that say where they are.

use voxtrace_cli::part::{fnv1a64, Part, Placement};
use voxtrace_cli::tiles::Grid;

/// Tile `tile` of a `width x height` frame cut by `grid`, whose pixel at
/// (x, y) is `x + 1000 y`, with `settings` as its settings text (and its
/// hash); a still, frame 0.
pub fn numbered_part(grid: Grid, width: u32, height: u32, tile: u32, settings: &str) -> Part {
    let rect = grid.tile(width, height, tile).unwrap();
    let pixels = (rect.y..rect.y + rect.height)
        .flat_map(|y| (rect.x..rect.x + rect.width).map(move |x| x + 1000 * y))
        .collect();
    Part {
        placement: Placement {
            frame_width: width,
            frame_height: height,
            grid,
            tile,
            rect,
            frame_number: 0,
            hash: fnv1a64(settings.as_bytes()),
        },
        settings: settings.to_string(),
        pixels,
    }
}
