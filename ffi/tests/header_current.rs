//! `include/shearcut.h` is what cbindgen makes of this crate today: the test
//! regenerates it with the cbindgen library and `ffi/cbindgen.toml` and
//! compares. `SHEARCUT_BLESS=1 cargo test -p shearcut-ffi --test
//! header_current` writes the new header instead.

use std::path::Path;

#[test]
fn the_committed_header_is_current() {
    let crate_dir = Path::new(env!("CARGO_MANIFEST_DIR"));
    let config = cbindgen::Config::from_file(crate_dir.join("cbindgen.toml")).unwrap();
    let bindings = cbindgen::Builder::new()
        .with_crate(crate_dir)
        .with_config(config)
        .generate()
        .expect("cbindgen generates the header");
    let mut generated = Vec::new();
    bindings.write(&mut generated);
    let generated = String::from_utf8(generated).unwrap();
    let path = crate_dir.join("../include/shearcut.h");
    if std::env::var_os("SHEARCUT_BLESS").is_some() {
        std::fs::write(&path, &generated).unwrap();
        return;
    }
    let committed = std::fs::read_to_string(&path).unwrap_or_default();
    assert!(
        committed == generated,
        "include/shearcut.h is out of date with ffi/src: regenerate it with \
         `SHEARCUT_BLESS=1 cargo test -p shearcut-ffi --test header_current` and commit it"
    );
}
