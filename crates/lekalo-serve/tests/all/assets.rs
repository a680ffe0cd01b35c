//! The editor's files: every ES module under `assets/js/` is served at its path, every import
//! of a served module and the page's module script resolve to a served module, and each is
//! answered as JavaScript (a module the browser cannot load stops the whole editor).

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};

use axum::body::Body;
use axum::http::{header, Request, StatusCode};
use http_body_util::BodyExt;
use lekalo_serve::{router, Limits, EDITOR_SCRIPTS};
use tower::ServiceExt;

fn files_under(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in std::fs::read_dir(dir).expect("assets/js") {
        let path = entry.expect("entry").path();
        if path.is_dir() {
            files_under(&path, out);
        } else if path.extension().is_some_and(|e| e == "js") {
            out.push(path);
        }
    }
}

/// `import … from './x.js'` and `from '../x.js'` of a module at `path`, as served paths.
fn imports(path: &str, text: &str) -> Vec<String> {
    let dir = &path[..path.rfind('/').expect("a folder")];
    text.lines()
        .filter(|l| l.starts_with("import ") || l.starts_with("} from "))
        .filter_map(|l| l.split(" from '").nth(1))
        .filter_map(|l| l.split('\'').next())
        .map(|rel| {
            let mut parts: Vec<&str> = dir.split('/').collect();
            for p in rel.split('/') {
                match p {
                    "." => {}
                    ".." => {
                        parts.pop();
                    }
                    p => parts.push(p),
                }
            }
            parts.join("/")
        })
        .collect()
}

#[test]
fn every_module_is_served_and_every_import_resolves() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("assets");
    let mut files = Vec::new();
    files_under(&root.join("js"), &mut files);
    let on_disk: BTreeSet<String> = files
        .iter()
        .map(|p| {
            let rel = p.strip_prefix(&root).expect("under assets");
            format!("/{}", rel.to_string_lossy().replace('\\', "/"))
        })
        .collect();
    let served: BTreeSet<String> = EDITOR_SCRIPTS.iter().map(|(p, _)| p.to_string()).collect();
    assert_eq!(
        served, on_disk,
        "EDITOR_SCRIPTS lists every file of assets/js"
    );
    for (path, text) in EDITOR_SCRIPTS {
        for import in imports(path, text) {
            assert!(
                served.contains(&import),
                "{path} imports {import}, which is not served"
            );
        }
    }
    let html = std::fs::read_to_string(root.join("index.html")).expect("index.html");
    assert!(
        html.contains(r#"<script type="module" src="/js/main.js"></script>"#),
        "the page loads main.js as a module"
    );
}

#[tokio::test]
async fn modules_are_answered_as_javascript() {
    for (path, text) in EDITOR_SCRIPTS {
        let req = Request::get(*path).body(Body::empty()).expect("request");
        let resp = router(Limits::default())
            .oneshot(req)
            .await
            .expect("answer");
        assert_eq!(resp.status(), StatusCode::OK, "{path}");
        let mime = resp.headers()[header::CONTENT_TYPE]
            .to_str()
            .expect("mime")
            .to_string();
        assert!(mime.starts_with("text/javascript"), "{path}: {mime}");
        let body = resp.into_body().collect().await.expect("body").to_bytes();
        assert_eq!(body, text.as_bytes(), "{path}");
    }
}
