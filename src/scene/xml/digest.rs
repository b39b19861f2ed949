//! The content hash of a scene file: the element tree after includes and `$name`
//! substitution (tags and attributes in document order, not their file positions), and
//! the bytes of every file a `filename` property names (meshes, textures, environment
//! maps). Two renders whose hashes agree rendered the same scene, whatever the paths or
//! the include structure that produced it.

use super::tree::Element;
use crate::sampling::rng::hash_bytes;

/// The content hash of the scene rooted at `root`.
pub fn digest(root: &Element) -> u64 {
    let mut h = 0x6c69_6768_746c_6162; // "lightlab"
    walk(root, &mut h);
    h
}

fn walk(el: &Element, h: &mut u64) {
    *h = hash_bytes(*h, el.tag.as_bytes());
    for (key, value) in &el.attrs {
        *h = hash_bytes(*h, key.as_bytes());
        *h = hash_bytes(*h, value.as_bytes());
    }
    if el.tag == "string"
        && el.attr("name") == Some("filename")
        && let Some(file) = el.attr("value")
    {
        // A file that cannot be read fails the scene's loading; its name stands in here.
        match std::fs::read(el.dir.join(file)) {
            Ok(bytes) => *h = hash_bytes(*h, &bytes),
            Err(_) => *h = hash_bytes(*h, b"<unreadable>"),
        }
    }
    *h = hash_bytes(*h, &(el.children.len() as u64).to_le_bytes());
    for child in &el.children {
        walk(child, h);
    }
}
