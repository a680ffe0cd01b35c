//! The `OpenAPI` description (`docs/openapi.json`, served at `/api/openapi.json`) and the router
//! agree: every route of the router is described with its method, and every described route
//! answers (not 404, not 405).

#![allow(clippy::missing_assert_message)] // assert_eq! prints both sides

use std::collections::BTreeSet;

use axum::body::Body;
use axum::http::{Method, Request, StatusCode};
use http_body_util::BodyExt;
use lekalo_serve::{router, routes, Limits, OPENAPI};
use serde_json::Value;
use tower::ServiceExt;

fn described() -> BTreeSet<(String, String)> {
    let doc: Value = serde_json::from_str(OPENAPI).expect("docs/openapi.json is JSON");
    assert_eq!(doc["openapi"], "3.1.0", "an OpenAPI 3.1 document");
    let paths = doc["paths"].as_object().expect("paths");
    paths
        .iter()
        .flat_map(|(path, ops)| {
            ops.as_object()
                .expect("operations")
                .keys()
                .map(move |m| (path.clone(), m.to_uppercase()))
        })
        .collect()
}

#[test]
fn every_route_is_described_and_every_description_is_a_route() {
    let routed: BTreeSet<(String, String)> = routes()
        .into_iter()
        .map(|(p, m, _)| (p.to_string(), m.to_string()))
        .collect();
    let described = described();
    let undescribed: Vec<_> = routed.difference(&described).collect();
    assert!(
        undescribed.is_empty(),
        "routes missing from docs/openapi.json: {undescribed:?}"
    );
    let missing: Vec<_> = described.difference(&routed).collect();
    assert!(missing.is_empty(), "described but not routed: {missing:?}");
}

#[tokio::test]
async fn every_described_route_answers_and_the_description_is_served() {
    for (path, method) in described() {
        let method = Method::from_bytes(method.as_bytes()).expect("method");
        let req = Request::builder()
            .method(method.clone())
            .uri(&path)
            .body(Body::from("{}"))
            .expect("request");
        let resp = router(Limits::default())
            .oneshot(req)
            .await
            .expect("answer");
        let status = resp.status();
        assert!(
            status != StatusCode::NOT_FOUND && status != StatusCode::METHOD_NOT_ALLOWED,
            "{method} {path}: {status}"
        );
        if path == "/api/openapi.json" {
            let bytes = resp.into_body().collect().await.expect("body").to_bytes();
            assert_eq!(
                bytes,
                OPENAPI.as_bytes(),
                "the served description is the file"
            );
        }
    }
    // and an undescribed route is not answered
    let req = Request::get("/api/nothing")
        .body(Body::empty())
        .expect("request");
    let resp = router(Limits::default())
        .oneshot(req)
        .await
        .expect("answer");
    assert_eq!(resp.status(), StatusCode::NOT_FOUND);
}
