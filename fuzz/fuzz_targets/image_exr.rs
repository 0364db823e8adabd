//! The compare crate's OpenEXR loading on arbitrary bytes: errors, never panics.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let _ = stratus_compare::Image::decode(data, stratus_compare::FileKind::Exr, "fuzz.exr");
});
