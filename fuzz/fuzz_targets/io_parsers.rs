//! The CLI's text parsers in `lekalo-io` on arbitrary text: the points reader (CSV, whitespace,
//! JSON), number lists, JSON Lines and the versioned object readers. A parsed object must be
//! finite and must read back from its own serialisation.
#![no_main]

use lekalo_io::{
    envelope_type, parse_number_list, read_bezier_surface, read_bspline_surface, read_json_lines,
    read_piecewise_polynomial, read_points, read_points_bytes, Header, Object,
};
use libfuzzer_sys::fuzz_target;

fn assert_finite(what: &str, values: &[f64]) {
    assert!(
        values.iter().all(|v| v.is_finite()),
        "{what} accepted a non-finite value: {values:?}"
    );
}

fn check_object(o: &Object) {
    let back = Object::from_json_str(&o.to_json_line(), "round trip");
    assert!(back.is_ok(), "{o:?} does not read back: {back:?}");
    let _ = o.to_json_pretty();
    let _ = o.display_name();
}

fuzz_target!(|data: &[u8]| {
    // the points reader of files takes the bytes, and checks them as UTF-8 as it parses: it
    // accepts exactly the UTF-8 texts the reader of `&str` accepts, with the same points
    let from_bytes = read_points_bytes(data, "fuzz", Header::Auto);
    match std::str::from_utf8(data) {
        Ok(t) => assert_eq!(
            from_bytes.as_ref().map_err(ToString::to_string),
            lekalo_io::read_points_with(t, "fuzz", Header::Auto)
                .as_ref()
                .map_err(ToString::to_string),
            "read_points_bytes and read_points_with differ"
        ),
        Err(_) => assert!(from_bytes.is_err(), "read_points_bytes accepted bytes that are not UTF-8"),
    }
    // the other parsers take `&str`; invalid UTF-8 is refused before them by the CLI
    let text = String::from_utf8_lossy(data);
    if let Ok(p) = read_points(&text, "fuzz") {
        assert_finite("read_points", p.as_slice());
    }
    if let Ok(v) = parse_number_list(&text, "fuzz") {
        assert_finite("parse_number_list", &v);
    }
    let _ = envelope_type(&text);
    if let Ok(o) = Object::from_json_str(&text, "fuzz") {
        check_object(&o);
    }
    for (_, o) in read_json_lines(&text, "fuzz") {
        if let Ok(o) = o {
            check_object(&o);
        }
    }
    if let Ok(s) = read_bspline_surface(&text, "fuzz") {
        assert_finite("read_bspline_surface", s.control_points().as_slice());
    }
    if let Ok(s) = read_bezier_surface(&text, "fuzz") {
        assert_finite("read_bezier_surface", s.control_points().as_slice());
    }
    let _ = read_piecewise_polynomial(&text, "fuzz");
});
