//! A small WebDriver client (W3C WebDriver, JSON over HTTP) for the few
//! commands the browser tests use. The driver listens on 127.0.0.1 only,
//! so each command is one HTTP/1.1 request on its own connection.

use std::io::{Read, Write};
use std::net::{SocketAddr, TcpStream};
use std::time::Duration;

use anyhow::{bail, Context, Result};
use serde_json::{json, Value};

/// The key under which WebDriver names an element.
const ELEMENT_KEY: &str = "element-6066-11e4-a52e-4f735466cecf";
/// How long one command may take; a page that stops answering fails the
/// command (and the test) instead of hanging it.
const COMMAND_TIMEOUT: Duration = Duration::from_secs(90);

/// Sends one request to the WebDriver server at `address`; returns the
/// HTTP status and the parsed JSON body.
pub fn request(address: SocketAddr, method: &str, path: &str, body: Option<&Value>) -> Result<(u16, Value)> {
    let exchange = || -> Result<(u16, Value)> {
        let mut stream = TcpStream::connect_timeout(&address, Duration::from_secs(5))?;
        stream.set_read_timeout(Some(COMMAND_TIMEOUT))?;
        stream.set_write_timeout(Some(COMMAND_TIMEOUT))?;
        let body = body.map(Value::to_string).unwrap_or_default();
        write!(
            stream,
            "{method} {path} HTTP/1.1\r\nHost: {address}\r\nContent-Type: application/json; charset=utf-8\r\n\
             Content-Length: {}\r\nConnection: close\r\n\r\n{body}",
            body.len()
        )?;
        // chromedriver answers `Connection: close` but keeps the connection
        // open: the response ends where its Content-Length says.
        let mut response = Vec::new();
        let mut chunk = [0; 16 * 1024];
        while !is_complete(&response)? {
            let read = stream.read(&mut chunk)?;
            if read == 0 {
                break;
            }
            response.extend_from_slice(&chunk[..read]);
        }
        parse_response(&response)
    };
    exchange().with_context(|| format!("WebDriver {method} {path} at {address}"))
}

/// The header block of `response` and the length of the body it
/// announces, once the whole header block is there.
fn head_of(response: &[u8]) -> Result<Option<(&str, usize, usize)>> {
    let Some(split) = response.windows(4).position(|w| w == b"\r\n\r\n") else { return Ok(None) };
    let head = std::str::from_utf8(&response[..split]).context("response headers are not UTF-8")?;
    let header = |name: &str| {
        head.lines().find_map(|line| {
            let (key, value) = line.split_once(':')?;
            key.trim().eq_ignore_ascii_case(name).then(|| value.trim().to_string())
        })
    };
    if header("transfer-encoding").is_some_and(|value| value.contains("chunked")) {
        bail!("chunked responses are not read here");
    }
    let length = match header("content-length") {
        Some(value) => value.parse().with_context(|| format!("bad Content-Length `{value}`"))?,
        None => 0,
    };
    Ok(Some((head, split + 4, length)))
}

/// Whether `response` holds its headers and the whole body they announce.
fn is_complete(response: &[u8]) -> Result<bool> {
    Ok(head_of(response)?.is_some_and(|(_, body_start, length)| response.len() >= body_start + length))
}

/// Splits a complete HTTP/1.1 response into its status and JSON body.
fn parse_response(response: &[u8]) -> Result<(u16, Value)> {
    let (head, body_start, length) = head_of(response)?.context("no end of headers in the response")?;
    let status = head.split_whitespace().nth(1).and_then(|s| s.parse().ok()).context("no HTTP status")?;
    let body = response.get(body_start..body_start + length).context("the response ends before its body")?;
    let value = if body.is_empty() { Value::Null } else { serde_json::from_slice(body).context("body is not JSON")? };
    Ok((status, value))
}

/// One WebDriver session; deleted (which closes the browser) on drop.
pub struct Session {
    address: SocketAddr,
    id: String,
}

impl Session {
    /// Starts a session with `capabilities` (the `alwaysMatch` object).
    pub fn new(address: SocketAddr, capabilities: Value) -> Result<Self> {
        let body = json!({ "capabilities": { "alwaysMatch": capabilities } });
        let (status, reply) = request(address, "POST", "/session", Some(&body))?;
        let value = &reply["value"];
        if status != 200 {
            bail!("the browser did not start: {}", value["message"].as_str().unwrap_or("no message"));
        }
        let id = value["sessionId"].as_str().context("no sessionId in the reply")?.to_string();
        Ok(Self { address, id })
    }

    /// Runs `command` (a path under the session) and returns its `value`,
    /// or fails with WebDriver's error and message.
    fn command(&self, method: &str, command: &str, body: Option<Value>) -> Result<Value> {
        let path = format!("/session/{}{command}", self.id);
        let (status, mut reply) = request(self.address, method, &path, body.as_ref())?;
        let value = reply["value"].take();
        if status != 200 {
            bail!(
                "WebDriver {method} {command}: {}: {}",
                value["error"].as_str().unwrap_or("error"),
                value["message"].as_str().unwrap_or("no message")
            );
        }
        Ok(value)
    }

    /// Sets the script and page-load timeouts.
    pub fn set_timeouts(&self, script: Duration, page_load: Duration) -> Result<()> {
        let body = json!({ "script": script.as_millis() as u64, "pageLoad": page_load.as_millis() as u64 });
        self.command("POST", "/timeouts", Some(body)).map(drop)
    }

    pub fn navigate(&self, url: &str) -> Result<()> {
        self.command("POST", "/url", Some(json!({ "url": url }))).map(drop)
    }

    pub fn refresh(&self) -> Result<()> {
        self.command("POST", "/refresh", Some(json!({}))).map(drop)
    }

    /// Runs `script` (a function body; `arguments` holds `args`) in the page
    /// and returns what it returns.
    pub fn execute(&self, script: &str, args: Vec<Value>) -> Result<Value> {
        self.command("POST", "/execute/sync", Some(json!({ "script": script, "args": args })))
    }

    /// The first element matching the CSS `selector`.
    pub fn find(&self, selector: &str) -> Result<Element> {
        let value = self.command("POST", "/element", Some(json!({ "using": "css selector", "value": selector })))?;
        let id = value[ELEMENT_KEY].as_str().with_context(|| format!("no element id for `{selector}` in {value}"))?;
        Ok(Element(id.to_string()))
    }

    /// Clicks `element` as a user would (scrolled into view, real events).
    pub fn click(&self, element: &Element) -> Result<()> {
        self.command("POST", &format!("/element/{}/click", element.0), Some(json!({}))).map(drop)
    }

    /// Types `text` into `element` (for a file input: the file's path).
    pub fn send_keys(&self, element: &Element, text: &str) -> Result<()> {
        self.command("POST", &format!("/element/{}/value", element.0), Some(json!({ "text": text }))).map(drop)
    }

    /// Performs input source actions (pointer moves, presses, releases).
    pub fn perform_actions(&self, actions: Value) -> Result<()> {
        self.command("POST", "/actions", Some(json!({ "actions": actions })))?;
        self.command("DELETE", "/actions", None).map(drop)
    }
}

impl Drop for Session {
    fn drop(&mut self) {
        // The driver may already be gone; the browser goes with it then.
        let _ = request(self.address, "DELETE", &format!("/session/{}", self.id), None);
    }
}

/// An element of the page, by its WebDriver id.
#[derive(Clone, Debug)]
pub struct Element(String);

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_response_splits_into_status_and_json() {
        let body = br#"{"value":{"error":"no such element"}}"#;
        let mut response = format!("HTTP/1.1 404 Not Found\r\nContent-Length:{}\r\n\r\n", body.len()).into_bytes();
        assert!(!is_complete(&response).unwrap());
        response.extend_from_slice(body);
        assert!(is_complete(&response).unwrap());
        let (status, value) = parse_response(&response).unwrap();
        assert_eq!(status, 404);
        assert_eq!(value["value"]["error"], "no such element");
        assert!(parse_response(b"HTTP/1.1 200 OK\r\nTransfer-Encoding: chunked\r\n\r\n2\r\n{}\r\n0\r\n\r\n").is_err());
        assert!(parse_response(b"HTTP/1.1 200 OK\r\n").is_err());
        assert!(parse_response(b"HTTP/1.1 200 OK\r\nContent-Length: 9\r\n\r\n{}").is_err());
    }
}
