//! Placement of point labels (a marker's name drawn next to it) so that labels overlap neither
//! each other nor the markers nor the plot's edge.
//!
//! Greedy, in the order given: each label takes the first free position (clear of the placed
//! labels, every marker and the given obstacles, e.g. a curve's segments) among candidates
//! around its marker — right, left, above, below and the four diagonals, first close to the
//! marker and then on wider rings. When no candidate is free the one with the least
//! overlap is taken. Positions farther than the first ring are flagged so the caller can draw
//! a leader line from the marker to its label. Deterministic: the same input gives the same
//! placement.

/// Rings of candidate positions tried around a marker.
const RINGS: i32 = 6;

/// An axis-aligned pixel rectangle: left, top, width, height.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Rect {
    /// Left edge (px).
    pub x: i32,
    /// Top edge (px).
    pub y: i32,
    /// Width (px).
    pub w: i32,
    /// Height (px).
    pub h: i32,
}

impl Rect {
    /// Area (px²) shared with `o`.
    fn overlap(&self, o: &Rect) -> i64 {
        let dx = (self.x + self.w).min(o.x + o.w) - self.x.max(o.x);
        let dy = (self.y + self.h).min(o.y + o.h) - self.y.max(o.y);
        if dx > 0 && dy > 0 {
            dx as i64 * dy as i64
        } else {
            0
        }
    }

    /// Area (px²) of `self` outside `bounds`.
    fn outside(&self, bounds: &Rect) -> i64 {
        self.w as i64 * self.h as i64 - self.overlap(bounds)
    }
}

/// The thin box (px) covering a horizontal or vertical segment from `a` to `b` drawn with a
/// line of width ≈ 3 px (an obstacle for [`place_labels`]).
pub fn segment_box(a: (i32, i32), b: (i32, i32)) -> Rect {
    let (x0, x1) = (a.0.min(b.0), a.0.max(b.0));
    let (y0, y1) = (a.1.min(b.1), a.1.max(b.1));
    Rect {
        x: x0 - 1,
        y: y0 - 1,
        w: x1 - x0 + 3,
        h: y1 - y0 + 3,
    }
}

/// A marker: centre and radius (px).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Marker {
    /// Centre x (px).
    pub x: i32,
    /// Centre y (px).
    pub y: i32,
    /// Radius (px).
    pub r: i32,
}

/// Where a label went.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Placement {
    /// The label's box (px).
    pub rect: Rect,
    /// Whether the label sits away from its marker (draw a leader line).
    pub detached: bool,
}

/// Places one label of size `sizes[i]` (width, height in px) next to each of `markers[i]`,
/// inside `bounds`, clear of `obstacles` where possible. See the module documentation for the
/// rule.
pub fn place_labels(
    markers: &[Marker],
    sizes: &[(i32, i32)],
    obstacles: &[Rect],
    bounds: Rect,
) -> Vec<Placement> {
    let blocks: Vec<Rect> = markers
        .iter()
        .map(|m| Rect {
            x: m.x - m.r,
            y: m.y - m.r,
            w: 2 * m.r + 1,
            h: 2 * m.r + 1,
        })
        .collect();
    let mut placed: Vec<Rect> = Vec::with_capacity(markers.len());
    let mut out = Vec::with_capacity(markers.len());
    for (m, &(w, h)) in markers.iter().zip(sizes) {
        let mut best: Option<(i64, Placement)> = None;
        'rings: for ring in 0..RINGS {
            for rect in candidates(m, w, h, ring) {
                let cost = rect.outside(&bounds) * 4
                    + placed.iter().map(|p| rect.overlap(p)).sum::<i64>() * 2
                    + blocks.iter().map(|b| rect.overlap(b)).sum::<i64>()
                    + obstacles.iter().map(|b| rect.overlap(b)).sum::<i64>();
                let p = Placement {
                    rect,
                    detached: ring > 0,
                };
                if best.is_none_or(|(c, _)| cost < c) {
                    best = Some((cost, p));
                }
                if cost == 0 {
                    break 'rings;
                }
            }
        }
        let (_, p) = best.expect("at least one candidate");
        placed.push(p.rect);
        out.push(p);
    }
    out
}

/// Candidate boxes of a `w × h` label around `m` on ring `ring` (0: touching the marker;
/// ring k ≥ 1: k label heights up or down beside the marker, or k rows above or below it).
fn candidates(m: &Marker, w: i32, h: i32, ring: i32) -> Vec<Rect> {
    let gap = 3;
    let (l, r) = (m.x - m.r - gap - w, m.x + m.r + gap);
    let (t, b) = (m.y - m.r - gap - h, m.y + m.r + gap);
    let (cx, cy) = (m.x - w / 2, m.y - h / 2);
    let at = |x, y| Rect { x, y, w, h };
    if ring == 0 {
        return vec![
            at(r, cy),
            at(r, t + h / 2),
            at(r, b - h / 2),
            at(l, cy),
            at(cx, t),
            at(cx, b),
            at(l, t + h / 2),
            at(l, b - h / 2),
        ];
    }
    let step = ring * (h + 2);
    vec![
        at(r, cy - step),
        at(r, cy + step),
        at(l, cy - step),
        at(l, cy + step),
        at(cx, t - step),
        at(cx, b + step),
        at(r + step, cy),
        at(l - step, cy),
    ]
}

#[cfg(test)]
mod tests {
    use super::*;

    const BOUNDS: Rect = Rect {
        x: 0,
        y: 0,
        w: 600,
        h: 400,
    };

    #[test]
    fn a_lone_label_sits_right_of_its_marker() {
        let p = place_labels(
            &[Marker {
                x: 100,
                y: 100,
                r: 5,
            }],
            &[(60, 12)],
            &[],
            BOUNDS,
        );
        assert_eq!(p[0].rect.x, 108);
        assert_eq!(p[0].rect.y, 94);
        assert!(!p[0].detached);
    }

    #[test]
    fn crowded_labels_do_not_overlap_each_other_markers_or_the_edge() {
        // a cluster of 12 markers 10 px apart, one near the right edge
        let markers: Vec<Marker> = (0..12)
            .map(|i| Marker {
                x: 300 + (i % 4) * 10,
                y: 200 + (i / 4) * 10,
                r: 5,
            })
            .chain([Marker { x: 595, y: 5, r: 5 }])
            .collect();
        let sizes = vec![(70, 12); markers.len()];
        let p = place_labels(&markers, &sizes, &[], BOUNDS);
        for (i, a) in p.iter().enumerate() {
            assert_eq!(a.rect.outside(&BOUNDS), 0, "label {i} leaves the plot");
            for b in &p[i + 1..] {
                assert_eq!(a.rect.overlap(&b.rect), 0, "label {i} overlaps another");
            }
            for m in &markers {
                let block = Rect {
                    x: m.x - m.r,
                    y: m.y - m.r,
                    w: 2 * m.r + 1,
                    h: 2 * m.r + 1,
                };
                assert_eq!(a.rect.overlap(&block), 0, "label {i} covers a marker");
            }
        }
        // the crowd pushes some labels out to a wider ring
        assert!(p.iter().any(|q| q.detached));
    }

    #[test]
    fn a_label_avoids_a_line_through_its_first_choice() {
        let m = Marker {
            x: 100,
            y: 100,
            r: 5,
        };
        let line = segment_box((100, 100), (400, 100));
        let p = place_labels(&[m], &[(60, 12)], &[line], BOUNDS);
        assert_eq!(p[0].rect.overlap(&line), 0);
        assert!(!p[0].detached);
    }
}
