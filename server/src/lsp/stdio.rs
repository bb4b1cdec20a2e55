//! A filter between stdin and the protocol library.
//!
//! `tower-lsp-server` reads stdin through a `FramedRead`, and a framed stream
//! ends at its first decoding error: one malformed message from a client would
//! stop the server. This filter frames messages itself, passes valid ones
//! through unchanged, and replaces a body that is not JSON with a harmless
//! `$/` notification (which the library ignores), so the session goes on.

use serde::de::IgnoredAny;
use tokio::io::{
    AsyncBufRead, AsyncBufReadExt, AsyncRead, AsyncReadExt, AsyncWrite, AsyncWriteExt, BufReader,
};

const MALFORMED: &[u8] = br#"{"jsonrpc":"2.0","method":"$/partscope/malformedMessage"}"#;

/// Reads one message body. Header blocks without a usable `Content-Length`
/// are skipped. `None` at end of input.
async fn read_frame<R: AsyncBufRead + Unpin>(r: &mut R) -> std::io::Result<Option<Vec<u8>>> {
    loop {
        let mut len: Option<u64> = None;
        let mut saw_header = false;
        loop {
            let mut line = Vec::new();
            if r.read_until(b'\n', &mut line).await? == 0 {
                return Ok(None);
            }
            let text = String::from_utf8_lossy(&line);
            let text = text.trim();
            if text.is_empty() {
                if saw_header {
                    break;
                }
                continue;
            }
            saw_header = true;
            if let Some((name, value)) = text.split_once(':') {
                if name.trim().eq_ignore_ascii_case("content-length") {
                    len = value.trim().parse().ok();
                }
            }
        }
        let Some(len) = len else {
            eprintln!("partscope lsp: skipped a message without a valid Content-Length");
            continue;
        };
        let mut body = Vec::new();
        r.take(len).read_to_end(&mut body).await?;
        return Ok(Some(body));
    }
}

/// Copies framed messages from `input` to `output`, replacing malformed bodies.
pub async fn filter<R: AsyncRead + Unpin, W: AsyncWrite + Unpin>(
    input: R,
    mut output: W,
) -> std::io::Result<()> {
    let mut input = BufReader::with_capacity(1 << 16, input);
    while let Some(body) = read_frame(&mut input).await? {
        let body: &[u8] = if serde_json::from_slice::<IgnoredAny>(&body).is_ok() {
            &body
        } else {
            eprintln!(
                "partscope lsp: ignored a message that is not JSON ({} bytes)",
                body.len()
            );
            MALFORMED
        };
        output
            .write_all(format!("Content-Length: {}\r\n\r\n", body.len()).as_bytes())
            .await?;
        output.write_all(body).await?;
        output.flush().await?;
    }
    output.shutdown().await
}

/// Stdin with malformed messages neutralised.
pub fn filtered_stdin() -> impl AsyncRead {
    let (writer, reader) = tokio::io::duplex(1 << 20);
    tokio::spawn(async move {
        if let Err(e) = filter(tokio::io::stdin(), writer).await {
            eprintln!("partscope lsp: reading stdin failed: {e}");
        }
    });
    reader
}

#[cfg(test)]
mod tests {
    use super::*;

    #[tokio::test]
    async fn malformed_bodies_are_replaced_and_framing_recovers() {
        let input = b"Content-Length: 2\r\n\r\n{}Content-Length: 5\r\n\r\n{bad}garbage\r\n\r\nContent-Length: 4\r\n\r\n[1]\n".to_vec();
        let mut out = Vec::new();
        filter(&input[..], &mut out).await.unwrap();
        let expected = format!(
            "Content-Length: 2\r\n\r\n{{}}Content-Length: {}\r\n\r\n{}Content-Length: 4\r\n\r\n[1]\n",
            MALFORMED.len(),
            String::from_utf8_lossy(MALFORMED)
        );
        assert_eq!(String::from_utf8(out).unwrap(), expected);
    }
}
