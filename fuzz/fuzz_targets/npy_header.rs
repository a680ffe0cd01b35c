//! The `.npy` reader on arbitrary bytes, header first: any version, header length, dict
//! literal (repeated keys, odd values) and shape gives an error naming the field or points,
//! never a panic or an allocation larger than the data; every coordinate read is finite.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    if let Ok(p) = lekalo_io::read_npy_points(data, "fuzz.npy") {
        assert!(
            p.as_slice().iter().all(|v| v.is_finite()),
            "a non-finite coordinate was accepted"
        );
    }
});
