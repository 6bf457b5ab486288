//! Where a grid lesson's tiles go in an area: 16:9 tiles in rows of at most `max_columns`,
//! as large as the area allows, centred. The slide and the viewer lay grids out alike.

/// A tile's place in the area's unit (pixels or points): `[left, top, width, height]`.
pub type Cell = [f32; 4];

/// The places of `count` 16:9 tiles in `area` (`[left, top, width, height]`), `gap` apart in a
/// row and `label_row` apart between rows (a row of labels under each row of tiles but the
/// last), in the column count that makes them largest (of equally large ones, the fewest empty
/// cells), centred. With `blocks` above 1 the rows are laid out that many times, one block
/// under the other (a slide's insets under its tiles): the cells of block `b` follow those of
/// block `b − 1`. Tile sizes are whole units, at least 16 wide.
pub fn tile_cells(
    count: usize,
    area: [f32; 4],
    gap: f32,
    label_row: f32,
    max_columns: usize,
    blocks: usize,
) -> Vec<Cell> {
    let [x0, y0, width, height] = area;
    let blocks = blocks.max(1);
    if count == 0 {
        return Vec::new();
    }
    // The tile width with `columns` columns: limited by the width and by the height.
    let tile_width = |columns: usize| {
        let rows = count.div_ceil(columns) * blocks;
        let by_width = (width - gap * (columns - 1) as f32) / columns as f32;
        let by_height = ((height - label_row * (rows - 1) as f32) / rows as f32) * 16.0 / 9.0;
        by_width.min(by_height).floor().max(16.0)
    };
    let empty = |columns: usize| columns * count.div_ceil(columns) - count;
    let columns = (1..=count.min(max_columns.max(1)))
        .max_by(|&a, &b| tile_width(a).total_cmp(&tile_width(b)).then(empty(b).cmp(&empty(a))))
        .unwrap_or(1);
    let rows = count.div_ceil(columns);
    let w = tile_width(columns);
    let h = (w * 9.0 / 16.0).round();
    let row_width = w * columns as f32 + gap * (columns - 1) as f32;
    let left = x0 + (width - row_width) / 2.0;
    // The tiles (and the labels between their rows) centred in the height they leave free.
    let used = h * (rows * blocks) as f32 + label_row * (rows * blocks - 1) as f32;
    let top = y0 + ((height - used) / 2.0).max(0.0);
    (0..count * blocks)
        .map(|i| {
            let (block, i) = (i / count, i % count);
            let (column, row) = ((i % columns) as f32, (block * rows + i / columns) as f32);
            [(left + column * (w + gap)).round(), (top + row * (h + label_row)).round(), w, h]
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn four_tiles_in_a_wide_area_make_one_row_and_in_a_square_one_two_by_two() {
        let wide = tile_cells(4, [0.0, 0.0, 1600.0, 300.0], 0.0, 0.0, 4, 1);
        assert!(wide.iter().all(|c| c[1] == wide[0][1]), "one row: {wide:?}");
        let square = tile_cells(4, [0.0, 0.0, 1000.0, 1000.0], 0.0, 0.0, 4, 1);
        assert_eq!(square[2][0], square[0][0], "two by two: {square:?}");
        assert!(square[2][1] > square[0][1]);
    }

    #[test]
    fn tiles_stay_inside_the_area_and_do_not_overlap() {
        for (count, blocks) in (1..=6).flat_map(|count| [(count, 1), (count, 2)]) {
            let area = [10.0, 20.0, 960.0, 400.0];
            let cells = tile_cells(count, area, 8.0, 20.0, 4, blocks);
            for (i, c) in cells.iter().enumerate() {
                assert!(c[0] >= area[0] - 0.5 && c[0] + c[2] <= area[0] + area[2] + 0.5, "{count}: {c:?}");
                assert!(c[1] >= area[1] - 0.5 && c[1] + c[3] <= area[1] + area[3] + 0.5, "{count}: {c:?}");
                for d in &cells[i + 1..] {
                    let apart =
                        c[0] + c[2] <= d[0] || d[0] + d[2] <= c[0] || c[1] + c[3] <= d[1] || d[1] + d[3] <= c[1];
                    assert!(apart, "{count}: {c:?} overlaps {d:?}");
                }
            }
        }
    }
}
