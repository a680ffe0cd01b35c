//! The IGES reader on arbitrary text: Hollerith strings of any count, multi-byte characters in
//! any column and declared sizes of any magnitude give an error (with the line) or shapes,
//! never a panic or an allocation the file cannot back; every coordinate read is finite.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let text = String::from_utf8_lossy(data);
    if let Ok(r) = lekalo_io::read_iges(&text, "fuzz.igs") {
        for (_, s) in &r.shapes {
            assert!(
                s.control_points().as_slice().iter().all(|v| v.is_finite()),
                "a non-finite control point was accepted"
            );
        }
    }
});
