//! The writer against the `exr` crate's reader (its own ZIP decoder): every channel's
//! bits, the header's attributes, blocks stored compressed and raw, long and non-Latin
//! names and values, and the names a text attribute may not take.

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

fn temp(name: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("lightlab-exr-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name)
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
    let path = temp("blocks.exr");
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
    let path = temp("raw.exr");
    write_exr(&film, &path, &[]).unwrap();
    assert_eq!(read_channels(&path), expected_channels(&film));
}

#[test]
fn text_attributes_round_trip_in_utf8_with_long_names() {
    let film = film(3, 2, 4, 1);
    let path = temp("text.exr");
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
    let path = temp("names.exr");
    let too_long = "n".repeat(MAX_NAME + 1);
    for name in ["", "spp", "channels", "software", "a\0b", too_long.as_str()] {
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
