//! Tests of the continuation sweep's blocks, hysteresis mark and carried state.

#![cfg(test)]

use super::chain::state_overrides;
use super::hysteresis::marks_hysteresis;
use super::plan::{blocks, shard_blocks, Continuation, Direction};
use crate::io::schema::StrobeRow;
use crate::scene::Scene;
use crate::sweep::shard::Shard;

fn vals(n: usize) -> Vec<toml::Value> {
    (0..n).map(|i| toml::Value::Float(i as f64)).collect()
}

#[test]
fn blocks_cover_each_branch_in_order_with_warmup() {
    let mut c = Continuation::new(Direction::Both);
    c.block = Some(4);
    c.overlap = 2;
    let b = blocks(&vals(10), &c);
    assert_eq!(b.len(), 6);
    assert!(b[0].warmup.is_empty());
    assert_eq!(b[1].warmup, [(2, 2), (3, 3)]);
    assert_eq!(b[1].points, [(4, 4), (5, 5), (6, 6), (7, 7)]);
    // down: points 10..19, values decreasing
    assert_eq!(b[3].points[0], (19, 9));
    // down runs 9, 8, …, 0 in blocks [9..6], [5..2], [1, 0]: the second warms up on 7, 6
    assert_eq!(b[4].warmup, [(17, 7), (16, 6)]);
    assert_eq!(b[4].points[0], (15, 5));
    let covered: usize = b.iter().map(|x| x.points.len()).sum();
    assert_eq!(covered, 20);
    // shards: contiguous ranges of blocks, all covered once
    let mut seen = 0;
    for k in 0..4 {
        seen += shard_blocks(&b, Shard { index: k, count: 4 }).len();
    }
    assert_eq!(seen, 6);
}

#[test]
fn hysteresis_needs_a_regime_change_or_a_non_chaotic_amplitude_jump() {
    let m = marks_hysteresis;
    // two periodic orbits: 2 against 3 impacts per period, or a jump in amplitude
    assert!(m(Some(0.01), Some(1.0 / 3.0), "periodic", "periodic", 0.05));
    assert!(m(Some(0.5), Some(0.0), "periodic", "chaotic", 0.05));
    // the same orbit judged differently, and two chaotic windows, are not marked
    assert!(!m(Some(0.005), Some(0.0), "chaotic", "periodic", 0.05));
    assert!(!m(Some(0.5), Some(0.2), "chaotic", "chaotic", 0.05));
    assert!(!m(Some(0.01), Some(0.0), "undetermined", "periodic", 0.05));
    // no analysis: amplitude and impacts decide
    assert!(m(Some(0.5), None, "", "", 0.05));
    assert!(!m(None, None, "", "", 0.05));
}

#[test]
fn state_overrides_from_a_strobe_row() {
    let s = Scene::thesis_b_impact();
    let row: StrobeRow = "7,0.01,0.002,-0.5,0.25".parse().unwrap();
    let ov = state_overrides(&row, &s).unwrap();
    let get = |k: &str| {
        ov.iter()
            .find(|(x, _)| x == k)
            .unwrap()
            .1
            .as_float()
            .unwrap()
    };
    assert_eq!(get("primary.initial_displacement"), 0.002);
    assert_eq!(get("primary.initial_velocity"), 0.25);
    assert_eq!(get("damper.initial_height"), 0.01 - 0.002);
    assert_eq!(get("damper.initial_velocity"), -0.5);
}
