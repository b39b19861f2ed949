//! Triangulation of a simple planar polygon (convex or concave) by ear clipping
//! (Meisters 1975, "Polygons have ears"; Eberly, "Triangulation by Ear Clipping").

use glam::Vec2;

/// Twice the signed area of the polygon (shoelace formula); positive when counter-clockwise.
pub fn signed_area_2x(vertices: &[Vec2]) -> f32 {
    let n = vertices.len();
    (0..n)
        .map(|i| vertices[i].perp_dot(vertices[(i + 1) % n]))
        .sum()
}

/// Whether `p` lies in the closed triangle (a, b, c) of positive orientation.
fn in_triangle(p: Vec2, a: Vec2, b: Vec2, c: Vec2) -> bool {
    (b - a).perp_dot(p - a) >= 0.0
        && (c - b).perp_dot(p - b) >= 0.0
        && (a - c).perp_dot(p - c) >= 0.0
}

/// Index triples of n − 2 triangles covering the simple polygon `vertices` (either
/// orientation; triangles come out counter-clockwise in the polygon's own orientation),
/// or `None` if no ear can be found (a self-intersecting polygon). Collinear vertices
/// are clipped as zero-area ears. O(n³), meant for light-sized polygons.
pub fn triangulate(vertices: &[Vec2]) -> Option<Vec<[usize; 3]>> {
    let ccw = signed_area_2x(vertices) >= 0.0;
    // Work on a counter-clockwise index list.
    let mut ring: Vec<usize> = (0..vertices.len()).collect();
    if !ccw {
        ring.reverse();
    }
    let mut triangles = Vec::with_capacity(vertices.len().saturating_sub(2));
    while ring.len() > 3 {
        let n = ring.len();
        let corner = |i: usize| (ring[(i + n - 1) % n], ring[i], ring[(i + 1) % n]);
        let is_ear = |i: usize| {
            let (a, b, c) = corner(i);
            let (pa, pb, pc) = (vertices[a], vertices[b], vertices[c]);
            (pb - pa).perp_dot(pc - pb) > 0.0
                && ring.iter().all(|&j| {
                    j == a || j == b || j == c || {
                        let q = vertices[j];
                        q == pa || q == pb || q == pc || !in_triangle(q, pa, pb, pc)
                    }
                })
        };
        let is_flat = |i: usize| {
            let (a, b, c) = corner(i);
            (vertices[b] - vertices[a]).perp_dot(vertices[c] - vertices[b]) == 0.0
        };
        let i = (0..n)
            .find(|&i| is_ear(i))
            .or_else(|| (0..n).find(|&i| is_flat(i)))?;
        let (a, b, c) = corner(i);
        triangles.push([a, b, c]);
        ring.remove(i);
    }
    triangles.push([ring[0], ring[1], ring[2]]);
    if !ccw {
        for t in &mut triangles {
            t.swap(1, 2);
        }
    }
    Some(triangles)
}

/// Whether `p` is inside the polygon by the crossing-number (even–odd) rule.
pub fn contains(vertices: &[Vec2], p: Vec2) -> bool {
    let n = vertices.len();
    let mut inside = false;
    for i in 0..n {
        let (a, b) = (vertices[i], vertices[(i + 1) % n]);
        if (a.y > p.y) != (b.y > p.y) {
            let x = a.x + (p.y - a.y) / (b.y - a.y) * (b.x - a.x);
            if p.x < x {
                inside = !inside;
            }
        }
    }
    inside
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn concave_polygons_are_covered_exactly() {
        let l_shape = [
            (0.0, 0.0),
            (2.0, 0.0),
            (2.0, 1.0),
            (1.0, 1.0),
            (1.0, 2.0),
            (0.0, 2.0),
        ];
        let comb = [
            (0.0, 0.0),
            (3.0, 0.0),
            (3.0, 2.0),
            (2.0, 1.0),
            (1.5, 2.0),
            (1.0, 1.0),
            (0.0, 2.0),
        ];
        for shape in [&l_shape[..], &comb[..]] {
            for reversed in [false, true] {
                let mut v: Vec<Vec2> = shape.iter().map(|&(x, y)| Vec2::new(x, y)).collect();
                if reversed {
                    v.reverse();
                }
                let tris = triangulate(&v).expect("simple polygon");
                assert_eq!(tris.len(), v.len() - 2);
                let area: f32 = tris
                    .iter()
                    .map(|t| signed_area_2x(&[v[t[0]], v[t[1]], v[t[2]]]))
                    .sum();
                assert!((area - signed_area_2x(&v)).abs() < 1e-5, "{area}");
                for t in &tris {
                    let centroid = (v[t[0]] + v[t[1]] + v[t[2]]) / 3.0;
                    assert!(contains(&v, centroid), "triangle {t:?} outside");
                }
            }
        }
    }
}
