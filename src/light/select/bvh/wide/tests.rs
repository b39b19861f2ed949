//! The wide nodes' importances against the scalar [`PreparedBounds::importance`], bit
//! for bit.

use super::*;
use crate::geometry::Aabb;
use crate::light::LightBounds;
use glam::Vec3;

/// Numbers in [−1, 1) from a xorshift generator seeded with `state`.
fn numbers(mut state: u64) -> impl FnMut() -> f32 {
    move || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 40) as f32 / (1u64 << 24) as f32 * 2.0 - 1.0
    }
}

/// Checks that each lane of `node` at `at` (case `case`) is the scalar importance of
/// its bounds in `scalar` (0 past them), bit for bit; returns the lanes and how many
/// are positive.
fn lanes_are_scalar(
    node: &WideNode,
    scalar: &[PreparedBounds],
    at: &ShadingPoint,
    case: usize,
) -> ([f32; LANES], u32) {
    let lanes = node.importance(at);
    let mut positive = 0;
    for (l, lane) in lanes.iter().enumerate() {
        let expected = scalar.get(l).map_or(0.0, |b| b.importance(at));
        assert_eq!(lane.to_bits(), expected.to_bits(), "case {case} lane {l}");
        positive += (expected > 0.0) as u32;
    }
    (lanes, positive)
}

/// A node and the shading point of case `i` (1 to 4 lanes used: flat, point-like and
/// solid boxes; some points at a light's centre), with each lane's bounds.
type Case = (WideNode, Vec<PreparedBounds>, ShadingPoint);

fn general_case(next: &mut impl FnMut() -> f32, i: usize) -> Case {
    let mut node = WideNode::empty();
    let mut scalar = Vec::new();
    for l in 0..1 + i % LANES {
        let lo = Vec3::new(next(), next(), next()) * 4.0;
        let size = match (i + l) % 3 {
            0 => Vec3::new(next().abs(), 0.0, next().abs()),
            1 => Vec3::ZERO,
            _ => Vec3::new(next(), next(), next()).abs() * 3.0,
        };
        let b = PreparedBounds::new(&LightBounds {
            aabb: Aabb {
                min: lo,
                max: lo + size,
            },
            phi: next().abs() * 10.0,
            w: Vec3::new(next(), next(), next()).normalize_or(Vec3::Z),
            cos_theta_o: next(),
            cos_theta_e: if l % 2 == 0 { 0.0 } else { next() },
            two_sided: (i + l).is_multiple_of(5),
        });
        node.set_bounds(l, &b);
        scalar.push(b);
    }
    let p = if i.is_multiple_of(7) {
        scalar[0].centre
    } else {
        Vec3::new(next(), next(), next()) * 6.0
    };
    let at = ShadingPoint {
        p,
        ng: Vec3::Y,
        n: Vec3::new(next(), next(), next()).normalize_or(Vec3::Y),
    };
    (node, scalar, at)
}

#[test]
fn every_lane_equals_the_scalar_importance_bit_for_bit() {
    let mut next = numbers(0x2545_f491_4f6c_dd1d);
    let mut nonzero = 0;
    for i in 0..50_000 {
        let (node, scalar, at) = general_case(&mut next, i);
        nonzero += lanes_are_scalar(&node, &scalar, &at, i).1;
    }
    assert!(nonzero > 25_000, "only {nonzero} lanes with importance");
}

/// A point light's bounds: at `c`, power `phi`.
fn point(c: Vec3, phi: f32) -> PreparedBounds {
    PreparedBounds::new(&LightBounds {
        aabb: Aabb { min: c, max: c },
        phi,
        w: Vec3::Z,
        cos_theta_o: -1.0,
        cos_theta_e: 0.0,
        two_sided: false,
    })
}

/// A node of 1 to 4 point lights (some of power 0) and the shading point of case `i`:
/// at the first light, right below it facing it (cos θ_i at 1, where rounding may pass
/// it), or anywhere.
fn point_case(next: &mut impl FnMut() -> f32, i: usize) -> Case {
    let mut node = WideNode::empty();
    let mut scalar = Vec::new();
    for l in 0..1 + i % LANES {
        let phi = if (i + l).is_multiple_of(11) {
            0.0
        } else {
            next().abs() * 10.0
        };
        let b = point(Vec3::new(next(), next(), next()) * 4.0, phi);
        assert!(b.is_point());
        node.set_bounds(l, &b);
        scalar.push(b);
    }
    node.mark_points(&scalar);
    assert!(node.points);
    let c = scalar[0].centre;
    let at = match i % 5 {
        0 => ShadingPoint {
            p: c,
            ng: Vec3::Y,
            n: Vec3::Y,
        },
        1 => {
            let up = Vec3::new(next(), next(), next()).normalize_or(Vec3::Y);
            ShadingPoint {
                p: c - up * (next().abs() * 3.0 + 1e-3),
                ng: up,
                n: up,
            }
        }
        _ => ShadingPoint {
            p: Vec3::new(next(), next(), next()) * 6.0,
            ng: Vec3::Y,
            n: Vec3::new(next(), next(), next()).normalize_or(Vec3::Y),
        },
    };
    (node, scalar, at)
}

/// Nodes of point lights take the short formula, bit for bit the scalar importance:
/// shading points anywhere, on a light, and right below one facing it (cos θ_i at 1,
/// where rounding may pass it); a node with one lane of another light does not.
#[test]
fn point_nodes_equal_the_scalar_importance_bit_for_bit() {
    let mut next = numbers(0x1234_5678_9abc_def1);
    let (mut nonzero, mut at_one) = (0, 0);
    for i in 0..50_000 {
        let (node, scalar, at) = point_case(&mut next, i);
        let c = scalar[0].centre;
        let (lanes, positive) = lanes_are_scalar(&node, &scalar, &at, i);
        nonzero += positive;
        if i % 5 == 1 && scalar[0].phi > 0.0 {
            at_one += (lanes[0] == scalar[0].phi / (at.p - c).length_squared()) as u32;
        }
    }
    assert!(nonzero > 20_000, "only {nonzero} lanes with importance");
    assert!(
        at_one > 1_000,
        "only {at_one} points straight below a light"
    );
    // A sphere light's bounds in one lane: the node takes the cones.
    let mut node = WideNode::empty();
    let sphere = PreparedBounds::new(&LightBounds {
        aabb: Aabb {
            min: Vec3::splat(-0.5),
            max: Vec3::splat(0.5),
        },
        phi: 1.0,
        w: Vec3::Z,
        cos_theta_o: -1.0,
        cos_theta_e: 0.0,
        two_sided: false,
    });
    node.mark_points(&[point(Vec3::ONE, 1.0), sphere]);
    assert!(!sphere.is_point() && !node.points);
    // Bounds that miss one condition each are not a point's: a degenerate area light
    // (θ_o = 0), no emission cone (θ_e = 0), an extent too small to square, an axis
    // that is not a number.
    let bounds = |min: Vec3, max: Vec3, cos_theta_o: f32, cos_theta_e: f32, w: Vec3| {
        PreparedBounds::new(&LightBounds {
            aabb: Aabb { min, max },
            phi: 1.0,
            w,
            cos_theta_o,
            cos_theta_e,
            two_sided: false,
        })
    };
    let (o, z) = (Vec3::ONE, Vec3::Z);
    assert!(bounds(o, o, -1.0, 0.0, z).is_point());
    for (i, b) in [
        bounds(o, o, 1.0, 0.0, z),
        bounds(o, o, -1.0, 1.0, z),
        bounds(Vec3::ZERO, Vec3::splat(1e-30), -1.0, 0.0, z),
        bounds(o, o, -1.0, 0.0, Vec3::NAN),
    ]
    .iter()
    .enumerate()
    {
        assert!(!b.is_point(), "case {i}: {b:?}");
    }
}

/// Two nodes' importances in one pass over eight AVX lanes ([`importance_pair`]) are
/// each node's four-lane importances bit for bit: pairs of general nodes, of point
/// nodes (the short formula) and of one of each (the full formula for the point node).
#[cfg(target_arch = "x86_64")]
#[test]
fn pairs_equal_the_four_lane_importances_bit_for_bit() {
    if !std::arch::is_x86_feature_detected!("avx2") {
        eprintln!("no AVX2: the pairs are never computed here");
        return;
    }
    let (mut general, mut points) = (numbers(0x9e37_79b9_7f4a_7c15), numbers(0x0dd_ba11));
    // Kinds general, general, point, point, …: every order of two kinds in a row.
    // Each kind's cases numbered on their own, so each has 1 to 4 lanes used.
    let (mut g, mut q) = (0, 0);
    let cases: Vec<Case> = (0..40_000)
        .map(|i| {
            if i % 4 < 2 {
                g += 1;
                general_case(&mut general, g)
            } else {
                q += 1;
                point_case(&mut points, q)
            }
        })
        .collect();
    let bits = |x: [f32; LANES]| x.map(f32::to_bits);
    let mut nonzero = [0; 4];
    for (k, pair) in cases.windows(2).enumerate() {
        let ((a, _, at_a), (b, _, at_b)) = (&pair[0], &pair[1]);
        // SAFETY: the processor has AVX2, checked above.
        let (ia, ib) = unsafe { importance_pair(a, at_a, b, at_b) };
        assert_eq!(bits(ia), bits(a.importance(at_a)), "pair {k}: first node");
        assert_eq!(bits(ib), bits(b.importance(at_b)), "pair {k}: second node");
        nonzero[k % 4] += ia.iter().chain(&ib).filter(|&&x| x > 0.0).count();
    }
    // Each order of kinds has lanes that contribute.
    assert!(nonzero.iter().all(|&n| n > 10_000), "{nonzero:?}");
}
