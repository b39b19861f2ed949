//! Registry rows for the warps, with the parameters each is tested at (Phong exponents,
//! cone angles, spherical shapes seen from near, far and grazing points).

use glam::{Vec2, Vec3};

use super::{Draw, Entry, Family, boxed};
use crate::sampling::Rng32;
use crate::sampling::chi2::Domain;
use crate::sampling::warp::*;

fn entry(
    name: &str,
    description: &str,
    domain: Domain,
    draw: Draw,
    pdf: Box<dyn Fn(Vec3) -> f32>,
) -> Entry {
    Entry {
        name: name.into(),
        description: description.into(),
        family: Family::Warp,
        domain,
        draw,
        pdf,
        inverse: None,
        samples: 1_000_000,
        resolution: None,
    }
}

fn with_inverse(mut e: Entry, inverse: Box<dyn Fn(Vec3) -> Vec2>) -> Entry {
    e.inverse = Some(inverse);
    e
}

fn square(f: impl Fn(Vec2) -> (Vec3, f32) + 'static) -> Draw {
    Draw::Square(boxed(f))
}

fn stream(f: impl Fn(&mut Rng32) -> (Vec3, f32) + 'static) -> Draw {
    Draw::Stream(Box::new(f))
}

fn flat(p: Vec2) -> Vec3 {
    p.extend(0.0)
}

/// The smallest cap around the mean direction that holds the outline through `points`
/// (seen from `from`), sampled densely along each edge, with a small margin.
fn cap_around(from: Vec3, points: &[Vec3]) -> Domain {
    let dirs: Vec<Vec3> = (0..points.len())
        .flat_map(|i| {
            let (a, b) = (points[i], points[(i + 1) % points.len()]);
            (0..64).map(move |k| (a + (b - a) * (k as f32 / 64.0) - from).normalize())
        })
        .collect();
    let axis = dirs.iter().copied().sum::<Vec3>().normalize();
    let z_min = dirs.iter().map(|d| d.dot(axis)).fold(1.0f32, f32::min);
    Domain::cap(axis, 1.0 - (1.0 - z_min) * 1.02)
}

fn basic_entries() -> Vec<Entry> {
    vec![
        with_inverse(
            entry(
                "sphere-uniform",
                "uniform sphere by (z, phi)",
                Domain::sphere(),
                square(square_to_uniform_sphere),
                boxed(uniform_sphere_pdf),
            ),
            boxed(uniform_sphere_to_square),
        ),
        entry(
            "sphere-cube-rejection",
            "uniform sphere by rejection from the cube",
            Domain::sphere(),
            stream(cube_rejection_to_sphere),
            boxed(uniform_sphere_pdf),
        ),
        with_inverse(
            entry(
                "hemisphere-uniform",
                "uniform hemisphere by (z, phi)",
                Domain::hemisphere(),
                square(square_to_uniform_hemisphere),
                boxed(uniform_hemisphere_pdf),
            ),
            boxed(uniform_hemisphere_to_square),
        ),
        entry(
            "hemisphere-cube-rejection",
            "uniform hemisphere by rejection from the cube",
            Domain::hemisphere(),
            stream(cube_rejection_to_hemisphere),
            boxed(uniform_hemisphere_pdf),
        ),
        with_inverse(
            entry(
                "hemisphere-theta-phi",
                "uniform (theta, phi): crowds the pole, true pdf 1/(pi^2 sin theta)",
                Domain::hemisphere(),
                square(square_to_theta_phi_hemisphere),
                boxed(theta_phi_hemisphere_pdf),
            ),
            boxed(theta_phi_hemisphere_to_square),
        ),
        with_inverse(
            entry(
                "cosine-concentric",
                "cosine hemisphere by Malley over the concentric disk",
                Domain::hemisphere(),
                square(square_to_cosine_hemisphere),
                boxed(cosine_hemisphere_pdf),
            ),
            boxed(cosine_hemisphere_to_square),
        ),
        entry(
            "cosine-malley-rejection",
            "cosine hemisphere by Malley over the rejection disk",
            Domain::hemisphere(),
            stream(malley_rejection_hemisphere),
            boxed(cosine_hemisphere_pdf),
        ),
        with_inverse(
            entry(
                "disk-polar",
                "uniform disk by r = sqrt(u0), phi = 2 pi u1",
                Domain::square(-1.0, 1.0),
                square(|u| {
                    (
                        flat(square_to_uniform_disk_polar(u)),
                        uniform_disk_pdf(square_to_uniform_disk_polar(u)),
                    )
                }),
                boxed(|x: Vec3| uniform_disk_pdf(x.truncate())),
            ),
            boxed(|x: Vec3| uniform_disk_polar_to_square(x.truncate())),
        ),
        with_inverse(
            entry(
                "disk-concentric",
                "uniform disk by Shirley-Chiu concentric map",
                Domain::square(-1.0, 1.0),
                square(|u| {
                    let p = square_to_uniform_disk_concentric(u);
                    (flat(p), uniform_disk_pdf(p))
                }),
                boxed(|x: Vec3| uniform_disk_pdf(x.truncate())),
            ),
            boxed(|x: Vec3| uniform_disk_concentric_to_square(x.truncate())),
        ),
        entry(
            "disk-rejection",
            "uniform disk by rejection from the square",
            Domain::square(-1.0, 1.0),
            stream(|r| {
                let p = disk_rejection(r);
                (flat(p), uniform_disk_pdf(p))
            }),
            boxed(|x: Vec3| uniform_disk_pdf(x.truncate())),
        ),
        with_inverse(
            entry(
                "xi-squared",
                "the lecture's x = u^2, pdf 1/(2 sqrt x)",
                Domain::UNIT_INTERVAL,
                square(|u| {
                    let (x, p) = uniform_to_xi_squared(u.x);
                    (Vec3::new(x, 0.0, 0.0), p)
                }),
                boxed(|x: Vec3| xi_squared_pdf(x.x)),
            ),
            boxed(|x: Vec3| Vec2::new(xi_squared_to_uniform(x.x), 0.0)),
        ),
        with_inverse(
            entry(
                "bilinear",
                "density ∝ bilinear weights 0.05, 1, 2, 0.5 at the corners (Hart et al. 2020)",
                Domain::UNIT_SQUARE,
                square(|u| {
                    let (p, pdf) = square_to_bilinear(u, BILINEAR_TEST_WEIGHTS);
                    (flat(p), pdf)
                }),
                boxed(|x: Vec3| bilinear_pdf(x.truncate(), BILINEAR_TEST_WEIGHTS)),
            ),
            boxed(|x: Vec3| bilinear_to_square(x.truncate(), BILINEAR_TEST_WEIGHTS)),
        ),
    ]
}

/// Corner weights of the registry's bilinear row: uneven, one nearly zero.
const BILINEAR_TEST_WEIGHTS: [f32; 4] = [0.05, 1.0, 2.0, 0.5];

fn lobe_entries() -> Vec<Entry> {
    let mut list = Vec::new();
    list.extend([1.0f32, 10.0, 100.0, 1000.0].map(phong_entry));
    list.extend([1.0f32, 30.0, 90.0, 150.0].map(cone_entry));
    list
}

/// The Phong lobe cosⁿ θ (`phong-N`, any exponent n ≥ 0: `lightlab warp phong-37`).
pub(super) fn phong_entry(n: f32) -> Entry {
    // A cap holding all but 10⁻⁴ of the lobe: P(cos θ < z) = z^(n+1).
    let z_min = if n < 50.0 {
        0.0
    } else {
        1e-4f32.powf(1.0 / (n + 1.0))
    };
    let e = entry(
        &format!("phong-{n}"),
        &format!("Phong lobe cos^{n}: theta = arccos u0^(1/(n+1))"),
        Domain::cap(Vec3::Z, z_min),
        square(move |u| square_to_phong_lobe(u, n)),
        boxed(move |w| phong_lobe_pdf(w, n)),
    );
    with_inverse(e, boxed(move |w| phong_lobe_to_square(w, n)))
}

/// The uniform cone of half-angle `degrees` (`cone-D`, 0 < D ≤ 180: `lightlab warp
/// cone-12`).
pub(super) fn cone_entry(degrees: f32) -> Entry {
    let cos_max = degrees.to_radians().cos();
    let e = entry(
        &format!("cone-{degrees}"),
        &format!("uniform cone of half-angle {degrees} degrees"),
        Domain::cap(Vec3::Z, cos_max),
        square(move |u| square_to_uniform_cone(u, cos_max)),
        boxed(move |w| uniform_cone_pdf(w, cos_max)),
    );
    with_inverse(e, boxed(move |w| uniform_cone_to_square(w, cos_max)))
}

fn planar_entries() -> Vec<Entry> {
    let (p0, p1, p2) = (
        Vec3::new(0.5, -0.2, 0.1),
        Vec3::new(2.0, 0.3, 0.6),
        Vec3::new(0.2, 1.4, -0.3),
    );
    let triangle = Domain::Plane {
        origin: p0,
        edge_u: p1 - p0,
        edge_v: p2 - p0,
    };
    let on_triangle = move |b: Vec2| sample_triangle(p0, p1, p2, b).unwrap_or((p0, 0.0));
    let pdf = move || boxed(move |x: Vec3| triangle_pdf(p0, p1, p2, x));
    let mut list = vec![
        entry(
            "triangle-rejection",
            "uniform triangle: barycentrics by rejection (a + b < 1)",
            triangle,
            stream(move |r| on_triangle(triangle_rejection(r))),
            pdf(),
        ),
        entry(
            "triangle-fold",
            "uniform triangle: fold (a, b) -> (1 - a, 1 - b) above the diagonal",
            triangle,
            square(move |u| on_triangle(square_to_triangle_fold(u))),
            pdf(),
        ),
        with_inverse(
            entry(
                "triangle-sqrt",
                "uniform triangle: square-root map (b1, b2) = sqrt(u0)(1 - u1, u1)",
                triangle,
                square(move |u| on_triangle(square_to_triangle_sqrt(u))),
                pdf(),
            ),
            boxed(move |x| triangle_sqrt_to_square(triangle_to_barycentrics(p0, p1, p2, x))),
        ),
    ];
    let (a, b, d) = (
        Vec3::new(-1.0, 0.0, 0.5),
        Vec3::new(1.0, 0.5, 0.0),
        Vec3::new(-0.5, 1.0, 1.5),
    );
    list.push(with_inverse(
        entry(
            "parallelogram",
            "uniform parallelogram a + u0 (b - a) + u1 (d - a)",
            Domain::Plane {
                origin: a,
                edge_u: b - a,
                edge_v: d - a,
            },
            square(move |u| square_to_parallelogram(a, b, d, u).unwrap_or((a, 0.0))),
            boxed(move |x| parallelogram_pdf(a, b, d, x)),
        ),
        boxed(move |x| parallelogram_to_square(a, b, d, x)),
    ));
    // Polygons in a tilted plane: an L (concave) and an octagon (convex).
    let (origin, eu, ev) = (
        Vec3::new(0.2, 0.1, -0.3),
        Vec3::new(1.0, 0.2, 0.3),
        Vec3::new(-0.1, 0.8, 0.4),
    );
    let l_shape = [(0., 0.), (2., 0.), (2., 1.), (1., 1.), (1., 2.), (0., 2.)];
    let octagon = [
        (1., 0.),
        (2., 0.),
        (3., 1.),
        (3., 2.),
        (2., 3.),
        (1., 3.),
        (0., 2.),
        (0., 1.),
    ];
    for (shape, outline, size) in [("l", &l_shape[..], 2.0), ("octagon", &octagon[..], 3.0)] {
        let vertices: Vec<Vec3> = outline
            .iter()
            .map(|&(s, t)| origin + s * eu + t * ev)
            .collect();
        let Ok(polygon) = Polygon::new(&vertices) else {
            continue;
        };
        let domain = Domain::Plane {
            origin,
            edge_u: eu * size,
            edge_v: ev * size,
        };
        let (p1, p2, p3, p4) = (polygon.clone(), polygon.clone(), polygon.clone(), polygon);
        list.push(entry(
            &format!("polygon-{shape}-rejection"),
            "uniform planar polygon by rejection from its bounding rectangle",
            domain,
            stream(move |r| p1.sample_rejection(r)),
            boxed(move |x| p2.pdf(x)),
        ));
        list.push(entry(
            &format!("polygon-{shape}-triangulated"),
            "uniform planar polygon by area-weighted ear-clipped triangles",
            domain,
            square(move |u| p3.sample_triangulated(u)),
            boxed(move |x| p4.pdf(x)),
        ));
    }
    list
}

fn spherical_entries() -> Vec<Entry> {
    let mut list = Vec::new();
    // (case, shading point, a triangle's vertices / a rectangle's corner and edges)
    let cases = [
        (
            "near",
            Vec3::ZERO,
            [
                Vec3::new(-1.0, -0.5, 0.3),
                Vec3::new(1.2, -0.8, 0.5),
                Vec3::new(0.2, 1.0, 0.4),
            ],
        ),
        (
            "far",
            Vec3::new(0.3, -0.2, -60.0),
            [
                Vec3::new(-0.5, -0.4, 1.0),
                Vec3::new(0.6, -0.3, 1.2),
                Vec3::new(0.1, 0.7, 0.8),
            ],
        ),
        (
            "grazing",
            Vec3::new(0.0, 0.0, 0.25),
            [
                Vec3::new(1.0, -1.0, 0.0),
                Vec3::new(1.0, 1.0, 0.0),
                Vec3::new(2.5, 0.0, 0.0),
            ],
        ),
    ];
    for (case, from, [v0, v1, v2]) in cases {
        let Some(t) = SphericalTriangle::new(from, v0, v1, v2) else {
            continue;
        };
        let e = entry(
            &format!("spherical-triangle-{case}"),
            &format!(
                "triangle uniform in solid angle (Arvo 1995), {case} view, {:.2e} sr",
                t.solid_angle()
            ),
            cap_around(from, &[v0, v1, v2]),
            square(move |u| t.sample(u)),
            boxed(move |w| t.pdf(w)),
        );
        list.push(with_inverse(e, boxed(move |w| t.to_square(w))));
        // The renderer's fast path of the same map (no libm trigonometry).
        if let Some(f) = FastSphericalTriangle::new(from, v0, v1, v2) {
            list.push(entry(
                &format!("spherical-triangle-fast-{case}"),
                &format!(
                    "the renderer's fast path of spherical-triangle (no libm atan2, sin_cos), {case} view, {:.2e} sr",
                    f.solid_angle()
                ),
                cap_around(from, &[v0, v1, v2]),
                square(move |u| {
                    let w = f.sample(u).0;
                    (w, f.pdf(w))
                }),
                boxed(move |w| f.pdf(w)),
            ));
        }
        // A rectangle on the triangle's first two edges' plane: corner v0, edges along v1 − v0 and its perpendicular.
        let ex = v1 - v0;
        let ey = (v2 - v0) - (v2 - v0).dot(ex) / ex.length_squared() * ex;
        let corners = [v0, v0 + ex, v0 + ex + ey, v0 + ey];
        let Some(r) = SphericalRectangle::new(from, v0, ex, ey) else {
            continue;
        };
        let e = entry(
            &format!("spherical-rectangle-{case}"),
            &format!(
                "rectangle uniform in solid angle (Urena et al. 2013), {case} view, {:.2e} sr",
                r.solid_angle()
            ),
            cap_around(from, &corners),
            square(move |u| r.sample(u)),
            boxed(move |w| r.pdf(w)),
        );
        list.push(with_inverse(e, boxed(move |w| r.to_square(w))));
        // The renderer's fast path of the same map (no inverse of its own).
        let Some(f) = FastSphericalRectangle::new(from, v0, ex, ey) else {
            continue;
        };
        list.push(entry(
            &format!("spherical-rectangle-fast-{case}"),
            &format!(
                "the renderer's fast path of spherical-rectangle (no f64 acos), {case} view, {:.2e} sr",
                f.solid_angle()
            ),
            cap_around(from, &corners),
            // As for the f64 map: a far edge point's f32 direction may round to just
            // outside, and its density is what `pdf` says of the direction returned.
            square(move |u| {
                let w = f.sample(u).0;
                (w, f.pdf(w))
            }),
            boxed(move |w| f.pdf(w)),
        ));
    }
    list
}

/// Convex outlines sampled ∝ cos θ (projected solid angle): near, far, cut by the
/// horizon, and around the zenith.
fn projected_entries() -> Vec<Entry> {
    let near = [
        Vec3::new(-1.0, -0.5, 0.3),
        Vec3::new(1.2, -0.8, 0.5),
        Vec3::new(0.2, 1.0, 0.4),
    ];
    let far_rectangle = [
        Vec3::new(-0.5, -0.4, 1.0),
        Vec3::new(0.6, -0.4, 1.0),
        Vec3::new(0.6, 0.5, 1.2),
        Vec3::new(-0.5, 0.5, 1.2),
    ];
    let grazing = [
        Vec3::new(1.0, -1.0, 0.0),
        Vec3::new(1.0, 1.0, 0.0),
        Vec3::new(2.5, 0.0, 0.0),
    ];
    let around_zenith = [
        Vec3::new(-0.3, -0.6, 0.5),
        Vec3::new(0.7, -0.6, 0.5),
        Vec3::new(0.7, 0.4, 0.5),
        Vec3::new(-0.3, 0.4, 0.5),
    ];
    let cases: [(&str, Vec3, Vec3, &[Vec3]); 4] = [
        ("triangle-near", Vec3::ZERO, Vec3::Z, &near),
        (
            "rectangle-far",
            Vec3::new(0.3, -0.2, -60.0),
            Vec3::Z,
            &far_rectangle,
        ),
        (
            "triangle-horizon",
            Vec3::new(0.0, 0.0, 0.25),
            Vec3::new(0.2, 0.0, 1.0).normalize(),
            &grazing,
        ),
        ("rectangle-zenith", Vec3::ZERO, Vec3::Z, &around_zenith),
    ];
    let mut list = Vec::new();
    for (case, from, normal, outline) in cases {
        let vertices: Vec<_> = outline.iter().map(|v| v.as_dvec3()).collect();
        let Some(p) = ProjectedPolygon::new(from.as_dvec3(), normal.as_dvec3(), &vertices) else {
            continue;
        };
        let description = format!(
            "convex polygon ∝ cos θ above the horizon (projected solid angle, after Peters 2021), {case}, Ω⊥ {:.2e} sr",
            p.projected_solid_angle()
        );
        let q = p.clone();
        list.push(entry(
            &format!("projected-polygon-{case}"),
            &description,
            cap_around(from, outline),
            // The density is what `pdf` says of the f32 direction returned.
            square(move |u| {
                let w = p.sample(u.as_dvec2()).0.as_vec3();
                (w, p.pdf(w.as_dvec3()) as f32)
            }),
            boxed(move |w: Vec3| q.pdf(w.as_dvec3()) as f32),
        ));
    }
    list
}

pub(super) fn entries() -> Vec<Entry> {
    let mut list = basic_entries();
    list.extend(projected_entries());
    list.extend(lobe_entries());
    list.extend(planar_entries());
    list.extend(spherical_entries());
    list
}
