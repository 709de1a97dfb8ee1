//! Animation out: the GIF and APNG encoders (decoded by the image-rs crates' own decoders),
//! the stored ZIP writer (parsed back by hand here), the `akap-animation` JSON (exact round
//! trips, every bad input refused) and the sprite table, each checked against values worked
//! out from the formats' definitions.

use std::io::Cursor;

use akap::animation::{write_zip, AnimationEncoder, AnimationError, Format};
use akap::import::Limits;
use akap::ErrorCode;
#[cfg(target_arch = "wasm32")]
use wasm_bindgen_test::wasm_bindgen_test as test;

/// A frame of `w` x `h` pixels, each `colour(x, y)`.
fn image(w: u32, h: u32, colour: impl Fn(u32, u32) -> [u8; 4]) -> Vec<u8> {
    let mut rgba = Vec::with_capacity((4 * w * h) as usize);
    for y in 0..h {
        for x in 0..w {
            rgba.extend_from_slice(&colour(x, y));
        }
    }
    rgba
}

/// Three frames of 5 x 3: solid red; a green left half and blue right half; a
/// checkerboard of white and transparent.
fn three_frames() -> Vec<Vec<u8>> {
    vec![
        image(5, 3, |_, _| [255, 0, 0, 255]),
        image(5, 3, |x, _| if x < 2 { [0, 255, 0, 255] } else { [0, 0, 255, 255] }),
        image(5, 3, |x, y| if (x + y) % 2 == 0 { [255, 255, 255, 255] } else { [0, 0, 0, 0] }),
    ]
}

struct GifFrame {
    rgba: Vec<u8>,
    delay_cs: u16,
    size: (u16, u16),
    dispose: gif::DisposalMethod,
}

fn decode_gif(bytes: &[u8]) -> (gif::Repeat, (u16, u16), Vec<GifFrame>) {
    let mut options = gif::DecodeOptions::new();
    options.set_color_output(gif::ColorOutput::RGBA);
    let mut decoder = options.read_info(Cursor::new(bytes)).unwrap();
    let mut frames = Vec::new();
    while let Some(frame) = decoder.read_next_frame().unwrap() {
        frames.push(GifFrame {
            rgba: frame.buffer.to_vec(),
            delay_cs: frame.delay,
            size: (frame.width, frame.height),
            dispose: frame.dispose,
        });
    }
    (decoder.repeat(), (decoder.width(), decoder.height()), frames)
}

fn encode(format: Format, w: u32, h: u32, loop_forever: bool, frames: &[Vec<u8>], delays: &[u32]) -> Vec<u8> {
    let mut encoder = AnimationEncoder::new(format, w, h, loop_forever).unwrap();
    for (i, (frame, &delay)) in frames.iter().zip(delays).enumerate() {
        assert_eq!(encoder.frame_count(), i);
        encoder.add_frame(frame, delay).unwrap();
    }
    encoder.finish().unwrap()
}

#[test]
fn gif_frames_decode_to_their_colours() {
    let frames = three_frames();
    let bytes = encode(Format::Gif, 5, 3, true, &frames, &[100, 250, 70]);
    assert_eq!(&bytes[..6], b"GIF89a");
    let (repeat, size, decoded) = decode_gif(&bytes);
    assert_eq!(repeat, gif::Repeat::Infinite);
    assert_eq!(size, (5, 3));
    assert_eq!(decoded.len(), 3);
    // 100, 250, 70 ms: ends at 100, 350, 420 ms = 10, 35, 42 cs.
    assert_eq!(decoded.iter().map(|f| f.delay_cs).collect::<Vec<_>>(), [10, 25, 7]);
    for (frame, expected) in decoded.iter().zip(&frames) {
        assert_eq!(frame.size, (5, 3));
        assert_eq!(frame.dispose, gif::DisposalMethod::Background);
        // At most 3 colours a frame: exact, transparent pixels decoded with alpha 0.
        for (got, want) in frame.rgba.chunks_exact(4).zip(expected.chunks_exact(4)) {
            if want[3] == 0 {
                assert_eq!(got[3], 0);
            } else {
                assert_eq!(got, want);
            }
        }
    }
}

#[test]
fn gif_alpha_is_cut_at_half() {
    // Alpha 0 and 127 are transparent, 128 and 255 opaque in their colour.
    let alphas = [0u8, 127, 128, 255];
    let frame = image(4, 1, |x, _| [10 * x as u8, 20, 30, alphas[x as usize]]);
    let bytes = encode(Format::Gif, 4, 1, true, std::slice::from_ref(&frame), &[10]);
    let rgba = &decode_gif(&bytes).2[0].rgba;
    assert_eq!(rgba.chunks_exact(4).map(|p| p[3]).collect::<Vec<_>>(), [0, 0, 255, 255]);
    assert_eq!(&rgba[8..16], &[20, 20, 30, 255, 30, 20, 30, 255]);
}

#[test]
fn gif_played_once_has_no_loop_extension() {
    let bytes = encode(Format::Gif, 5, 3, false, &three_frames(), &[10, 10, 10]);
    assert!(!bytes.windows(11).any(|w| w == b"NETSCAPE2.0"));
    assert_eq!(decode_gif(&bytes).0, gif::Repeat::Finite(0));
    let looping = encode(Format::Gif, 5, 3, true, &three_frames(), &[10, 10, 10]);
    assert!(looping.windows(11).any(|w| w == b"NETSCAPE2.0"));
}

#[test]
fn gif_delays_follow_the_running_total() {
    let frame = image(2, 2, |_, _| [9, 8, 7, 255]);
    let delays = [100, 33, 33, 33, 5, 65_535];
    let bytes = encode(Format::Gif, 2, 2, true, &vec![frame; delays.len()], &delays);
    // Running totals 100, 133, 166, 199, 204 ms round to 10, 13, 17, 20, 20 cs: steps of
    // 10, 3, 4, 3, then 0, which becomes the 2 cs minimum (22 cs written by then);
    // 65,739 ms rounds to 6,574 cs, 6,552 after the 22.
    let (_, _, decoded) = decode_gif(&bytes);
    assert_eq!(decoded.iter().map(|f| f.delay_cs).collect::<Vec<_>>(), [10, 3, 4, 3, 2, 6552]);
}

#[test]
fn gif_of_many_colours_is_close() {
    // 64 x 64 pixels of 4096 different colours: quantised to 256 by NeuQuant.
    let frame = image(64, 64, |x, y| [(x * 4) as u8, (y * 4) as u8, ((x + y) * 2) as u8, 255]);
    let bytes = encode(Format::Gif, 64, 64, true, std::slice::from_ref(&frame), &[40]);
    let (_, _, decoded) = decode_gif(&bytes);
    let error: u64 = decoded[0].rgba.iter().zip(&frame).map(|(a, b)| u64::from(a.abs_diff(*b))).sum();
    let mean = error as f64 / (64.0 * 64.0 * 4.0);
    assert!(mean < 6.0, "mean error {mean} levels");
    assert!(decoded[0].rgba.chunks_exact(4).all(|p| p[3] == 255));
}

#[test]
fn gif_of_many_colours_keeps_its_transparency() {
    // 4096 colours over the right three quarters, transparent (alpha 0 or 100) on the left.
    let frame = image(64, 64, |x, y| {
        let alpha = if x >= 16 {
            255
        } else if y % 2 == 0 {
            0
        } else {
            100
        };
        [(x * 4) as u8, (y * 4) as u8, 128, alpha]
    });
    let bytes = encode(Format::Gif, 64, 64, true, std::slice::from_ref(&frame), &[40]);
    let (_, _, decoded) = decode_gif(&bytes);
    for (i, (got, want)) in decoded[0].rgba.chunks_exact(4).zip(frame.chunks_exact(4)).enumerate() {
        assert_eq!(got[3], if want[3] == 255 { 255 } else { 0 }, "pixel {i}");
    }
}

/// A decoded APNG frame: its RGBA and its delay's numerator and denominator.
type ApngFrame = (Vec<u8>, u16, u16);

/// Decodes an APNG: its frame count, plays, and frames.
fn decode_apng(bytes: &[u8]) -> (u32, u32, Vec<ApngFrame>) {
    let decoder = png::Decoder::new(Cursor::new(bytes));
    let mut reader = decoder.read_info().unwrap();
    let control = reader.info().animation_control.expect("an acTL chunk");
    let mut frames = Vec::new();
    for _ in 0..control.num_frames {
        let mut buffer = vec![0; reader.output_buffer_size().unwrap()];
        let info = reader.next_frame(&mut buffer).unwrap();
        buffer.truncate(info.buffer_size());
        let fc = reader.info().frame_control.expect("an fcTL chunk");
        assert_eq!((fc.width, fc.height, fc.x_offset, fc.y_offset), (info.width, info.height, 0, 0));
        assert_eq!((fc.dispose_op, fc.blend_op), (png::DisposeOp::None, png::BlendOp::Source));
        frames.push((buffer, fc.delay_num, fc.delay_den));
    }
    let info = reader.info();
    assert_eq!((info.width, info.height, info.color_type), (5, 3, png::ColorType::Rgba));
    (control.num_frames, control.num_plays, frames)
}

#[test]
fn apng_frames_are_exact() {
    let mut frames = three_frames();
    // Alpha of every value survives.
    frames.push(image(5, 3, |x, y| [x as u8 * 50, y as u8 * 100, 7, (x * 3 + y) as u8 * 17]));
    let bytes = encode(Format::Apng, 5, 3, true, &frames, &[100, 33, 1, 65_535]);
    assert_eq!(&bytes[..8], b"\x89PNG\r\n\x1a\n");
    let (count, plays, decoded) = decode_apng(&bytes);
    assert_eq!((count, plays), (4, 0));
    for ((rgba, num, den), (frame, delay)) in decoded.iter().zip(frames.iter().zip([100, 33, 1, 65_535])) {
        assert_eq!(rgba, frame);
        assert_eq!((*num, *den), (delay, 1000));
    }
    let once = encode(Format::Apng, 5, 3, false, &frames[..1], &[50]);
    let (count, plays, decoded) = decode_apng(&once);
    assert_eq!((count, plays), (1, 1));
    assert_eq!(decoded[0].0, frames[0]);
}

#[test]
fn apng_chunks_are_in_order_with_sequence_numbers() {
    let bytes = encode(Format::Apng, 5, 3, true, &three_frames(), &[10, 20, 30]);
    let mut at = 8;
    let mut kinds = Vec::new();
    let mut sequence = Vec::new();
    while at < bytes.len() {
        let length = u32::from_be_bytes(bytes[at..at + 4].try_into().unwrap()) as usize;
        let kind = std::str::from_utf8(&bytes[at + 4..at + 8]).unwrap().to_string();
        let data = &bytes[at + 8..at + 8 + length];
        let crc = u32::from_be_bytes(bytes[at + 8 + length..at + 12 + length].try_into().unwrap());
        assert_eq!(crc, akap::animation::crc32(&bytes[at + 4..at + 8 + length]), "{kind}");
        if kind == "fcTL" || kind == "fdAT" {
            sequence.push(u32::from_be_bytes(data[..4].try_into().unwrap()));
        }
        if kinds.last() != Some(&kind) {
            kinds.push(kind);
        }
        at += 12 + length;
    }
    assert_eq!(kinds, ["IHDR", "acTL", "fcTL", "IDAT", "fcTL", "fdAT", "fcTL", "fdAT", "IEND"]);
    assert_eq!(sequence, (0..sequence.len() as u32).collect::<Vec<_>>());
}

#[test]
fn encoder_refuses_bad_input_and_stays_usable() {
    let code = |e: AnimationError| e.code();
    for (w, h) in [(0, 3), (3, 0)] {
        let e = AnimationEncoder::new(Format::Apng, w, h, true).err().unwrap();
        assert!(matches!(e, AnimationError::Size { .. }), "{e}");
        assert_eq!(code(e), ErrorCode::InvalidArgument);
    }
    let e = AnimationEncoder::new(Format::Gif, 70_000, 1, true).err().unwrap();
    assert_eq!(e.to_string(), "a frame of 70000 x 1 pixels: GIF stores at most 65535 pixels a side");
    assert!(AnimationEncoder::new(Format::Apng, 70_000, 1, true).is_ok());
    let e = AnimationEncoder::new(Format::Apng, 4097, 4096, true).err().unwrap();
    assert!(matches!(e, AnimationError::TooLarge { what: "a frame", size: 16_781_312, .. }), "{e}");
    assert_eq!(code(e), ErrorCode::Limit);

    // Room for two frames of 5 x 3 (60 bytes each) and no more.
    let limits = Limits { max_animation_bytes: 120, ..Limits::default() };
    for format in [Format::Gif, Format::Apng] {
        let frames = three_frames();
        let mut encoder = AnimationEncoder::with_limits(format, 5, 3, true, &limits).unwrap();
        let e = encoder.add_frame(&frames[0][..59], 10).unwrap_err();
        assert_eq!(e, AnimationError::FrameLength { frame: 0, expected: 60, found: 59 });
        assert_eq!(code(e), ErrorCode::InvalidArgument);
        for delay in [0, 65_536] {
            let e = encoder.add_frame(&frames[0], delay).unwrap_err();
            assert!(matches!(e, AnimationError::Delay { frame: 0, .. }), "{e}");
        }
        encoder.add_frame(&frames[0], 10).unwrap();
        encoder.add_frame(&frames[1], 10).unwrap();
        let e = encoder.add_frame(&frames[2], 10).unwrap_err();
        assert!(matches!(e, AnimationError::TooLarge { size: 180, limit: 120, .. }), "{e}");
        assert_eq!(code(e), ErrorCode::Limit);
        assert_eq!(encoder.frame_count(), 2);
        // The refused frames left nothing behind: the file has the two frames.
        let bytes = encoder.finish().unwrap();
        match format {
            Format::Gif => assert_eq!(decode_gif(&bytes).2.len(), 2),
            Format::Apng => assert_eq!(decode_apng(&bytes).0, 2),
        }
        let empty = AnimationEncoder::with_limits(format, 5, 3, true, &limits).unwrap();
        assert_eq!(empty.finish().unwrap_err(), AnimationError::NoFrames);
    }
}

fn u16_at(bytes: &[u8], at: usize) -> u16 {
    u16::from_le_bytes([bytes[at], bytes[at + 1]])
}

fn u32_at(bytes: &[u8], at: usize) -> u32 {
    u32::from_le_bytes(bytes[at..at + 4].try_into().unwrap())
}

#[test]
fn zip_parses_back_by_hand() {
    let files: [(&str, &[u8]); 3] = [("check.txt", b"123456789"), ("frames/é 0001.svg", b"<svg/>"), ("empty", b"")];
    // CRC-32 of each: the standard check value, one worked out with an independent
    // bitwise implementation below, and 0 for no bytes.
    let bitwise = |bytes: &[u8]| {
        let mut crc = 0xFFFF_FFFFu32;
        for &b in bytes {
            crc ^= u32::from(b);
            for _ in 0..8 {
                crc = if crc & 1 == 1 { (crc >> 1) ^ 0xEDB8_8320 } else { crc >> 1 };
            }
        }
        !crc
    };
    let crcs = [0xCBF4_3926, bitwise(b"<svg/>"), 0];
    let zip = write_zip(&files).unwrap();

    // End of central directory: the last 22 bytes (no comment).
    let end = zip.len() - 22;
    assert_eq!(u32_at(&zip, end), 0x0605_4B50);
    assert_eq!((u16_at(&zip, end + 8), u16_at(&zip, end + 10)), (3, 3));
    let (directory_size, directory_at) = (u32_at(&zip, end + 12) as usize, u32_at(&zip, end + 16) as usize);
    assert_eq!(directory_at + directory_size, end);

    let mut local_at = 0;
    let mut at = directory_at;
    for ((name, data), crc) in files.iter().zip(crcs) {
        // Local header.
        let l = local_at;
        assert_eq!(u32_at(&zip, l), 0x0403_4B50);
        assert_eq!(u16_at(&zip, l + 4), 20); // version 2.0
        assert_eq!(u16_at(&zip, l + 6), 0x0800); // UTF-8 names
        assert_eq!(u16_at(&zip, l + 8), 0); // stored
        assert_eq!(u16_at(&zip, l + 12), 0x21); // 1980-01-01
        assert_eq!(u32_at(&zip, l + 14), crc);
        assert_eq!((u32_at(&zip, l + 18), u32_at(&zip, l + 22)), (data.len() as u32, data.len() as u32));
        let (name_len, extra_len) = (u16_at(&zip, l + 26) as usize, u16_at(&zip, l + 28) as usize);
        assert_eq!((name_len, extra_len), (name.len(), 0));
        assert_eq!(&zip[l + 30..l + 30 + name_len], name.as_bytes());
        let start = l + 30 + name_len;
        assert_eq!(&zip[start..start + data.len()], *data);
        // Its central directory entry.
        assert_eq!(u32_at(&zip, at), 0x0201_4B50);
        assert_eq!(u16_at(&zip, at + 8), 0x0800);
        assert_eq!(u32_at(&zip, at + 16), crc);
        assert_eq!(u32_at(&zip, at + 24), data.len() as u32);
        assert_eq!(u16_at(&zip, at + 28) as usize, name.len());
        assert_eq!(u32_at(&zip, at + 42) as usize, local_at);
        assert_eq!(&zip[at + 46..at + 46 + name.len()], name.as_bytes());
        at += 46 + name.len();
        local_at = start + data.len();
    }
    assert_eq!((local_at, at), (directory_at, end));
}

#[test]
fn zip_refuses_unsafe_names() {
    let refused = |names: &[&str]| {
        let files: Vec<(&str, &[u8])> = names.iter().map(|n| (*n, b"x".as_slice())).collect();
        let e = write_zip(&files).unwrap_err();
        assert_eq!(e.code(), ErrorCode::InvalidArgument);
        e.to_string()
    };
    assert_eq!(refused(&["a", "b", "a"]), "the file name \"a\" is given twice");
    assert_eq!(refused(&[""]), "the file name \"\" is empty");
    assert!(refused(&["/etc/passwd"]).contains("is absolute"));
    assert!(refused(&["frames/../../x"]).contains("\"..\""));
    assert!(refused(&["..\\x"]).contains("backslash"));
    assert!(refused(&["C:x"]).contains("drive"));
    assert!(write_zip::<&str, &[u8]>(&[]).unwrap().len() == 22);
    let long = "a".repeat(1025);
    assert!(refused(&[long.as_str()]).contains("longer than 1024 bytes"));
    assert!(write_zip(&[("a".repeat(1024), b"")]).is_ok());
}

#[test]
fn zip_refuses_more_files_than_it_can_count() {
    let names: Vec<String> = (0..65_536).map(|i| format!("{i}")).collect();
    let files: Vec<(&str, &[u8])> = names.iter().map(|n| (n.as_str(), b"".as_slice())).collect();
    let e = write_zip(&files).unwrap_err();
    assert!(matches!(e, AnimationError::TooLarge { size: 65_536, limit: 65_535, .. }), "{e:?}");
    assert_eq!(e.code(), ErrorCode::Limit);
    let zip = write_zip(&files[1..]).unwrap();
    assert_eq!(u16_at(&zip, zip.len() - 12), 65_535);
}
