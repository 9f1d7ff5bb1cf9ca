//! A minimal LSP client over a child process's stdio, for tests and the latency benchmark.
#![allow(dead_code)]

use serde_json::{json, Value};
use std::io::{BufRead, BufReader, Read, Write};
use std::process::{Child, ChildStdin, Command, Stdio};
use std::sync::mpsc::{channel, Receiver};
use std::time::{Duration, Instant};

pub struct Client {
    child: Child,
    stdin: ChildStdin,
    rx: Receiver<Value>,
    next_id: i64,
    /// Notifications received while waiting for responses.
    pub notifications: Vec<Value>,
    /// Responses received while waiting for something else.
    pub responses: Vec<Value>,
    /// Requests the server sent (e.g. `client/registerCapability`), answered with null.
    pub server_requests: Vec<Value>,
}

impl Client {
    pub fn start(bin: &str) -> Client {
        let mut cmd = Command::new(bin);
        cmd.arg("lsp");
        Client::spawn(cmd)
    }

    /// Starts the server with a command line of the caller's (e.g. under `ulimit`).
    pub fn spawn(mut cmd: Command) -> Client {
        let mut child = cmd
            .stdin(Stdio::piped())
            .stdout(Stdio::piped())
            .stderr(Stdio::null())
            .spawn()
            .expect("start server");
        let stdin = child.stdin.take().unwrap();
        let stdout = child.stdout.take().unwrap();
        let (tx, rx) = channel();
        std::thread::spawn(move || {
            let mut r = BufReader::new(stdout);
            loop {
                let mut len = 0usize;
                loop {
                    let mut line = String::new();
                    if r.read_line(&mut line).unwrap_or(0) == 0 {
                        return;
                    }
                    let line = line.trim_end();
                    if line.is_empty() {
                        break;
                    }
                    if let Some(v) = line.strip_prefix("Content-Length: ") {
                        len = v.parse().unwrap_or(0);
                    }
                }
                let mut buf = vec![0; len];
                if r.read_exact(&mut buf).is_err() {
                    return;
                }
                if let Ok(v) = serde_json::from_slice::<Value>(&buf) {
                    if tx.send(v).is_err() {
                        return;
                    }
                }
            }
        });
        Client {
            child,
            stdin,
            rx,
            next_id: 1,
            notifications: Vec::new(),
            responses: Vec::new(),
            server_requests: Vec::new(),
        }
    }

    fn send(&mut self, v: &Value) {
        let body = serde_json::to_string(v).unwrap();
        write!(self.stdin, "Content-Length: {}\r\n\r\n{}", body.len(), body).unwrap();
        self.stdin.flush().unwrap();
    }

    /// The server's process id.
    pub fn pid(&self) -> u32 {
        self.child.id()
    }

    pub fn notify(&mut self, method: &str, params: Value) {
        self.send(&json!({ "jsonrpc": "2.0", "method": method, "params": params }));
    }

    /// Sends a request without waiting; returns its id.
    pub fn send_request(&mut self, method: &str, params: Value) -> i64 {
        let id = self.next_id;
        self.next_id += 1;
        self.send(&json!({ "jsonrpc": "2.0", "id": id, "method": method, "params": params }));
        id
    }

    /// The next message, answering requests of the server (null) on the way.
    fn recv(&mut self, deadline: Instant) -> Option<Value> {
        loop {
            let v = self
                .rx
                .recv_timeout(deadline.saturating_duration_since(Instant::now()))
                .ok()?;
            if v.get("method").is_some() && v.get("id").is_some() {
                let rid = v["id"].clone();
                self.send(&json!({ "jsonrpc": "2.0", "id": rid, "result": null }));
                self.server_requests.push(v);
                continue;
            }
            return Some(v);
        }
    }

    /// Waits for the response to request `id` (`None` after the timeout).
    pub fn wait_response(&mut self, id: i64, timeout: Duration) -> Option<Value> {
        if let Some(i) = self.responses.iter().position(|r| r["id"] == json!(id)) {
            return Some(self.responses.remove(i));
        }
        let deadline = Instant::now() + timeout;
        loop {
            let v = self.recv(deadline)?;
            if v.get("method").is_none() {
                if v["id"] == json!(id) {
                    return Some(v);
                }
                self.responses.push(v);
            } else {
                self.notifications.push(v);
            }
        }
    }

    /// Sends a request and waits for its response (`result` or `error`).
    pub fn request(&mut self, method: &str, params: Value) -> Value {
        let id = self.send_request(method, params);
        self.wait_response(id, Duration::from_secs(30))
            .expect("response in time")
    }

    /// Waits for the next notification of `method` (already received ones first).
    pub fn wait_notification(&mut self, method: &str, timeout: Duration) -> Option<Value> {
        if let Some(i) = self
            .notifications
            .iter()
            .position(|n| n["method"] == method)
        {
            return Some(self.notifications.remove(i));
        }
        let deadline = Instant::now() + timeout;
        loop {
            let v = self.recv(deadline)?;
            if v["method"] == method {
                return Some(v);
            }
            if v.get("method").is_none() {
                self.responses.push(v);
            } else {
                self.notifications.push(v);
            }
        }
    }

    /// Waits for diagnostics of the document `uri` (others are kept).
    pub fn wait_diagnostics(&mut self, uri: &str, timeout: Duration) -> Option<Value> {
        let want = decode_uri(uri);
        let is = |n: &Value| {
            n["method"] == "textDocument/publishDiagnostics"
                && n["params"]["uri"].as_str().map(decode_uri) == Some(want.clone())
        };
        if let Some(i) = self.notifications.iter().position(is) {
            return Some(self.notifications.remove(i));
        }
        let deadline = Instant::now() + timeout;
        loop {
            let v = self.recv(deadline)?;
            if is(&v) {
                return Some(v);
            }
            if v.get("method").is_none() {
                self.responses.push(v);
            } else {
                self.notifications.push(v);
            }
        }
    }

    /// `initialize` with parameters of the caller's, then `initialized`.
    pub fn initialize_with(&mut self, params: Value) -> Value {
        let r = self.request("initialize", params);
        self.notify("initialized", json!({}));
        r
    }

    pub fn initialize(&mut self, root: &std::path::Path, options: Value) -> Value {
        let uri = format!("file://{}", root.display());
        let r = self.request(
            "initialize",
            json!({ "processId": null, "capabilities": {}, "initializationOptions": options, "workspaceFolders": [{ "uri": uri, "name": "ws" }] }),
        );
        self.notify("initialized", json!({}));
        r
    }

    /// `exit` without `shutdown` (the server must exit with status 1).
    pub fn exit_without_shutdown(mut self) -> std::process::ExitStatus {
        self.notify("exit", Value::Null);
        drop(self.stdin);
        self.child.wait().unwrap()
    }

    pub fn shutdown(mut self) -> std::process::ExitStatus {
        let _ = self.request("shutdown", Value::Null);
        self.notify("exit", Value::Null);
        drop(self.stdin);
        self.child.wait().unwrap()
    }
}

/// The `file:` URI of a path, percent-encoded (spaces, umlauts).
pub fn uri(p: &std::path::Path) -> String {
    let mut out = String::from("file://");
    for b in p.to_string_lossy().bytes() {
        if b.is_ascii_alphanumeric() || b"-._~/".contains(&b) {
            out.push(b as char);
        } else {
            out.push_str(&format!("%{b:02X}"));
        }
    }
    out
}

/// A URI with its percent-escapes decoded (servers may escape differently).
pub fn decode_uri(s: &str) -> String {
    let b = s.as_bytes();
    let mut out = Vec::new();
    let mut i = 0;
    while i < b.len() {
        if b[i] == b'%' && i + 2 < b.len() {
            if let Ok(v) = u8::from_str_radix(&s[i + 1..i + 3], 16) {
                out.push(v);
                i += 3;
                continue;
            }
        }
        out.push(b[i]);
        i += 1;
    }
    String::from_utf8_lossy(&out).into_owned()
}
