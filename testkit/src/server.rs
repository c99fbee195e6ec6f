//! The real server on an ephemeral loopback port, called over HTTP with reqwest.

use reqwest::StatusCode;
use restitution::http::sweeps::Streams;
use restitution::http::{AppState, ServiceConfig, app_with, serve_router_until};
use serde_json::Value;

pub struct TestApp {
    pub addr: std::net::SocketAddr,
    pub base: String,
    pub client: reqwest::Client,
    /// The application's streamed sweeps still computing.
    pub streams: Streams,
}

/// Starts the application on an ephemeral loopback port.
pub async fn spawn_app(config: ServiceConfig) -> TestApp {
    let listener = tokio::net::TcpListener::bind("127.0.0.1:0")
        .await
        .expect("bind loopback");
    let addr = listener.local_addr().expect("local addr");
    let state = AppState::default();
    let streams = state.streams.clone();
    let router = app_with(&config, state);
    tokio::spawn(async move { serve_router_until(listener, router, &config, std::future::pending()).await });
    TestApp {
        addr,
        base: format!("http://{addr}"),
        client: reqwest::Client::new(),
        streams,
    }
}

impl TestApp {
    /// GETs `path`; returns the status and the body as JSON (`Null` if it is not JSON).
    pub async fn get(&self, path: &str) -> (StatusCode, Value) {
        let response = self
            .client
            .get(format!("{}{path}", self.base))
            .send()
            .await
            .expect("send");
        let status = response.status();
        (status, response.json().await.unwrap_or(Value::Null))
    }

    /// Waits until no streamed or reduced sweep is computing, failing after ten seconds.
    pub async fn until_sweeps_stop(&self) {
        let deadline = std::time::Instant::now() + std::time::Duration::from_secs(10);
        while self.streams.active() > 0 {
            assert!(
                std::time::Instant::now() < deadline,
                "a sweep went on after its client left"
            );
            tokio::time::sleep(std::time::Duration::from_millis(5)).await;
        }
    }

    pub async fn post(&self, path: &str, body: &Value) -> (StatusCode, reqwest::header::HeaderMap, Value) {
        let response = self
            .client
            .post(format!("{}{path}", self.base))
            .json(body)
            .send()
            .await
            .expect("send");
        let status = response.status();
        let headers = response.headers().clone();
        let value = response.json().await.unwrap_or(Value::Null);
        (status, headers, value)
    }
    pub async fn post_raw(
        &self,
        path: &str,
        content_type: Option<&str>,
        body: Vec<u8>,
    ) -> (StatusCode, String, Value) {
        let mut request = self.client.post(format!("{}{path}", self.base)).body(body);
        if let Some(ct) = content_type {
            request = request.header("content-type", ct);
        }
        let response = request.send().await.expect("send");
        let status = response.status();
        let ct = response
            .headers()
            .get("content-type")
            .map(|v| v.to_str().unwrap().to_owned())
            .unwrap_or_default();
        (status, ct, response.json().await.unwrap_or(Value::Null))
    }
}

impl TestApp {
    /// Posts JSON with an `Accept` header; returns status, headers and the raw body.
    pub async fn post_accept(
        &self,
        path: &str,
        accept: &str,
        body: &Value,
    ) -> (StatusCode, reqwest::header::HeaderMap, Vec<u8>) {
        let response = self
            .client
            .post(format!("{}{path}", self.base))
            .header("accept", accept)
            .json(body)
            .send()
            .await
            .expect("send");
        let status = response.status();
        let headers = response.headers().clone();
        let bytes = response.bytes().await.expect("body").to_vec();
        (status, headers, bytes)
    }
}
