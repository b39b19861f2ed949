//! Built-in scenes: each is a figure the lecture draws, so students can reproduce it.

mod assignment;
mod envmap;
mod materials;
pub mod shirley100;
pub mod sphere_near_plane;
mod stage;
mod variance_sources;
mod veach_mis;

use super::{Scene, SceneError};

/// A built-in scene: its name, what it shows, and its builder.
pub struct Builtin {
    /// Name after `builtin:`.
    pub name: &'static str,
    /// One line on what the scene shows.
    pub description: &'static str,
    /// Builds the scene.
    pub build: fn() -> Result<Scene, SceneError>,
}

/// Every built-in scene; the first is the default scene.
pub const BUILTINS: &[Builtin] = &[
    Builtin {
        name: "assignment",
        description: "one small area light over diffuse and Phong (n = 10, 100, 1000) spheres: hemisphere vs BRDF vs light sampling",
        build: assignment::build,
    },
    Builtin {
        name: "sphere-near-plane",
        description: "a sphere light just above a diffuse floor, a grazing rectangle light and an emitting octahedron: where G varies most",
        build: sphere_near_plane::build,
    },
    Builtin {
        name: "veach-mis",
        description: "Veach's four plates of rising gloss (Phong n = 30 … 30000) and four equal-power sphere lights: light vs BSDF sampling vs MIS",
        build: veach_mis::build,
    },
    Builtin {
        name: "envmap",
        description: "diffuse and glossy spheres under a procedural sky with a small, very bright sun: environment-map sampling",
        build: envmap::build,
    },
    Builtin {
        name: "shirley-100",
        description: "a hundred luminaires (spheres and quads, radiances over two decades) over a floor with objects: light selection",
        build: shirley100::build,
    },
    Builtin {
        name: "many-lights",
        description: "the shirley-100 generator with N luminaires: many-lights?n=N, 1 ≤ N ≤ 10⁶ (default 1000)",
        build: shirley100::build_default_many,
    },
    Builtin {
        name: "variance-sources",
        description: "the lecture's three sources of variance in one view: a glossy Phong sphere, a sphere light just above the floor, a shadow boundary under a floating ball",
        build: variance_sources::build,
    },
    Builtin {
        name: "materials",
        description: "smooth and rough conductors and plastics (Mitsuba 3's models) under one area light",
        build: materials::build,
    },
];

/// The scene `render` draws when none is given.
pub const DEFAULT_SCENE: &str = "builtin:assignment";

/// Builds the built-in scene `name`; `many-lights?n=N` takes the luminaire count.
pub fn build(name: &str) -> Result<Scene, SceneError> {
    if let Some((base, query)) = name.split_once('?') {
        return build_with_query(name, base, query);
    }
    match BUILTINS.iter().find(|b| b.name == name) {
        Some(b) => (b.build)(),
        None => {
            let known: Vec<_> = BUILTINS.iter().map(|b| b.name).collect();
            Err(SceneError::new(
                format!("builtin:{name}"),
                None,
                format!("unknown built-in scene (known: {})", known.join(", ")),
            ))
        }
    }
}

/// `NAME?key=value`: `many-lights?n=N` (luminaire count) and
/// `sphere-near-plane?emitters=A,B` (a subset of sphere, rectangle, mesh, polygon, disk).
fn build_with_query(spec: &str, base: &str, query: &str) -> Result<Scene, SceneError> {
    let err = |m: String| SceneError::new(format!("builtin:{spec}"), None, m);
    if base == "sphere-near-plane" {
        return near_plane_with_query(query).map_err(err);
    }
    if base != "many-lights" {
        return Err(err(format!(
            "built-in scene \"{base}\" takes no parameters (only many-lights?n=N and \
             sphere-near-plane?emitters=LIST do)"
        )));
    }
    let Some(value) = query.strip_prefix("n=") else {
        return Err(err(format!(
            "unknown parameter \"{query}\": expected n=N, e.g. many-lights?n=10000"
        )));
    };
    let n: usize = value.trim().parse().map_err(|_| {
        err(format!(
            "n = \"{value}\" is not a whole number (1 ≤ n ≤ {})",
            shirley100::MAX_LUMINAIRES
        ))
    })?;
    shirley100::build_many(n)
}

/// `sphere-near-plane?emitters=rectangle,polygon`: the floor and camera with only the
/// named emitters, to measure one shape's strategies at a time.
fn near_plane_with_query(query: &str) -> Result<Scene, String> {
    use sphere_near_plane::NearPlaneEmitter as E;
    let list = query.strip_prefix("emitters=").ok_or_else(|| {
        format!("unknown parameter \"{query}\": expected emitters=LIST, e.g. emitters=sphere,mesh")
    })?;
    let emitters = list
        .split(',')
        .map(|name| match name.trim() {
            "sphere" => Ok(E::Sphere),
            "rectangle" => Ok(E::Rectangle),
            "mesh" => Ok(E::Mesh),
            "polygon" => Ok(E::Polygon),
            "disk" => Ok(E::Disk),
            other => Err(format!(
                "unknown emitter \"{other}\" (known: sphere, rectangle, mesh, polygon, disk)"
            )),
        })
        .collect::<Result<Vec<_>, _>>()?;
    sphere_near_plane::build_with(&emitters).map_err(|e| e.to_string())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn many_lights_takes_its_count_and_rejects_bad_ones() {
        let scene = build("many-lights?n=250").expect("scene");
        assert_eq!(scene.lights.len(), 250);
        assert_eq!(build("shirley-100").expect("scene").lights.len(), 100);
        let one = build("sphere-near-plane?emitters=polygon").expect("scene");
        assert_eq!(one.lights.len(), 1);
        for bad in [
            "many-lights?n=0",
            "many-lights?n=-3",
            "many-lights?n=x",
            "many-lights?n=2000000",
            "many-lights?m=3",
            "assignment?n=3",
            "sphere-near-plane?emitters=cube",
            "sphere-near-plane?n=3",
        ] {
            let e = build(bad).expect_err(bad);
            assert!(e.to_string().contains("many-lights") || e.to_string().contains("n"));
        }
    }
}
