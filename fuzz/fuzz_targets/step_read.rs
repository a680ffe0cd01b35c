//! The STEP reader on arbitrary text: an exchange structure of any nesting, counts,
//! multiplicities and units gives an error (with the line) or shapes, never a panic, a stack
//! overflow or an allocation the file cannot back; every coordinate read is finite and the
//! unit factor positive.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let text = String::from_utf8_lossy(data);
    if let Ok(r) = lekalo_io::read_step(&text, "fuzz.step") {
        assert!(
            r.scale_to_mm.is_finite() && r.scale_to_mm > 0.0,
            "a unit of {} mm was accepted",
            r.scale_to_mm
        );
        for (_, s) in &r.shapes {
            assert!(
                s.control_points().as_slice().iter().all(|v| v.is_finite()),
                "a non-finite control point was accepted"
            );
        }
    }
});
