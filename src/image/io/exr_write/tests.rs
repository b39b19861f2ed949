//! The writer against the `exr` crate's reader (its own ZIP decoder): every channel's
//! bits, the header's attributes, blocks stored compressed and raw, long and non-Latin
//! names and values (the long-names flag from 32 bytes), and the names a text attribute
//! may not take; the layout of a one-pixel file and every header value in it (the
//! pixel data through the reader), and the same bytes on any number of threads.

use super::*;
use crate::image::io::read_image;
use crate::math::Spectrum;
use crate::sampling::rng::Rng32;
use exr::prelude::{AttributeValue, Compression, LineOrder, Text, read_all_flat_layers_from_file};

/// A film of `width`×`height` whose pixels hold `count` samples each, multiples of 1/16
/// in [0, 1) drawn from the stream `seed` (so that its blocks compress).
fn film(width: u32, height: u32, count: u32, seed: u64) -> Film {
    let mut rng = Rng32::new(seed);
    let mut film = Film::new(width, height);
    for p in film.pixels.iter_mut() {
        for _ in 0..count {
            let mut value = || (rng.next_u32() >> 28) as f32 / 16.0;
            p.add(Spectrum::new(value(), value(), value()));
        }
    }
    film
}

/// A film whose means and squared deviations have random bits (signs and exponents too,
/// finite), which no compression can shorten.
fn wild_film(width: u32, height: u32, seed: u64) -> Film {
    let mut rng = Rng32::new(seed);
    let mut film = Film::new(width, height);
    for p in film.pixels.iter_mut() {
        let mut value = || f32::from_bits(rng.next_u32() & 0xbf7f_ffff);
        p.mean = Spectrum::new(value(), value(), value());
        p.m2 = Spectrum::new(value(), value(), value()).abs();
        (p.count, p.weight, p.weight2) = (2, 2.0, 2.0);
    }
    film
}

/// A scratch folder of one test, removed with everything in it when dropped.
struct Scratch(std::path::PathBuf);

impl Scratch {
    fn new(test: &str) -> Scratch {
        let name = format!("lightlab-exr-{}-{test}", std::process::id());
        let dir = std::env::temp_dir().join(name);
        std::fs::create_dir_all(&dir).unwrap();
        Scratch(dir)
    }

    fn file(&self, name: &str) -> std::path::PathBuf {
        self.0.join(name)
    }
}

impl Drop for Scratch {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

/// Every channel of every pixel as the `exr` crate reads it, in the file's channel order.
fn read_channels(path: &Path) -> Vec<Vec<u32>> {
    let image = read_all_flat_layers_from_file(path).unwrap();
    let layer = &image.layer_data[0];
    let names: Vec<String> = layer
        .channel_data
        .list
        .iter()
        .map(|c| c.name.to_string())
        .collect();
    let expected: Vec<&str> = CHANNELS.iter().map(|c| c.0).collect();
    assert_eq!(names, expected);
    layer
        .channel_data
        .list
        .iter()
        .map(|c| c.sample_data.values_as_f32().map(f32::to_bits).collect())
        .collect()
}

/// Each channel's bits as the film holds them, found by the channel's name (apart from
/// the writer's own [`values`]).
fn expected_channels(film: &Film) -> Vec<Vec<u32>> {
    let value = |name: &str, p: &PixelStats| {
        let (s, axis) = match name.strip_prefix("variance.") {
            Some(axis) => (p.variance_of_mean(), axis),
            None => (p.mean, name),
        };
        match axis {
            "R" => s.x,
            "G" => s.y,
            _ => s.z,
        }
    };
    CHANNELS
        .iter()
        .map(|(name, _)| {
            film.pixels
                .iter()
                .map(|p| value(name, p).to_bits())
                .collect()
        })
        .collect()
}

/// The data size a chunk declares (after its row, before its data).
fn stored_size(chunk: &[u8]) -> usize {
    i32::from_le_bytes(chunk[4..8].try_into().unwrap()) as usize
}

#[test]
fn every_channel_reads_back_bit_for_bit_over_many_blocks() {
    // 53 rows: three whole blocks of 16 and a last one of 5.
    let film = film(37, 53, 3, 7);
    for y in (0..53).step_by(ROWS) {
        let rows = &film.pixels[y * 37..(y + ROWS).min(53) * 37];
        let size = stored_size(&chunk(rows, 37, y).unwrap());
        assert!(
            size < rows.len() * 4 * CHANNELS.len(),
            "block {y} is compressed"
        );
    }
    let scratch = Scratch::new("blocks");
    let path = scratch.file("blocks.exr");
    write_exr(&film, &path, &[]).unwrap();
    assert_eq!(read_channels(&path), expected_channels(&film));
    let meta = exr::meta::MetaData::read_from_file(&path, false).unwrap();
    let header = &meta.headers[0];
    assert_eq!(header.compression, Compression::ZIP16);
    assert_eq!(header.line_order, LineOrder::Increasing);
    assert_eq!(header.chunk_count, 4);
    assert_eq!(
        (header.layer_size.width(), header.layer_size.height()),
        (37, 53)
    );
    let software = header.own_attributes.software_name.as_ref();
    assert_eq!(software.map(|t| t.to_string()).as_deref(), Some("lightlab"));
    let spp = header.own_attributes.other.get(&Text::from("spp"));
    assert_eq!(spp, Some(&AttributeValue::I32(3)));
    let loaded = read_image(&path).unwrap();
    assert_eq!(loaded.rgb, film.means());
    assert_eq!(loaded.spp, Some(3));
}

#[test]
fn blocks_that_do_not_compress_are_stored_as_they_are() {
    let film = wild_film(16, 20, 99);
    let rows = &film.pixels[..16 * 16];
    assert_eq!(
        stored_size(&chunk(rows, 16, 0).unwrap()),
        16 * 16 * 4 * CHANNELS.len(),
        "random bits stay raw"
    );
    let smooth = self::film(16, 16, 1, 5);
    assert!(
        stored_size(&chunk(&smooth.pixels, 16, 0).unwrap()) < 16 * 16 * 4 * CHANNELS.len(),
        "smooth values compress"
    );
    let scratch = Scratch::new("raw");
    let path = scratch.file("raw.exr");
    write_exr(&film, &path, &[]).unwrap();
    assert_eq!(read_channels(&path), expected_channels(&film));
}

#[test]
fn text_attributes_round_trip_in_utf8_with_long_names() {
    let film = film(3, 2, 4, 1);
    let scratch = Scratch::new("text");
    let path = scratch.file("text.exr");
    let long = "lightlab.a-name-longer-than-thirty-one-bytes".to_string();
    let meta = vec![
        (
            "lightlab.scene".to_string(),
            "/tmp/日本/scène.xml".to_string(),
        ),
        (long, "x".to_string()),
        ("lightlab.empty".to_string(), String::new()),
    ];
    write_exr(&film, &path, &meta).unwrap();
    let mut sorted = meta.clone();
    sorted.sort();
    assert_eq!(read_image(&path).unwrap().metadata, sorted);
}

#[test]
fn names_a_text_attribute_may_not_take_are_errors() {
    let film = film(2, 2, 1, 1);
    let scratch = Scratch::new("names");
    let path = scratch.file("names.exr");
    let too_long = "n".repeat(MAX_NAME + 1);
    let refused = [
        "",
        "spp",
        "channels",
        "software",
        "chunkCount",
        "type",
        "name",
    ];
    let typed = [
        "owner",
        "comments",
        "capDate",
        "wrapmodes",
        "renderingTransform",
    ];
    for name in refused
        .into_iter()
        .chain(typed)
        .chain(["a\0b", too_long.as_str()])
    {
        let meta = [(name.to_string(), "v".to_string())];
        let err = write_exr(&film, &path, &meta).unwrap_err();
        assert!(err.message.contains("attribute name"), "{name:?}: {err}");
    }
    assert!(!path.exists(), "no file is written for a refused header");
    for (w, h) in [(0, 2), (2, 0), (u32::MAX / 64, 1), (3, 3)] {
        let film = Film {
            width: w,
            height: h,
            pixels: Vec::new(),
        };
        let err = write_exr(&film, &path, &[]).unwrap_err();
        assert!(err.message.contains("cannot write a"), "{w}x{h}: {err}");
    }
    assert!(!path.exists());
}

/// The version field of the file at `path` (bit 10: names longer than 31 bytes).
fn version_field(path: &Path) -> u32 {
    let bytes = std::fs::read(path).unwrap();
    u32::from_le_bytes(bytes[4..8].try_into().unwrap())
}

#[test]
fn the_long_names_flag_is_set_from_32_bytes() {
    let film = film(2, 2, 1, 3);
    let scratch = Scratch::new("long");
    let path = scratch.file("long.exr");
    for (len, flag) in [(31, 0), (32, 1 << 10)] {
        let name = format!("lightlab.{}", "n".repeat(len - 9));
        assert_eq!(name.len(), len);
        write_exr(&film, &path, &[(name.clone(), "v".to_string())]).unwrap();
        assert_eq!(version_field(&path), 2 | flag, "a name of {len} bytes");
        let loaded = read_image(&path).unwrap();
        assert_eq!(loaded.metadata, vec![(name, "v".to_string())]);
    }
}

#[test]
fn the_file_is_the_same_on_any_number_of_threads() {
    // Five blocks, the last of six rows.
    let film = film(29, 70, 2, 11);
    let scratch = Scratch::new("threads");
    let write_on = |threads: usize| {
        let path = scratch.file(&format!("t{threads}.exr"));
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        pool.install(|| write_exr(&film, &path, &[])).unwrap();
        std::fs::read(&path).unwrap()
    };
    let one = write_on(1);
    for threads in [2, 3, 5] {
        assert!(
            write_on(threads) == one,
            "{threads} threads wrote other bytes"
        );
    }
}

#[test]
fn a_one_pixel_file_has_the_layout_and_values_of_the_specification() {
    let film = film(1, 1, 2, 4);
    let scratch = Scratch::new("layout");
    let path = scratch.file("one.exr");
    write_exr(&film, &path, &[("lightlab.k".to_string(), "v".to_string())]).unwrap();
    let bytes = std::fs::read(&path).unwrap();
    assert_eq!(bytes[..4], 20000630u32.to_le_bytes(), "magic number");
    assert_eq!(version_field(&path), 2, "version 2, single-part scanline");
    let int = |at: usize| i32::from_le_bytes(bytes[at..at + 4].try_into().unwrap());
    let word = |at: &mut usize| {
        let len = bytes[*at..].iter().position(|&b| b == 0).unwrap();
        let s = std::str::from_utf8(&bytes[*at..*at + len])
            .unwrap()
            .to_string();
        *at += len + 1;
        s
    };
    // Attributes (name, type, size, value) up to the header's closing zero byte.
    let mut at = 8;
    let mut attributes = Vec::new();
    while bytes[at] != 0 {
        let (name, kind) = (word(&mut at), word(&mut at));
        let size = int(at) as usize;
        attributes.push((name, kind, size, bytes[at + 4..at + 4 + size].to_vec()));
        at += 4 + size;
    }
    let end = at + 1;
    let listed: Vec<(&str, &str, usize)> = attributes
        .iter()
        .map(|(n, k, s, _)| (n.as_str(), k.as_str(), *s))
        .collect();
    assert_eq!(
        listed,
        [
            // Three channels of 2 + 16 bytes, three of 11 + 16, and the list's end.
            ("channels", "chlist", 136),
            ("compression", "compression", 1),
            ("dataWindow", "box2i", 16),
            ("displayWindow", "box2i", 16),
            ("lineOrder", "lineOrder", 1),
            ("pixelAspectRatio", "float", 4),
            ("screenWindowCenter", "v2f", 8),
            ("screenWindowWidth", "float", 4),
            ("software", "string", 8),
            ("spp", "int", 4),
            ("lightlab.k", "string", 1),
        ]
    );
    let value = |name: &str| &attributes.iter().find(|a| a.0 == name).unwrap().3;
    // Each channel: its name, FLOAT (2), pLinear (set for the variances), three reserved
    // bytes, x and y sampling 1; then the list's closing zero.
    let mut channels = Vec::new();
    for (name, linear) in [("B", 0), ("G", 0), ("R", 0)].into_iter().chain([
        ("variance.B", 1),
        ("variance.G", 1),
        ("variance.R", 1),
    ]) {
        channels.extend_from_slice(name.as_bytes());
        channels.push(0);
        channels.extend_from_slice(&[2, 0, 0, 0, linear, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0]);
    }
    channels.push(0);
    assert_eq!(value("channels"), &channels);
    assert_eq!(value("compression"), &[3], "ZIP, blocks of 16 rows");
    assert_eq!(value("dataWindow"), &[0; 16], "the box (0, 0)–(0, 0)");
    assert_eq!(value("displayWindow"), &[0; 16]);
    assert_eq!(value("lineOrder"), &[0], "increasing y");
    assert_eq!(value("pixelAspectRatio"), &1f32.to_le_bytes());
    assert_eq!(value("screenWindowCenter"), &[0; 8]);
    assert_eq!(value("screenWindowWidth"), &1f32.to_le_bytes());
    assert_eq!(
        value("software"),
        b"lightlab",
        "no closing zero in the value"
    );
    assert_eq!(value("spp"), &2i32.to_le_bytes());
    assert_eq!(value("lightlab.k"), b"v");
    // One chunk: the offset table's only entry points just past itself, at the chunk of
    // row 0, whose data runs to the end of the file.
    let offset = u64::from_le_bytes(bytes[end..end + 8].try_into().unwrap()) as usize;
    assert_eq!(offset, end + 8);
    assert_eq!(int(offset), 0, "the chunk's first row");
    assert_eq!(int(offset + 4) as usize, bytes.len() - offset - 8);
}
