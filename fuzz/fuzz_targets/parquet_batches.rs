//! The Parquet batch readers on arbitrary bytes: a file that is not Parquet, or a Parquet file
//! of any schema, gives an error or groups, never a panic; every point read is finite.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    // the readers take a path (they read one row group at a time)
    let path = std::env::temp_dir().join(format!("lekalo-fuzz-{}.parquet", std::process::id()));
    if std::fs::write(&path, data).is_err() {
        return;
    }
    let _ = lekalo_io::read_point_groups(&path, None, |groups| {
        for (_, p) in groups {
            if let Ok(p) = p {
                assert!(
                    p.as_slice().iter().all(|v| v.is_finite()),
                    "a non-finite coordinate was accepted"
                );
            }
        }
        Ok(())
    });
    let _ = lekalo_io::read_curve_groups(&path, None, |_| Ok(()));
    let _ = std::fs::remove_file(&path);
});
