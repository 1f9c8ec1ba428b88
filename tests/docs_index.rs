//! The docs are found in one click: the docs index (docs/README.md) and
//! the README's documentation table link every page of `docs/`.

/// The file names of `docs/*.md` other than the index, sorted.
fn doc_pages() -> Vec<String> {
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/docs");
    let mut pages: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.ends_with(".md") && n != "README.md")
        .collect();
    pages.sort();
    pages
}

/// The text of `path` below the repository's root.
fn read(path: &str) -> String {
    std::fs::read_to_string(format!("{}/{path}", env!("CARGO_MANIFEST_DIR"))).unwrap()
}

/// Asserts that the markdown file `index` links every docs page, its
/// target written `prefix` then the page's name (`](docs/model.md)`).
fn assert_links_every_page(index: &str, prefix: &str) {
    let text = read(index);
    for page in doc_pages() {
        assert!(
            text.contains(&format!("]({prefix}{page})")),
            "{index} does not link {prefix}{page}"
        );
    }
}

#[test]
fn the_docs_index_links_every_page() {
    assert_links_every_page("docs/README.md", "");
}

#[test]
fn the_readme_links_every_page() {
    assert_links_every_page("README.md", "docs/");
}

/// The README is a front door a newcomer reads in minutes: at most 200
/// lines, the rest lives in docs/.
#[test]
fn the_readme_is_at_most_200_lines() {
    let lines = read("README.md").lines().count();
    assert!(lines <= 200, "README.md has {lines} lines");
}
